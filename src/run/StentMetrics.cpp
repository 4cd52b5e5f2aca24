#include "run/StentMetrics.hpp"

#include <algorithm>
#include <cmath>

#include "mesh/MeshQuery.hpp"

namespace stentor {

namespace {

const char* kPath = "Output->Stent Metrics->";

double dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

StentMetrics::StentMetrics(const Model& model)
    : m_(model), c_(model.cfg.output.metrics), axisymmetric_(model.cfg.problem.axisymmetric()) {
  const Mesh& mesh = m_.mesh;
  require_group(mesh, c_.stent, true, std::string(kPath) + "stent");
  require_group(mesh, c_.lumen, true, std::string(kPath) + "lumen");
  require_group(mesh, c_.artery, false, std::string(kPath) + "artery");
  if (m_.dim == 2) {
    const bool in_plane = c_.axis[2] == 0.0, normal = std::abs(c_.axis[2]) == 1.0;
    if (!in_plane && !normal)
      throw InputError(std::string("'") + kPath + "axis' must lie in the plane (axial section) or be (0, 0, 1) (cross-section) in a 2D model");
    axial_ = in_plane;
  }
  for (Group* g : {&stent_, &lumen_}) {
    g->nodes = boundary_nodes(mesh, g == &stent_ ? c_.stent : c_.lumen);
    for (GId n : g->nodes) g->z0.push_back(axial_coordinate(mesh.coord(n)));
  }
  const auto span = std::minmax_element(stent_.z0.begin(), stent_.z0.end());
  z_lo_ = *span.first, z_hi_ = *span.second;
  for (std::size_t b = 0; b < mesh.volumes.size(); ++b)
    if (mesh.volumes[b].name == c_.artery) artery_blocks_.push_back(static_cast<int>(b));
  if (axial_) return;
  // The lumen curve's segments (line2; line3 as two segments through the mid node).
  auto index = [&](GId n) { return static_cast<GId>(std::lower_bound(lumen_.nodes.begin(), lumen_.nodes.end(), n) - lumen_.nodes.begin()); };
  for (const CellBlock* b : boundary_blocks(mesh, c_.lumen)) {
    for (std::size_t f = 0; f < b->num_cells(); ++f) {
      const GId* v = &b->conn[f * static_cast<std::size_t>(b->nodes_per_cell)];
      if (b->nodes_per_cell == 3)
        lumen_facets_.push_back({index(v[0]), index(v[2]), index(v[2]), index(v[1])});
      else if (b->nodes_per_cell == 2)
        lumen_facets_.push_back({index(v[0]), index(v[1])});
    }
  }
}

std::vector<std::string> StentMetrics::columns() const {
  std::vector<std::string> c = {"lumen_radius_mean", "lumen_radius_min"};
  if (!axial_) c.push_back("lumen_area");
  c.push_back("stent_radius_mean");
  if (axial_) c.insert(c.end(), {"stent_radius_middle", "stent_radius_ends", "dogboning", "stent_length", "foreshortening"});
  c.insert(c.end(), {"artery_von_mises_max", "artery_hoop_stress_max", "contact_pressure_max"});
  return c;
}

double StentMetrics::axial_coordinate(const double* x) const {
  const double r[3] = {x[0] - c_.axis_point[0], x[1] - c_.axis_point[1], x[2] - c_.axis_point[2]};
  return dot(r, c_.axis.data());
}

double StentMetrics::radius(const double* x) const {
  double r[3] = {x[0] - c_.axis_point[0], x[1] - c_.axis_point[1], x[2] - c_.axis_point[2]};
  const double a = dot(r, c_.axis.data());
  for (int k = 0; k < 3; ++k) r[k] -= a * c_.axis[static_cast<std::size_t>(k)];
  return std::sqrt(dot(r, r));
}


// Largest von Mises and circumferential (e_t . sigma e_t, e_t = axis x e_r at the cell's
// reference centroid; in axisymmetry the hoop component sigma_thth) Cauchy stress over the
// artery's cells.
void StentMetrics::stresses(const la::Vector& u, double& von_mises, double& hoop) const {
  const Assembler::CellFields cf = m_.assembler->cell_fields(u);
  const Mesh& mesh = m_.mesh;
  double loc[2] = {-1e300, -1e300}, glob[2];
  std::size_t c = 0;
  for (const LocalBlock& lb : m_.dist->blocks()) {
    const bool artery = std::find(artery_blocks_.begin(), artery_blocks_.end(), lb.volume_block) != artery_blocks_.end();
    const CellBlock& mb = mesh.volumes[static_cast<std::size_t>(lb.volume_block)];
    for (std::size_t i = 0; i < lb.cell_ids.size(); ++i, ++c) {
      if (!artery) continue;
      double xc[3] = {0, 0, 0};
      const auto npc = static_cast<std::size_t>(mb.nodes_per_cell);
      const std::size_t first = static_cast<std::size_t>(lb.cell_index[i]) * npc;
      for (std::size_t a = 0; a < npc; ++a)
        for (std::size_t k = 0; k < 3; ++k) xc[k] += mesh.coord(mb.conn[first + a])[k] / double(npc);
      double er[3] = {xc[0] - c_.axis_point[0], xc[1] - c_.axis_point[1], xc[2] - c_.axis_point[2]};
      const double al = dot(er, c_.axis.data());
      for (std::size_t k = 0; k < 3; ++k) er[k] -= al * c_.axis[k];
      const double* a = c_.axis.data();
      double et[3] = {a[1] * er[2] - a[2] * er[1], a[2] * er[0] - a[0] * er[2], a[0] * er[1] - a[1] * er[0]};
      const double len = std::sqrt(dot(et, et));
      const double* s = &cf.stress[6 * c];  // xx yy zz xy yz xz
      if (axisymmetric_) {
        loc[1] = std::max(loc[1], s[2]);  // (rr, zz, thth, rz, 0, 0): the hoop stress
      } else if (len > 0.0) {
        for (double& e : et) e /= len;
        const double st = s[0] * et[0] * et[0] + s[1] * et[1] * et[1] + s[2] * et[2] * et[2] +
                          2.0 * (s[3] * et[0] * et[1] + s[4] * et[1] * et[2] + s[5] * et[0] * et[2]);
        loc[1] = std::max(loc[1], st);
      }
      loc[0] = std::max(loc[0], cf.von_mises[c]);
    }
  }
  Teuchos::reduceAll(*m_.comm, Teuchos::REDUCE_MAX, 2, loc, glob);
  von_mises = glob[0] > -1e300 ? glob[0] : 0.0;
  hoop = glob[1] > -1e300 ? glob[1] : 0.0;
}

// Area enclosed by the lumen curve, star-shaped about the axis point: the sum of the
// triangles (axis point, segment).
double StentMetrics::lumen_area(const std::vector<double>& x) const {
  double area = 0.0;
  for (const auto& f : lumen_facets_)
    for (std::size_t s = 0; s + 1 < f.size(); s += 2) {
      const double* a = &x[3 * static_cast<std::size_t>(f[s])];
      const double* b = &x[3 * static_cast<std::size_t>(f[s + 1])];
      const double ax = a[0] - c_.axis_point[0], ay = a[1] - c_.axis_point[1];
      const double bx = b[0] - c_.axis_point[0], by = b[1] - c_.axis_point[1];
      area += 0.5 * std::abs(ax * by - ay * bx);
    }
  return area;
}

std::vector<double> StentMetrics::evaluate(const la::Vector& u) {
  const std::vector<double> xs = current_positions(m_, stent_.nodes, u), xl = current_positions(m_, lumen_.nodes, u);
  double lsum = 0.0, lmin = 1e300;
  long ln = 0;
  for (std::size_t i = 0; i < lumen_.nodes.size(); ++i) {
    if (axial_ && (lumen_.z0[i] < z_lo_ || lumen_.z0[i] > z_hi_)) continue;
    const double r = radius(&xl[3 * i]);
    lsum += r, lmin = std::min(lmin, r), ++ln;
  }
  std::vector<double> v = {ln ? lsum / double(ln) : 0.0, ln ? lmin : 0.0};
  if (!axial_) v.push_back(lumen_area(xl));
  const double L0 = z_hi_ - z_lo_, zc = 0.5 * (z_lo_ + z_hi_), f = c_.end_fraction * L0;
  double sum = 0.0, mid = 0.0, ends = 0.0, zmin = 1e300, zmax = -1e300;
  long nmid = 0, nends = 0;
  for (std::size_t i = 0; i < stent_.nodes.size(); ++i) {
    const double r = radius(&xs[3 * i]), z0 = stent_.z0[i], z = axial_coordinate(&xs[3 * i]);
    sum += r;
    zmin = std::min(zmin, z), zmax = std::max(zmax, z);
    if (std::abs(z0 - zc) <= 0.5 * f) mid += r, ++nmid;
    if (z0 - z_lo_ <= f || z_hi_ - z0 <= f) ends += r, ++nends;
  }
  v.push_back(stent_.nodes.empty() ? 0.0 : sum / double(stent_.nodes.size()));
  if (axial_) {
    mid = nmid ? mid / double(nmid) : 0.0;
    ends = nends ? ends / double(nends) : 0.0;
    v.insert(v.end(), {mid, ends, mid > 0.0 ? (ends - mid) / mid : 0.0, zmax - zmin, L0 > 0.0 ? (L0 - (zmax - zmin)) / L0 : 0.0});
  }
  double vm = 0.0, hoop = 0.0;
  stresses(u, vm, hoop);
  double p_loc = 0.0, p = 0.0;
  if (m_.contact) {
    const Contact::NodalFields nf = m_.contact->nodal_fields();
    for (std::size_t i = 0; i < nf.nodes.size(); ++i) p_loc = std::max(p_loc, nf.values[Contact::kNodalValues * i + 3]);
  }
  Teuchos::reduceAll(*m_.comm, Teuchos::REDUCE_MAX, 1, &p_loc, &p);
  v.insert(v.end(), {vm, hoop, p});
  return v;
}

}  // namespace stentor
