// Nodal recovery of cell values (the output fields cauchy_stress_nodal, von_mises_nodal;
// docs/deck.md, "Outputs"): at each node, the mean of the values of the cells around it
// weighted by the cells' (reference) volumes, over the cells of one body only: a node that
// cells of several volume blocks share takes the mean over the cells of the first block
// (mesh.volumes order, = the output's cell_block) that has it, so nothing is averaged
// across a material interface. Nodes of no volume cell get 0.
// A field constant over a body is recovered exactly at its nodes.
#pragma once
#include <vector>

#include "mesh/Mesh.hpp"

namespace stentor {

// `cell_values`: k values per cell, `volume`: one per cell, both indexed by the global cell
// id (CellBlock::cell_id). Returns k values per node.
std::vector<double> recover_at_nodes(const Mesh& mesh, const std::vector<double>& cell_values, int k,
                                     const std::vector<double>& volume);

// Cells given with their nodes (what a rank receives of other ranks' cells): cell j is of
// volume block block[j] (Mesh::volumes index) and has the nodes nodes[first[j] ..
// first[j+1]) (gmsh order; `first` has one entry more than there are cells).
struct CellNodes {
  std::vector<int> block;
  std::vector<std::size_t> first{0};
  std::vector<GId> nodes;
  std::size_t size() const { return block.size(); }
  void add(int b, const GId* cell_nodes, std::size_t count) {
    block.push_back(b);
    nodes.insert(nodes.end(), cell_nodes, cell_nodes + count);
    first.push_back(nodes.size());
  }
};

// The same values on the nodes [begin, end) only, from the cells `cells`, k values and one
// volume each in their order (a partitioned mesh: each rank its rows of the nodes, from
// the cells that touch them; no mesh is read). Every cell with a node in the range must be
// given; with the cells in ascending id order (= block order, the order recover_at_nodes
// sums in), the result equals recover_at_nodes' bitwise.
std::vector<double> recover_at_node_rows(std::size_t begin, std::size_t end, const CellNodes& cells,
                                         const std::vector<double>& cell_values, int k, const std::vector<double>& volume);

}  // namespace stentor
