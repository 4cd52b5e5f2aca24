// The device metrics of a generated stent (Output->Stent Metrics with Mesh->generator =
// stent; docs/stent.md "Stent metrics"), from the generator's groups and axis (z through
// the origin): outer diameters 2 r (r the current distance of an `outer` node from the
// axis) over the whole stent, per ring (`ring_<k>`; also at its crowns: the outer nodes of
// the crown sections, theta = multiples of pi / crowns) and over the links; the stent's
// length (axial extent of the `inner` and `outer` nodes) and each ring's, foreshortening
// (L0 - L) / L0; the peak of the expansion, the step with the largest mean outer diameter
// so far, and from it the radial recoil (D_peak - D) / D_peak and the longitudinal recoil
// (L_peak - L) / L_peak; dogboning (D_end - D_centre) / D_centre of the end and centre
// rings' mean diameters (three rings or more); the largest equivalent plastic strain
// (cell averages of the Gauss points) and where (ring, nearest crown, the cell's reference
// centroid); the metal-to-artery ratio, outer metal area / (pi D_mean L), current; the
// metal volume and mass.
//
// Symmetry reductions give the whole stent's values: a node on a symmetry plane (theta = 0
// and theta = Theta of a sector, z = total length / 2 of a half length) weighs 1/2 in the
// means, so the node means equal the whole stent's node means for a symmetric solution; the
// half length's stent length is twice the extent of its half; areas and volumes are
// multiplied by the copies that make the whole (StentConfig::symmetry_copies: 4 for a
// quarter, 2 crowns / h for a sector of h half pitches, 2 for a half length). Diameters need
// no correction: the axis is in the model. Every rank computes the same values (the group nodes' displacements summed over
// ranks, each from its owner; cell maxima and volumes reduced).
#pragma once
#include <map>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "run/Model.hpp"

namespace stentor {

class RingMetrics {
 public:
  explicit RingMetrics(const Model& model);
  // The peak of the expansion counts again from a new smallest D_mean: one below the
  // smallest so far by more than 1e-9 of it (a crimp; not round-off). Shared with the
  // diameter plot, which finds the same peak in the CSV.
  static bool new_smallest(double D, double D_min) { return D < D_min * (1.0 - 1e-9); }
  // The boundary groups every rank needs whole (Model distributes them so).
  static std::vector<std::string> whole_groups(const Config& cfg);

  // Column names with their units: "D_mean [mm]".
  std::vector<std::string> columns() const;
  std::vector<std::string> diameter_columns() const;  // the plot's: stent and ring means, crowns, links
  // One value per column at u (collective). The first call is the reference (as cut).
  std::vector<double> evaluate(const la::Vector& u, double t);
  // The per-ring table at the last evaluate() (rank 0 writes; every rank may call).
  void table(std::ostream& log) const;
  // The last evaluate() is the start of a stage: the table's "D at start" (the first
  // evaluate() starts the first stage).
  void begin_stage();
  // What the metrics carry from step to step (the as-cut lengths, the peak and the smallest
  // diameter so far, the stage's start) as named values for a checkpoint, and back: a run
  // restarted from it goes on measuring from the same reference, peak and stage start.
  void save(std::map<std::string, double>& out, const std::string& prefix) const;
  // false (nothing changed) when a value is missing.
  bool restore(const std::map<std::string, double>& in, const std::string& prefix);

 private:
  struct NodeSet {
    std::vector<std::size_t> idx;  // indices into nodes_
    std::vector<double> w;         // symmetry weight of each
  };
  struct Stats {
    double mean = 0.0, min = 0.0, max = 0.0;
  };
  Stats diameters(const NodeSet& s, const std::vector<double>& x) const;
  static double extent(const NodeSet& s, const std::vector<double>& x);
  void plastic(const la::Vector& u, std::vector<double>& out);  // collective
  double outer_area(const std::vector<double>& x) const;
  int cell_ring(const GId* conn, int npc) const;
  std::string unit(const char* kind) const;

  const Model& m_;
  int rings_ = 0;              // rings in the model
  int rings_full_ = 0;         // rings of the whole stent
  double sym_area_ = 1.0;      // whole stent / model, areas and volumes
  double sym_length_ = 1.0;    // whole stent / model, length
  std::vector<GId> nodes_;     // outer and inner nodes, sorted
  NodeSet outer_, all_, links_;
  std::vector<NodeSet> ring_, crown_, ring_span_;  // ring_span_: outer and inner nodes of each ring
  std::vector<std::vector<std::size_t>> outer_facets_;  // quad4, indices into nodes_
  std::map<std::pair<long long, long long>, int> place_ring_;  // (theta, z) of a ring's nodes -> ring
  std::vector<int> cell_ring_;       // ring of each local cell (-1: a link), Distribution::blocks() order
  std::string eps_name_;             // the history variable, "" without plasticity
  std::string length_unit_, mass_unit_;
  // Reference and peak state.
  bool started_ = false;
  double L0_ = 0.0, volume_ = 0.0, density_ = 0.0;
  std::vector<double> ring_L0_;
  // The peak: the largest D_mean since the smallest so far (D_min_).
  double D_peak_ = -1.0, L_peak_ = 0.0, t_peak_ = 0.0, D_min_ = 0.0;
  std::vector<double> ring_D_peak_, ring_D_now_, ring_L_now_, ring_eps_;
  double D_start_ = -1.0;  // at the current stage's start
  std::vector<double> ring_D_start_;
  static const std::pair<const char*, double RingMetrics::*> kSaved[8];  // save / restore
  double dogbone_peak_ = 0.0, centre_peak_ = 0.0;
  double D_now_ = 0.0, L_now_ = 0.0;
};

}  // namespace stentor
