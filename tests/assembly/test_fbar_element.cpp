// F-bar hex8 (assembly/HyperelasticElement.hpp, ElementTechnology::FBar; docs/elements.md):
//  - the element tangent against central finite differences of the element residual, for an
//    elastic law (neo-Hookean, Ciarlet-Geymonat) and for plasticity with an active return map;
//    the tangent is not symmetric (de Souza Neto's Q (x) (G0 - G) term);
//  - patch test: a homogeneous deformation of a distorted 2x2x2 hex8 mesh is reproduced exactly
//    (F-bar residuals equal the full element's, the interior node is in equilibrium);
//  - global: Newton on a distorted 3x3x3 mesh (dense assembly of the element tangents) converges
//    quadratically, elastic nearly incompressible and plastic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "assembly/HyperelasticElement.hpp"
#include "material/Damage.hpp"
#include "material/ElasticLaw.hpp"
#include "material/NeoHookean.hpp"
#include "material/Plasticity.hpp"

using namespace stentor;

namespace {

constexpr int kNd = 24;  // hex8 dofs

// A structured n x n x n hex8 mesh of the unit cube; every node not on a face of the cube is
// moved by up to 0.25 h, face nodes within their face: every cell is distorted.
struct HexMesh {
  int n = 0;
  std::vector<std::array<double, 3>> X;
  std::vector<std::array<int, 8>> cells;
  int node(int i, int j, int k) const { return i + (n + 1) * (j + (n + 1) * k); }
};

HexMesh make_mesh(int n) {
  HexMesh m;
  m.n = n;
  const double h = 1.0 / n;
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const int idx[3] = {i, j, k};
        std::array<double, 3> x{};
        for (int d = 0; d < 3; ++d) {
          x[d] = idx[d] * h;
          if (idx[d] > 0 && idx[d] < n) x[d] += 0.25 * h * std::sin(1.7 * i + 2.3 * j + 3.1 * k + 1.3 * d);
        }
        m.X.push_back(x);
      }
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        m.cells.push_back({m.node(i, j, k), m.node(i + 1, j, k), m.node(i + 1, j + 1, k), m.node(i, j + 1, k),
                           m.node(i, j, k + 1), m.node(i + 1, j, k + 1), m.node(i + 1, j + 1, k + 1), m.node(i, j + 1, k + 1)});
  return m;
}

// One distorted cell (the first of a 2x2x2 mesh, whose interior corner moved).
void one_cell(double (*X)[3]) {
  const HexMesh m = make_mesh(2);
  for (int a = 0; a < 8; ++a)
    for (int d = 0; d < 3; ++d) X[a][d] = m.X[static_cast<std::size_t>(m.cells[7][static_cast<std::size_t>(a)])][static_cast<std::size_t>(d)];
}

// Element residual / tangent / Gauss-point history of one cell.
struct Eval {
  double r[kMaxCellDofs];
  double K[kMaxCellDofs][kMaxCellDofs];
  double energy = 0.0, plastic = 0.0;
  int status = 0;
};

template <class Law>
Eval eval(const Law& law, ElementTechnology tech, const double (*X)[3], const double (*U)[3], const double* hn = nullptr,
          double* h1 = nullptr) {
  const QuadRule q = make_rule(CellType::Hex8, stiffness_quadrature_degree(CellType::Hex8));
  Eval e;
  double dc = 0.0;
  if constexpr (kHasHistory<Law>)
    e.status = solid_element<true>(3, Kinematics::Cartesian, tech, CellType::Hex8, 8, X, U, U, law, ElementTime{}, q, e.r,
                                   e.K, e.energy, dc, CellHistory{hn, h1, Law::kNumHist}, &e.plastic);
  else
    e.status = solid_element<true>(3, Kinematics::Cartesian, tech, CellType::Hex8, 8, X, U, U, law, ElementTime{}, q, e.r,
                                   e.K, e.energy, dc);
  return e;
}

// max |K - FD(r)| / max |K| and the asymmetry max |K - K^T| / max |K| of one cell at U.
template <class Law>
void fd_check(const Law& law, const double (*X)[3], const double (*U)[3], const double* hn, double& err, double& asym) {
  std::vector<double> h1(8 * 64 + 1);
  const Eval e = eval(law, ElementTechnology::FBar, X, U, hn, h1.data());
  ASSERT_EQ(e.status, kElementOk);
  const double h = 1e-7;
  double kmax = 0.0, kerr = 0.0, kasym = 0.0;
  for (int j = 0; j < kNd; ++j) {
    double Up[8][3], Um[8][3];
    std::copy(&U[0][0], &U[0][0] + 24, &Up[0][0]);
    std::copy(&U[0][0], &U[0][0] + 24, &Um[0][0]);
    Up[j / 3][j % 3] += h, Um[j / 3][j % 3] -= h;
    const Eval p = eval(law, ElementTechnology::FBar, X, Up, hn, h1.data());
    const Eval m = eval(law, ElementTechnology::FBar, X, Um, hn, h1.data());
    for (int i = 0; i < kNd; ++i) {
      kmax = std::max(kmax, std::abs(e.K[i][j]));
      kerr = std::max(kerr, std::abs(e.K[i][j] - (p.r[i] - m.r[i]) / (2 * h)));
      kasym = std::max(kasym, std::abs(e.K[i][j] - e.K[j][i]));
    }
  }
  err = kerr / kmax;
  asym = kasym / kmax;
}

// A smooth non-homogeneous displacement (stretch, shear, bending) times amp.
void smooth_displacement(const double (*X)[3], double amp, double (*U)[3]) {
  for (int a = 0; a < 8; ++a) {
    const double x = X[a][0], y = X[a][1], z = X[a][2];
    U[a][0] = amp * (0.10 * x + 0.08 * y * z + 0.05 * std::sin(3 * y));
    U[a][1] = amp * (-0.06 * y + 0.07 * x * x + 0.04 * z);
    U[a][2] = amp * (-0.05 * z + 0.09 * x * y - 0.03 * std::cos(2 * x));
  }
}

std::vector<double> initial_history(int ngp, int nh, const HistoryVar* vars) {
  std::vector<double> h(static_cast<std::size_t>(ngp * nh));
  for (int g = 0; g < ngp; ++g)
    for (int i = 0; i < nh; ++i) h[static_cast<std::size_t>(g * nh + i)] = vars[i].initial;
  return h;
}

// Initial history of `cells` hex8 cells (8 Gauss points each); empty for a law without one.
template <class Law>
std::vector<double> mesh_history(std::size_t cells) {
  std::vector<double> h;
  if constexpr (kHasHistory<Law>)
    for (std::size_t c = 0; c < cells; ++c) {
      const auto hc = initial_history(8, Law::kNumHist, Law::kHistory);
      h.insert(h.end(), hc.begin(), hc.end());
    }
  return h;
}

}  // namespace

TEST(FBarElement, ElasticTangentAgainstFiniteDifferences) {
  double X[8][3], U[8][3];
  one_cell(X);
  smooth_displacement(X, 1.0, U);
  double err = 0.0, asym = 0.0;
  fd_check(NeoHookean{1.0, 500.0}, X, U, nullptr, err, asym);
  std::printf("[fbar element] neo-Hookean lambda/mu = 500: max |K - FD(r)|/max|K| %.2e, max |K - K^T|/max|K| %.2e\n", err, asym);
  EXPECT_LT(err, 1e-6);
  EXPECT_GT(asym, 1e-3);  // de Souza Neto's term: F-bar is not the derivative of a potential
  fd_check(CiarletGeymonat{1.0, 0.3, 20.0}, X, U, nullptr, err, asym);
  std::printf("[fbar element] Ciarlet-Geymonat: max |K - FD(r)|/max|K| %.2e, max |K - K^T|/max|K| %.2e\n", err, asym);
  EXPECT_LT(err, 1e-6);
  EXPECT_GT(asym, 1e-3);
}

// The other laws through the same element code: Mooney-Rivlin and Holzapfel-Gasser-Ogden
// (fibres at the Gauss points) behind the ElasticLaw dispatch, neo-Hookean plasticity and
// damage with history.
TEST(FBarElement, EveryLawTangentAgainstFiniteDifferences) {
  double X[8][3], U[8][3];
  one_cell(X);
  smooth_displacement(X, 1.0, U);
  double err = 0.0, asym = 0.0;
  fd_check(ElasticLaw::mooney_rivlin(MooneyRivlin{0.4, 0.1, 50.0}), X, U, nullptr, err, asym);
  std::printf("[fbar element] Mooney-Rivlin: max |K - FD(r)|/max|K| %.2e\n", err);
  EXPECT_LT(err, 1e-6);
  const HolzapfelGasserOgden hgo{NeoHookean{1.0, 50.0}, 2.0, 1.0, {1.0, 0.0, 0.0}, {1.0, 0.0, 0.0}};
  fd_check(ElasticLaw::holzapfel_gasser_ogden(hgo, FibreFrame{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 0.5}), X, U, nullptr, err, asym);
  std::printf("[fbar element] Holzapfel-Gasser-Ogden: max |K - FD(r)|/max|K| %.2e\n", err);
  EXPECT_LT(err, 1e-6);
  using NHP = NeoHookeanPlasticity;
  const std::vector<double> hp = initial_history(8, NHP::kNumHist, NHP::kHistory);
  fd_check(NHP{NeoHookean{1.0, 50.0}, 0.02, 0.1}, X, U, hp.data(), err, asym);
  std::printf("[fbar element] neo-Hookean plasticity: max |K - FD(r)|/max|K| %.2e\n", err);
  EXPECT_LT(err, 1e-6);
  using Dmg = IsotropicDamage<NeoHookean>;
  const std::vector<double> hd = initial_history(8, Dmg::kNumHist, Dmg::kHistory);
  fd_check(Dmg{NeoHookean{1.0, 50.0}, 0.5, 0.05}, X, U, hd.data(), err, asym);
  std::printf("[fbar element] neo-Hookean damage: max |K - FD(r)|/max|K| %.2e\n", err);
  EXPECT_LT(err, 1e-6);
}

TEST(FBarElement, PlasticTangentAgainstFiniteDifferences) {
  double X[8][3], U[8][3];
  one_cell(X);
  smooth_displacement(X, 1.0, U);
  using Law = CiarletGeymonatPlasticity;
  for (double H : {0.0, 0.2}) {
    const Law law{CiarletGeymonat{1.0, 0.3, 20.0}, 0.02, H};
    const std::vector<double> hn = initial_history(8, Law::kNumHist, Law::kHistory);
    std::vector<double> h1(hn.size());
    const Eval e = eval(law, ElementTechnology::FBar, X, U, hn.data(), h1.data());
    ASSERT_EQ(e.status, kElementOk);
    int yielding = 0;
    for (int g = 0; g < 8; ++g) yielding += h1[static_cast<std::size_t>(g * Law::kNumHist + Law::kYielding)] > 0.5;
    EXPECT_EQ(yielding, 8) << "every Gauss point's return map is active";
    EXPECT_GT(e.plastic, 0.0);
    double err = 0.0, asym = 0.0;
    fd_check(law, X, U, hn.data(), err, asym);
    std::printf("[fbar element] Ciarlet-Geymonat plasticity H = %.1f, %d/8 points yielding: max |K - FD(r)|/max|K| %.2e, "
                "asymmetry %.2e\n",
                H, yielding, err, asym);
    EXPECT_LT(err, 1e-6);
  }
}

namespace {

// Global residual (and dense tangent) of the mesh at the nodal displacements u (3 per node).
// hn/h1: per cell 8 Gauss points of history (laws with history), or empty.
template <class Law>
void assemble(const HexMesh& m, const Law& law, ElementTechnology tech, const std::vector<double>& u, const std::vector<double>& hn,
              std::vector<double>& h1, std::vector<double>& r, std::vector<double>* K, std::vector<Eval>* cells = nullptr) {
  const std::size_t nd = 3 * m.X.size();
  r.assign(nd, 0.0);
  if (K) K->assign(nd * nd, 0.0);
  const int stride = 8 * LawHistorySize<Law>::value;
  for (std::size_t c = 0; c < m.cells.size(); ++c) {
    double X[8][3], U[8][3];
    for (int a = 0; a < 8; ++a)
      for (int d = 0; d < 3; ++d) {
        const std::size_t n = static_cast<std::size_t>(m.cells[c][static_cast<std::size_t>(a)]);
        X[a][d] = m.X[n][static_cast<std::size_t>(d)];
        U[a][d] = u[3 * n + static_cast<std::size_t>(d)];
      }
    const Eval e = stride > 0 ? eval(law, tech, X, U, hn.data() + c * stride, h1.data() + c * stride) : eval(law, tech, X, U);
    ASSERT_EQ(e.status, kElementOk);
    if (cells) cells->push_back(e);
    for (int i = 0; i < kNd; ++i) {
      const std::size_t gi = 3 * static_cast<std::size_t>(m.cells[c][static_cast<std::size_t>(i / 3)]) + i % 3;
      r[gi] += e.r[i];
      if (K)
        for (int j = 0; j < kNd; ++j) {
          const std::size_t gj = 3 * static_cast<std::size_t>(m.cells[c][static_cast<std::size_t>(j / 3)]) + j % 3;
          (*K)[gi * nd + gj] += e.K[i][j];
        }
    }
  }
}

// Solves A x = b (dense, n x n, row-major) by Gaussian elimination with partial pivoting.
std::vector<double> solve_dense(std::vector<double> A, std::vector<double> b) {
  const std::size_t n = b.size();
  for (std::size_t k = 0; k < n; ++k) {
    std::size_t p = k;
    for (std::size_t i = k + 1; i < n; ++i)
      if (std::abs(A[i * n + k]) > std::abs(A[p * n + k])) p = i;
    if (p != k) {
      for (std::size_t j = 0; j < n; ++j) std::swap(A[k * n + j], A[p * n + j]);
      std::swap(b[k], b[p]);
    }
    for (std::size_t i = k + 1; i < n; ++i) {
      const double f = A[i * n + k] / A[k * n + k];
      for (std::size_t j = k; j < n; ++j) A[i * n + j] -= f * A[k * n + j];
      b[i] -= f * b[k];
    }
  }
  std::vector<double> x(n);
  for (std::size_t k = n; k-- > 0;) {
    double s = b[k];
    for (std::size_t j = k + 1; j < n; ++j) s -= A[k * n + j] * x[j];
    x[k] = s / A[k * n + k];
  }
  return x;
}

bool on_boundary(const std::array<double, 3>& x) {
  for (double v : x)
    if (v < 1e-12 || v > 1.0 - 1e-12) return true;
  return false;
}

// The homogeneous deformation u = (F - I) X.
std::vector<double> affine(const HexMesh& m, const double (&F)[3][3]) {
  std::vector<double> u(3 * m.X.size());
  for (std::size_t n = 0; n < m.X.size(); ++n)
    for (int i = 0; i < 3; ++i) {
      double s = -m.X[n][static_cast<std::size_t>(i)];
      for (int J = 0; J < 3; ++J) s += F[i][J] * m.X[n][static_cast<std::size_t>(J)];
      u[3 * n + static_cast<std::size_t>(i)] = s;
    }
  return u;
}

constexpr double kF[3][3] = {{1.08, 0.12, -0.05}, {0.03, 0.93, 0.07}, {-0.04, 0.06, 1.02}};

template <class Law>
void patch_test(const Law& law, const char* name) {
  const HexMesh m = make_mesh(2);
  const std::vector<double> u = affine(m, kF);
  const std::vector<double> hn = mesh_history<Law>(m.cells.size());
  std::vector<double> h1(hn.size()), h1f(hn.size()), r, rf;
  std::vector<Eval> cb, cf;
  assemble(m, law, ElementTechnology::FBar, u, hn, h1, r, nullptr, &cb);
  assemble(m, law, ElementTechnology::Full, u, hn, h1f, rf, nullptr, &cf);
  double rmax = 0.0, diff = 0.0, interior = 0.0, hdiff = 0.0;
  for (std::size_t c = 0; c < cb.size(); ++c)
    for (int i = 0; i < kNd; ++i) {
      rmax = std::max(rmax, std::abs(cf[c].r[i]));
      diff = std::max(diff, std::abs(cb[c].r[i] - cf[c].r[i]));
    }
  for (std::size_t n = 0; n < m.X.size(); ++n)
    if (!on_boundary(m.X[n]))
      for (int d = 0; d < 3; ++d) interior = std::max(interior, std::abs(r[3 * n + static_cast<std::size_t>(d)]));
  for (std::size_t k = 0; k < h1.size(); ++k) hdiff = std::max(hdiff, std::abs(h1[k] - h1f[k]));
  std::printf("[fbar patch] %s, distorted 2x2x2 hex8, homogeneous F: max |r_fbar - r_full|/max|r| %.1e, interior node "
              "|r|/max|r| %.1e, max |history difference| %.1e\n",
              name, diff / rmax, interior / rmax, hdiff);
  EXPECT_GT(rmax, 1e-3);
  EXPECT_LT(diff / rmax, 1e-12);
  EXPECT_LT(interior / rmax, 1e-12);
  EXPECT_LT(hdiff, 1e-12);
}

}  // namespace

TEST(FBarElement, HomogeneousDeformationPatchTest) {
  patch_test(NeoHookean{1.0, 500.0}, "neo-Hookean");
  patch_test(CiarletGeymonatPlasticity{CiarletGeymonat{1.0, 0.3, 20.0}, 0.02, 0.1}, "Ciarlet-Geymonat plasticity");
}

namespace {

// Newton on the distorted 3x3x3 mesh: z = 0 clamped, z = 1 moved by (0.02, 0, -0.015) in 4
// equal steps (history committed after each), the rest free; full Newton steps from a
// predictor (no line search: at lambda/mu = 1000, or with plasticity, steps 4 times larger
// leave its basin). Returns |r_free| per iteration (iterate 0 first) of each step.
template <class Law>
std::vector<std::vector<double>> newton(const Law& law, std::vector<double> hn) {
  const HexMesh m = make_mesh(3);
  const std::size_t nd = 3 * m.X.size();
  std::vector<double> u(nd, 0.0);
  std::vector<std::size_t> free, top;
  for (std::size_t n = 0; n < m.X.size(); ++n)
    for (std::size_t d = 0; d < 3; ++d) {
      const double z = m.X[n][2];
      if (z > 1.0 - 1e-12) top.push_back(3 * n + d);
      if (z > 1e-12 && z < 1.0 - 1e-12) free.push_back(3 * n + d);
    }
  const int steps = 4;
  std::vector<std::vector<double>> all;
  std::vector<double> h1(hn.size()), r, K;
  for (int step = 1; step <= steps; ++step) {
    // The top's increment, and the predictor: the free nodes moved by it times z.
    const double inc[3] = {0.02 / steps, 0.0, -0.015 / steps};
    for (std::size_t k : top) u[k] += inc[k % 3];
    for (std::size_t k : free) u[k] += m.X[k / 3][2] * inc[k % 3];
    std::vector<double> norms;
    for (int it = 0; it < 12; ++it) {
      assemble(m, law, ElementTechnology::FBar, u, hn, h1, r, &K);
      const std::size_t nf = free.size();
      std::vector<double> Kf(nf * nf), rf(nf);
      double nr = 0.0;
      for (std::size_t i = 0; i < nf; ++i) {
        rf[i] = -r[free[i]];
        nr += rf[i] * rf[i];
        for (std::size_t j = 0; j < nf; ++j) Kf[i * nf + j] = K[free[i] * nd + free[j]];
      }
      norms.push_back(std::sqrt(nr));
      if (norms.back() < 1e-12 * norms.front()) break;
      const std::vector<double> du = solve_dense(Kf, rf);
      for (std::size_t i = 0; i < nf; ++i) u[free[i]] += du[i];
    }
    hn = h1;
    all.push_back(norms);
  }
  return all;
}

// Quadratic convergence of every step: once |r| < 1e-3 |r_0|, each iterate's relative
// residual is below 100 times the square of the previous one, down to 1e-10 (round-off at
// lambda/mu = 1000 is ~1e-12). Linear convergence would leave b ~ rho a >> 100 a^2 there.
void expect_quadratic(const std::vector<std::vector<double>>& steps, const char* name) {
  int checked = 0;
  for (const auto& norms : steps) {
    std::printf("[fbar newton] %s:", name);
    for (double v : norms) std::printf(" %.2e", v / norms.front());
    std::printf("\n");
    ASSERT_GE(norms.size(), 3u);
    EXPECT_LT(norms.back(), 1e-12 * norms.front()) << name << ": Newton did not converge";
    EXPECT_LE(norms.size(), 9u) << name;
    for (std::size_t k = 0; k + 1 < norms.size(); ++k) {
      const double a = norms[k] / norms.front(), b = norms[k + 1] / norms.front();
      if (a < 1e-3 && b > 1e-10) {
        EXPECT_LT(b, 100.0 * a * a) << name << ": iteration " << k + 1;
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, 2) << name << ": no iterate in the quadratic range";
}

}  // namespace

TEST(FBarElement, GlobalNewtonConvergesQuadratically) {
  expect_quadratic(newton(NeoHookean{1.0, 1000.0}, {}), "neo-Hookean lambda/mu = 1000");
  using Law = CiarletGeymonatPlasticity;
  const Law law{CiarletGeymonat{1.0, 0.3, 10.0}, 0.02, 0.05};
  expect_quadratic(newton(law, mesh_history<Law>(27)), "Ciarlet-Geymonat plasticity");
}
