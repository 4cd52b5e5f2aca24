// The mesh as every rank sees it: a plain, replicated, Trilinos-free description.
// Nodes are numbered 0..num_nodes-1 (compact renumbering of gmsh's node tags);
// this index is the node's global id everywhere in Stentor (dof gid = node*dim + c).
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
  std::vector<GId> cell_id;  // global cell id (unique over all volume blocks), one per cell
  std::size_t num_cells() const { return nodes_per_cell ? conn.size() / nodes_per_cell : 0; }
};

struct Mesh {
  int dim = 0;                  // 2 (plane strain, z ignored) or 3
  std::string source;           // file it came from (for messages)
  std::vector<double> x;        // 3 coordinates per node (z = 0 in 2D)
  std::vector<CellBlock> volumes;     // cells of dimension `dim`, one block per (group, type)
  std::vector<CellBlock> boundaries;  // cells of dimension dim-1 (and dim-2/points for node sets)
  std::size_t num_nodes() const { return x.size() / 3; }
  std::size_t num_volume_cells() const {
    std::size_t n = 0;
    for (const auto& b : volumes) n += b.num_cells();
    return n;
  }
  // Names of the physical groups present (volumes and boundaries), for error messages.
  std::vector<std::string> volume_group_names() const;
  std::vector<std::string> boundary_group_names() const;

  // Axis-aligned box of all nodes (z = 0 in 2D), and its diagonal's length: the model's size.
  struct Box {
    double lo[3], hi[3];
    double diagonal() const;
  };
  Box bounding_box() const;
};

// Where the volume cell with global id `id` is: its block in Mesh::volumes and its index
// there. A block's ids are consecutive (GmshReader numbers the cells so); throws
// std::logic_error when no block holds `id` or a block's ids are not consecutive.
std::pair<std::size_t, std::size_t> locate_cell(const Mesh& m, GId id);

// The mesh as bytes and back (every field): for the broadcast and for the mesh that
// gmsh's own process hands back (mesh/GmshReader.hpp). deserialize_mesh throws
// std::runtime_error on truncated or trailing data.
std::vector<char> serialize_mesh(const Mesh& m);
Mesh deserialize_mesh(const std::vector<char>& buf);

}  // namespace stentor
