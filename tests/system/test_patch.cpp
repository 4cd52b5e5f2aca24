// Patch tests (docs/verification.md, "Statics (mesh)"): a homogeneous finite deformation
// u = H X, imposed through a Dirichlet `field` on every boundary group of a distorted mesh,
// must be reproduced to round-off at every node. With F = I + H constant, P(F) is constant,
// Div P = 0, so u = H X solves the nonlinear problem exactly; it lies in every element space
// used (P1/P2 isoparametric simplices, Q1 quads and hexes, curved P2 edges included), so the
// discrete solution must equal it.
//
// Distortion: the .geo files below (written into the build dir) have a curved side (circle
// arc: curved tri6/tet10 boundary cells), a slanted extrusion (3D), and embedded interior
// points with very different local sizes, so the unstructured cells are strongly graded and
// irregular; recombined quads/hexes are general (non-parallelogram) quadrilaterals.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "fem/Geometry.hpp"
#include "fem/Quadrature.hpp"
#include "fem/Shape.hpp"
#include "run/Simulation.hpp"
#include "TestDir.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

fs::path work_dir() { return stentor::testing::test_dir("patch"); }

// 2D: quadrilateral with a circular top side, four boundary groups, three embedded points
// with small sizes at irregular positions.
const char* kGeo2d = R"(
Point(1) = {0, 0, 0, 0.22};
Point(2) = {1, 0.1, 0, 0.3};
Point(3) = {1.1, 0.9, 0, 0.12};
Point(4) = {-0.1, 0.9, 0, 0.25};
Point(5) = {0.5, -0.6, 0, 1.0};   // arc centre
Point(6) = {0.31, 0.43, 0, 0.03};
Point(7) = {0.74, 0.27, 0, 0.06};
Point(8) = {0.62, 0.71, 0, 0.04};
Line(1) = {1, 2};
Line(2) = {2, 3};
Circle(3) = {3, 5, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point{6, 7, 8} In Surface{1};
Physical Surface("body") = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("arc") = {3};
Physical Curve("left") = {4};
)";

// 3D: the same base (without embedded points), extruded along a slanted vector, with
// embedded points in the volume. Sizes are scaled by s (set before this text).
const char* kGeo3d = R"(
Point(1) = {0, 0, 0, 0.3 * s};
Point(2) = {1, 0.1, 0, 0.4 * s};
Point(3) = {1.1, 0.9, 0, 0.2 * s};
Point(4) = {-0.1, 0.9, 0, 0.35 * s};
Point(5) = {0.5, -0.6, 0, 1.0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Circle(3) = {3, 5, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
out[] = Extrude {0.15, -0.1, 0.8} { Surface{1}; };
Point(20) = {0.35, 0.4, 0.3, 0.06 * s};
Point(21) = {0.7, 0.3, 0.55, 0.09 * s};
Point{20, 21} In Volume{out[1]};
Physical Volume("body") = {out[1]};
Physical Surface("base") = {1};
Physical Surface("top") = {out[0]};
Physical Surface("sides") = {out[2], out[3], out[4], out[5]};
)";

std::string write_geo(const std::string& name, const char* text, double s = 1.0) {
  fs::create_directories(work_dir());
  const fs::path p = work_dir() / name;
  std::ofstream(p) << "s = " << s << ";\n" << text;
  return p.string();
}

struct PatchResult {
  bool converged = false;
  double rel_error = 1e300;             // max_n |u_h - H X| / max_n |H X|
  std::map<CellType, std::size_t> cells;  // volume cells by type
  double size_ratio = 0;                  // largest / smallest cell measure (grading)
};

// Largest / smallest cell area (2D) or volume (3D).
double cell_measure_ratio(const Mesh& mesh) {
  double lo = 1e300, hi = 0;
  double xi[kMaxQuadPoints][3], w[kMaxQuadPoints];
  for (const auto& blk : mesh.volumes) {
    const int nq = quadrature(blk.type, 2, xi, w), nn = blk.nodes_per_cell;
    for (std::size_t c = 0; c < blk.num_cells(); ++c) {
      double X[kMaxCellNodes][3], N[kMaxCellNodes], dN[kMaxCellNodes][3], dNdX[kMaxCellNodes][3], m = 0;
      for (int a = 0; a < nn; ++a)
        for (int d = 0; d < 3; ++d) X[a][d] = mesh.x[3 * static_cast<std::size_t>(blk.conn[c * nn + a]) + d];
      for (int q = 0; q < nq; ++q) {
        shape_functions(blk.type, xi[q], N, dN);
        m += w[q] * reference_gradients(mesh.dim, nn, X, dN, dNdX);
      }
      lo = std::min(lo, m), hi = std::max(hi, m);
    }
  }
  return hi / lo;
}

PatchResult run_patch(const std::string& geo, int dim, int order, bool recombine, const std::string& tag) {
  // A general (non-symmetric, volume-changing) H with entries 0.03-0.09: finite strain.
  const double H[3][3] = {{0.07, -0.04, 0.05}, {0.03, -0.06, 0.08}, {-0.05, 0.09, 0.04}};
  auto exact = [H, dim](const double* X) {
    std::array<double, 3> u{0.0, 0.0, 0.0};
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j) u[static_cast<std::size_t>(i)] += H[i][j] * X[j];
    return u;
  };

  Config cfg;
  cfg.deck_path = geo;
  cfg.problem.title = "patch test " + tag;
  cfg.mesh.file = geo;
  cfg.mesh.size = 0.0;  // the .geo's own (graded) point sizes
  cfg.mesh.order = order;
  cfg.mesh.recombine = recombine;
  MaterialConfig m;
  m.name = "m";
  m.C1 = 0.8, m.C2 = 0.3, m.D = 1.5;
  cfg.materials.push_back(m);
  BodyConfig b;
  b.name = "body", b.group = "body", b.material = "m";
  cfg.bodies.push_back(b);
  const std::vector<std::string> groups =
      dim == 2 ? std::vector<std::string>{"bottom", "right", "arc", "left"} : std::vector<std::string>{"base", "top", "sides"};
  for (const auto& g : groups) {
    LoadConfig l;
    l.type = LoadConfig::Type::Dirichlet;
    l.name = "u_" + g;
    l.group = g;
    l.components = {true, true, true};
    l.all_components = true;
    l.field = exact;
    cfg.loads.push_back(l);
  }
  // Steps: a Dirichlet increment moves only the boundary nodes at the start of a step, so a
  // whole-H step would invert some boundary cells (the run would cut the step back anyway).
  cfg.stepping.num_steps = dim == 2 ? 2 : 4;
  cfg.newton.residual_tolerance = 1e-13;
  cfg.newton.absolute_tolerance = 1e-15;
  cfg.newton.increment_tolerance = 1e-14;
  cfg.linear.method = "direct";
  cfg.output.fields = false;
  cfg.output.basename = tag;
  RunOptions opts;
  opts.output_dir = (work_dir() / ("out_" + tag)).string();

  RunResult res;
  PatchResult pr;
  if (run_simulation(cfg, opts, &res) != 0) return pr;
  pr.converged = res.converged;
  for (const auto& blk : res.mesh.volumes) pr.cells[blk.type] += blk.num_cells();
  pr.size_ratio = cell_measure_ratio(res.mesh);
  std::vector<char> used(res.mesh.num_nodes(), 0);
  for (const auto& blk : res.mesh.volumes)
    for (GId n : blk.conn) used[static_cast<std::size_t>(n)] = 1;
  double err = 0.0, scale = 0.0;
  for (std::size_t n = 0; n < res.mesh.num_nodes(); ++n) {
    if (!used[n]) continue;
    const auto ue = exact(&res.mesh.x[3 * n]);
    double e2 = 0.0, s2 = 0.0;
    for (int k = 0; k < dim; ++k) {
      e2 += std::pow(res.displacement[3 * n + k] - ue[static_cast<std::size_t>(k)], 2);
      s2 += ue[static_cast<std::size_t>(k)] * ue[static_cast<std::size_t>(k)];
    }
    err = std::max(err, std::sqrt(e2));
    scale = std::max(scale, std::sqrt(s2));
  }
  pr.rel_error = err / scale;
  std::printf("[patch] %-6s cells:", tag.c_str());
  for (const auto& [t, c] : pr.cells) std::printf(" %zu %s", c, cell_name(t));
  std::printf("  (largest/smallest cell %.0f)  newton %d  max nodal error / max |u| = %.3e\n", pr.size_ratio, res.newton_iterations,
              pr.rel_error);
  return pr;
}

void expect_patch(const std::string& geo, int dim, int order, bool recombine, CellType main_type, const std::string& tag) {
  const PatchResult r = run_patch(geo, dim, order, recombine, tag);
  ASSERT_TRUE(r.converged) << tag;
  ASSERT_TRUE(r.cells.count(main_type) && r.cells.at(main_type) > 0) << tag << ": no " << cell_name(main_type) << " cells";
  EXPECT_GT(r.size_ratio, 5.0) << tag << ": the mesh is not graded as intended";
  EXPECT_LT(r.rel_error, 1e-9) << tag;
}

}  // namespace

TEST(Patch, Tri3) { expect_patch(write_geo("patch2d.geo", kGeo2d), 2, 1, false, CellType::Tri3, "tri3"); }
TEST(Patch, Tri6CurvedBoundary) { expect_patch(write_geo("patch2d.geo", kGeo2d), 2, 2, false, CellType::Tri6, "tri6"); }
TEST(Patch, Quad4) { expect_patch(write_geo("patch2d.geo", kGeo2d), 2, 1, true, CellType::Quad4, "quad4"); }
TEST(Patch, Tet4) { expect_patch(write_geo("patch3d.geo", kGeo3d, 0.8), 3, 1, false, CellType::Tet4, "tet4"); }
TEST(Patch, Tet10CurvedBoundary) { expect_patch(write_geo("patch3d.geo", kGeo3d), 3, 2, false, CellType::Tet10, "tet10"); }
// Hexes: every tet split into 4, so a coarser tet mesh.
TEST(Patch, Hex8) { expect_patch(write_geo("patch3d_hex.geo", kGeo3d, 1.6), 3, 1, true, CellType::Hex8, "hex8"); }
