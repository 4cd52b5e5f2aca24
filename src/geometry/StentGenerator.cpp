#include "geometry/StentGenerator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <vector>

#include "deck/Config.hpp"
#include "mesh/MeshCheck.hpp"
#include "geometry/TubeGrid.hpp"
#include "stentor/format.hpp"

namespace stentor {
namespace {

// One ring's centreline z = zc + sgn a cos(k u) in the unrolled plane.
struct Curve {
  double zc, a, k, half_w;
  int sgn;
  double z(double u) const { return zc + sgn * a * std::cos(k * u); }
  double dz(double u) const { return -sgn * a * k * std::sin(k * u); }
  // Point at offset d along the unit normal (-z', 1) / |.|.
  void at(double u, double d, double& pu, double& pz) const {
    const double s = dz(u), n = std::sqrt(1.0 + s * s);
    pu = u - d * s / n;
    pz = z(u) + d / n;
  }
  double arc(double u0, double u1) const {  // Simpson
    const int n = 64;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
      const double u = u0 + (u1 - u0) * i / n, f = std::sqrt(1.0 + dz(u) * dz(u));
      sum += f * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
    }
    return sum * (u1 - u0) / (3.0 * n);
  }
  // u in [u0, u1] at arc length `target` from u0 (from_end: back from u1), by bisection.
  double u_at_arc(double u0, double u1, double target, bool from_end = false) const {
    double lo = u0, hi = u1;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      const bool short_of = (from_end ? arc(mid, u1) : arc(u0, mid)) < target;
      (short_of != from_end ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }
  // Offset (from the crown at uc) of the centreline parameter where the edge on `side`
  // (+1: +z side, -1: -z side) reaches u = uc + half_link.
  double link_offset(double uc, int side, double half_link, double half_pitch) const {
    double lo = uc, hi = uc + half_pitch;
    for (int it = 0; it < 80; ++it) {
      const double mid = 0.5 * (lo + hi);
      double pu, pz;
      at(mid, side * half_w, pu, pz);
      (pu < uc + half_link ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi) - uc;
  }
};

// The nodes along one ring's centreline (periodic), and where its crowns are.
struct RingPlan {
  Curve c;
  std::vector<double> u;          // one per node along the ring
  std::vector<int> crown_node;    // node index of each half pitch h (u = h lambda / 2)
};

struct Plan {
  const StentConfig& s;
  std::vector<RingPlan> rings;
  int half_link = 0;  // cells across half a link
  int link_len = 0;   // cells along a link (even)
};

// Crown half-pitch indices (mod 2 crowns) of ring k's links on its side `side`.
std::vector<int> link_halves(const StentConfig& s, int ring, int side) {
  std::vector<int> out;
  const int gap = side > 0 ? ring : ring - 1;
  if (s.links_per_ring == 0 || gap < 0 || gap + 1 >= s.rings) return out;
  for (int j = 0; j < s.links_per_ring; ++j)
    out.push_back(static_cast<int>(std::llround(2.0 * s.link_position(gap, j))) % (2 * s.crowns));
  return out;
}

RingPlan plan_ring(const Plan& p, int k) {
  const StentConfig& s = p.s;
  const double lambda = s.pitch(), hp = 0.5 * lambda, h = s.element_h(), hl = 0.5 * s.link_w();
  RingPlan r;
  r.c = Curve{s.ring_z(k), s.amplitude(), 2.0 * kPi / lambda, 0.5 * s.strut_width, s.sign(k)};
  const int n_half = 2 * s.crowns;
  std::vector<double> off(n_half, 0.0);  // centreline offset of a link's side from crown h
  for (int side : {1, -1})
    for (int hh : link_halves(s, k, side)) off[hh] = r.c.link_offset(hh * hp, side, hl, hp);
  for (int hh = 0; hh < n_half; ++hh) {
    const double ua = hh * hp, ub = ua + hp;
    const double da = off[hh], db = off[(hh + 1) % n_half];
    if (da + db >= hp)
      throw InputError("'Mesh->Stent->link width' = " + format_number(s.link_w()) +
                       ": two links' edges meet on one strut between neighbouring crowns (a narrower link)");
    // Pieces [ua, ua + da], [.., ub - db], [ub - db, ub], with the link pieces' counts fixed.
    std::vector<std::pair<double, int>> pieces;  // (end, cells)
    if (da > 0) pieces.push_back({ua + da, p.half_link});
    pieces.push_back({ub - db, 0});
    if (db > 0) pieces.push_back({ub, p.half_link});
    r.crown_node.push_back(static_cast<int>(r.u.size()));
    double start = ua;
    for (auto [end, cells] : pieces) {
      const double len = r.c.arc(start, end);
      const int n = cells > 0 ? cells : std::max(1, static_cast<int>(std::ceil(len / h - 1e-9)));
      // The second half measured from the end: a piece symmetric about its middle (a strut
      // from crown to crown) gets mirror-symmetric nodes, up to round-off (Simpson's error in
      // the partial arcs is ~1e-10 of a strut, and a sector's symmetry planes would see it).
      for (int i = 0; i < n; ++i)
        r.u.push_back(i == 0 ? start : 2 * i <= n ? r.c.u_at_arc(start, end, len * i / n) : r.c.u_at_arc(start, end, len * (n - i) / n, true));
      start = end;
    }
  }
  return r;
}

// The stent's nodes and cells before the reduction.
struct Raw {
  std::vector<double> x;           // 3 per node
  std::vector<int> layer;          // radial layer per node
  std::vector<std::array<GId, 8>> cells;
  std::vector<int> part;           // ring index per cell, -1: link
  GId anchor = 0;
};

class Builder {
 public:
  explicit Builder(const Plan& p) : p_(p), s_(p.s), nw_(s_.elements_width), nt_(s_.elements_thickness) {}
  Raw build() {
    for (std::size_t k = 0; k < p_.rings.size(); ++k) add_ring(static_cast<int>(k));
    for (int g = 0; g + 1 < s_.rings; ++g)
      for (int j = 0; j < s_.links_per_ring; ++j) add_link(g, j);
    raw_.anchor = ring_node(0, p_.rings[0].crown_node[0], 0, 0);
    return std::move(raw_);
  }

 private:
  const Plan& p_;
  const StentConfig& s_;
  int nw_, nt_;
  Raw raw_;
  std::vector<GId> ring_first_;

  GId add_node(double u, double z, int l) {
    const double r = s_.inner_radius() + s_.thickness * l / nt_, th = u / s_.mid_radius();
    double x = r * std::cos(th), y = r * std::sin(th);
    const double q = th / (0.5 * kPi), qr = std::round(q);  // exactly on the planes x = 0, y = 0
    if (std::abs(q - qr) < 1e-12) {
      const int quad = static_cast<int>(((static_cast<long long>(qr) % 4) + 4) % 4);
      x = quad == 0 ? r : quad == 2 ? -r : 0.0;
      y = quad == 1 ? r : quad == 3 ? -r : 0.0;
    }
    raw_.x.insert(raw_.x.end(), {x, y, z});
    raw_.layer.push_back(l);
    return static_cast<GId>(raw_.layer.size() - 1);
  }
  GId ring_node(int k, int i, int q, int l) const {
    const int n = static_cast<int>(p_.rings[k].u.size());
    i = ((i % n) + n) % n;
    return ring_first_[k] + (static_cast<GId>(i) * (nw_ + 1) + q) * (nt_ + 1) + l;
  }
  void add_hex(const std::array<GId, 8>& h, int part) {
    raw_.cells.push_back(h);
    raw_.part.push_back(part);
  }
  void add_ring(int k) {
    const RingPlan& r = p_.rings[k];
    ring_first_.push_back(static_cast<GId>(raw_.layer.size()));
    for (double u : r.u)
      for (int q = 0; q <= nw_; ++q) {
        double pu, pz;
        r.c.at(u, (-1.0 + 2.0 * q / nw_) * r.c.half_w, pu, pz);
        for (int l = 0; l <= nt_; ++l) add_node(pu, pz, l);
      }
    const int n = static_cast<int>(r.u.size());
    for (int i = 0; i < n; ++i)
      for (int q = 0; q < nw_; ++q)
        for (int l = 0; l < nt_; ++l)
          add_hex({ring_node(k, i, q, l), ring_node(k, i + 1, q, l), ring_node(k, i + 1, q + 1, l),
                   ring_node(k, i, q + 1, l), ring_node(k, i, q, l + 1), ring_node(k, i + 1, q, l + 1),
                   ring_node(k, i + 1, q + 1, l + 1), ring_node(k, i, q + 1, l + 1)},
                  k);
  }
  // Link j of gap g: from ring g's +z edge to ring g+1's -z edge at the crown uc.
  void add_link(int g, int j) {
    const int hh = static_cast<int>(std::llround(2.0 * s_.link_position(g, j))) % (2 * s_.crowns);
    const double uc = hh * 0.5 * s_.pitch(), period = s_.crowns * s_.pitch();
    const int ib = p_.rings[g].crown_node[hh], it = p_.rings[g + 1].crown_node[hh];
    const int m = 2 * p_.half_link, nl = p_.link_len;
    std::vector<GId> id(static_cast<std::size_t>((m + 1) * (nl + 1) * (nt_ + 1)));
    auto at = [&](int a, int b, int l) -> GId& { return id[(static_cast<std::size_t>(a) * (nl + 1) + b) * (nt_ + 1) + l]; };
    auto unrolled = [&](GId node, double& u, double& z) {
      const double* X = &raw_.x[3 * node];
      u = std::atan2(X[1], X[0]) * s_.mid_radius();
      u = uc + std::remainder(u - uc, period);
      z = X[2];
    };
    for (int a = 0; a <= m; ++a)
      for (int l = 0; l <= nt_; ++l) {
        at(a, 0, l) = ring_node(g, ib - m / 2 + a, nw_, l);
        at(a, nl, l) = ring_node(g + 1, it - m / 2 + a, 0, l);
        double u0, z0, u1, z1;
        unrolled(at(a, 0, l), u0, z0);
        unrolled(at(a, nl, l), u1, z1);
        for (int b = 1; b < nl; ++b) {
          const double f = static_cast<double>(b) / nl;
          at(a, b, l) = add_node(u0 + f * (u1 - u0), z0 + f * (z1 - z0), l);
        }
      }
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < nl; ++b)
        for (int l = 0; l < nt_; ++l)
          add_hex({at(a, b, l), at(a + 1, b, l), at(a + 1, b + 1, l), at(a, b + 1, l), at(a, b, l + 1),
                   at(a + 1, b, l + 1), at(a + 1, b + 1, l + 1), at(a, b + 1, l + 1)},
                  -1);
  }
};

Plan make_plan(const StentConfig& s) {
  Plan p{s, {}, 0, 0};
  const double h = s.element_h();
  p.half_link = std::max(1, static_cast<int>(std::ceil(0.5 * s.link_w() / h - 1e-9)));
  p.link_len = 2 * std::max(1, static_cast<int>(std::ceil(0.5 * s.gap / h - 1e-9)));
  return p;
}

// Cells before the reduction, in floating point (no overflow for absurd sizes).
double full_cell_count(const StentConfig& s, const Plan& p) {
  const double h = s.element_h();
  // At most 3 pieces per half pitch, each rounded up: < 6 extra cells per crown.
  const double along = s.rings * (s.centreline_length() / h + 6.0 * s.crowns);
  const double links = s.rings > 1 ? (s.rings - 1.0) * s.links_per_ring * 2.0 * p.half_link * p.link_len : 0.0;
  return (along * s.elements_width + links) * s.elements_thickness;
}

double reduction_fraction(const StentConfig& s) {
  return 1.0 / s.symmetry_copies();
}

// The kept cells' nodes, renumbered 0.. in the original order.
struct Kept {
  std::vector<GId> new_id;  // -1: dropped
  std::vector<std::size_t> cells;
};

// A cell centroid strictly inside the sector 0 < theta < Theta (Theta <= pi).
bool in_sector(const StentConfig& s, const double* m) {
  const double th = s.sector_angle();
  return m[1] > 0.0 && std::sin(th) * m[0] - std::cos(th) * m[1] > 0.0;
}

Kept reduce(const StentConfig& s, const Raw& raw) {
  Kept k;
  const double zmid = 0.5 * s.total_length();
  k.new_id.assign(raw.layer.size(), -1);
  for (std::size_t c = 0; c < raw.cells.size(); ++c) {
    double m[3] = {0, 0, 0};
    for (GId n : raw.cells[c])
      for (int d = 0; d < 3; ++d) m[d] += raw.x[3 * n + d] / 8.0;
    if (s.sector != "full" && !in_sector(s, m)) continue;
    if (s.half_length && !(m[2] < zmid)) continue;
    k.cells.push_back(c);
    for (GId n : raw.cells[c]) k.new_id[n] = 0;
  }
  GId next = 0;
  for (auto& v : k.new_id)
    if (v == 0) v = next++;
  return k;
}

void classify_faces(const StentConfig& s, const Raw& raw, const Kept& kept, Mesh& m) {
  std::map<std::array<GId, 4>, std::pair<std::size_t, int>> seen;  // sorted nodes -> (cell, face)
  std::map<std::array<GId, 4>, int> count;
  for (std::size_t c : kept.cells)
    for (int f = 0; f < 6; ++f) {
      std::array<GId, 4> key;
      for (int v = 0; v < 4; ++v) key[v] = kept.new_id[raw.cells[c][kHexFace[f][v]]];
      std::sort(key.begin(), key.end());
      seen.emplace(key, std::make_pair(c, f));
      ++count[key];
    }
  const double tol = 1e-9 * s.outer_radius(), zmid = 0.5 * s.total_length();
  std::vector<std::string> order = {"inner",      "outer",      "end_proximal",    "end_distal",
                                    "symmetry_x", "symmetry_y", "symmetry_sector", "symmetry_z"};
  const double th = s.sector_angle(), ct = std::cos(th), st = std::sin(th);
  for (int k = 0; k < s.rings; ++k) order.push_back("ring_" + std::to_string(k));
  order.push_back("links");
  order.push_back("sides");
  order.push_back("inner_and_sides");
  std::map<std::string, std::vector<GId>> groups;
  for (const auto& [key, cf] : seen) {
    if (count[key] != 1) continue;
    const auto [c, f] = cf;
    std::vector<GId> q;
    bool on[4] = {true, true, true, true};  // x = 0, y = 0, z = middle, theta = Theta
    for (int v = 0; v < 4; ++v) {
      const GId n = raw.cells[c][kHexFace[f][v]];
      q.push_back(kept.new_id[n]);
      on[0] = on[0] && std::abs(raw.x[3 * n]) <= tol;
      on[1] = on[1] && std::abs(raw.x[3 * n + 1]) <= tol;
      on[2] = on[2] && std::abs(raw.x[3 * n + 2] - zmid) <= tol;
      on[3] = on[3] && std::abs(st * raw.x[3 * n] - ct * raw.x[3 * n + 1]) <= tol && ct * raw.x[3 * n] + st * raw.x[3 * n + 1] > 0.0;
    }
    const int part = raw.part[c];
    auto add = [&](const std::string& g) { groups[g].insert(groups[g].end(), q.begin(), q.end()); };
    if (f == 0) add("inner");
    if (f == 1) {
      add("outer");
      add(part >= 0 ? "ring_" + std::to_string(part) : "links");
    }
    if (f >= 2 && s.sector == "quarter" && on[0]) add("symmetry_x");
    if (f >= 2 && s.sector != "full" && on[1]) add("symmetry_y");
    if (f >= 2 && s.sector == "period" && on[3]) add("symmetry_sector");
    if (f >= 2 && s.half_length && on[2]) add("symmetry_z");
    if ((f == 2 || f == 3) && !(on[0] || on[1] || on[2] || on[3])) {
      add("sides");
      add("inner_and_sides");
    }
    if (f == 0) add("inner_and_sides");
    if (f == 2 && part == 0) add("end_proximal");
    if (f == 3 && part == s.rings - 1 && !s.half_length) add("end_distal");
  }
  int tag = 2;
  GId next_id = 0;
  for (const std::string& name : order) {
    auto it = groups.find(name);
    if (it == groups.end()) continue;
    CellBlock b;
    b.name = name;
    b.physical_tag = tag++;
    b.type = CellType::Quad4;
    b.nodes_per_cell = 4;
    b.conn = std::move(it->second);
    for (std::size_t i = 0; i < b.num_cells(); ++i) b.cell_id.push_back(next_id++);
    m.boundaries.push_back(std::move(b));
  }
  CellBlock a;
  a.name = "anchor";
  a.physical_tag = tag;
  a.type = CellType::Point1;
  a.nodes_per_cell = 1;
  a.conn = {kept.new_id[raw.anchor]};
  a.cell_id = {next_id};
  m.boundaries.push_back(std::move(a));
}

}  // namespace

Mesh generate_stent(const StentConfig& s, double max_cells, const std::string& source) {
  const std::string why = stent_config_error(s);
  if (!why.empty()) throw InputError(source + ": " + why);
  Plan p = make_plan(s);
  const double estimate = full_cell_count(s, p) * reduction_fraction(s);
  if (estimate > max_cells)
    throw InputError(source + ": the stent would have about " + format_number(estimate) +
                     " cells, more than 'Mesh->max cells' = " + format_number(max_cells) +
                     "; use a larger 'Mesh->Stent->element length' or fewer elements through the "
                     "width or thickness, or raise 'Mesh->max cells' to mesh this fine on purpose");
  for (int k = 0; k < s.rings; ++k) p.rings.push_back(plan_ring(p, k));
  const Raw raw = Builder(p).build();
  const Kept kept = reduce(s, raw);

  Mesh m;
  m.dim = 3;
  m.source = source;
  m.x.assign(3 * static_cast<std::size_t>(std::count_if(kept.new_id.begin(), kept.new_id.end(), [](GId v) { return v >= 0; })), 0.0);
  for (std::size_t n = 0; n < kept.new_id.size(); ++n)
    if (kept.new_id[n] >= 0)
      for (int d = 0; d < 3; ++d) m.x[3 * kept.new_id[n] + d] = raw.x[3 * n + d];
  CellBlock vol;
  vol.name = "stent";
  vol.physical_tag = 1;
  vol.type = CellType::Hex8;
  vol.nodes_per_cell = 8;
  for (std::size_t c : kept.cells) {
    for (GId n : raw.cells[c]) vol.conn.push_back(kept.new_id[n]);
    vol.cell_id.push_back(static_cast<GId>(vol.cell_id.size()));
  }
  m.volumes.push_back(std::move(vol));
  classify_faces(s, raw, kept, m);
  const std::size_t bad = count_inverted_cells(m);
  if (bad)
    throw InputError(source + ": " + std::to_string(bad) +
                     " cells of the stent came out inverted: the links ('link "
                     "width' = " +
                     format_number(s.link_w()) + ", 'Mesh->Stent->links' = " + s.links +
                     ") do not fit the crowns they join; use a narrower 'Mesh->Stent->link width'");
  return m;
}

}  // namespace stentor
