// A rank's part of the mesh (the form described in mesh/Mesh.hpp), cut from the whole
// mesh on one rank and sent to each rank, so that no rank but the reader holds the whole
// volume mesh.
#pragma once
#include <mpi.h>

#include <string>
#include <vector>

#include "mesh/Mesh.hpp"

namespace stentor {

// The outward side of each facet of `facets` (a boundary block of dimension dim-1 of the
// whole mesh `m`), against the centroid of a volume cell holding the facet's vertices
// (gmsh does not orient physical curves/surfaces consistently with the body they bound):
// side +1 if the reference normal (fem/Geometry.hpp) points out, -1 if in, 0 when the
// facet bounds no volume cell; adjacent: that cell's global id (-1: none).
struct FacetSides {
  std::vector<signed char> side;
  std::vector<GId> adjacent;
};
FacetSides facet_sides(const Mesh& m, const CellBlock& facets);

// The part of the whole mesh `m` (every boundary block of dimension dim-1 already with
// its sides) for part r of the cell partition `cell_part` (one entry per global cell id):
// the cells of part r and those sharing a node with them; the boundary groups named in
// `whole_groups` whole, of the others the cells whose nodes all lie on those cells (every
// facet or point a load or support of part r's nodes needs) and the facets that bound no
// volume cell (so that every rank reports them alike); the coordinates of all their nodes.
Mesh mesh_part(const Mesh& m, const std::vector<int>& cell_part, int r, const std::vector<std::string>& whole_groups);

// Collective. On root, `m` is the whole mesh: root partitions it (METIS,
// partition_cells), works out the boundary facets' sides, and sends every rank its part
// (mesh_part, with `whole_groups` the boundary groups every rank needs whole: contact
// surfaces, the stent metrics' groups); on return `m` is this rank's part on every rank
// (root's too). An InputError on
// root (more ranks than cells) is rethrown with the same message on every rank, any other
// failure there as std::runtime_error, so no rank hangs. One rank: `m` stays whole.
void distribute_mesh(Mesh& m, MPI_Comm comm, const std::vector<std::string>& whole_groups, int root = 0);

}  // namespace stentor
