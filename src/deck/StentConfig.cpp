#include "deck/StentConfig.hpp"

#include <cmath>
#include <set>
#include <sstream>

#include "stentor/format.hpp"

namespace stentor {
namespace {

std::string par(const char* name) { return std::string("'Mesh->Stent->") + name + "'"; }

// Link crowns of one gap, as angles in crown pitches modulo crowns.
std::set<long long> link_set(const StentConfig& s, int gap) {
  std::set<long long> out;  // in half pitches, to stay exact
  for (int j = 0; j < s.links_per_ring; ++j) {
    const long long h = std::llround(2.0 * s.link_position(gap, j));
    out.insert(((h % (2LL * s.crowns)) + 2LL * s.crowns) % (2LL * s.crowns));
  }
  return out;
}

// The links of every gap are mirror images of themselves about theta = 0 and the plane
// `half` half pitches further.
bool links_mirror_symmetric(const StentConfig& s, long long half) {
  if (s.rings < 2 || s.links_per_ring == 0) return true;
  const long long n2 = 2LL * s.crowns;  // half pitches around the ring
  for (int g = 0; g + 1 < s.rings; ++g) {
    const std::set<long long> set = link_set(s, g);
    for (long long h : set) {
      if (!set.count((n2 - h) % n2)) return false;                        // theta -> -theta
      if (!set.count(((2 * half - h) % n2 + n2) % n2)) return false;      // theta -> 2 Theta - theta
    }
  }
  return true;
}

std::string geometry_error(const StentConfig& s) {
  if (!(s.thickness < s.outer_radius()))
    return par("thickness") + " = " + format_number(s.thickness) + " must be below the outer radius " +
           format_number(s.outer_radius()) + " ('outer diameter' / 2)";
  if (!(s.ring_length > s.strut_width))
    return par("ring length") + " = " + format_number(s.ring_length) +
           " must exceed 'strut width' = " + format_number(s.strut_width) +
           " (the crowns' amplitude is (ring length - strut width) / 2)";
  const double lambda = s.pitch();
  if (!(s.strut_width < 0.5 * lambda))
    return par("strut width") + " = " + format_number(s.strut_width) +
           " must be below half the crown pitch, pi (D - t) / crowns / 2 = " + format_number(0.5 * lambda) +
           ": neighbouring struts would overlap (fewer crowns or a narrower strut)";
  if (!(s.crown_radius() > 0.5 * s.strut_width))
    return par("ring length") + " = " + format_number(s.ring_length) +
           ": the crowns' centreline radius lambda^2 / (4 pi^2 a) = " + format_number(s.crown_radius()) +
           " (crown pitch lambda = " + format_number(lambda) + ", amplitude a = " + format_number(s.amplitude()) +
           ") must exceed half the strut width, " + format_number(0.5 * s.strut_width) +
           ": the crown would fold onto itself (a shorter ring, fewer crowns or a narrower strut)";
  return "";
}

std::string link_error(const StentConfig& s) {
  if (s.rings > 1 && !(s.gap > 0.0))
    return par("gap") +
           " must be > 0 with more than one ring (the axial distance between neighbouring rings, the "
           "links' length), got " +
           format_number(s.gap);
  if (s.links_per_ring == 0 || s.rings == 1) return "";
  if (s.links_per_ring > s.crowns || s.crowns % s.links_per_ring)
    return par("links per ring") + " = " + std::to_string(s.links_per_ring) + " must divide 'crowns' = " +
           std::to_string(s.crowns) + " (links are evenly spaced on the crowns)";
  const int m = s.crowns / s.links_per_ring;
  if (s.links == "peak-to-valley" && s.rings > 2 && m % 2)
    return par("links per ring") + " = " + std::to_string(s.links_per_ring) + ": with 'peak-to-valley' links and more "
           "than two rings, crowns / links per ring must be even (every other gap's links are shifted by half their "
           "spacing, so that no crown carries a link on both sides), got " + std::to_string(m);
  const double lambda = s.pitch(), wl = s.link_w();
  // A link lands on the facing edge of the next ring between u_c -+ wl/2: inside a crown's
  // concave side (peak-to-valley) it must clear the crown's two legs.
  const double room = s.links == "peak-to-valley" ? 0.5 * lambda - s.strut_width : 0.5 * lambda;
  if (!(wl < room))
    return par("link width") + " = " + format_number(wl) + " must be below " + format_number(room) +
           (s.links == "peak-to-valley" ? " (half the crown pitch less the strut width: the link lands inside a crown)"
                                        : " (half the crown pitch)");
  return "";
}

std::string reduction_error(const StentConfig& s) {
  if (s.sector == "quarter") {
    if (s.crowns % 4)
      return par("sector") + " = quarter needs 'crowns' divisible by 4 (the planes x = 0 and y = 0 through crowns), got " +
             std::to_string(s.crowns);
    if (s.rings > 1 && s.links_per_ring > 0 && !links_mirror_symmetric(s, s.crowns / 2))
      return par("sector") + " = quarter: the links (" + std::to_string(s.links_per_ring) + " per ring, '" + s.links +
             "') are not symmetric about the planes x = 0 and y = 0; use 'sector' = full or another 'links per ring'";
  }
  if (s.sector == "period" && s.sector_half_pitches() == 0)
    return par("sector") + " = period: the links (" + std::to_string(s.links_per_ring) + " per ring, '" + s.links +
           "') are not mirror images of themselves about the plane theta = 0 through a crown, so no sector between two "
           "symmetry planes repeats the stent; use 'sector' = full";
  if (s.half_length && (s.rings % 2 || s.links != "peak-to-peak"))
    return par("half length") + " = true needs an even number of 'rings' and 'links' = peak-to-peak (the stent is "
           "then its own mirror image about its middle plane), got " + std::to_string(s.rings) + " rings, '" + s.links + "'";
  return "";
}

}  // namespace

double StentConfig::pitch() const { return 2.0 * kPi * mid_radius() / crowns; }

double StentConfig::crown_radius() const {
  const double a = amplitude();
  return a > 0.0 ? pitch() * pitch() / (4.0 * kPi * kPi * a) : HUGE_VAL;
}

double StentConfig::ring_z(int ring) const {
  const double spacing = links == "peak-to-peak" ? gap + ring_length : gap + strut_width;
  return 0.5 * ring_length + ring * spacing;
}

double StentConfig::link_position(int gap_index, int j) const {
  const int m = crowns / links_per_ring;
  double o = 0.0;
  if (links == "peak-to-valley") {
    o = gap_index % 2 ? 0.5 * m : 0.0;
  } else if (sign(gap_index) < 0) {
    o = m % 2 ? 0.5 * m : 0.5;  // a half-integer: the crowns of ring gap_index that point to +z
  }
  return o + static_cast<double>(j) * m;
}

int StentConfig::sector_half_pitches() const {
  if (sector == "full") return 2 * crowns;
  if (sector == "quarter") return crowns / 2;
  for (int h = 1; h <= crowns; ++h)
    if (crowns % h == 0 && links_mirror_symmetric(*this, h)) return h;
  return 0;
}

double StentConfig::sector_angle() const { return sector_half_pitches() * kPi / crowns; }

double StentConfig::symmetry_copies() const {
  const int h = sector_half_pitches();
  return (h > 0 ? 2.0 * crowns / h : 1.0) * (half_length ? 2.0 : 1.0);
}

double StentConfig::centreline_length() const {
  const double lambda = pitch(), k = 2.0 * kPi / lambda, a = amplitude();
  const int n = 2000;  // Simpson over one period
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double u = lambda * i / n;
    const double f = std::sqrt(1.0 + std::pow(a * k * std::sin(k * u), 2));
    sum += f * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
  }
  return crowns * sum * lambda / (3.0 * n);
}

std::string stent_config_error(const StentConfig& s) {
  for (const std::string& e : {geometry_error(s), link_error(s), reduction_error(s)})
    if (!e.empty()) return e;
  return "";
}

}  // namespace stentor
