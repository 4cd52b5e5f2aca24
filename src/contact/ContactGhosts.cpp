// Surface ghosting of the contact pairs with master surfaces (docs/contact.md, "Master
// positions in parallel"): which surface nodes a rank imports, and their positions.
#include <Teuchos_CommHelpers.hpp>
#include <mpi.h>

#include <algorithm>
#include <cmath>

#include "contact/Contact.hpp"
#include "parallel/RawComm.hpp"

namespace stentor {

void Contact::update_master_positions(const la::Vector& u, std::vector<double>& xm) const {
  master_u_->doImport(u, *master_import_, Tpetra::INSERT);
  auto mh = master_u_->getLocalViewHost(Tpetra::Access::ReadOnly);
  xm = master_X_;  // absent nodes keep their reference positions (never read: their facets are not binned)
  for (std::size_t i = 0; i < ghost_pos_.size(); ++i) {
    const auto pos = static_cast<std::size_t>(ghost_pos_[i]);
    for (int c = 0; c < dim_; ++c) xm[3 * pos + static_cast<std::size_t>(c)] += mh(i * static_cast<std::size_t>(dim_) + static_cast<std::size_t>(c), 0);
  }
}


// Every rank's box of its slave nodes (of master-surface pairs) is gathered; the owner of
// each surface node sends it to every rank whose box, grown by the margin (8 h), holds it.
// That covers the facets a slave node can find within the search radius 2h, their nodes
// (within h of the closest point), a mortar node's slave neighbours, and motions of 2h of
// slave and master nodes until ghosts_outrun() asks for a rebuild. The import, export and
// vectors are rebuilt (collectively) only when some rank's set changed.
void Contact::rebuild_ghosts(const la::Vector& u) {
  const la::Comm& comm = *dist_.comm();
  auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
  double box[6] = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
  for (const auto& p : pairs_) {
    if (!p.master) continue;
    for (const auto& nd : p.nodes)
      for (int c = 0; c < 3; ++c) {
        const double x = nd.X[c] + (c < dim_ ? uh(nd.lid * dim_ + c, 0) : 0.0);
        box[c] = std::min(box[c], x);
        box[3 + c] = std::max(box[3 + c], x);
      }
  }
  std::copy(box, box + 6, ghost_box_);
  const int np = comm.getSize();
  std::vector<double> boxes(6 * static_cast<std::size_t>(np));
  Teuchos::gatherAll(comm, 6, box, 6 * np, boxes.data());
  const double m = ghost_margin_;
  std::vector<std::vector<long long>> send(static_cast<std::size_t>(np));
  ghost_x_.assign(3 * master_nodes_.size(), 0.0);
  for (std::size_t pos = 0; pos < master_nodes_.size(); ++pos) {
    const GId g = master_nodes_[pos];
    if (!dist_.owns_node(g)) continue;
    const la::LO l = dist_.local_node(g);
    double x[3];
    for (int c = 0; c < 3; ++c) x[c] = master_X_[3 * pos + static_cast<std::size_t>(c)] + (c < dim_ ? uh(l * dim_ + c, 0) : 0.0);
    std::copy(x, x + 3, &ghost_x_[3 * pos]);
    for (int r = 0; r < np; ++r) {
      const double* b = &boxes[6 * static_cast<std::size_t>(r)];
      bool near = b[0] <= b[3];
      for (int c = 0; c < dim_ && near; ++c) near = x[c] >= b[c] - m && x[c] <= b[3 + c] + m;
      if (near) send[static_cast<std::size_t>(r)].push_back(static_cast<long long>(g));
    }
  }
  std::vector<int> scount(static_cast<std::size_t>(np)), rcount(static_cast<std::size_t>(np)), sdispl(static_cast<std::size_t>(np), 0),
      rdispl(static_cast<std::size_t>(np), 0);
  std::vector<long long> sbuf;
  for (int r = 0; r < np; ++r) {
    scount[static_cast<std::size_t>(r)] = static_cast<int>(send[static_cast<std::size_t>(r)].size());
    sdispl[static_cast<std::size_t>(r)] = static_cast<int>(sbuf.size());
    sbuf.insert(sbuf.end(), send[static_cast<std::size_t>(r)].begin(), send[static_cast<std::size_t>(r)].end());
  }
  const MPI_Comm mc = raw_mpi_comm(comm);
  MPI_Alltoall(scount.data(), 1, MPI_INT, rcount.data(), 1, MPI_INT, mc);
  int total = 0;
  for (int r = 0; r < np; ++r) rdispl[static_cast<std::size_t>(r)] = total, total += rcount[static_cast<std::size_t>(r)];
  std::vector<long long> rbuf(static_cast<std::size_t>(total));
  MPI_Alltoallv(sbuf.data(), scount.data(), sdispl.data(), MPI_LONG_LONG, rbuf.data(), rcount.data(), rdispl.data(), MPI_LONG_LONG, mc);
  std::vector<int> pos;
  for (long long g : rbuf) pos.push_back(master_pos(static_cast<GId>(g)));
  std::sort(pos.begin(), pos.end());
  pos.erase(std::unique(pos.begin(), pos.end()), pos.end());
  long changed = (pos != ghost_pos_ || master_map_.is_null()) ? 1 : 0, any = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &changed, &any);
  if (any == 0) return;
  ghost_pos_ = pos;
  present_.assign(master_nodes_.size(), 0);
  ghost_index_.assign(master_nodes_.size(), -1);
  std::vector<la::GO> gids;
  for (std::size_t i = 0; i < ghost_pos_.size(); ++i) {
    const auto q = static_cast<std::size_t>(ghost_pos_[i]);
    present_[q] = 1;
    ghost_index_[q] = static_cast<int>(i);
    for (int c = 0; c < dim_; ++c) gids.push_back(static_cast<la::GO>(master_nodes_[q]) * dim_ + c);
  }
  master_map_ = Teuchos::rcp(new la::Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(), Teuchos::ArrayView<const la::GO>(gids), 0,
                                         dist_.comm()));
  master_import_ = Teuchos::rcp(new la::Import(dist_.owned_map(), master_map_));
  master_export_ = Teuchos::rcp(new la::Export(master_map_, dist_.owned_map()));
  master_u_ = Teuchos::rcp(new la::Vector(master_map_));
  master_r_ = Teuchos::rcp(new la::Vector(master_map_));
}

bool Contact::ghosts_outrun(const la::Vector& u) const {
  auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
  const double allow = 0.25 * ghost_margin_;
  long out = 0, any = 0;
  for (const auto& p : pairs_) {
    if (!p.master) continue;
    for (const auto& nd : p.nodes)
      for (int c = 0; c < dim_; ++c) {
        const double x = nd.X[c] + uh(nd.lid * dim_ + c, 0);
        out += x < ghost_box_[c] - allow || x > ghost_box_[3 + c] + allow;
      }
  }
  for (std::size_t pos = 0; pos < master_nodes_.size() && out == 0; ++pos) {
    const GId g = master_nodes_[pos];
    if (!dist_.owns_node(g)) continue;
    const la::LO l = dist_.local_node(g);
    for (int c = 0; c < dim_; ++c) out += std::abs(master_X_[3 * pos + static_cast<std::size_t>(c)] + uh(l * dim_ + c, 0) - ghost_x_[3 * pos + static_cast<std::size_t>(c)]) > allow;
  }
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_MAX, 1, &out, &any);
  return any > 0;
}

}  // namespace stentor
