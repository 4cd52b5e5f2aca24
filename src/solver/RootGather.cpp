#include "solver/RootGather.hpp"

namespace stentor {

RootGather::RootGather(const la::Map& rows, const la::RCP<const la::Comm>& comm) {
  const auto inv = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  contiguous_ = Teuchos::rcp(new la::Map(inv, rows.getNodeNumElements(), 0, comm));
  const auto n = static_cast<size_t>(contiguous_->getGlobalNumElements());
  root_ = Teuchos::rcp(new la::Map(n, comm->getRank() == 0 ? n : 0, 0, comm));
  to_root_ = Teuchos::rcp(new la::Import(contiguous_, root_));
}

std::vector<la::GO> RootGather::column_numbers(const la::CrsMatrix& A) const {
  const auto om = A.getRowMap();
  // Each row's new number, carried to the column map as doubles (exact below 2^53).
  la::Vector ids(om), ids_col(A.getColMap());
  {
    auto h = ids.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t i = 0; i < om->getNodeNumElements(); ++i) h(i, 0) = static_cast<double>(row(i));
  }
  ids_col.doImport(ids, la::Import(om, A.getColMap()), Tpetra::INSERT);
  auto ch = ids_col.getLocalViewHost(Tpetra::Access::ReadOnly);
  std::vector<la::GO> out(ch.extent(0));
  for (size_t k = 0; k < out.size(); ++k) out[k] = static_cast<la::GO>(ch(k, 0));
  return out;
}

std::vector<double> RootGather::to_root(const la::Vector& b) const {
  la::Vector bc(contiguous_), b0(root_);
  {
    auto bh = b.getLocalViewHost(Tpetra::Access::ReadOnly);
    auto ch = bc.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t i = 0; i < b.getLocalLength(); ++i) ch(i, 0) = bh(i, 0);
  }
  b0.doImport(bc, *to_root_, Tpetra::INSERT);
  auto h = b0.getLocalViewHost(Tpetra::Access::ReadOnly);
  return std::vector<double>(h.data(), h.data() + b0.getLocalLength());
}

void RootGather::from_root(const std::vector<double>& on_root, la::Vector& x) const {
  la::Vector x0(root_), xc(contiguous_);
  {
    auto h = x0.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t i = 0; i < x0.getLocalLength(); ++i) h(i, 0) = on_root[i];
  }
  xc.doExport(x0, *to_root_, Tpetra::INSERT);
  auto xh = x.getLocalViewHost(Tpetra::Access::OverwriteAll);
  auto ch = xc.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t i = 0; i < x.getLocalLength(); ++i) xh(i, 0) = ch(i, 0);
}

}  // namespace stentor
