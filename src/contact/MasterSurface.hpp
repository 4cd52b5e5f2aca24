// The master side of a deformable contact pair (and, for mortar, the slave side): the
// oriented boundary facets of a group (their connectivity on every rank, like the mesh;
// positions only where Contact imported them), and a bin search for the facet closest to
// a slave point in the current configuration.
//
// Search: facets are binned by their centroid on a uniform grid of spacing 3 max(h, h_c)
// (h: the largest facet extent of the reference mesh; h_c: of the binned facets at the
// current positions); a query visits the 3^dim bins around the point, so every facet
// whose closest point lies within the search radius 2h is seen. Bins are rebuilt at every
// evaluation from the current positions (linear in the number of binned facets, small
// beside the assembly). Only facets whose nodes are all present on this rank are binned
// (Contact imports the surface nodes near its slave nodes, not the whole surface). The
// decisions (radius 2h, a point more than h behind a facet is not in contact, ties between
// equally distant facets to the lower index) do not depend on which facets a rank holds,
// so any partition finds the same facets.
#pragma once
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include "contact/FacetGeometry.hpp"
#include "mesh/Mesh.hpp"

namespace stentor {

class MasterSurface {
 public:
  // Throws InputError naming `where` for groups that are missing, not facets, or of an
  // unsupported facet type.
  MasterSurface(const Mesh& mesh, const std::string& group, const std::string& where);
  // `node_pos` maps a mesh node to its index among the master nodes (positions are passed
  // as 3 values per master node).
  void index(const std::function<int(GId)>& node_pos);

  struct Facet {
    CellType type = CellType::Invalid;
    int nn = 0;
    int node[facet::kMaxNodes] = {};  // indices of master nodes
    GId gid[facet::kMaxNodes] = {};   // mesh node ids
    double orient = 1.0;
  };
  const std::vector<Facet>& facets() const { return facets_; }
  // Mesh nodes of the group's facets (sorted, unique).
  const std::vector<GId>& nodes() const { return nodes_; }

  // Rebuilds the bins from the current master positions (3 per master node); with
  // `present` (per master node), only the facets whose nodes are all present.
  void build(const std::vector<double>& x, const std::vector<char>* present = nullptr);
  double search_radius() const { return 2.0 * h_; }
  double size() const { return h_; }  // largest facet extent of the reference mesh

  struct Hit {
    int facet = -1;
    double xi[2] = {0, 0};
    double xi_free[2] = {0, 0};  // before clamping (= xi when inside)
    bool inside = false;
    double dist = 0.0;
  };
  // Closest facet to xs within the search radius (facet -1: none). Thread-safe after build().
  Hit closest(int dim, const double xs[3], const std::vector<double>& x) const;
  // The projection of xs on facet f, extended by `band` (parametric) past its edges; facet
  // -1 when it falls outside that, or xs is beyond the search radius or more than h behind.
  Hit on_facet(int f, int dim, const double xs[3], const std::vector<double>& x, double band) const;
  // Facets whose centre lies within one bin spacing (3h) of the box [lo, hi] (after build()):
  // every facet that can overlap a slave facet with that box, or lie within 2h of it.
  void near(const double lo[3], const double hi[3], std::vector<int>& out) const;

 private:
  void cell_of(const double* p, long long* i) const;
  static long long key(const long long* i);
  std::vector<Facet> facets_;
  std::vector<GId> nodes_;
  double h_ = 0.0, cell_ = 1.0;
  std::unordered_map<long long, std::vector<int>> bins_;
};

}  // namespace stentor
