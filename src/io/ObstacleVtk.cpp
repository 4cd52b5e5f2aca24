#include "io/ObstacleVtk.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "io/Csv.hpp"
#include "io/WriteError.hpp"

namespace stentor {

namespace {

using V3 = std::array<double, 3>;
constexpr double kPi = 3.14159265358979323846;
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

ObstacleVtkWriter::ObstacleVtkWriter(std::string dir, std::string basename, int dim, double extent, std::array<double, 3> centre)
    : dir_(std::move(dir)), basename_(std::move(basename)), dim_(dim), extent_(extent), centre_(centre) {}

void ObstacleVtkWriter::write(double t, const std::vector<ObstacleShape>& shapes) {
  const std::string name = basename_ + "_obstacles_" + std::to_string(steps_.size()) + ".vtp";
  const std::string path = dir_ + "/" + name;
  std::ostringstream pts, conn, offs, ids;
  pts.precision(17);
  std::size_t np = 0, nc = 0, off = 0;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const ObstacleSurface s = sample_obstacle(shapes[i], dim_, extent_, centre_);
    for (const auto& x : s.points) pts << x[0] << " " << x[1] << " " << x[2] << "\n";
    for (const auto& c : s.cells) {
      for (int k : c) conn << k + static_cast<int>(np) << " ";
      off += c.size();
      offs << off << " ";
      ids << i << " ";
      ++nc;
    }
    np += s.points.size();
  }
  const char* cell_kind = dim_ == 2 ? "Lines" : "Polys";
  {
    std::ofstream f(path);
    f << "<?xml version=\"1.0\"?>\n<!-- Stentor rigid obstacles at t = " << t << " -->\n"
      << "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>\n<Piece NumberOfPoints=\"" << np
      << "\" NumberOfVerts=\"0\" NumberOfLines=\"" << (dim_ == 2 ? nc : 0) << "\" NumberOfStrips=\"0\" NumberOfPolys=\""
      << (dim_ == 2 ? 0 : nc) << "\">\n<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n" << pts.str()
      << "</DataArray></Points>\n<" << cell_kind << "><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">" << conn.str()
      << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" << offs.str() << "</DataArray></" << cell_kind
      << ">\n<CellData Scalars=\"obstacle\"><DataArray type=\"Int32\" Name=\"obstacle\" format=\"ascii\">" << ids.str()
      << "</DataArray></CellData>\n</Piece>\n</PolyData>\n</VTKFile>\n";
    f.flush();
    errno = 0;
    check_write(static_cast<bool>(f), "writing", path);
  }
  steps_.emplace_back(t, name);
  const std::string pvd = dir_ + "/" + basename_ + "_obstacles.pvd", tmp = pvd + ".tmp";
  {
    std::ofstream f(tmp);
    f.precision(17);
    f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
    for (const auto& s : steps_) f << "    <DataSet timestep=\"" << format_double(s.first) << "\" file=\"" << s.second << "\"/>\n";
    f << "  </Collection>\n</VTKFile>\n";
    f.flush();
    errno = 0;
    check_write(static_cast<bool>(f), "writing", pvd);
  }
  if (std::rename(tmp.c_str(), pvd.c_str()) != 0) throw_write_error("renaming to", pvd, errno);
}

}  // namespace stentor
