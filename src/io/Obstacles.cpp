#include "io/Obstacles.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "stentor/format.hpp"

namespace stentor {

namespace {

using V3 = std::array<double, 3>;
constexpr int kAround = 64;  // segments of a full turn

V3 add(const V3& a, const V3& b, double s = 1.0) { return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]}; }
V3 unit(const V3& a) {
  const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  return {a[0] / n, a[1] / n, a[2] / n};
}
V3 cross(const V3& a, const V3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Two unit vectors orthogonal to `a` and to each other.
void basis(const V3& a, V3& e1, V3& e2) {
  const V3 t = std::abs(a[0]) < 0.9 ? V3{1, 0, 0} : V3{0, 1, 0};
  e1 = unit(cross(a, t));
  e2 = cross(a, e1);
}

// Profile (distance from the axis, position along it) of a body of revolution about the
// axis through `p` along `a`: the start cap, the straight part, the end cap.
std::vector<std::array<double, 2>> profile(const ObstacleShape& o, double z0, double z1, bool caps) {
  std::vector<std::array<double, 2>> pr;
  const int nq = kAround / 4;
  if (caps)
    for (int k = 0; k < nq; ++k) {
      const double th = -0.5 * kPi + 0.5 * kPi * k / nq;
      pr.push_back({o.radius * std::cos(th), z0 + o.radius * std::sin(th)});
    }
  pr.push_back({o.radius, z0});
  if (z1 > z0) pr.push_back({o.radius, z1});
  if (caps)
    for (int k = 1; k <= nq; ++k) {
      const double th = 0.5 * kPi * k / nq;
      pr.push_back({o.radius * std::cos(th), z1 + o.radius * std::sin(th)});
    }
  return pr;
}

// 3D: the profile revolved into quads (degenerate quads at the poles are kept: ParaView
// draws them as triangles).
ObstacleSurface revolve(const V3& p, const V3& a, const std::vector<std::array<double, 2>>& pr) {
  V3 e1, e2;
  basis(a, e1, e2);
  ObstacleSurface s;
  for (const auto& rz : pr)
    for (int j = 0; j < kAround; ++j) {
      const double ph = 2.0 * kPi * j / kAround;
      V3 x = add(p, a, rz[1]);
      x = add(x, e1, rz[0] * std::cos(ph));
      s.points.push_back(add(x, e2, rz[0] * std::sin(ph)));
    }
  for (std::size_t i = 0; i + 1 < pr.size(); ++i)
    for (int j = 0; j < kAround; ++j) {
      const int a0 = static_cast<int>(i) * kAround, a1 = a0 + kAround, j1 = (j + 1) % kAround;
      s.cells.push_back({a0 + j, a0 + j1, a1 + j1, a1 + j});
    }
  return s;
}

ObstacleSurface sample_2d(const ObstacleShape& o, double extent) {
  ObstacleSurface s;
  const V3 p = o.point;
  if (o.kind == 0) {
    const V3 t = {-o.normal[1], o.normal[0], 0.0};
    s.points = {add(p, t, -extent), add(p, t, extent)};
    s.cells = {{0, 1}};
    return s;
  }
  // Circle (length 0) or stadium: half circles around both ends of the axis segment.
  const V3 a = o.kind == 3 ? unit(o.axis) : V3{1, 0, 0};
  const V3 n = {-a[1], a[0], 0.0};
  const double len = o.kind == 3 ? o.length : 0.0;
  const int nh = kAround / 2;
  for (int end = 0; end < 2; ++end) {
    const V3 c = add(p, a, end ? len : 0.0);
    for (int k = 0; k <= nh; ++k) {
      const double th = kPi * k / nh + (end ? -0.5 * kPi : 0.5 * kPi);  // end: -90..90 deg from a
      const double ca = std::cos(th), sa = std::sin(th);
      s.points.push_back({c[0] + o.radius * (ca * a[0] + sa * n[0]), c[1] + o.radius * (ca * a[1] + sa * n[1]), 0.0});
    }
  }
  std::vector<int> loop;
  for (int i = 0; i < static_cast<int>(s.points.size()); ++i) loop.push_back(i);
  loop.push_back(0);
  s.cells = {loop};
  return s;
}

}  // namespace

ObstacleSurface sample_obstacle(const ObstacleShape& o, int dim, double extent, const std::array<double, 3>& centre) {
  if (dim == 2) return sample_2d(o, extent);
  if (o.kind == 0) {
    V3 e1, e2;
    const V3 n = unit(o.normal);
    basis(n, e1, e2);
    const V3 c = add(centre, n, dot(n, add(o.point, centre, -1.0)));  // the centre projected on the plane
    ObstacleSurface s;
    for (int k = 0; k < 4; ++k) s.points.push_back(add(add(c, e1, (k == 1 || k == 2 ? 1 : -1) * extent), e2, (k >= 2 ? 1 : -1) * extent));
    s.cells = {{0, 1, 2, 3}};
    return s;
  }
  if (o.kind == 1) return revolve(o.point, {0, 0, 1}, profile(o, 0.0, 0.0, true));
  const V3 a = unit(o.axis);
  if (o.kind == 3) return revolve(o.point, a, profile(o, 0.0, o.length, true));
  const double zc = dot(add(centre, o.point, -1.0), a);  // cylinder: drawn around the mesh's centre
  return revolve(o.point, a, profile(o, zc - extent, zc + extent, false));
}

ObstacleWriter::ObstacleWriter(std::string dir, std::string basename, int dim, double extent, std::array<double, 3> centre,
                               std::vector<std::string> names)
    : dir_(std::move(dir)), basename_(std::move(basename)), dim_(dim), extent_(extent), centre_(centre), names_(std::move(names)) {}

ObstacleWriter::~ObstacleWriter() = default;

namespace {

// The shapes as a mesh: one block per obstacle (line segments in 2D, quadrilaterals in 3D).
Mesh obstacle_mesh(const std::vector<ObstacleSurface>& surfaces, const std::vector<std::string>& names, int dim) {
  Mesh m;
  m.dim = dim;
  GId cell = 0;
  for (std::size_t i = 0; i < surfaces.size(); ++i) {
    const ObstacleSurface& s = surfaces[i];
    const GId off = static_cast<GId>(m.num_nodes());
    for (const auto& x : s.points) m.x.insert(m.x.end(), x.begin(), x.end());
    CellBlock b;
    b.name = names[i];
    b.type = dim == 2 ? CellType::Line2 : CellType::Quad4;
    b.nodes_per_cell = dim == 2 ? 2 : 4;
    for (const auto& c : s.cells) {
      if (dim == 2)  // a polyline: its segments
        for (std::size_t j = 0; j + 1 < c.size(); ++j) b.conn.insert(b.conn.end(), {off + c[j], off + c[j + 1]});
      else
        for (int k : c) b.conn.push_back(off + k);
    }
    for (std::size_t c = 0; c < b.num_cells(); ++c) b.cell_id.push_back(cell++);
    m.volumes.push_back(std::move(b));
  }
  return m;
}

}  // namespace

void ObstacleWriter::write(double t, const std::vector<ObstacleShape>& shapes) {
  if (shapes.size() != names_.size()) throw std::logic_error("ObstacleWriter: one shape per named obstacle expected");
  std::vector<ObstacleSurface> surfaces;
  for (const ObstacleShape& o : shapes) surfaces.push_back(sample_obstacle(o, dim_, extent_, centre_));
  const Mesh m = obstacle_mesh(surfaces, names_, dim_);
  if (!xdmf_) {
    xdmf_ = std::make_unique<XdmfWriter>(dir_, basename_ + "_obstacles", m);
    x0_ = m.x;
  }
  if (m.x.size() != x0_.size()) throw std::logic_error("ObstacleWriter: the obstacles' sampling changed between outputs");
  std::vector<double> u(m.x.size());
  for (std::size_t i = 0; i < u.size(); ++i) u[i] = m.x[i] - x0_[i];
  xdmf_->begin_step(t);
  xdmf_->geometry(m.x);
  xdmf_->node_field("displacement", 3, u);
  xdmf_->end_step();
}

}  // namespace stentor
