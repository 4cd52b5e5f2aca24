#include "run/RingMetrics.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <utility>

#include "io/Units.hpp"
#include "mesh/MeshQuery.hpp"
#include "stentor/format.hpp"

namespace stentor {

namespace {

// The generator's metal: its volume group `stent` (a deck's `Mesh->Balloon` adds another).
bool metal(const CellBlock& b) { return b.name == "stent"; }

bool has_links(const StentConfig& s) { return s.rings > 1 && s.links_per_ring > 0; }

// A node's place on the tube, the same for every radial layer: (theta, z) on a grid far
// finer than any cell (the generator puts the layers' nodes at the same theta and z).
std::pair<long long, long long> key(const double* x, double ro) {
  return {std::llround(std::atan2(x[1], x[0]) * 1e8), std::llround(x[2] / ro * 1e8)};
}

}  // namespace

std::vector<std::string> RingMetrics::whole_groups(const Config& cfg) {
  const StentConfig& s = cfg.mesh.stent;
  std::vector<std::string> g = {"outer", "inner"};
  for (int k = 0; k < s.model_rings(); ++k) g.push_back("ring_" + std::to_string(k));
  if (has_links(s)) g.push_back("links");
  return g;
}

RingMetrics::RingMetrics(const Model& model) : m_(model) {
  const StentConfig& s = m_.cfg.mesh.stent;
  const Mesh& mesh = m_.mesh;
  rings_ = s.model_rings(), rings_full_ = s.rings;
  const bool sector = s.sector != "full";
  sym_area_ = s.symmetry_copies();
  sym_length_ = s.half_length ? 2.0 : 1.0;
  const UnitLabels u = unit_labels(m_.cfg.problem.units, 3);
  length_unit_ = u.length, mass_unit_ = u.mass;
  const std::vector<std::string> groups = whole_groups(m_.cfg);
  for (const std::string& g : groups) {
    const std::vector<GId> n = boundary_nodes(mesh, g);
    nodes_.insert(nodes_.end(), n.begin(), n.end());
  }
  std::sort(nodes_.begin(), nodes_.end());
  nodes_.erase(std::unique(nodes_.begin(), nodes_.end()), nodes_.end());
  auto index = [&](GId n) { return static_cast<std::size_t>(std::lower_bound(nodes_.begin(), nodes_.end(), n) - nodes_.begin()); };
  const double ro = s.outer_radius(), zsym = 0.5 * s.total_length(), tol = 1e-9 * ro;
  const double ct = std::cos(s.sector_angle()), st = std::sin(s.sector_angle());
  auto weight = [&](const double* x) {
    double w = 1.0;
    if (sector && (std::abs(x[1]) < tol || std::abs(st * x[0] - ct * x[1]) < tol)) w *= 0.5;  // theta = 0, Theta
    if (s.half_length && std::abs(x[2] - zsym) < tol) w *= 0.5;
    return w;
  };
  auto set_of = [&](const std::string& g) {
    NodeSet ns;
    for (GId n : boundary_nodes(mesh, g)) ns.idx.push_back(index(n)), ns.w.push_back(weight(mesh.coord(n)));
    return ns;
  };
  outer_ = set_of("outer");
  for (std::size_t i = 0; i < nodes_.size(); ++i) all_.idx.push_back(i), all_.w.push_back(weight(mesh.coord(nodes_[i])));
  for (int k = 0; k < rings_; ++k) {
    ring_.push_back(set_of("ring_" + std::to_string(k)));
    NodeSet c;
    for (std::size_t j = 0; j < ring_.back().idx.size(); ++j) {
      const std::size_t i = ring_.back().idx[j];
      const double* x = mesh.coord(nodes_[i]);
      place_ring_[key(x, ro)] = k;
      const double h = std::atan2(x[1], x[0]) * s.crowns / kPi;
      if (std::abs(h - std::round(h)) < 1e-7) c.idx.push_back(i), c.w.push_back(ring_.back().w[j]);
    }
    crown_.push_back(c);
  }
  // A ring's length: its outer nodes and the inner nodes at their (theta, z).
  ring_span_.resize(static_cast<std::size_t>(rings_));
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const auto it = place_ring_.find(key(mesh.coord(nodes_[i]), ro));
    if (it != place_ring_.end()) ring_span_[static_cast<std::size_t>(it->second)].idx.push_back(i);
  }
  if (has_links(s)) links_ = set_of("links");
  for (const CellBlock* b : boundary_blocks(mesh, "outer"))
    for (std::size_t f = 0; f < b->num_cells(); ++f) {
      std::vector<std::size_t> q;
      for (int a = 0; a < b->nodes_per_cell; ++a) q.push_back(index(b->conn[f * static_cast<std::size_t>(b->nodes_per_cell) + static_cast<std::size_t>(a)]));
      outer_facets_.push_back(q);
    }
  if (m_.assembler && m_.assembler->has_history()) eps_name_ = "equivalent_plastic_strain";
  for (std::size_t b = 0; b < mesh.volumes.size(); ++b)
    if (metal(mesh.volumes[b]) && m_.block_mat.size() > b && m_.block_mat[b] >= 0)
      density_ = std::max(density_, m_.cfg.materials[static_cast<std::size_t>(m_.block_mat[b])].density);
}

std::string RingMetrics::unit(const char* kind) const {
  const std::string k = kind;
  const std::string u = k == "length" ? length_unit_ : k == "mass" ? mass_unit_ : "-";
  return u.empty() ? "" : " [" + u + "]";
}

std::vector<std::string> RingMetrics::columns() const {
  const std::string L = unit("length"), one = unit("");
  std::vector<std::string> c = {"D_mean" + L, "D_min" + L, "D_max" + L};
  for (int k = 0; k < rings_; ++k) {
    const std::string r = "ring" + std::to_string(k) + "_";
    for (const char* q : {"D_mean", "D_min", "D_max", "D_crown_mean", "D_crown_min", "D_crown_max", "length"})
      c.push_back(r + q + L);
  }
  if (!links_.idx.empty())
    for (const char* q : {"links_D_mean", "links_D_min", "links_D_max"}) c.push_back(q + L);
  c.insert(c.end(), {"length" + L, "foreshortening" + one, "radial_recoil" + one, "longitudinal_recoil" + one});
  if (rings_full_ >= 3) c.push_back("dogboning" + one);
  c.push_back("metal_to_artery_ratio" + one);
  if (!eps_name_.empty())
    c.insert(c.end(), {"eps_p_max" + one, "eps_p_max_ring" + one, "eps_p_max_crown" + one, "eps_p_max_x" + L,
                       "eps_p_max_y" + L, "eps_p_max_z" + L});
  return c;
}

std::vector<std::string> RingMetrics::diameter_columns() const {
  const std::string L = unit("length");
  std::vector<std::string> c = {"D_mean" + L};
  for (int k = 0; k < rings_; ++k) {
    c.push_back("ring" + std::to_string(k) + "_D_mean" + L);
    c.push_back("ring" + std::to_string(k) + "_D_crown_mean" + L);
  }
  if (!links_.idx.empty()) c.push_back("links_D_mean" + L);
  return c;
}

RingMetrics::Stats RingMetrics::diameters(const NodeSet& s, const std::vector<double>& x) const {
  Stats st{0.0, 1e300, -1e300};
  double wsum = 0.0;
  for (std::size_t j = 0; j < s.idx.size(); ++j) {
    const double* p = &x[3 * s.idx[j]];
    const double d = 2.0 * std::hypot(p[0], p[1]);
    st.mean += s.w[j] * d, wsum += s.w[j];
    st.min = std::min(st.min, d), st.max = std::max(st.max, d);
  }
  if (wsum > 0.0) st.mean /= wsum;
  else st = Stats{};
  return st;
}

double RingMetrics::extent(const NodeSet& s, const std::vector<double>& x) {
  double lo = 1e300, hi = -1e300;
  for (std::size_t i : s.idx) lo = std::min(lo, x[3 * i + 2]), hi = std::max(hi, x[3 * i + 2]);
  return s.idx.empty() ? 0.0 : hi - lo;
}

// Quad4 area 0.5 |d1 x d2| (the diagonals): exact for a flat quad.
double RingMetrics::outer_area(const std::vector<double>& x) const {
  double area = 0.0;
  for (const auto& q : outer_facets_) {
    if (q.size() != 4) continue;
    double d1[3], d2[3];
    for (std::size_t k = 0; k < 3; ++k) d1[k] = x[3 * q[2] + k] - x[3 * q[0] + k], d2[k] = x[3 * q[3] + k] - x[3 * q[1] + k];
    const double c[3] = {d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2], d1[0] * d2[1] - d1[1] * d2[0]};
    area += 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  }
  return area * sym_area_;
}

// The ring of a cell: k when every node lies on ring k's (theta, z) places, else -1 (a link).
int RingMetrics::cell_ring(const GId* conn, int npc) const {
  const double ro = m_.cfg.mesh.stent.outer_radius();
  int ring = -3;
  for (int a = 0; a < npc; ++a) {
    const auto it = place_ring_.find(key(m_.mesh.coord(conn[a]), ro));
    const int r = it == place_ring_.end() ? -1 : it->second;
    if (ring == -3) ring = r;
    if (r != ring || r < 0) return -1;
  }
  return ring;
}

void RingMetrics::plastic(const la::Vector& u, std::vector<double>& out) {
  const Assembler::CellFields cf = m_.assembler->cell_fields(u);
  const Mesh& mesh = m_.mesh;
  const auto e = std::find(cf.extra_names.begin(), cf.extra_names.end(), eps_name_);
  const std::size_t nx = cf.extra_names.size(), ie = static_cast<std::size_t>(e - cf.extra_names.begin());
  if (cell_ring_.empty()) {
    for (const LocalBlock& lb : m_.dist->blocks()) {
      const CellBlock& mb = mesh.volumes[static_cast<std::size_t>(lb.volume_block)];
      for (std::size_t i = 0; i < lb.cell_ids.size(); ++i)
        cell_ring_.push_back(cell_ring(&mb.conn[static_cast<std::size_t>(lb.cell_index[i]) * static_cast<std::size_t>(mb.nodes_per_cell)], mb.nodes_per_cell));
    }
  }
  // Per ring (and the links, last) the largest value; the overall largest with its place.
  std::vector<double> loc(static_cast<std::size_t>(rings_) + 1, 0.0), glob(loc.size(), 0.0);
  double best = -1.0, best_id = 0.0, where[4] = {0, 0, 0, 0};
  std::size_t c = 0;
  for (const LocalBlock& lb : m_.dist->blocks()) {
    const CellBlock& mb = mesh.volumes[static_cast<std::size_t>(lb.volume_block)];
    const auto npc = static_cast<std::size_t>(mb.nodes_per_cell);
    for (std::size_t i = 0; i < lb.cell_ids.size(); ++i, ++c) {
      if (!metal(mb)) continue;
      const double v = e == cf.extra_names.end() ? 0.0 : cf.extra[nx * c + ie];
      const int r = cell_ring_[c];
      double& slot = loc[r >= 0 ? static_cast<std::size_t>(r) : loc.size() - 1];
      slot = std::max(slot, v);
      const double id = static_cast<double>(lb.cell_ids[i]);
      if (v < best || (v == best && id > best_id)) continue;  // ties: the lowest global cell id
      best = v, best_id = id, where[0] = r;
      for (int k = 0; k < 3; ++k) where[k + 1] = 0.0;
      const std::size_t first = static_cast<std::size_t>(lb.cell_index[i]) * npc;
      for (std::size_t a = 0; a < npc; ++a)
        for (int k = 0; k < 3; ++k) where[k + 1] += mesh.coord(mb.conn[first + a])[k] / double(npc);
    }
  }
  Teuchos::reduceAll(*m_.comm, Teuchos::REDUCE_MAX, static_cast<int>(loc.size()), loc.data(), glob.data());
  ring_eps_ = glob;
  double gbest = 0.0;
  Teuchos::reduceAll(*m_.comm, Teuchos::REDUCE_MAX, 1, &best, &gbest);
  // The place of the largest: its cell of lowest global id, whatever the partition.
  double mine = best == gbest ? best_id : 1e300, first = 0.0;
  Teuchos::reduceAll(*m_.comm, Teuchos::REDUCE_MIN, 1, &mine, &first);
  double w[4] = {0, 0, 0, 0};
  if (mine != first)
    for (double& v : where) v = 0.0;
  Teuchos::reduceAll(*m_.comm, Teuchos::REDUCE_SUM, 4, where, w);
  const double theta = std::atan2(w[2], w[1]);
  const int crowns2 = 2 * m_.cfg.mesh.stent.crowns;
  const long h = std::lround(theta * m_.cfg.mesh.stent.crowns / kPi);
  out.insert(out.end(), {std::max(gbest, 0.0), w[0], double(((h % crowns2) + crowns2) % crowns2), w[1], w[2], w[3]});
}

std::vector<double> RingMetrics::evaluate(const la::Vector& u, double t) {
  const std::vector<double> x = current_positions(m_, nodes_, u);

  const Stats all = diameters(outer_, x);
  std::vector<double> v = {all.mean, all.min, all.max};
  ring_D_now_.assign(static_cast<std::size_t>(rings_), 0.0);
  ring_L_now_.assign(static_cast<std::size_t>(rings_), 0.0);
  for (int k = 0; k < rings_; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const Stats r = diameters(ring_[kk], x), c = diameters(crown_[kk], x);
    ring_D_now_[kk] = r.mean, ring_L_now_[kk] = extent(ring_span_[kk], x);
    v.insert(v.end(), {r.mean, r.min, r.max, c.mean, c.min, c.max, ring_L_now_[kk]});
  }
  if (!links_.idx.empty()) {
    const Stats l = diameters(links_, x);
    v.insert(v.end(), {l.mean, l.min, l.max});
  }
  const double L = sym_length_ * extent(all_, x);
  double dogbone = 0.0, dc = 0.0;
  if (rings_full_ >= 3) {
    // End rings: 0 and the last; centre: the middle one or two (a half length holds ring 0
    // and the centre ring next to its mirror plane).
    const int n = rings_full_;
    std::vector<int> ends = {0, n - 1}, centre = n % 2 ? std::vector<int>{n / 2} : std::vector<int>{n / 2 - 1, n / 2};
    auto mean = [&](const std::vector<int>& rs) {
      double s = 0.0;
      int c = 0;
      for (int r : rs)
        if (r < rings_) s += ring_D_now_[static_cast<std::size_t>(r)], ++c;
      return c ? s / c : 0.0;
    };
    const double de = mean(ends);
    dc = mean(centre);
    dogbone = dc > 0.0 ? (de - dc) / dc : 0.0;
  }
  if (!started_) {
    L0_ = L;
    ring_L0_ = ring_L_now_;
    started_ = true;
  }
  // The peak of the expansion: the largest D_mean since the smallest one so far (as cut,
  // or crimped), so that a crimp is no recoil and the recoil counts from the expansion. A
  // new smallest diameter is one below the last by more than round-off (new_smallest), so
  // that a stent that springs back to its as-cut diameter shows its whole recoil.
  const bool smallest = D_peak_ < 0.0 || new_smallest(all.mean, D_min_);
  if (smallest) D_min_ = all.mean;
  if (smallest || all.mean > D_peak_) {
    D_peak_ = all.mean, L_peak_ = L, t_peak_ = t;
    ring_D_peak_ = ring_D_now_;
    dogbone_peak_ = dogbone, centre_peak_ = dc;
  }
  D_now_ = all.mean, L_now_ = L;
  if (D_start_ < 0.0) begin_stage();
  v.insert(v.end(), {L, L0_ > 0.0 ? (L0_ - L) / L0_ : 0.0, (D_peak_ - all.mean) / D_peak_, L_peak_ > 0.0 ? (L_peak_ - L) / L_peak_ : 0.0});
  if (rings_full_ >= 3) v.push_back(dogbone);
  const double cyl = kPi * all.mean * L;
  v.push_back(cyl > 0.0 ? outer_area(x) / cyl : 0.0);
  if (!eps_name_.empty()) plastic(u, v);
  if (volume_ == 0.0) {
    const Assembler::CellFields cf = m_.assembler->cell_fields(u);
    double vl = 0.0;
    std::size_t c = 0;
    for (const LocalBlock& lb : m_.dist->blocks()) {
      const bool in_metal = metal(m_.mesh.volumes[static_cast<std::size_t>(lb.volume_block)]);
      for (std::size_t i = 0; i < lb.cell_ids.size(); ++i, ++c)
        if (in_metal) vl += cf.volume[c];
    }
    Teuchos::reduceAll(*m_.comm, Teuchos::REDUCE_SUM, 1, &vl, &volume_);
    volume_ *= sym_area_;
  }
  return v;
}

void RingMetrics::begin_stage() {
  D_start_ = D_now_;
  ring_D_start_ = ring_D_now_;
}

namespace {
// Per-ring values as prefix + name + "_" + k.
void save_rings(std::map<std::string, double>& out, const std::string& key, const std::vector<double>& v) {
  for (std::size_t k = 0; k < v.size(); ++k) out[key + "_" + std::to_string(k)] = v[k];
}
bool restore_rings(const std::map<std::string, double>& in, const std::string& key, std::vector<double>& v) {
  for (std::size_t k = 0; k < v.size(); ++k) {
    const auto it = in.find(key + "_" + std::to_string(k));
    if (it == in.end()) return false;
    v[k] = it->second;
  }
  return true;
}
}  // namespace

// The scalars a checkpoint carries, by name.
const std::pair<const char*, double RingMetrics::*> RingMetrics::kSaved[] = {
    {"L0", &RingMetrics::L0_},         {"D_peak", &RingMetrics::D_peak_},
    {"L_peak", &RingMetrics::L_peak_}, {"t_peak", &RingMetrics::t_peak_},
    {"D_min", &RingMetrics::D_min_},   {"dogbone_peak", &RingMetrics::dogbone_peak_},
    {"centre_peak", &RingMetrics::centre_peak_}, {"D_start", &RingMetrics::D_start_}};

void RingMetrics::save(std::map<std::string, double>& out, const std::string& prefix) const {
  if (!started_) return;
  for (const auto& [name, member] : kSaved) out[prefix + name] = this->*member;
  save_rings(out, prefix + "ring_L0", ring_L0_);
  save_rings(out, prefix + "ring_D_peak", ring_D_peak_);
  save_rings(out, prefix + "ring_D_start", ring_D_start_);
}

bool RingMetrics::restore(const std::map<std::string, double>& in, const std::string& prefix) {
  for (const auto& [name, member] : kSaved)
    if (!in.count(prefix + name)) return false;
  const auto n = static_cast<std::size_t>(rings_);
  std::vector<double> L0(n), peak(n), start(n);
  if (!restore_rings(in, prefix + "ring_L0", L0) || !restore_rings(in, prefix + "ring_D_peak", peak) ||
      !restore_rings(in, prefix + "ring_D_start", start))
    return false;
  for (const auto& [name, member] : kSaved) this->*member = in.at(prefix + name);
  ring_L0_ = L0, ring_D_peak_ = peak, ring_D_start_ = start;
  started_ = true;
  return true;
}

void RingMetrics::table(std::ostream& log) const {
  if (!started_) return;
  const std::string L = length_unit_.empty() ? "" : " [" + length_unit_ + "]";
  log << std::fixed << "  stent (whole, from the model" << (sym_area_ > 1.0 ? " x its symmetry" : "") << "): metal volume "
      << std::scientific << std::setprecision(4) << volume_ << (length_unit_.empty() ? "" : " " + length_unit_ + "^3");
  if (density_ > 0.0)
    log << ", mass " << density_ * volume_ << (mass_unit_.empty() ? "" : " " + mass_unit_);
  else
    log << ", mass not known (no density in the stent's material)";
  log << "; peak of the expansion at t = " << std::defaultfloat << t_peak_ << "\n";
  log << "  ring | " << std::setw(15) << "D at start" + L << " | " << std::setw(15) << "D at peak" + L << " | "
      << std::setw(15) << "D now" + L << " | change % | radial recoil % | foreshortening % | dogboning % | max eps_p\n";
  auto row = [&](const std::string& name, double ds, double dp, double dn, double l0, double l, double dog, double eps) {
    log << "  " << std::left << std::setw(4) << name << std::right << " | " << std::fixed << std::setprecision(4)
        << std::setw(15) << ds << " | " << std::setw(15) << dp << " | " << std::setw(15) << dn << " | "
        << std::setprecision(3) << std::setw(8) << 100.0 * (dn - ds) / ds << " | " << std::setw(15)
        << 100.0 * (dp - dn) / dp << " | " << std::setw(16) << (l0 > 0.0 ? 100.0 * (l0 - l) / l0 : 0.0) << " | ";
    if (std::isnan(dog))
      log << std::setw(11) << "-" << " | ";
    else
      log << std::setw(11) << 100.0 * dog << " | ";
    if (eps_name_.empty())
      log << "-\n";
    else
      log << std::setprecision(4) << eps << "\n";
  };
  for (int k = 0; k < rings_; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const double dog = rings_full_ >= 3 && centre_peak_ > 0.0 ? (ring_D_peak_[kk] - centre_peak_) / centre_peak_ : std::nan("");
    row(std::to_string(k), ring_D_start_[kk], ring_D_peak_[kk], ring_D_now_[kk], ring_L0_[kk], ring_L_now_[kk], dog,
        ring_eps_.empty() ? 0.0 : ring_eps_[kk]);
  }
  if (!links_.idx.empty() && ring_eps_.size() > static_cast<std::size_t>(rings_))
    log << "  links: max eps_p " << std::setprecision(4) << ring_eps_.back() << "\n";
  row("all", D_start_, D_peak_, D_now_, L0_, L_now_, rings_full_ >= 3 ? dogbone_peak_ : std::nan(""),
      ring_eps_.empty() ? 0.0 : *std::max_element(ring_eps_.begin(), ring_eps_.end()));
  log << "  (change: D now against D at the stage's start; the peak: the largest D since the smallest so far (as cut or\n"
         "  crimped); dogboning (D_ring - D_centre) / D_centre at the peak, D_centre the centre ring"
      << (rings_full_ % 2 ? "" : "s'") << " mean; the stent's row: end rings against centre)\n";
  log << std::defaultfloat;
}

}  // namespace stentor
