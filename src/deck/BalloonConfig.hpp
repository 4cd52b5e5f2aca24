// The deformable balloon of `Mesh->Balloon` (docs/stent.md, "The deformable balloon"): a
// thin tube inside the generated stent, on the stent's axis and centred on it, meshed with
// the stent's reductions. Plain data, Teuchos-free; src/geometry/BalloonGenerator.hpp
// meshes it.
#pragma once
#include <string>

#include "deck/StentConfig.hpp"

namespace stentor {

struct BalloonConfig {
  bool enabled = false;               // the deck has `Mesh->Balloon`
  double outer_diameter = 0.0;        // "outer diameter" as mounted (below the stent's inner diameter)
  double thickness = 0.0;             // "thickness" (radial)
  double length = 0.0;                // "length": the whole balloon's, centred on the stent
  int elements_thickness = 2;         // "elements through thickness"
  double element_length = 0.0;        // "element length" around and along (0: the stent's strut width)

  double outer_radius() const { return 0.5 * outer_diameter; }
  double inner_radius() const { return outer_radius() - thickness; }
  double element_h(const StentConfig& s) const { return element_length > 0.0 ? element_length : s.strut_width; }
  // Cells around the stent's kept sector (at the outer radius), and along the modelled length.
  int cells_around(const StentConfig& s) const;
  int cells_along(const StentConfig& s) const;
  // Axial range of the modelled balloon: z0 = the stent's middle - length / 2, z1 = the
  // middle (half length) or the middle + length / 2.
  double z_begin(const StentConfig& s) const;
  double z_end(const StentConfig& s) const;
  double cells(const StentConfig& s) const {
    return static_cast<double>(cells_around(s)) * cells_along(s) * elements_thickness;
  }
};

// "" when the balloon fits the stent, else the message naming the parameter
// ('Mesh->Balloon-><name>'), what was given and what is needed.
std::string balloon_config_error(const BalloonConfig& b, const StentConfig& s);

}  // namespace stentor
