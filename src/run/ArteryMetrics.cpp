#include "run/ArteryMetrics.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>

#include "io/Units.hpp"
#include "mesh/MeshQuery.hpp"

namespace stentor {

namespace {
const char* const kLayers[] = {"plaque", "intima", "media", "adventitia"};
constexpr std::size_t kLayerColumn = 8;  // the first layer's column (after the lumen's and the apposition's)
constexpr double kPi = 3.14159265358979323846;
}  // namespace

ArteryMetrics::ArteryMetrics(const Model& model) : m_(model) {
  const Mesh& mesh = m_.mesh;
  const StentConfig& s = m_.cfg.mesh.stent;
  const UnitLabels u = unit_labels(m_.cfg.problem.units, 3);
  length_unit_ = u.length, stress_unit_ = u.stress;
  lumen_ = boundary_nodes(mesh, "lumen");
  // Stations: the lumen's node planes z = const within the stent's reference span (the
  // stent's proximal end at z = 0; with `half length` up to its middle plane).
  const double ri = 0.5 * m_.cfg.mesh.artery.inner_diameter, tol = 1e-9 * ri;
  const double z_hi = s.half_length ? 0.5 * s.total_length() : s.total_length();
  const bool sector = s.sector != "full";
  const double ct = std::cos(s.sector_angle()), st = std::sin(s.sector_angle());
  std::map<long long, Station> by_z;  // z in units of tol
  for (std::size_t i = 0; i < lumen_.size(); ++i) {
    const double* x = mesh.coord(lumen_[i]);
    if (x[2] < -tol || x[2] > z_hi + tol) continue;
    const bool on_plane = sector && (std::abs(x[1]) < tol || std::abs(st * x[0] - ct * x[1]) < tol);
    Station& g = by_z[std::llround(x[2] / (1e3 * tol))];
    g.idx.push_back(i);
    g.w.push_back(on_plane ? 0.5 : 1.0);
  }
  for (auto& [z, g] : by_z) stations_.push_back(std::move(g));
  if (stations_.empty())
    throw InputError("'Output->Stent Metrics': no node of the artery's 'lumen' lies within the stent's axial span (0 to " +
                     std::to_string(z_hi) + ")");
  // The stent against the wall: the lumen's facets, the outer nodes and their areas.
  wall_ = std::make_unique<MasterSurface>(mesh, "lumen", "'Output->Stent Metrics'");
  const std::vector<GId>& wn = wall_->nodes();
  wall_->index([&](GId g) { return static_cast<int>(std::lower_bound(wn.begin(), wn.end(), g) - wn.begin()); });
  outer_ = boundary_nodes(mesh, "outer");
  const std::map<GId, double> area = tributary_areas(mesh, "outer");
  for (GId g : outer_) {
    outer_area_.push_back(area.at(g));
    const double* x = mesh.coord(g);
    outer_w_.push_back(sector && (std::abs(x[1]) < tol || std::abs(st * x[0] - ct * x[1]) < tol) ? 0.5 : 1.0);
  }
  // Struts: each ring's outer facets by the half crown pitch their centroid lies in.
  const int per_ring = 2 * s.crowns;
  const auto pitch_of = [&](const double* c) {
    double theta = std::atan2(c[1], c[0]);
    if (theta < 0.0) theta += 2.0 * kPi;
    return std::min(per_ring - 1, static_cast<int>(std::floor(theta / (kPi / s.crowns))));
  };
  for (int k = 0; k < s.model_rings(); ++k) {
    const auto parts = tributary_areas_by(mesh, "ring_" + std::to_string(k), per_ring, pitch_of);
    for (int j = 0; j < per_ring; ++j) {
      if (parts[static_cast<std::size_t>(j)].empty()) continue;
      Strut st;
      st.ring = k, st.index = j;
      for (const auto& [g, a] : parts[static_cast<std::size_t>(j)]) {
        st.idx.push_back(static_cast<std::size_t>(std::lower_bound(outer_.begin(), outer_.end(), g) - outer_.begin()));
        st.area.push_back(a);
      }
      struts_.push_back(std::move(st));
    }
  }
  threshold_ = m_.cfg.output.metrics.malapposition_threshold > 0.0 ? m_.cfg.output.metrics.malapposition_threshold : 0.1 * s.thickness;
  layer_of_block_.assign(mesh.volumes.size(), -1);
  for (const char* name : kLayers) {
    bool found = false;
    for (std::size_t b = 0; b < mesh.volumes.size(); ++b)
      if (mesh.volumes[b].name == name) layer_of_block_[b] = static_cast<int>(layers_.size()), found = true;
    if (found) layers_.emplace_back(name);
  }
}

std::vector<std::string> ArteryMetrics::columns() const {
  const std::string L = length_unit_.empty() ? "" : " [" + length_unit_ + "]";
  const std::string S = stress_unit_.empty() ? "" : " [" + stress_unit_ + "]";
  const std::string A = length_unit_.empty() ? "" : " [" + length_unit_ + "^2]";
  std::vector<std::string> c = {"lumen_D_mean" + L, "lumen_D_min" + L, "lumen_contact_area" + A,
                                "stent_wall_gap_max" + L, "malapposed_area [%]", "prolapse_max" + L,
                                "malapposed_struts [%]", "strut_gap_max" + L};
  for (const std::string& l : layers_) c.insert(c.end(), {l + "_sigma1_max" + S, l + "_sigma1_p99" + S});
  return c;
}

std::vector<std::string> ArteryMetrics::diameter_columns() const {
  const std::vector<std::string> c = columns();
  return {c[0], c[1]};
}

std::vector<std::string> ArteryMetrics::stress_columns() const {
  const std::vector<std::string> c = columns();
  return {c.begin() + kLayerColumn, c.end()};
}

double ArteryMetrics::nearest_rank(std::vector<double>& v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::min(v.size(), std::max<std::size_t>(k, 1)) - 1];
}

// Per layer the largest principal stress of each cell, gathered on every rank (padded to
// the largest rank's count), then the maximum and the 99th percentile.
void ArteryMetrics::layer_stresses(const la::Vector& u, std::vector<double>& out) const {
  Assembler::CellFieldRequest req;
  req.principal = true;
  const Assembler::CellFields cf = m_.assembler->cell_fields(u, req);
  std::vector<std::vector<double>> mine(layers_.size());
  std::size_t c = 0;
  for (const LocalBlock& lb : m_.dist->blocks()) {
    const int l = layer_of_block_[static_cast<std::size_t>(lb.volume_block)];
    for (std::size_t i = 0; i < lb.cell_ids.size(); ++i, ++c)
      if (l >= 0) mine[static_cast<std::size_t>(l)].push_back(cf.principal[3 * c]);
  }
  const int ranks = m_.comm->getSize();
  for (auto& v : mine) {
    int n = static_cast<int>(v.size()), n_max = 0;
    Teuchos::reduceAll(*m_.comm, Teuchos::REDUCE_MAX, 1, &n, &n_max);
    std::vector<double> send(static_cast<std::size_t>(n_max), -HUGE_VAL), all(static_cast<std::size_t>(n_max) * static_cast<std::size_t>(ranks));
    std::copy(v.begin(), v.end(), send.begin());
    if (n_max > 0) Teuchos::gatherAll(*m_.comm, n_max, send.data(), static_cast<int>(all.size()), all.data());
    all.erase(std::remove(all.begin(), all.end(), -HUGE_VAL), all.end());
    const double mx = all.empty() ? 0.0 : *std::max_element(all.begin(), all.end());
    out.insert(out.end(), {mx, nearest_rank(all, 0.99)});
  }
}

std::vector<double> ArteryMetrics::evaluate(const la::Vector& u) {
  const std::vector<double> x = current_positions(m_, lumen_, u);
  double sum = 0.0, dmin = HUGE_VAL;
  for (const Station& g : stations_) {
    double rw = 0.0, w = 0.0;
    for (std::size_t j = 0; j < g.idx.size(); ++j) {
      const double* xj = &x[3 * g.idx[j]];
      rw += g.w[j] * std::hypot(xj[0], xj[1]);
      w += g.w[j];
    }
    const double D = 2.0 * rw / w;
    sum += D, dmin = std::min(dmin, D);
  }
  // The lumen's area in contact (its slave nodes' reference tributary areas) times the
  // copies of the model that make the whole stent.
  const double area = m_.contact ? m_.contact->contact_area("lumen") * m_.cfg.mesh.stent.symmetry_copies() : 0.0;
  // The stent against the wall: the largest gap, the outer surface's share off the wall.
  const std::vector<double> xo = current_positions(m_, outer_, u);
  const std::vector<double> gaps = wall_gaps(xo, u);
  double gap_max = 0.0, a_all = 0.0, a_off = 0.0;
  for (std::size_t i = 0; i < gaps.size(); ++i) {
    gap_max = std::max(gap_max, gaps[i]);
    a_all += outer_area_[i];
    if (gaps[i] > threshold_) a_off += outer_area_[i];
  }
  const double malapposed = a_all > 0.0 ? 100.0 * (a_off / a_all) : 0.0;
  const std::vector<double> ds = strut_distances(gaps);
  int off = 0;
  farthest_ = -1;
  for (std::size_t k = 0; k < ds.size(); ++k) {
    off += ds[k] > threshold_;
    if (farthest_ < 0 || ds[k] > ds[static_cast<std::size_t>(farthest_)]) farthest_ = static_cast<int>(k);
  }
  const double struts_off = ds.empty() ? 0.0 : 100.0 * off / static_cast<double>(ds.size());
  now_ = {sum / static_cast<double>(stations_.size()), dmin, area, gap_max, malapposed, prolapse(x, xo), struts_off,
          farthest_ >= 0 ? ds[static_cast<std::size_t>(farthest_)] : 0.0};
  if (D_mean0_ < 0.0) D_mean0_ = now_[0], D_min0_ = now_[1];
  layer_stresses(u, now_);
  return now_;
}

std::vector<double> ArteryMetrics::wall_gaps(const la::Vector& u) const { return wall_gaps(current_positions(m_, outer_, u), u); }

std::vector<double> ArteryMetrics::wall_gaps(const std::vector<double>& xo, const la::Vector& u) const {
  const std::vector<double> xw = current_positions(m_, wall_->nodes(), u);
  wall_->build(xw);
  const auto& facets = wall_->facets();
  // The signed distance of xs to facet f: along its normal at the closest point inside it,
  // or, where that is on its edge, the distance to it with the sign of the normal's side.
  auto distance = [&](std::size_t f, const double* xs) {
    const MasterSurface::Facet& fc = facets[f];
    double xf[facet::kMaxNodes][3];
    for (int a = 0; a < fc.nn; ++a)
      for (int k = 0; k < 3; ++k) xf[a][k] = xw[3 * static_cast<std::size_t>(fc.node[a]) + static_cast<std::size_t>(k)];
    double xi[2];
    const bool inside = facet::project(fc.type, fc.nn, 3, xf, xs, xi);
    facet::Frame<double> fr;
    facet::frame(fc.type, fc.nn, 3, fc.orient, xf, xi, fr);
    const double r[3] = {xs[0] - fr.xm[0], xs[1] - fr.xm[1], xs[2] - fr.xm[2]};
    const double along = r[0] * fr.n[0] + r[1] * fr.n[1] + r[2] * fr.n[2];
    return inside ? along : std::copysign(std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]), along);
  };
  std::vector<double> d(outer_.size(), 0.0);
  for (std::size_t i = 0; i < outer_.size(); ++i) {
    const double* xs = &xo[3 * i];
    const MasterSurface::Hit h = wall_->closest(3, xs, xw);
    if (h.facet >= 0) {
      d[i] = distance(static_cast<std::size_t>(h.facet), xs);
    } else {  // farther from the wall than the search radius: the nearest of every facet
      double best = HUGE_VAL;
      for (std::size_t f = 0; f < facets.size(); ++f) {
        const double df = distance(f, xs);
        if (std::abs(df) < std::abs(best)) best = df;
      }
      d[i] = facets.empty() ? 0.0 : best;
    }
  }
  return d;
}

std::vector<double> ArteryMetrics::strut_distances(const std::vector<double>& gaps) const {
  std::vector<double> d;
  for (const Strut& st : struts_) {
    double ga = 0.0, a = 0.0;
    for (std::size_t i = 0; i < st.idx.size(); ++i) ga += st.area[i] * gaps[st.idx[i]], a += st.area[i];
    d.push_back(a > 0.0 ? ga / a : 0.0);
  }
  return d;
}

double ArteryMetrics::prolapse(const std::vector<double>& xl, const std::vector<double>& xo) const {
  // Each station's current axial position (its nodes' weighted mean).
  std::vector<double> zs(stations_.size(), 0.0);
  for (std::size_t j = 0; j < stations_.size(); ++j) {
    double w = 0.0;
    for (std::size_t k = 0; k < stations_[j].idx.size(); ++k)
      zs[j] += stations_[j].w[k] * xl[3 * stations_[j].idx[k] + 2], w += stations_[j].w[k];
    zs[j] /= w;
  }
  double worst = 0.0;
  for (std::size_t j = 0; j < stations_.size(); ++j) {
    const double below = j > 0 ? zs[j] - zs[j - 1] : HUGE_VAL, above = j + 1 < zs.size() ? zs[j + 1] - zs[j] : HUGE_VAL;
    const double band = 0.5 * std::min(below, above);
    double rw = 0.0, w = 0.0;
    for (std::size_t i = 0; i < outer_.size(); ++i)
      if (std::abs(xo[3 * i + 2] - zs[j]) <= band) rw += outer_w_[i] * std::hypot(xo[3 * i], xo[3 * i + 1]), w += outer_w_[i];
    if (w == 0.0) continue;  // no strut crosses this station
    const double Rs = rw / w;
    for (std::size_t k : stations_[j].idx) worst = std::max(worst, Rs - std::hypot(xl[3 * k], xl[3 * k + 1]));
  }
  return worst;
}

void ArteryMetrics::table(std::ostream& log) const {
  if (now_.empty()) return;
  const std::string L = length_unit_.empty() ? "" : " " + length_unit_, S = stress_unit_.empty() ? "" : " " + stress_unit_;
  log << std::fixed << std::setprecision(4) << "  artery (stented segment): lumen D mean " << D_mean0_ << " -> " << now_[0] << L << " (gain "
      << std::setprecision(2) << 100.0 * (now_[0] - D_mean0_) / D_mean0_ << " %), minimum lumen diameter " << std::setprecision(4) << D_min0_
      << " -> " << now_[1] << L << " (acute gain " << now_[1] - D_min0_ << L << "), lumen in contact " << now_[2]
      << (length_unit_.empty() ? "" : " " + length_unit_ + "^2") << "\n";
  log << std::setprecision(4) << "  stent against the wall: largest gap " << now_[3] << L << ", malapposed " << std::setprecision(2) << now_[4]
      << " % of the outer surface (gap > " << std::setprecision(4) << threshold_ << L << "), tissue prolapse " << now_[5] << L << "\n";
  if (!struts_.empty()) {
    const Strut& far = struts_[static_cast<std::size_t>(std::max(farthest_, 0))];
    log << "  struts (" << struts_.size() << " in the model; a strut's distance: its outer surface's mean distance to the lumen): "
        << std::setprecision(2) << now_[6] << " % malapposed (distance > " << std::setprecision(4) << threshold_ << L
        << "), the farthest " << now_[7] << L << " (ring " << far.ring << ", strut " << far.index << ")\n";
  }
  if (layers_.empty()) return;
  log << "  artery: largest principal stress, max / 99th percentile of the cells:" << std::scientific << std::setprecision(3);
  for (std::size_t l = 0; l < layers_.size(); ++l)
    log << (l ? "," : "") << " " << layers_[l] << " " << now_[kLayerColumn + 2 * l] << " / " << now_[kLayerColumn + 1 + 2 * l] << S;
  log << "\n" << std::defaultfloat;
}

void ArteryMetrics::save(std::map<std::string, double>& out, const std::string& prefix) const {
  if (D_mean0_ < 0.0) return;
  out[prefix + "D_mean0"] = D_mean0_;
  out[prefix + "D_min0"] = D_min0_;
}

bool ArteryMetrics::restore(const std::map<std::string, double>& in, const std::string& prefix) {
  const auto a = in.find(prefix + "D_mean0"), b = in.find(prefix + "D_min0");
  if (a == in.end() || b == in.end()) return false;
  D_mean0_ = a->second, D_min0_ = b->second;
  return true;
}

}  // namespace stentor
