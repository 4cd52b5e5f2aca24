// The parametric artery of `Mesh->Artery` (docs/artery.md): a straight circular tube of
// three concentric layers (intima, media, adventitia) along z, its axis the z axis,
// z from 0 to `length`. Plain data, Teuchos-free; src/geometry/ArteryGenerator.hpp meshes it.
#pragma once
#include <string>

namespace stentor {

struct ArteryConfig {
  double inner_diameter = 0.0;        // "inner diameter": the lumen's diameter
  double length = 0.0;                // "length" (axial)
  double thickness[3] = {0, 0, 0};    // "intima thickness", "media thickness", "adventitia thickness"
  int elements_layer[3] = {1, 2, 1};  // "elements through intima", "... media", "... adventitia"
  int elements_around = 32;           // "elements around": cells around the whole circumference
  int elements_along = 8;             // "elements along": cells along the whole length
  std::string sector = "full";        // "sector": "full" | "half" (y >= 0) | "quarter" (x, y >= 0)
  bool half_length = false;           // "half length": 0 <= z <= length / 2

  double inner_radius() const { return 0.5 * inner_diameter; }
  // Radius of the outer surface of layer l (0 intima, 1 media, 2 adventitia).
  double layer_outer_radius(int l) const;
  double outer_radius() const { return layer_outer_radius(2); }
  // Fraction of the circumference that is meshed (1, 1/2, 1/4).
  double sector_fraction() const { return sector == "quarter" ? 0.25 : sector == "half" ? 0.5 : 1.0; }
  int cells_around() const { return static_cast<int>(elements_around * sector_fraction() + 0.5); }
  int cells_through() const { return elements_layer[0] + elements_layer[1] + elements_layer[2]; }
  int cells_along() const { return half_length ? elements_along / 2 : elements_along; }
  double modelled_length() const { return half_length ? 0.5 * length : length; }
  double cells() const { return static_cast<double>(cells_around()) * cells_through() * cells_along(); }
};

extern const char* const kArteryLayer[3];  // "intima", "media", "adventitia"

// "" when the artery can be built, else the message (naming the parameter, as
// 'Mesh->Artery-><name>', what was given and what is needed).
std::string artery_config_error(const ArteryConfig& a);

}  // namespace stentor
