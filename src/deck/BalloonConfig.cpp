#include "deck/BalloonConfig.hpp"

#include <algorithm>
#include <cmath>

#include "stentor/format.hpp"

namespace stentor {
namespace {

std::string par(const char* name) { return std::string("'Mesh->Balloon->") + name + "'"; }

}  // namespace

int BalloonConfig::cells_around(const StentConfig& s) const {
  const double arc = s.sector_angle() * outer_radius();
  return std::max(s.sector == "full" ? 8 : 2, static_cast<int>(std::ceil(arc / element_h(s) - 1e-9)));
}

int BalloonConfig::cells_along(const StentConfig& s) const {
  const double modelled = s.half_length ? 0.5 * length : length;
  return std::max(2, static_cast<int>(std::ceil(modelled / element_h(s) - 1e-9)));
}

double BalloonConfig::z_begin(const StentConfig& s) const { return 0.5 * s.total_length() - 0.5 * length; }

double BalloonConfig::z_end(const StentConfig& s) const {
  return 0.5 * s.total_length() + (s.half_length ? 0.0 : 0.5 * length);
}

std::string balloon_config_error(const BalloonConfig& b, const StentConfig& s) {
  if (!(b.thickness < b.outer_radius()))
    return par("thickness") + " = " + format_number(b.thickness) + " must be below the balloon's outer radius " +
           format_number(b.outer_radius()) + " ('outer diameter' / 2)";
  if (!(b.outer_radius() < s.inner_radius()))
    return par("outer diameter") + " = " + format_number(b.outer_diameter) +
           " must be below the stent's inner diameter " + format_number(2.0 * s.inner_radius()) +
           " ('Mesh->Stent->outer diameter' - 2 'thickness'): the balloon is mounted inside the stent";
  if (!(b.length > s.total_length()))
    return par("length") + " = " + format_number(b.length) + " must exceed the stent's length " +
           format_number(s.total_length()) + ": the balloon carries the whole stent, its ends beyond the stent's";
  if (b.element_h(s) > b.thickness * 50.0)
    return par("element length") + " = " + format_number(b.element_h(s)) +
           " must be at most 50 times the balloon's 'thickness' = " + format_number(b.thickness) +
           ": flatter cells do not carry the wall's bending";
  return "";
}

}  // namespace stentor
