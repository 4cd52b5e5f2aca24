// The parametric stent of `Mesh->Stent` (docs/stent.md): the deck's parameters, the
// quantities derived from them, and the checks that refuse a stent that cannot be built.
// Plain data, Teuchos-free; src/geometry/StentGenerator.hpp meshes it.
//
// The pattern is drawn on the mid-surface cylinder of radius Rm = D/2 - t/2, unrolled to
// the plane (u = Rm theta, z). Ring k's centreline is
//     z = z_k + s_k a cos(2 pi u / lambda),   lambda = 2 pi Rm / crowns,
// with a = (ring length - strut width) / 2 the amplitude (the ring spans ring length
// axially: 2 a between the crowns' centrelines, plus half a width each side) and
// s_k = +1 for every ring (`peak-to-valley`: rings in phase) or (-1)^k (`peak-to-peak`:
// neighbouring rings mirror each other, crowns face crowns). The strut is the band of
// width w about the centreline (offset along its normal in the plane), radially from
// Rm - t/2 to Rm + t/2. The centreline's radius of curvature at a crown is
//     rho = lambda^2 / (4 pi^2 a),
// the crown's inner radius rho - w/2. Neighbouring rings are `gap` apart (axially,
// between the struts' edges at the linked crowns); a link is a straight axial bar of
// width `link width` and length `gap` from a crown of ring k to the facing edge of ring k+1.
#pragma once
#include <string>

namespace stentor {

struct StentConfig {
  int rings = 1;                      // "rings"
  int crowns = 8;                     // "crowns": crowns (periods of the centreline) per ring
  double outer_diameter = 0.0;        // "outer diameter" D
  double thickness = 0.0;             // "thickness" t (radial)
  double strut_width = 0.0;           // "strut width" w (in the tube surface)
  double ring_length = 0.0;           // "ring length" (axial extent of a ring)
  double gap = 0.0;                   // "gap" between neighbouring rings (= the links' length)
  std::string links = "peak-to-peak"; // "links": "peak-to-peak" | "peak-to-valley"
  int links_per_ring = 0;             // "links per ring" (between each pair of neighbouring rings)
  double link_width = 0.0;            // "link width" (0: the strut width)
  int elements_width = 3;             // "elements through width"
  int elements_thickness = 3;         // "elements through thickness"
  double element_length = 0.0;       // "element length" along the struts (0: width / elements through width)
  std::string sector = "full";        // "sector": "full" | "quarter" (0 <= theta <= pi/2) | "period" (sector_angle)
  bool half_length = false;           // "half length": the proximal half, z <= total length / 2

  // Derived.
  double outer_radius() const { return 0.5 * outer_diameter; }
  double mid_radius() const { return outer_radius() - 0.5 * thickness; }
  double inner_radius() const { return outer_radius() - thickness; }
  double pitch() const;               // lambda = 2 pi Rm / crowns: crown to crown along u
  double amplitude() const { return 0.5 * (ring_length - strut_width); }
  double crown_radius() const;        // rho, the centreline's radius at a crown
  double link_w() const { return link_width > 0.0 ? link_width : strut_width; }
  double element_h() const { return element_length > 0.0 ? element_length : strut_width / elements_width; }
  int sign(int ring) const { return links == "peak-to-peak" && ring % 2 ? -1 : 1; }
  // Axial position of ring k's centreline mean (ring 0's lowest point is at z = 0).
  double ring_z(int ring) const;
  double total_length() const { return ring_z(rings - 1) + 0.5 * ring_length; }
  // Crown positions (in crown pitches along u, from theta = 0) of the links between
  // ring `gap_index` and ring gap_index + 1: where ring gap_index points towards +z,
  // every crowns / links per ring crowns, every other gap shifted by half that spacing.
  double link_position(int gap_index, int j) const;
  // Length of one ring's centreline (all crowns), by quadrature.
  double centreline_length() const;
  // The kept sector 0 <= theta <= sector_angle(): in half crown pitches (pi / crowns each),
  // 2 crowns for `full`, crowns / 2 for `quarter`, and for `period` the smallest h that
  // divides `crowns` and about whose planes theta = 0 and theta = h pi / crowns the links
  // are mirror images of themselves (1, one strut from crown to crown, without links);
  // 0 when no such sector exists.
  int sector_half_pitches() const;
  double sector_angle() const;
  // How many copies of the kept part make the whole stent (sectors x halves).
  double symmetry_copies() const;
  // The rings the model holds (ring_0 .. ring_<n-1>): half of them with `half length`.
  int model_rings() const { return half_length ? rings / 2 : rings; }
};

// "" when the stent can be built, else the message (naming the parameter, as
// 'Mesh->Stent-><name>', what was given and what is needed).
std::string stent_config_error(const StentConfig& s);

}  // namespace stentor
