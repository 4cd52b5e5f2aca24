// Manufactured solution (docs/verification.md, "Statics (mesh)"): a smooth, finite (but
// moderate) displacement field u* on the unit square / cube, the body force b = -Div P(F(u*))
// that makes it an equilibrium, u = u* prescribed on the whole boundary. The discrete
// solutions on a sequence of meshes must converge at the optimal rates:
//   P1: ||u - u_h||_L2 ~ h^2, |u - u_h|_H1 ~ h;   P2: h^3 and h^2.
//
// u*_i(X) = eps * prod_d sin(k_id X_d + phi_id) (d over the dimension), with eps = 0.05
// (|Grad u*| up to ~0.2: nonlinear, far from the small-strain regime's linear response).
// Div P is evaluated exactly through the chain rule, Div P_i = A_iJkL d_J d_L u*_k with
// A = dP/dF from src/material (the test checks it against central differences of P).
// Errors are integrated with the degree-5 rules of src/fem over the mesh of RunResult.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "fem/Geometry.hpp"
#include "fem/Quadrature.hpp"
#include "fem/Shape.hpp"
#include "material/CiarletGeymonat.hpp"
#include "material/Kinematics.hpp"
#include "run/Simulation.hpp"
#include "TestDir.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

const double kPi = 3.14159265358979323846;
fs::path work_dir() { return stentor::testing::test_dir("mms"); }

struct Manufactured {
  int dim = 2;
  double eps = 0.05;
  // Integer wave numbers (times pi), no phases: u* = 0 on the boundary of the unit square/cube.
  double k[3][3] = {{1 * kPi, 2 * kPi, 1 * kPi}, {2 * kPi, 1 * kPi, 1 * kPi}, {1 * kPi, 1 * kPi, 2 * kPi}};
  double ph[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  CiarletGeymonat mat{0.8, 0.3, 1.5};  // mu = 2.2, lambda = 7.2

  double s(int i, int d, const double* X) const { return std::sin(k[i][d] * X[d] + ph[i][d]); }
  double c(int i, int d, const double* X) const { return k[i][d] * std::cos(k[i][d] * X[d] + ph[i][d]); }

  std::array<double, 3> u(const double* X) const {
    std::array<double, 3> r{0.0, 0.0, 0.0};
    for (int i = 0; i < dim; ++i) {
      double v = eps;
      for (int d = 0; d < dim; ++d) v *= s(i, d, X);
      r[static_cast<std::size_t>(i)] = v;
    }
    return r;
  }
  // G[i][m] = d u_i / d X_m
  void grad(const double* X, double G[3][3]) const {
    for (int i = 0; i < 3; ++i)
      for (int m = 0; m < 3; ++m) G[i][m] = 0.0;
    for (int i = 0; i < dim; ++i)
      for (int m = 0; m < dim; ++m) {
        double v = eps;
        for (int d = 0; d < dim; ++d) v *= d == m ? c(i, d, X) : s(i, d, X);
        G[i][m] = v;
      }
  }
  // Hs[i][m][n] = d^2 u_i / dX_m dX_n
  void hess(const double* X, double Hs[3][3][3]) const {
    for (int i = 0; i < 3; ++i)
      for (int m = 0; m < 3; ++m)
        for (int n = 0; n < 3; ++n) Hs[i][m][n] = 0.0;
    for (int i = 0; i < dim; ++i)
      for (int m = 0; m < dim; ++m)
        for (int n = 0; n < dim; ++n) {
          double v = eps;
          if (m == n) {
            v *= -k[i][m] * k[i][m];
            for (int d = 0; d < dim; ++d) v *= s(i, d, X);
          } else {
            for (int d = 0; d < dim; ++d) v *= (d == m || d == n) ? c(i, d, X) : s(i, d, X);
          }
          Hs[i][m][n] = v;
        }
  }
  Mat3 F(const double* X) const {
    double G[3][3];
    grad(X, G);
    Mat3 f = Mat3::identity();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) f(i, j) += G[i][j];
    return f;  // plane strain: F_33 = 1, F_i3 = F_3i = 0
  }
  Mat3 P(const double* X) const {
    const Mat3 f = F(X);
    return first_piola(f, mat.stress(right_cauchy_green(f)));
  }
  // b = -Div P(F(u*)) = -A_iJkL d_J d_L u*_k
  std::array<double, 3> body_force(const double* X) const {
    const Mat3 f = F(X);
    Mat3 S;
    Ten4 CC, A;
    mat.stress_and_tangent(right_cauchy_green(f), S, CC);
    spatial_tangent_dPdF(f, S, CC, A);
    double Hs[3][3][3];
    hess(X, Hs);
    std::array<double, 3> b{0.0, 0.0, 0.0};
    for (int i = 0; i < dim; ++i) {
      double v = 0.0;
      for (int J = 0; J < dim; ++J)
        for (int kk = 0; kk < dim; ++kk)
          for (int L = 0; L < dim; ++L) v += A(i, J, kk, L) * Hs[kk][J][L];
      b[static_cast<std::size_t>(i)] = -v;
    }
    return b;
  }
  // Central differences of P, for checking body_force().
  std::array<double, 3> body_force_fd(const double* X, double h) const {
    std::array<double, 3> b{0.0, 0.0, 0.0};
    for (int J = 0; J < dim; ++J) {
      double Xp[3] = {X[0], X[1], X[2]}, Xm[3] = {X[0], X[1], X[2]};
      Xp[J] += h;
      Xm[J] -= h;
      const Mat3 Pp = P(Xp), Pm = P(Xm);
      for (int i = 0; i < dim; ++i) b[static_cast<std::size_t>(i)] -= (Pp(i, J) - Pm(i, J)) / (2.0 * h);
    }
    return b;
  }
};

struct Level {
  double h = 0;         // mean cell size (|Omega| / number of cells)^(1/dim)
  std::size_t nodes = 0, cells = 0;
  double l2 = 0, h1 = 0;  // error norms
  double u_l2 = 0, u_h1 = 0;  // norms of u* (for relative numbers)
};

Level solve_and_measure(const Manufactured& ms, int order, double size) {
  const int dim = ms.dim;
  Config cfg;
  const std::string geo = std::string(STENTOR_SOURCE_DIR) + (dim == 2 ? "/inputs/block2d.geo" : "/inputs/block3d.geo");
  cfg.deck_path = geo;
  cfg.problem.title = "manufactured solution";
  cfg.mesh.file = geo;
  cfg.mesh.size = size;
  cfg.mesh.order = order;
  MaterialConfig m;
  m.name = "m";
  m.C1 = ms.mat.C1, m.C2 = ms.mat.C2, m.D = ms.mat.D;
  cfg.materials.push_back(m);
  BodyConfig b;
  b.name = "block", b.group = "block", b.material = "m";
  cfg.bodies.push_back(b);
  const std::vector<std::string> sides = dim == 2 ? std::vector<std::string>{"left", "right", "bottom", "top"}
                                                  : std::vector<std::string>{"left", "right", "front", "back", "bottom", "top"};
  for (const auto& g : sides) {
    LoadConfig l;
    l.type = LoadConfig::Type::Dirichlet;
    l.name = "u_" + g;
    l.group = g;
    l.components = {true, true, true};
    l.all_components = true;
    l.field = [&ms](const double* X) { return ms.u(X); };
    cfg.loads.push_back(l);
  }
  LoadConfig bf;
  bf.type = LoadConfig::Type::BodyForce;
  bf.name = "b";
  bf.field = [&ms](const double* X) { return ms.body_force(X); };
  cfg.loads.push_back(bf);
  cfg.stepping.num_steps = 1;
  cfg.newton.residual_tolerance = 1e-12;
  cfg.newton.absolute_tolerance = 1e-14;
  cfg.newton.increment_tolerance = 1e-13;
  cfg.linear.method = "direct";
  cfg.output.fields = false;
  cfg.output.basename = "mms";
  RunOptions opts;
  opts.output_dir = (work_dir() / ("out_" + std::to_string(dim) + "d_p" + std::to_string(order) + "_" + std::to_string(size))).string();

  RunResult res;
  Level lv;
  EXPECT_EQ(run_simulation(cfg, opts, &res), 0);
  EXPECT_TRUE(res.converged);
  const Mesh& mesh = res.mesh;
  lv.nodes = mesh.num_nodes();
  lv.cells = mesh.num_volume_cells();
  lv.h = std::pow(1.0 / static_cast<double>(lv.cells), 1.0 / dim);  // |Omega| = 1

  double xi[kMaxQuadPoints][3], w[kMaxQuadPoints];
  for (const auto& blk : mesh.volumes) {
    const int nq = quadrature(blk.type, 5, xi, w);
    const int nn = blk.nodes_per_cell;
    for (std::size_t cell = 0; cell < blk.num_cells(); ++cell) {
      double X[kMaxCellNodes][3], U[kMaxCellNodes][3];
      for (int a = 0; a < nn; ++a) {
        const auto n = static_cast<std::size_t>(blk.conn[cell * nn + a]);
        for (int d = 0; d < 3; ++d) X[a][d] = mesh.x[3 * n + d], U[a][d] = res.displacement[3 * n + d];
      }
      for (int q = 0; q < nq; ++q) {
        double N[kMaxCellNodes], dN[kMaxCellNodes][3], dNdX[kMaxCellNodes][3];
        shape_functions(blk.type, xi[q], N, dN);
        const double detJ = reference_gradients(dim, nn, X, dN, dNdX);
        double xq[3] = {0, 0, 0}, uh[3] = {0, 0, 0}, Gh[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
        for (int a = 0; a < nn; ++a)
          for (int i = 0; i < 3; ++i) {
            xq[i] += N[a] * X[a][i];
            uh[i] += N[a] * U[a][i];
            for (int j = 0; j < 3; ++j) Gh[i][j] += U[a][i] * dNdX[a][j];
          }
        const auto ue = ms.u(xq);
        double Ge[3][3];
        ms.grad(xq, Ge);
        const double wq = w[q] * detJ;
        for (int i = 0; i < dim; ++i) {
          lv.l2 += wq * std::pow(uh[i] - ue[static_cast<std::size_t>(i)], 2);
          lv.u_l2 += wq * ue[static_cast<std::size_t>(i)] * ue[static_cast<std::size_t>(i)];
          for (int j = 0; j < dim; ++j) {
            lv.h1 += wq * std::pow(Gh[i][j] - Ge[i][j], 2);
            lv.u_h1 += wq * Ge[i][j] * Ge[i][j];
          }
        }
      }
    }
  }
  lv.l2 = std::sqrt(lv.l2), lv.h1 = std::sqrt(lv.h1), lv.u_l2 = std::sqrt(lv.u_l2), lv.u_h1 = std::sqrt(lv.u_h1);
  return lv;
}

// Runs the sizes, prints the table, checks every consecutive rate against the expected one.
void convergence(int dim, int order, const std::vector<double>& sizes, double tol) {
  Manufactured ms;
  ms.dim = dim;
  std::vector<Level> lv;
  for (double s : sizes) lv.push_back(solve_and_measure(ms, order, s));
  const double p_l2 = order + 1, p_h1 = order;
  std::printf("[mms] %dD P%d: size    nodes   cells   h=(1/cells)^(1/d)  L2 error    rate   H1 error    rate   (|u*|_L2 %.3e, |u*|_H1 %.3e)\n", dim,
              order, lv[0].u_l2, lv[0].u_h1);
  for (std::size_t i = 0; i < lv.size(); ++i) {
    double r2 = 0, r1 = 0;
    if (i > 0) {
      const double lh = std::log(lv[i - 1].h / lv[i].h);
      r2 = std::log(lv[i - 1].l2 / lv[i].l2) / lh;
      r1 = std::log(lv[i - 1].h1 / lv[i].h1) / lh;
      EXPECT_NEAR(r2, p_l2, tol) << dim << "D P" << order << " L2 rate, level " << i;
      EXPECT_NEAR(r1, p_h1, tol) << dim << "D P" << order << " H1 rate, level " << i;
    }
    std::printf("[mms]        %6.4f %7zu %7zu  %.4e         %.3e  %5.2f  %.3e  %5.2f\n", sizes[i], lv[i].nodes, lv[i].cells, lv[i].h, lv[i].l2, r2, lv[i].h1, r1);
  }
}

}  // namespace

// The body force by the chain rule equals central differences of P (h = 1e-5).
TEST(ManufacturedSolution, BodyForceMatchesFiniteDifferencesOfP) {
  for (int dim : {2, 3}) {
    Manufactured ms;
    ms.dim = dim;
    const double pts[3][3] = {{0.2, 0.7, 0.4}, {0.55, 0.1, 0.9}, {0.9, 0.45, 0.3}};
    for (const auto& X : pts) {
      const auto b = ms.body_force(X), bfd = ms.body_force_fd(X, 1e-5);
      double scale = 0.0;
      for (int i = 0; i < dim; ++i) scale = std::max(scale, std::abs(b[static_cast<std::size_t>(i)]));
      ASSERT_GT(scale, 0.1);
      for (int i = 0; i < dim; ++i) EXPECT_NEAR(b[static_cast<std::size_t>(i)], bfd[static_cast<std::size_t>(i)], 1e-8 * scale);
    }
  }
}

TEST(ManufacturedSolution, P1Rates2D) { convergence(2, 1, {0.1, 0.05, 0.025}, 0.25); }
TEST(ManufacturedSolution, P2Rates2D) { convergence(2, 2, {0.1, 0.05, 0.025}, 0.25); }
TEST(ManufacturedSolution, P1Rates3D) { convergence(3, 1, {0.2, 0.1}, 0.25); }
