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

namespace {

int comm_size(MPI_Comm comm) {
  int n = 1;
  MPI_Comm_size(comm, &n);
  return n;
}

// The most nodes a cell of the mesh has (the record width of a cell's nodes).
std::size_t max_nodes_per_cell(const Mesh& mesh) {
  std::size_t n = 0;
  for (const CellBlock& b : mesh.volumes) n = std::max(n, static_cast<std::size_t>(b.nodes_per_cell));
  return n;
}

// The global ids of this rank's owned nodes, in owned-local order.
std::vector<long long> owned_nodes(const Distribution& dist) {
  std::vector<long long> ids(static_cast<std::size_t>(dist.num_owned_nodes()));
  for (std::size_t l = 0; l < ids.size(); ++l) ids[l] = static_cast<long long>(dist.global_node(static_cast<la::LO>(l)));
  return ids;
}

// The coordinates of this rank's node rows `rows` of n: the owned nodes' routed to them.
std::vector<double> coordinates_on_rows(const Distribution& dist, MPI_Comm comm, std::size_t n, RowRange rows) {
  const Records got = route_to_rows(comm, n, owned_nodes(dist), dist.owned_coordinates(), 3);
  std::vector<double> x(3 * rows.size(), 0.0);
  for (std::size_t i = 0; i < got.ids.size(); ++i)
    std::copy_n(&got.values[3 * i], 3, &x[3 * (static_cast<std::size_t>(got.ids[i]) - rows.begin)]);
  return x;
}

// The blocks' connectivity on this rank's cell rows (xm.blocks[i].conn, xdmf_rows `rows`):
// the own cells' nodes (doubles: node ids are exact in them), routed to the rows' ranks.
void connectivity_on_rows(const Mesh& mesh, const Distribution& dist, MPI_Comm comm, const XdmfRows& rows, XdmfMesh& xm) {
  const std::size_t k = max_nodes_per_cell(mesh);
  std::vector<long long> ids;
  std::vector<double> nodes;
  for (const LocalBlock& lb : dist.blocks()) {
    const CellBlock& b = mesh.volumes[static_cast<std::size_t>(lb.volume_block)];
    const auto npc = static_cast<std::size_t>(b.nodes_per_cell);
    for (std::size_t c = 0; c < lb.cell_ids.size(); ++c) {
      ids.push_back(static_cast<long long>(lb.cell_ids[c]));
      const auto first = static_cast<std::size_t>(lb.cell_index[c]) * npc;
      for (std::size_t a = 0; a < k; ++a) nodes.push_back(a < npc ? static_cast<double>(b.conn[first + a]) : -1.0);
    }
  }
  std::size_t num_cells = 0;
  std::vector<std::size_t> offset;  // each block's first cell
  for (const XdmfMesh::Block& b : xm.blocks) offset.push_back(num_cells), num_cells += b.num_cells;
  const Records got = route_to_rows(comm, num_cells, ids, nodes, static_cast<int>(k));
  for (std::size_t i = 0; i < xm.blocks.size(); ++i)
    xm.blocks[i].conn.assign(rows.blocks[i].size() * static_cast<std::size_t>(cell_num_nodes(xm.blocks[i].type)), -1);
  for (std::size_t r = 0; r < got.ids.size(); ++r) {
    const auto row = static_cast<std::size_t>(got.ids[r]);
    const auto i = static_cast<std::size_t>(std::upper_bound(offset.begin(), offset.end(), row) - offset.begin()) - 1;
    const auto npc = static_cast<std::size_t>(cell_num_nodes(xm.blocks[i].type));
    const std::size_t at = (row - offset[i] - rows.blocks[i].begin) * npc;
    for (std::size_t a = 0; a < npc; ++a) xm.blocks[i].conn[at + a] = static_cast<long long>(got.values[r * k + a]);
  }
}

}  // namespace

XdmfMesh xdmf_mesh_on_rows(const Mesh& mesh, const Distribution& dist, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  XdmfMesh xm;
  xm.num_nodes = mesh.num_nodes();
  for (std::size_t b = 0; b < mesh.volumes.size(); ++b)
    xm.blocks.push_back(XdmfMesh::Block{mesh.volumes[b].name, mesh.volumes[b].type, mesh.block_cells(b), {}});
  const XdmfRows rows = xdmf_rows(xm, rank, comm_size(comm));
  xm.x = coordinates_on_rows(dist, comm, xm.num_nodes, rows.nodes);
  connectivity_on_rows(mesh, dist, comm, rows, xm);
  return xm;
}

NodeRows::NodeRows(const Distribution& dist, std::size_t num_nodes, const la::RCP<const la::Comm>& comm, RowRange rows)
    : rows_(rows), dim_(dist.dim()) {
  std::vector<long long> used = route_to_rows(raw_mpi_comm(*comm), num_nodes, owned_nodes(dist), {}, 0).ids;
  std::sort(used.begin(), used.end());  // each node once: it has one owner
  for (long long n : used)
    for (int k = 0; k < dim_; ++k) dofs_.push_back(static_cast<la::GO>(n) * dim_ + k);
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

namespace {

// A cell's record for the recovery: volume, block, nodes (k of them, -1 past the cell's
// own), then the columns' values.
struct RecoveryRecords {
  std::vector<int> dest;
  std::vector<long long> ids;
  std::vector<double> values;
};

// Each cell `ids[c]` (this rank's own) to every rank whose rows hold one of its nodes.
RecoveryRecords recovery_records(const Mesh& mesh, int nranks, const std::vector<GId>& ids,
                                 const std::vector<const std::vector<double>*>& columns, const std::vector<int>& k,
                                 const std::vector<double>& volume, std::size_t kn) {
  const std::size_t nn = mesh.num_nodes();
  RecoveryRecords out;
  std::vector<int> to;
  for (std::size_t c = 0; c < ids.size(); ++c) {
    const auto [b, i] = locate_cell(mesh, ids[c]);  // an own cell: in any part of the mesh
    const CellBlock& blk = mesh.volumes[b];
    const auto npc = static_cast<std::size_t>(blk.nodes_per_cell);
    const GId* nodes = &blk.conn[i * npc];
    to.clear();
    for (std::size_t a = 0; a < npc; ++a) to.push_back(block_row_owner(nn, nranks, static_cast<std::size_t>(nodes[a])));
    std::sort(to.begin(), to.end());
    to.erase(std::unique(to.begin(), to.end()), to.end());
    for (int r : to) {
      out.dest.push_back(r);
      out.ids.push_back(ids[c]);
      out.values.push_back(volume[c]);
      out.values.push_back(static_cast<double>(b));
      for (std::size_t a = 0; a < kn; ++a) out.values.push_back(a < npc ? static_cast<double>(nodes[a]) : -1.0);
      for (std::size_t col = 0; col < columns.size(); ++col)
        for (int j = 0; j < k[col]; ++j)
          out.values.push_back((*columns[col])[c * static_cast<std::size_t>(k[col]) + static_cast<std::size_t>(j)]);
    }
  }
  return out;
}

}  // namespace

std::vector<std::vector<double>> recover_on_rows(const Mesh& mesh, MPI_Comm comm, RowRange rows, const std::vector<GId>& ids,
                                                 const std::vector<const std::vector<double>*>& columns,
                                                 const std::vector<int>& k, const std::vector<double>& volume) {
  const std::size_t kn = max_nodes_per_cell(mesh);
  const auto kc = 2 + kn + static_cast<std::size_t>(std::accumulate(k.begin(), k.end(), 0));
  const RecoveryRecords send = recovery_records(mesh, comm_size(comm), ids, columns, k, volume, kn);
  const Records got = exchange_records(comm, send.dest, send.ids, send.values, static_cast<int>(kc));
  // The serial summation order: ascending cell ids.
  std::vector<std::size_t> order(got.ids.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return got.ids[a] < got.ids[b]; });
  CellNodes cells;
  std::vector<double> vol(order.size());
  std::vector<GId> nodes;
  for (std::size_t j = 0; j < order.size(); ++j) {
    const double* v = &got.values[order[j] * kc];
    vol[j] = v[0];
    const auto b = static_cast<int>(v[1]);
    const auto npc = static_cast<std::size_t>(mesh.volumes[static_cast<std::size_t>(b)].nodes_per_cell);
    nodes.assign(npc, 0);
    for (std::size_t a = 0; a < npc; ++a) nodes[a] = static_cast<GId>(v[2 + a]);
    cells.add(b, nodes.data(), npc);
  }
  std::vector<std::vector<double>> out;
  std::size_t off = 2 + kn;
  for (std::size_t col = 0; col < columns.size(); ++col) {
    const auto kk = static_cast<std::size_t>(k[col]);
    std::vector<double> vals(order.size() * kk);
    for (std::size_t j = 0; j < order.size(); ++j)
      for (std::size_t q = 0; q < kk; ++q) vals[j * kk + q] = got.values[order[j] * kc + off + q];
    out.push_back(recover_at_node_rows(rows.begin, rows.end, cells, vals, k[col], vol));
    off += kk;
  }
  return out;
}

}  // namespace stentor
