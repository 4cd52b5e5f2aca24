// The artery's metrics of a stent deployed in a generated artery (Output->Stent Metrics
// with Mesh->generator = stent and Mesh->Artery; docs/artery.md "Artery metrics"), beside
// the stent's (RingMetrics):
//
// * the lumen's diameter along the stented segment: the lumen's nodes grouped by their
//   reference axial coordinate into stations (the artery's node planes z = const), each
//   station's diameter 2 r_mean (r the current distance of its nodes from the axis, z, a
//   node on a symmetry plane of the sector weighing 1/2), over the stations within the
//   stent's reference axial span: their mean (`lumen_D_mean`) and their smallest, the
//   minimum lumen diameter (`lumen_D_min`, MLD); the acute gains against the first
//   evaluation (before the procedure); the lumen's area in contact (`lumen_contact_area`: the
//   reference tributary areas of the lumen's slave nodes in contact, times the model's
//   symmetry copies: the whole stent's; 0 where the lumen is no pair's slave);
// * per layer of the wall (the volume groups plaque, intima, media, adventitia that the
//   mesh has), the largest principal Cauchy stress of its cells (cell averages): the
//   largest value and the 99th percentile over the layer's cells (nearest rank), the
//   percentile being less sensitive to one cell at a strut's edge;
// * the stent against the wall: each `outer` node's signed distance to the lumen surface
//   (its closest point on the lumen's facets, along the facet's normal into the lumen:
//   > 0 off the wall, 0 in contact), the largest (`stent_wall_gap_max`), and the share of the
//   stent's outer surface farther than `malapposition threshold` from the wall
//   (`malapposed_area`, %: the nodes' reference tributary areas, mesh/MeshQuery.hpp; the
//   model's surface, so on a symmetry sector the whole stent's share);
// * per strut (a ring's outer surface between two successive crown apices, theta = m pi /
//   crowns, the generator's node lines: one strut per half crown pitch; the links are not
//   struts): the strut's distance to the wall, the mean of its outer nodes' distances
//   weighted by their tributary areas on the strut; the share of the model's struts farther
//   than `malapposition threshold` (`malapposed_struts`, %: OCT's malapposed strut count,
//   the same on the whole stent since every strut of the model stands for the same number
//   of copies) and the farthest strut's distance (`strut_gap_max`);
// * tissue prolapse: at each lumen station, the stent's contour radius R_s (the mean
//   current distance from the axis of the `outer` nodes whose current axial position lies
//   within the station's band, half-way to the neighbouring stations) less the radius of each
//   lumen node of the station, where positive: the lumen inside the stent's contour (tissue
//   between the struts, or a segment the stent did not open); `prolapse_max` is the largest
//   over the stations that a strut crosses.
//
// Every rank computes the same values (the lumen group is whole on every rank; the cell
// values are gathered), so they do not depend on the number of ranks.
#pragma once
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "contact/MasterSurface.hpp"
#include "run/Model.hpp"

namespace stentor {

class ArteryMetrics {
 public:
  explicit ArteryMetrics(const Model& model);
  // A stent deck with Mesh->Artery.
  static bool applies(const Config& cfg) { return cfg.mesh.generator == "stent" && cfg.mesh.artery.around_stent; }
  static std::vector<std::string> whole_groups() { return {"lumen"}; }

  std::vector<std::string> columns() const;  // with units: "lumen_D_mean [mm]"
  std::vector<std::string> diameter_columns() const;  // the diameter plot's: the lumen's
  std::vector<std::string> stress_columns() const;    // the stress plot's: the layers'
  // One value per column at u (collective). The first call is the reference of the gains.
  std::vector<double> evaluate(const la::Vector& u);
  // The paragraph of the stage's end (rank 0 writes; every rank may call).
  void table(std::ostream& log) const;
  // The outer nodes' signed distances to the lumen at u (collective; the same on every
  // rank), in the order of outer_nodes().
  std::vector<double> wall_gaps(const la::Vector& u) const;
  const std::vector<GId>& outer_nodes() const { return outer_; }
  void save(std::map<std::string, double>& out, const std::string& prefix) const;
  bool restore(const std::map<std::string, double>& in, const std::string& prefix);

  // The q-quantile (0 < q <= 1) of v by nearest rank: the smallest value with at least
  // ceil(q n) values at or below it (v is sorted in place; 0 for an empty v).
  static double nearest_rank(std::vector<double>& v, double q);

 private:
  struct Station {
    std::vector<std::size_t> idx;  // indices into lumen_
    std::vector<double> w;         // symmetry weights
  };
  struct Strut {
    int ring = 0, index = 0;       // ring, and the half crown pitch around it
    std::vector<std::size_t> idx;  // indices into outer_
    std::vector<double> area;      // their tributary areas on the strut
  };
  // The struts' distances to the wall from the outer nodes' gaps.
  std::vector<double> strut_distances(const std::vector<double>& gaps) const;
  void layer_stresses(const la::Vector& u, std::vector<double>& out) const;  // collective: max, p99 per layer
  // Signed distances of the outer nodes (at x_outer) to the lumen.
  std::vector<double> wall_gaps(const std::vector<double>& x_outer, const la::Vector& u) const;
  double prolapse(const std::vector<double>& x_lumen, const std::vector<double>& x_outer) const;

  const Model& m_;
  std::vector<GId> lumen_;              // the lumen's nodes, sorted
  std::vector<Station> stations_;       // within the stent's reference span, by increasing z
  std::unique_ptr<MasterSurface> wall_; // the lumen's facets (normals into the lumen)
  std::vector<GId> outer_;              // the stent's outer nodes, sorted
  std::vector<double> outer_area_;      // their tributary areas (reference)
  std::vector<double> outer_w_;         // their symmetry weights (1/2 on a sector's plane)
  std::vector<Strut> struts_;           // the model's struts, by ring and angle
  int farthest_ = -1;                   // the last evaluation's farthest strut (index into struts_)
  double threshold_ = 0.0;              // malapposition threshold [length]
  std::vector<std::string> layers_;     // the wall's volume groups in the mesh
  std::vector<int> layer_of_block_;     // Mesh::volumes index -> index into layers_ or -1
  std::string length_unit_, stress_unit_;
  double D_mean0_ = -1.0, D_min0_ = -1.0;  // the first evaluation's
  std::vector<double> now_;                // the last evaluation's values
};

}  // namespace stentor
