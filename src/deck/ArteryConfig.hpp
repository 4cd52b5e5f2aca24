// The parametric artery of `Mesh->Artery` (docs/artery.md): a circular tube of three
// concentric layers (intima, media, adventitia) along z, its axis the z axis, z from 0 to
// `length`; with `centreline radius` the same tube bent in the x-z plane. Plain data, Teuchos-free; src/geometry/ArteryGenerator.hpp meshes it.
//
// In a stent deck (`Mesh->generator` = stent, `around_stent`) the same tube is put around
// the generated stent: centred on it (its z from the stent's middle - length / 2), with the
// stent's sector and half length instead of its own `sector` and `half length`.
#pragma once
#include <string>

#include "deck/StentConfig.hpp"

namespace stentor {

struct ArteryConfig {
  bool around_stent = false;          // `Mesh->Artery` in a stent deck (the artery around the stent)
  double inner_diameter = 0.0;        // "inner diameter": the lumen's diameter
  double length = 0.0;                // "length" (axial)
  double thickness[3] = {0, 0, 0};    // "intima thickness", "media thickness", "adventitia thickness"
  int elements_layer[3] = {1, 2, 1};  // "elements through intima", "... media", "... adventitia"
  int elements_around = 32;           // "elements around": cells around the whole circumference
  int elements_along = 8;             // "elements along": cells along the whole length
  std::string sector = "full";        // "sector": "full" | "half" (y >= 0) | "quarter" (x, y >= 0)
  bool half_length = false;           // "half length": 0 <= z <= length / 2
  // The plaque ("plaque stenosis" > 0): the lumen narrowed by the thickness
  //   h(theta, z) = h_max s(z) e(theta),
  //   s(z) = (1 + cos(2 pi (z - zc) / Lp)) / 2 for |z - zc| <= Lp / 2, else 0,
  //   e = 1 (concentric) or (1 + cos theta) / 2 (eccentric: the plaque on the +x side),
  //   h_max = S Ri (concentric) or 2 S Ri (eccentric),
  // so that the lumen's diameter through the plaque's peak, along x, is (1 - S) times the
  // healthy one (the clinicians' diameter stenosis S). The innermost layer then spans
  // Ri - h .. Ri + t_intima with `elements through plaque` more cells, and its cells whose
  // centroid lies inside the healthy lumen (r < Ri) form the volume group `plaque`.
  double plaque_stenosis = 0.0;             // "plaque stenosis": S (0: no plaque)
  double plaque_length = 0.0;               // "plaque length": Lp
  double plaque_centre = -1.0;              // "plaque centre": zc (< 0: the middle of `length`)
  std::string plaque_shape = "concentric";  // "plaque shape": "concentric" | "eccentric"
  int elements_plaque = 2;                  // "elements through plaque"
  // "centreline radius" R > 0: the tube bent in the x-z plane towards +x, its centreline the
  // arc of radius R about the bend's centre (R, 0, length / 2) through (0, 0, length / 2),
  // where it is tangent to z: the straight tube's point (x, y, z) goes to (R - (R - x) cos phi,
  // y, length / 2 + (R - x) sin phi), phi = (z - length / 2) / R. 0: straight.
  double centreline_radius = 0.0;

  double inner_radius() const { return 0.5 * inner_diameter; }
  // Radius of the outer surface of layer l (0 intima, 1 media, 2 adventitia).
  double layer_outer_radius(int l) const;
  double outer_radius() const { return layer_outer_radius(2); }
  // Fraction of the circumference that is meshed (1, 1/2, 1/4).
  double sector_fraction() const { return sector == "quarter" ? 0.25 : sector == "half" ? 0.5 : 1.0; }
  int cells_around() const { return static_cast<int>(elements_around * sector_fraction() + 0.5); }
  bool has_plaque() const { return plaque_stenosis > 0.0; }
  double plaque_z() const { return plaque_centre < 0.0 ? 0.5 * length : plaque_centre; }
  double plaque_peak() const { return (plaque_shape == "eccentric" ? 2.0 : 1.0) * plaque_stenosis * inner_radius(); }
  double plaque_thickness(double theta, double z) const;  // h(theta, z) above; 0 without a plaque
  int cells_inner_layer() const { return elements_layer[0] + (has_plaque() ? elements_plaque : 0); }
  int cells_through() const { return cells_inner_layer() + elements_layer[1] + elements_layer[2]; }
  int cells_along() const { return half_length ? elements_along / 2 : elements_along; }
  double modelled_length() const { return half_length ? 0.5 * length : length; }
  double cells() const { return static_cast<double>(cells_around()) * cells_through() * cells_along(); }
  bool curved() const { return centreline_radius > 0.0; }
};

// The artery around the stent s (around_stent): cells around the stent's kept sector
// (`elements around` over the whole circumference), the z of its proximal end (the stent's
// middle - length / 2), and the configuration with the stent's `half length` (what the
// generator meshes: cells_along(), modelled_length(), the plaque's checks).
int cells_around_stent(const ArteryConfig& a, const StentConfig& s);
double z_begin_around_stent(const ArteryConfig& a, const StentConfig& s);
ArteryConfig with_stent_reductions(const ArteryConfig& a, const StentConfig& s);

extern const char* const kArteryLayer[3];  // "intima", "media", "adventitia"

// "" when the artery can be built, else the message (naming the parameter, as
// 'Mesh->Artery-><name>', what was given and what is needed).
std::string artery_config_error(const ArteryConfig& a);

// The same for the artery around the stent s: artery_config_error() of
// with_stent_reductions(a, s), and the fit to the stent: `elements around` cutting on the
// stent's sector planes, `length` beyond the stent's, the lumen's facets (chords at
// (Ri - h_max) cos(pi / N), N = `elements around`) clear of the stent's outer radius, an
// eccentric plaque only around a full stent.
std::string artery_around_stent_error(const ArteryConfig& a, const StentConfig& s);

}  // namespace stentor
