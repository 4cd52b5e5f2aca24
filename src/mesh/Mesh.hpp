// The mesh: a plain, Trilinos-free description, either whole (as read, and on one rank)
// or one rank's part of it (mesh/MeshPart.hpp distribute_mesh). Nodes are numbered
// 0..num_nodes()-1 (compact renumbering of gmsh's node tags); this index is the node's
// global id everywhere in Stentor (dof gid = node*dim + c), in both forms.
//
// A rank's part holds: its volume cells and the cells that share a node with them (the
// ghost layer: every cell around a node of its cells is there), each with its part; the
// boundary groups that contact and the stent metrics read whole, and of the others the
// cells on its volume cells (what loads and supports of its nodes need), with each
// facet's outward side and adjacent volume cell worked out on the whole mesh; and the
// coordinates of the nodes of all these cells only. Code that reads
// coordinates uses coord(g); code that visits nodes visits the stored ones
// (num_stored_nodes / stored_node); counts of the whole mesh are num_nodes(),
// num_volume_cells() and block_cells(b).
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "fem/CellType.hpp"

namespace stentor {

using GId = long long;  // Tpetra's default global ordinal

// A set of cells of one type that belong to one gmsh physical group.
struct CellBlock {
  std::string name;        // physical group name (or "tag<N>" when unnamed)
  int physical_tag = -1;   // gmsh physical tag
  CellType type = CellType::Invalid;
  int nodes_per_cell = 0;
  std::vector<GId> conn;  // nodes_per_cell entries per cell, gmsh node order
  std::vector<GId> cell_id;  // global cell id (unique over all volume blocks), one per cell; ascending
  std::size_t num_cells() const { return nodes_per_cell ? conn.size() / nodes_per_cell : 0; }

  // A rank's part of the mesh only (empty in a whole mesh):
  std::vector<int> part;             // volume blocks: the part (rank) of each stored cell
  std::vector<signed char> side;     // boundary facets (dimension dim-1): +1 if the reference normal
                                     // (fem/Geometry.hpp) points out of the body, -1 if in, 0: the
                                     // facet bounds no volume cell
  std::vector<GId> adjacent;         // boundary facets: the volume cell each bounds (-1: none)
  std::size_t whole_cells = 0;       // volume blocks: the block's cells in the whole mesh
};

struct Mesh {
  int dim = 0;                  // 2 (plane strain, z ignored) or 3
  std::string source;           // file it came from (for messages)
  std::vector<double> x;        // 3 coordinates per stored node (z = 0 in 2D)
  std::vector<CellBlock> volumes;     // cells of dimension `dim`, one block per (group, type)
  std::vector<CellBlock> boundaries;  // cells of dimension dim-1 (and dim-2/points for node sets)

  // A rank's part only: the global ids of the stored nodes (ascending; x holds their
  // coordinates in this order), the whole mesh's node count and bounding box.
  bool partial = false;
  std::vector<GId> node_ids;
  std::size_t whole_nodes = 0;

  // Counts of the whole mesh (in both forms).
  std::size_t num_nodes() const { return partial ? whole_nodes : x.size() / 3; }
  std::size_t block_cells(std::size_t volume_block) const {
    const CellBlock& b = volumes[volume_block];
    return partial ? b.whole_cells : b.num_cells();
  }
  std::size_t num_volume_cells() const {
    std::size_t n = 0;
    for (std::size_t b = 0; b < volumes.size(); ++b) n += block_cells(b);
    return n;
  }
  // The nodes stored here: all of them in a whole mesh.
  std::size_t num_stored_nodes() const { return x.size() / 3; }
  GId stored_node(std::size_t i) const { return partial ? node_ids[i] : static_cast<GId>(i); }
  // Index of global node g among the stored ones, or -1 when it is not stored.
  long long stored_index(GId g) const;
  // Reference coordinates (3) of global node g; throws std::logic_error when g is not stored.
  const double* coord(GId g) const;
  // Bytes of the arrays held (coordinates, node ids, every block's cells and facet data).
  std::size_t bytes() const;
  // Names of the physical groups present (volumes and boundaries), for error messages.
  std::vector<std::string> volume_group_names() const;
  std::vector<std::string> boundary_group_names() const;

  // Axis-aligned box of all nodes (z = 0 in 2D), and its diagonal's length: the model's size.
  struct Box {
    double lo[3], hi[3];
    double diagonal() const;
  };
  Box bounding_box() const;  // of the whole mesh (a part keeps the whole mesh's box)
  Box whole_box{};           // a part only
};

// Where the volume cell with global id `id` is: its block in Mesh::volumes and its index
// there. A whole mesh's block has consecutive ids (GmshReader numbers the cells so), a
// part's ascending ones; throws std::logic_error when no block holds `id` or a whole
// block's ids are not consecutive.
std::pair<std::size_t, std::size_t> locate_cell(const Mesh& m, GId id);

// The mesh as bytes and back (every field): for the broadcast and for the mesh that
// gmsh's own process hands back (mesh/GmshReader.hpp). deserialize_mesh throws
// std::runtime_error on truncated or trailing data.
std::vector<char> serialize_mesh(const Mesh& m);
Mesh deserialize_mesh(const std::vector<char>& buf);

}  // namespace stentor
