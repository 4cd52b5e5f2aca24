// Who owns what: the element partition (METIS), node ownership, and the Tpetra
// DOF maps built from them, from a rank's part of the mesh (the cells' parts come with
// it) or from a whole mesh (partitioned here); each rank keeps its cells.
//
// DOF global id = node * dim + component, independent of the partition, so results
// gathered for output come out in the same order on any number of ranks.
// Local (overlap) node numbering: owned nodes first, then ghosts, each along a Morton
// curve of their coordinates -- Tpetra's FE assembly needs owned rows to be a prefix of
// the overlap map.
#pragma once
#include <vector>

#include "mesh/Mesh.hpp"
#include "parallel/LinearAlgebra.hpp"

namespace stentor {

struct LocalBlock {
  int volume_block = -1;              // index into Mesh::volumes
  CellType type = CellType::Invalid;
  int nodes_per_cell = 0;
  Kokkos::View<int**, Kokkos::LayoutRight, la::ExecSpace> conn;  // local cell -> overlap local node
  std::vector<GId> cell_ids;        // global cell id of each local cell
  std::vector<GId> cell_index;      // index of each local cell within its mesh block
};

class Distribution {
 public:
  Distribution(const Mesh& mesh, const la::RCP<const la::Comm>& comm);

  int dim() const { return dim_; }
  int rank() const { return rank_; }
  int num_ranks() const { return nranks_; }
  la::LO num_owned_nodes() const { return num_owned_; }
  la::LO num_local_nodes() const { return static_cast<la::LO>(local_nodes_.size()); }
  // Overlap-local index of a global node, or -1 when this rank does not touch it.
  la::LO local_node(GId g) const;
  bool owns_node(GId g) const {
    const la::LO l = local_node(g);
    return l >= 0 && l < num_owned_;
  }
  GId global_node(la::LO l) const { return local_nodes_[static_cast<std::size_t>(l)]; }
  const std::vector<LocalBlock>& blocks() const { return blocks_; }
  std::size_t num_local_cells() const;

  const la::RCP<const la::Map>& owned_map() const { return owned_map_; }
  const la::RCP<const la::Map>& overlap_map() const { return overlap_map_; }
  const la::RCP<const la::Import>& importer() const { return importer_; }  // owned -> overlap
  const la::RCP<const la::Comm>& comm() const { return comm_; }
  // Reference coordinates of overlap-local nodes.
  const Kokkos::View<double* [3], Kokkos::LayoutRight, la::ExecSpace>& coords() const { return coords_; }
  // Reference coordinates of the owned nodes, 3 per node in owned-local order (what
  // LinearSolver::set_node_coordinates takes for every solver built on owned_map()).
  std::vector<double> owned_coordinates() const;

 private:
  void set_local_nodes(const Mesh& mesh, const std::vector<GId>& owned, const std::vector<GId>& ghost);
  LocalBlock local_block(const Mesh& mesh, std::size_t volume_block, const std::vector<int>& part) const;

  int dim_ = 0, rank_ = 0, nranks_ = 1;
  la::LO num_owned_ = 0;
  std::vector<GId> local_nodes_;
  std::vector<la::LO> node_g2l_;                         // a whole mesh: by global node
  std::vector<std::pair<GId, la::LO>> sparse_g2l_;       // a part: (global, local), sorted
  std::vector<LocalBlock> blocks_;
  la::RCP<const la::Comm> comm_;
  la::RCP<const la::Map> owned_map_, overlap_map_;
  la::RCP<const la::Import> importer_;
  Kokkos::View<double* [3], Kokkos::LayoutRight, la::ExecSpace> coords_;
};

}  // namespace stentor
