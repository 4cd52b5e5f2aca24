// The distributed side of the field output (Reporter::write_fields): values held by the
// ranks that own the nodes or cells, moved to the rows of the HDF5 datasets each rank
// writes (io/XdmfWriter.hpp: block_rows of the nodes and of the block-ordered cells). No
// rank holds a whole field, and nothing here reads more of the mesh than a rank's part of
// it has (mesh/Mesh.hpp): the whole mesh's counts and the blocks' names and types, the
// connectivity of this rank's own cells; everything else comes from the Distribution
// (owned nodes and their coordinates, own cells) and travels to the rows' ranks.
#pragma once
#include <mpi.h>

#include <memory>
#include <vector>

#include "io/XdmfWriter.hpp"
#include "mesh/Mesh.hpp"
#include "parallel/Distribution.hpp"
#include "parallel/RawComm.hpp"

namespace stentor {

// The rank whose block_rows(n, rank, nranks) holds `row`.
int block_row_owner(std::size_t n, int nranks, std::size_t row);

// Records of a row id and k values each.
struct Records {
  std::vector<long long> ids;
  std::vector<double> values;
  std::vector<int> from;  // the rank each record came from
};

// Sends record i (ids[i], values[k*i .. k*i+k)) to rank dest[i]; returns what this rank
// received, by sending rank, each rank's records in their order. Collective.
Records exchange_records(MPI_Comm comm, const std::vector<int>& dest, const std::vector<long long>& ids,
                         const std::vector<double>& values, int k);

// Records (ids: rows of n) sent each to the rank whose block_rows hold it. Collective.
Records route_to_rows(MPI_Comm comm, std::size_t n, const std::vector<long long>& ids, const std::vector<double>& values,
                      int k);

// The mesh for the writer (io/XdmfWriter.hpp XdmfMesh): the outline from the mesh's
// counts (num_nodes, block_cells) and blocks; this rank's rows (xdmf_rows over `comm`)
// of the coordinates from the owned nodes' (0 for the nodes of no volume cell: no rank
// owns them) and of the connectivity from the own cells', each routed to its row's rank.
// Collective.
XdmfMesh xdmf_mesh_on_rows(const Mesh& mesh, const Distribution& dist, MPI_Comm comm);

// A vector of the dof map (u, v: dof = node * dim + component) on this rank's node rows
// `rows` of the `num_nodes` nodes, 3 values per node (0 for the nodes of no volume cell,
// z = 0 in 2D). The rows' nodes with dofs are the owned nodes routed to them. Collective.
class NodeRows {
 public:
  NodeRows(const Distribution& dist, std::size_t num_nodes, const la::RCP<const la::Comm>& comm, RowRange rows);
  std::vector<double> values(const la::Vector& u);  // collective

 private:
  RowRange rows_;
  int dim_;
  std::vector<la::GO> dofs_;  // the used dofs of the rows
  la::RCP<const la::Map> map_;
  la::RCP<la::Import> import_;
  la::RCP<la::Vector> v_;
};

// Nodal recovery (mesh/NodalRecovery.hpp) on this rank's node rows `rows` of the cell
// values of each column (k values per local cell each) of this rank's own cells `ids`
// with volumes `volume`: every cell goes, with its block and nodes (read from `mesh` for
// these cells only), to the ranks whose rows its nodes are in, which sum in the serial
// order (equal to recover_at_nodes bitwise). Collective.
std::vector<std::vector<double>> recover_on_rows(const Mesh& mesh, MPI_Comm comm, RowRange rows, const std::vector<GId>& ids,
                                                 const std::vector<const std::vector<double>*>& columns,
                                                 const std::vector<int>& k, const std::vector<double>& volume);

}  // namespace stentor
