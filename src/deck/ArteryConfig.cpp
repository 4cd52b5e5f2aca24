#include "deck/ArteryConfig.hpp"

#include <cmath>
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

double ArteryConfig::plaque_thickness(double theta, double z) const {
  if (!has_plaque()) return 0.0;
  const double dz = z - plaque_z();
  if (std::abs(dz) > 0.5 * plaque_length) return 0.0;
  const double s = 0.5 * (1.0 + std::cos(2.0 * kPi * dz / plaque_length));
  const double e = plaque_shape == "eccentric" ? 0.5 * (1.0 + std::cos(theta)) : 1.0;
  return plaque_peak() * s * e;
}

namespace {

std::string plaque_error(const ArteryConfig& a) {
  if (!(a.plaque_stenosis >= 0.0 && a.plaque_stenosis < 1.0))
    return par("plaque stenosis") + " must be in [0, 1) (the fraction of the lumen's diameter the plaque takes), got " +
           format_number(a.plaque_stenosis);
  if (!a.has_plaque()) return "";
  const double wall = a.outer_radius() - a.inner_radius();
  if (a.plaque_peak() > wall)
    return par("plaque stenosis") + " = " + format_number(a.plaque_stenosis) + " makes the plaque " + format_number(a.plaque_peak()) +
           " thick, more than the wall (" + format_number(wall) + ")";
  if (!(a.plaque_length > 0.0)) return par("plaque length") + " must be > 0 with a plaque, got " + format_number(a.plaque_length);
  const double zc = a.plaque_z();
  if (zc - 0.5 * a.plaque_length < 0.0 || zc + 0.5 * a.plaque_length > a.length)
    return "the plaque (" + par("plaque centre") + " = " + format_number(zc) + ", " + par("plaque length") + " = " +
           format_number(a.plaque_length) + ") must lie within 0 <= z <= " + par("length") + " = " + format_number(a.length);
  if (a.half_length && std::abs(zc - 0.5 * a.length) > 1e-12 * a.length)
    return par("plaque centre") + " must be the middle of the tube (" + format_number(0.5 * a.length) +
           ") with 'half length' = true (the middle plane is a symmetry plane)";
  if (a.plaque_shape == "eccentric" && a.sector == "quarter")
    return par("plaque shape") + " = eccentric is not symmetric about x = 0: use 'sector' = half or full";
  if (a.elements_plaque < 1) return par("elements through plaque") + " must be >= 1, got " + std::to_string(a.elements_plaque);
  return "";
}

}  // namespace

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
  if (a.curved()) {
    if (!(a.centreline_radius > a.outer_radius()))
      return par("centreline radius") + " = " + format_number(a.centreline_radius) + " must exceed the tube's outer radius " +
             format_number(a.outer_radius()) + " (the inner side of the bend would cross its centre)";
    if (a.length > kPi * a.centreline_radius)
      return par("length") + " = " + format_number(a.length) + " bends the tube by more than 180 deg about a " +
             par("centreline radius") + " of " + format_number(a.centreline_radius) + "; shorten it or widen the bend";
    if (a.sector == "quarter")
      return par("sector") + " = quarter cuts the tube on x = 0, which is no symmetry plane of a tube bent in the x-z plane ('" +
             "centreline radius' > 0): use half (y >= 0) or full";
  }
  const int div = a.sector == "quarter" ? 4 : a.sector == "half" ? 2 : 1;
  if (a.elements_around < 4 || a.elements_around % div)
    return par("elements around") + " = " + std::to_string(a.elements_around) + " must be >= 4" +
           (div > 1 ? " and divisible by " + std::to_string(div) + " ('sector' = " + a.sector + ": the cut planes are node planes)"
                    : "");
  return plaque_error(a);
}

namespace {

// The lumen's facets are chords: between nodes 2 pi / N apart (N = `elements around`) at
// r = Ri - h they come as close to the axis as (Ri - h) cos(pi / N). The narrowest, at the
// plaque's peak h_max, must lie outside the stent's outer radius.
std::string lumen_clearance_error(const ArteryConfig& a, const StentConfig& s) {
  const double lumen = (a.inner_radius() - a.plaque_peak()) * std::cos(kPi / a.elements_around);
  if (lumen > s.outer_radius()) return "";
  return par("inner diameter") + " = " + format_number(a.inner_diameter) +
         (a.has_plaque() ? " less the plaque's 2 h_max = " + format_number(2.0 * a.plaque_peak()) : std::string()) +
         " puts the lumen's facets at the radius " + format_number(lumen) + " (the middle of a chord between lumen nodes " +
         "360 / 'elements around' = " + format_number(360.0 / a.elements_around) + " deg apart), not outside the stent's " +
         "outer radius " + format_number(s.outer_radius()) + " ('Mesh->Stent->outer diameter' / 2): the stent must lie "
         "inside the lumen";
}

}  // namespace

int cells_around_stent(const ArteryConfig& a, const StentConfig& s) {
  return static_cast<int>(static_cast<long long>(a.elements_around) * s.sector_half_pitches() / (2LL * s.crowns));
}

double z_begin_around_stent(const ArteryConfig& a, const StentConfig& s) { return 0.5 * (s.total_length() - a.length); }

ArteryConfig with_stent_reductions(const ArteryConfig& a, const StentConfig& s) {
  ArteryConfig b = a;
  b.sector = "full";  // the cells around come from cells_around_stent()
  b.half_length = s.half_length;
  return b;
}

std::string artery_around_stent_error(const ArteryConfig& a, const StentConfig& s) {
  if (s.half_length && a.elements_along % 2)
    return par("elements along") + " = " + std::to_string(a.elements_along) +
           " must be even ('Mesh->Stent->half length' = true: the stent's middle plane is a node plane of the artery)";
  const std::string why = artery_config_error(with_stent_reductions(a, s));
  if (!why.empty()) return why;
  if (s.sector_half_pitches() == 0) return stent_config_error(s);  // no sector repeats the stent
  const int copies = 2 * s.crowns / s.sector_half_pitches();  // the kept sector's copies around
  if (a.elements_around % copies)
    return par("elements around") + " = " + std::to_string(a.elements_around) + " must be divisible by " +
           std::to_string(copies) + " ('Mesh->Stent->sector' = " + s.sector + " keeps 1/" + std::to_string(copies) +
           " of the circumference: its cut planes are node planes of the artery)";
  if (!(a.length > s.total_length()))
    return par("length") + " = " + format_number(a.length) + " must exceed the stent's length " +
           format_number(s.total_length()) + ": the artery holds the whole stent, centred on it";
  const std::string clear = lumen_clearance_error(a, s);
  if (!clear.empty()) return clear;
  if (a.plaque_shape == "eccentric" && a.has_plaque() && s.sector != "full")
    return par("plaque shape") + " = eccentric is symmetric about y = 0 only: use 'Mesh->Stent->sector' = full";
  return "";
}

}  // namespace stentor
