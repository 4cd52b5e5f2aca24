// Nodal forces on a surface turned into a traction field (the output fields
// contact_pressure and contact_master_traction; docs/deck.md, "Outputs"): the L2 projection,
// with the row-sum lumped mass matrix, onto the piecewise-linear field over the facets'
// vertices (reference configuration):
//
//   p_v = f~_v / a_v,   f~_v = f_v + 1/2 sum over the mid-edge nodes m next to v of f_m,
//                       a_v = int L_v dA  (L_v: the P1 hat function of vertex v);
//   a mid-edge node m of the edge (v, w) takes (p_v + p_w) / 2.
//
// Why f~: P1 is inside P2, L_v = N_v + 1/2 sum_m N_m, so for consistent nodal forces
// f_a = int N_a t dA of a traction t, f~_v = int L_v t dA: the P1 consistent forces of the
// same traction. A uniform traction is therefore recovered exactly at every node of every
// facet type (line2, line3, tri3, tri6, quad4), and every weight a_v is positive. Dividing
// each node's own force by a lumped area instead fails on tri6 facets: under a uniform
// pressure p the consistent force of a corner node is int N_corner dA = 0 and that of a
// mid-edge node A/3, so f / (HRZ area) reads 0 at the corners and 1.1875 p at the mid-edge
// nodes (measured on a tet10 block, tests/system/test_contact_output.cpp). Why lumped, not
// the consistent projection M p = f: that one amplifies node-to-node noise (its alternating
// mode is divided by h/3 instead of h on line2 facets) and undershoots next to the edge of
// a contact zone; measured on the Hertz benchmark (tests/system/test_contact_benchmarks.cpp,
// h_c = 0.008, matching meshes) its profile error was 5.4 % of p0 against 0.26 % lumped.
// For line2, tri3 and quad4 facets (no mid-edge nodes) p_v = f_v / int N_v dA.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "mesh/Mesh.hpp"

namespace stentor {

class SurfaceProjection {
 public:
  // The facets (cells of dimension mesh.dim - 1) of the named boundary groups (a group
  // named twice counts once); throws InputError naming a missing group. `axisymmetric`: a
  // 2D mesh's (r, z) section, areas of the revolved facets (dA = 2 pi r ds).
  SurfaceProjection(const Mesh& mesh, const std::vector<std::string>& groups, bool axisymmetric = false);

  // The groups' nodes (of all their cells), sorted: the order of f and p in project().
  const std::vector<GId>& nodes() const { return nodes_; }
  // Position of node g in nodes(), or -1.
  long index(GId g) const;
  // The traction at the nodes from nodal forces f (k components per node of nodes(),
  // node-major; the same layout back). Nodes on no facet of the groups (a group's lone
  // points) get 0.
  std::vector<double> project(const std::vector<double>& f, int k) const;

 private:
  void add_facet(const Mesh& mesh, const CellBlock& b, std::size_t f, bool axisymmetric);

  std::vector<GId> nodes_;
  std::vector<double> vertex_area_;                  // a_v per node of nodes() (0: not a facet vertex)
  std::vector<std::pair<long, long>> edge_of_;       // per node: the vertices of its edge when it is a mid-edge node, else (-1, -1)
};

}  // namespace stentor
