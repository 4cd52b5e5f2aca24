#include "run/OutputRows.hpp"

#include <algorithm>
#include <numeric>

#include "mesh/NodalRecovery.hpp"

namespace stentor {

int block_row_owner(std::size_t n, int nranks, std::size_t row) {
  const auto p = static_cast<std::size_t>(nranks);
  const std::size_t q = n / p, extra = n % p;
  if (row < extra * (q + 1)) return static_cast<int>(row / (q + 1));
  return static_cast<int>(extra + (row - extra * (q + 1)) / q);
}

Records exchange_records(MPI_Comm comm, const std::vector<int>& dest, const std::vector<long long>& ids,
                         const std::vector<double>& values, int k) {
  int nranks = 1;
  MPI_Comm_size(comm, &nranks);
  const auto p = static_cast<std::size_t>(nranks), kk = static_cast<std::size_t>(k);
  std::vector<int> scount(p, 0), sdispl(p, 0), rcount(p, 0), rdispl(p, 0);
  for (int d : dest) ++scount[static_cast<std::size_t>(d)];
  MPI_Alltoall(scount.data(), 1, MPI_INT, rcount.data(), 1, MPI_INT, comm);
  std::partial_sum(scount.begin(), scount.end() - 1, sdispl.begin() + 1);
  std::partial_sum(rcount.begin(), rcount.end() - 1, rdispl.begin() + 1);
  // Packed by destination, in the given order within one.
  std::vector<long long> sid(ids.size());
  std::vector<double> sval(values.size());
  std::vector<int> at(sdispl);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const auto j = static_cast<std::size_t>(at[static_cast<std::size_t>(dest[i])]++);
    sid[j] = ids[i];
    std::copy_n(values.data() + i * kk, kk, sval.data() + j * kk);
  }
  const auto total = static_cast<std::size_t>(rdispl.back() + rcount.back());
  Records r;
  r.ids.resize(total);
  r.values.resize(total * kk);
  MPI_Alltoallv(sid.data(), scount.data(), sdispl.data(), MPI_LONG_LONG, r.ids.data(), rcount.data(), rdispl.data(),
                MPI_LONG_LONG, comm);
  for (std::size_t q = 0; q < p; ++q) {
    r.from.insert(r.from.end(), static_cast<std::size_t>(rcount[q]), static_cast<int>(q));
    scount[q] *= k, sdispl[q] *= k, rcount[q] *= k, rdispl[q] *= k;
  }
  MPI_Alltoallv(sval.data(), scount.data(), sdispl.data(), MPI_DOUBLE, r.values.data(), rcount.data(), rdispl.data(),
                MPI_DOUBLE, comm);
  return r;
}

Records route_to_rows(MPI_Comm comm, std::size_t n, const std::vector<long long>& ids, const std::vector<double>& values,
                      int k) {
  int nranks = 1;
  MPI_Comm_size(comm, &nranks);
  std::vector<int> dest(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) dest[i] = block_row_owner(n, nranks, static_cast<std::size_t>(ids[i]));
  return exchange_records(comm, dest, ids, values, k);
}

NodeRows::NodeRows(const Mesh& mesh, const Distribution& dist, const la::RCP<const la::Comm>& comm, RowRange rows)
    : rows_(rows), dim_(dist.dim()) {
  std::vector<char> used(rows.size(), 0);
  for (const auto& b : mesh.volumes)
    for (GId n : b.conn)
      if (static_cast<std::size_t>(n) >= rows.begin && static_cast<std::size_t>(n) < rows.end)
        used[static_cast<std::size_t>(n) - rows.begin] = 1;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (used[i])
      for (int k = 0; k < dim_; ++k) dofs_.push_back(static_cast<la::GO>(rows.begin + i) * dim_ + k);
  map_ = Teuchos::rcp(new la::Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                  Teuchos::ArrayView<const la::GO>(dofs_), 0, comm));
  import_ = Teuchos::rcp(new la::Import(dist.owned_map(), map_));
  v_ = Teuchos::rcp(new la::Vector(map_));
}

std::vector<double> NodeRows::values(const la::Vector& u) {
  std::vector<double> d(3 * rows_.size(), 0.0);
  v_->doImport(u, *import_, Tpetra::INSERT);
  auto vh = v_->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (std::size_t i = 0; i < dofs_.size(); ++i) {
    const auto node = static_cast<std::size_t>(dofs_[i] / dim_), k = static_cast<std::size_t>(dofs_[i] % dim_);
    d[3 * (node - rows_.begin) + k] = vh(i, 0);
  }
  return d;
}

std::vector<std::vector<double>> recover_on_rows(const Mesh& mesh, MPI_Comm comm, RowRange rows, const std::vector<GId>& ids,
                                                 const std::vector<const std::vector<double>*>& columns,
                                                 const std::vector<int>& k, const std::vector<double>& volume) {
  int nranks = 1;
  MPI_Comm_size(comm, &nranks);
  const std::size_t nn = mesh.num_nodes();
  const int kc = 1 + std::accumulate(k.begin(), k.end(), 0);
  std::vector<int> dest;
  std::vector<long long> sid;
  std::vector<double> sval;
  std::vector<int> to;
  for (std::size_t c = 0; c < ids.size(); ++c) {
    const auto [b, i] = locate_cell(mesh, ids[c]);
    const CellBlock& blk = mesh.volumes[b];
    const auto npc = static_cast<std::size_t>(blk.nodes_per_cell);
    to.clear();
    for (std::size_t a = 0; a < npc; ++a)
      to.push_back(block_row_owner(nn, nranks, static_cast<std::size_t>(blk.conn[i * npc + a])));
    std::sort(to.begin(), to.end());
    to.erase(std::unique(to.begin(), to.end()), to.end());
    for (int r : to) {
      dest.push_back(r);
      sid.push_back(ids[c]);
      sval.push_back(volume[c]);
      for (std::size_t col = 0; col < columns.size(); ++col)
        for (int j = 0; j < k[col]; ++j) sval.push_back((*columns[col])[c * static_cast<std::size_t>(k[col]) + static_cast<std::size_t>(j)]);
    }
  }
  const Records got = exchange_records(comm, dest, sid, sval, kc);
  // The serial summation order: ascending cell ids.
  std::vector<std::size_t> order(got.ids.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return got.ids[a] < got.ids[b]; });
  std::vector<GId> cells(order.size());
  std::vector<double> vol(order.size());
  for (std::size_t j = 0; j < order.size(); ++j) {
    cells[j] = static_cast<GId>(got.ids[order[j]]);
    vol[j] = got.values[order[j] * static_cast<std::size_t>(kc)];
  }
  std::vector<std::vector<double>> out;
  int off = 1;
  for (std::size_t col = 0; col < columns.size(); ++col) {
    std::vector<double> vals(order.size() * static_cast<std::size_t>(k[col]));
    for (std::size_t j = 0; j < order.size(); ++j)
      for (int q = 0; q < k[col]; ++q)
        vals[j * static_cast<std::size_t>(k[col]) + static_cast<std::size_t>(q)] =
            got.values[order[j] * static_cast<std::size_t>(kc) + static_cast<std::size_t>(off + q)];
    out.push_back(recover_at_node_rows(mesh, rows.begin, rows.end, cells, vals, k[col], vol));
    off += k[col];
  }
  return out;
}

}  // namespace stentor
