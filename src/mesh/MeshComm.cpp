#include "mesh/MeshComm.hpp"

#include <metis.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>

#include "mesh/GmshReader.hpp"
#include "mesh/MeshCheck.hpp"

namespace stentor {
namespace {

// f(offset, length) over [0, n) in chunks below MPI's int count limit.
template <class F>
void for_each_chunk(std::uint64_t n, F f) {
  const std::uint64_t chunk = 1u << 30;
  for (std::uint64_t off = 0; off < n; off += chunk) f(off, static_cast<int>(std::min(chunk, n - off)));
}

int num_vertices(CellType t) {
  switch (t) {
    case CellType::Tri3:
    case CellType::Tri6: return 3;
    case CellType::Quad4:
    case CellType::Quad8: return 4;
    case CellType::Tet4:
    case CellType::Tet10: return 4;
    case CellType::Hex8: return 8;
    case CellType::Line2:
    case CellType::Line3: return 2;
    case CellType::Point1: return 1;
    default: return 0;
  }
}

}  // namespace

void broadcast_bytes(std::vector<char>& buf, MPI_Comm comm, int root) {
  std::uint64_t n = buf.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, root, comm);
  buf.resize(n);
  for_each_chunk(n, [&](std::uint64_t off, int len) { MPI_Bcast(buf.data() + off, len, MPI_CHAR, root, comm); });
}

void send_bytes(const std::vector<char>& buf, int to, MPI_Comm comm) {
  const std::uint64_t n = buf.size();
  MPI_Send(&n, 1, MPI_UINT64_T, to, 0, comm);
  for_each_chunk(n, [&](std::uint64_t off, int len) { MPI_Send(buf.data() + off, len, MPI_CHAR, to, 1, comm); });
}

std::vector<char> recv_bytes(int from, MPI_Comm comm) {
  std::uint64_t n = 0;
  MPI_Recv(&n, 1, MPI_UINT64_T, from, 0, comm, MPI_STATUS_IGNORE);
  std::vector<char> buf(n);
  for_each_chunk(n, [&](std::uint64_t off, int len) {
    MPI_Recv(buf.data() + off, len, MPI_CHAR, from, 1, comm, MPI_STATUS_IGNORE);
  });
  return buf;
}

void on_root(const std::function<void()>& work, MPI_Comm comm, int root) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string err;  // first byte: 'I' (InputError) or 'R' (other), then the message
  if (rank == root) {
    try {
      work();
    } catch (const InputError& e) {
      err = std::string("I") + e.what();
    } catch (const std::exception& e) {
      err = std::string("R") + e.what();
    }
  }
  std::vector<char> buf(err.begin(), err.end());
  broadcast_bytes(buf, comm, root);
  if (buf.empty()) return;
  const std::string msg(buf.begin() + 1, buf.end());
  if (buf[0] == 'I') throw InputError(msg);
  throw std::runtime_error(msg);
}

void broadcast_mesh(Mesh& m, MPI_Comm comm, int root) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<char> buf;
  if (rank == root) buf = serialize_mesh(m);
  broadcast_bytes(buf, comm, root);
  if (rank == root) return;
  m = deserialize_mesh(buf);
}

Mesh read_mesh_on_root(const MeshConfig& cfg, MPI_Comm comm, bool check, bool verbose, int root) {
  Mesh m = read_mesh_on_root_only(cfg, comm, check, verbose, root);
  broadcast_mesh(m, comm, root);
  return m;
}

Mesh read_mesh_on_root_only(const MeshConfig& cfg, MPI_Comm comm, bool check, bool verbose, int root) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  Mesh m;
  std::vector<char> err;
  if (rank == root) {
    try {
      m = read_mesh(cfg, verbose);
      if (check) check_mesh(m);
    } catch (const InputError& e) {
      const std::string s = e.what();
      err.assign(s.begin(), s.end());
      if (err.empty()) err.push_back('?');
    }
  }
  broadcast_bytes(err, comm, root);
  if (!err.empty()) throw InputError(std::string(err.begin(), err.end()));
  return m;
}

std::vector<int> partition_cells_on_root(const Mesh& m, int nparts, MPI_Comm comm, int root) {
  std::vector<int> part;
  on_root([&] { part = partition_cells(m, nparts); }, comm, root);
  part.resize(m.num_volume_cells());
  MPI_Bcast(part.data(), static_cast<int>(part.size()), MPI_INT, root, comm);
  return part;
}

std::vector<int> partition_cells(const Mesh& m, int nparts) {
  const std::size_t nc = m.num_volume_cells();
  if (nparts < 1) throw std::invalid_argument("partition_cells: nparts must be >= 1");
  if (nparts == 1) return std::vector<int>(nc, 0);
  if (static_cast<std::size_t>(nparts) > nc)
    throw InputError(m.source + ": cannot split " + std::to_string(nc) + " cells into " +
                     std::to_string(nparts) + " parts (use fewer MPI ranks or a finer mesh)");
  if (nc > static_cast<std::size_t>(INT32_MAX) || m.num_nodes() > static_cast<std::size_t>(INT32_MAX))
    throw std::runtime_error("partition_cells: mesh too large for 32-bit METIS indices");

  // Cells in global id order, vertex nodes only.
  std::vector<idx_t> eptr(nc + 1, 0);
  std::vector<std::pair<const CellBlock*, std::size_t>> cell(nc, {nullptr, 0});
  for (const auto& b : m.volumes)
    for (std::size_t c = 0; c < b.num_cells(); ++c) {
      const GId id = b.cell_id[c];
      if (id < 0 || static_cast<std::size_t>(id) >= nc || cell[id].first)
        throw std::runtime_error("partition_cells: volume cell ids are not 0..N-1");
      cell[id] = {&b, c};
    }
  std::vector<idx_t> eind;
  eind.reserve(nc * 4);
  for (std::size_t e = 0; e < nc; ++e) {
    const CellBlock& b = *cell[e].first;
    const int nv = num_vertices(b.type);
    for (int a = 0; a < nv; ++a) eind.push_back(static_cast<idx_t>(b.conn[cell[e].second * b.nodes_per_cell + a]));
    eptr[e + 1] = static_cast<idx_t>(eind.size());
  }
  idx_t ne = static_cast<idx_t>(nc), nn = static_cast<idx_t>(m.num_nodes());
  idx_t ncommon = m.dim == 2 ? 2 : 3, np = nparts, objval = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 12345;
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> epart(nc), npart(m.num_nodes());
  const int status = METIS_PartMeshDual(&ne, &nn, eptr.data(), eind.data(), nullptr, nullptr, &ncommon, &np,
                                        nullptr, options, &objval, epart.data(), npart.data());
  if (status != METIS_OK)
    throw std::runtime_error("partition_cells: METIS_PartMeshDual failed (status " + std::to_string(status) + ")");
  return std::vector<int>(epart.begin(), epart.end());
}

std::vector<int> node_owners(const Mesh& m, const std::vector<int>& cell_part) {
  std::vector<int> owner(m.num_nodes(), INT_MAX);
  for (const auto& b : m.volumes)
    for (std::size_t c = 0; c < b.num_cells(); ++c) {
      const int p = cell_part.at(static_cast<std::size_t>(b.cell_id[c]));
      for (int a = 0; a < b.nodes_per_cell; ++a) {
        int& o = owner[b.conn[c * b.nodes_per_cell + a]];
        o = std::min(o, p);
      }
    }
  for (auto& o : owner)
    if (o == INT_MAX) o = 0;
  return owner;
}

}  // namespace stentor
