#include "deck/ArteryConfig.hpp"

#include <sstream>

#include "stentor/format.hpp"

namespace stentor {

const char* const kArteryLayer[3] = {"intima", "media", "adventitia"};

namespace {

std::string par(const std::string& name) { return "'Mesh->Artery->" + name + "'"; }

}  // namespace

double ArteryConfig::layer_outer_radius(int l) const {
  double r = inner_radius();
  for (int k = 0; k <= l; ++k) r += thickness[k];
  return r;
}

std::string artery_config_error(const ArteryConfig& a) {
  if (!(a.inner_diameter > 0.0)) return par("inner diameter") + " must be > 0, got " + format_number(a.inner_diameter);
  if (!(a.length > 0.0)) return par("length") + " must be > 0, got " + format_number(a.length);
  for (int l = 0; l < 3; ++l) {
    if (!(a.thickness[l] > 0.0))
      return par(std::string(kArteryLayer[l]) + " thickness") +
             " must be > 0 (every layer closes around the lumen), got " + format_number(a.thickness[l]);
    if (a.elements_layer[l] < 1)
      return par(std::string("elements through ") + kArteryLayer[l]) + " must be >= 1, got " +
             std::to_string(a.elements_layer[l]);
  }
  if (a.elements_along < 1 || (a.half_length && a.elements_along % 2))
    return par("elements along") + " = " + std::to_string(a.elements_along) + " must be >= 1" +
           (a.half_length ? " and even ('half length' = true: the middle plane is a node plane)" : "");
  const int div = a.sector == "quarter" ? 4 : a.sector == "half" ? 2 : 1;
  if (a.elements_around < 4 || a.elements_around % div)
    return par("elements around") + " = " + std::to_string(a.elements_around) + " must be >= 4" +
           (div > 1 ? " and divisible by " + std::to_string(div) + " ('sector' = " + a.sector + ": the cut planes are node planes)"
                    : "");
  return "";
}

}  // namespace stentor
