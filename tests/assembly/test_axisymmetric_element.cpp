// Axisymmetric element kernels (assembly/HyperelasticElement.hpp, assembly/PressureElement.hpp;
// docs/axisymmetric.md) one cell at a time:
//  - the residual is the derivative of the stored energy and the tangent that of the residual
//    (central finite differences), tri3, tri6 and quad4, cells away from and touching the axis,
//    end point and Gonzalez stresses, with viscosity;
//  - the follower-pressure tangent against finite differences of its residual (revolved edge);
//  - volumes and masses of the full revolution (Pappus), and the hoop stretch 1 + u_r/R.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

#include "assembly/HyperelasticElement.hpp"
#include "assembly/PressureElement.hpp"
#include "material/Damage.hpp"
#include "material/ElasticLaw.hpp"
#include "material/NeoHookean.hpp"
#include "material/Plasticity.hpp"

using namespace stentor;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Cell {
  CellType type;
  int nn;
  double X[kMaxCellNodes][3];
};

// A distorted cell with its lowest-left node at r = r0 (r0 = 0: an edge on the axis).
Cell make_cell(CellType t, double r0) {
  Cell c{t, cell_num_nodes(t), {}};
  const double tri[6][2] = {{0, 0}, {0.9, 0.1}, {0.2, 0.8}, {0.45, 0.05}, {0.55, 0.45}, {0.1, 0.4}};
  const double quad[4][2] = {{0, 0}, {1.0, 0.1}, {0.9, 0.8}, {0.0, 0.7}};
  for (int a = 0; a < c.nn; ++a) {
    const double* p = t == CellType::Quad4 ? quad[a] : tri[a];
    c.X[a][0] = r0 + (a == 0 || (t == CellType::Quad4 && a == 3) ? 0.0 : p[0]);
    c.X[a][1] = p[1];
    c.X[a][2] = 0.0;
  }
  if (t == CellType::Tri3 || t == CellType::Tri6) c.X[2][0] = r0 + (r0 == 0.0 ? 0.0 : 0.2), c.X[5][0] = r0 + (r0 == 0.0 ? 0.0 : 0.1);
  return c;
}

// A smooth displacement of the cell's nodes (stretch, shear, hoop) times amp, u_r = 0 on the axis.
void displacement(const Cell& c, double amp, double phase, double (*U)[3]) {
  for (int a = 0; a < c.nn; ++a) {
    const double r = c.X[a][0], z = c.X[a][1];
    U[a][0] = amp * (0.12 * r + 0.07 * r * z + phase * r * r);
    U[a][1] = amp * (-0.05 * z + 0.06 * std::sin(r + z) + phase * z * z);
    U[a][2] = 0.0;
  }
}

struct Eval {
  std::vector<double> r;
  std::vector<std::vector<double>> K;
  double energy = 0.0, dissipation = 0.0;
  int status = 0;
};

Eval eval(const Cell& c, const double (*U)[3], const double (*U0)[3], const ElementTime& et) {
  const NeoHookean law{1.0, 3.0};
  const QuadRule q = make_rule(c.type, stiffness_quadrature_degree(c.type));
  double re[kMaxCellDofs], ke[kMaxCellDofs][kMaxCellDofs];
  Eval e;
  e.status = solid_element<true>(2, Kinematics::Axisymmetric, ElementTechnology::Full, c.type, c.nn, c.X, U, U0, law, et, q, re, ke, e.energy, e.dissipation);
  const int nd = 2 * c.nn;
  e.r.assign(re, re + nd);
  for (int i = 0; i < nd; ++i) e.K.emplace_back(ke[i], ke[i] + nd);
  return e;
}

// Central differences (h = 1e-6) in each of the cell's nd displacement components at U of
// the residual and the energy of eval_at, against e = eval_at(U): max |K|, max |K - FD(r)|,
// max |r|, max |r - FD(E)|.
struct FdErrors {
  double kmax = 0, kerr = 0, rmax = 0, rerr = 0;
};
template <class E, class F>
FdErrors fd_errors(int nd, const double (*U)[3], const E& e, F eval_at) {
  const double h = 1e-6;
  FdErrors f;
  for (int j = 0; j < nd; ++j) {
    double Up[kMaxCellNodes][3], Um[kMaxCellNodes][3];
    std::copy(&U[0][0], &U[0][0] + 3 * kMaxCellNodes, &Up[0][0]);
    std::copy(&U[0][0], &U[0][0] + 3 * kMaxCellNodes, &Um[0][0]);
    Up[j / 2][j % 2] += h, Um[j / 2][j % 2] -= h;
    const E p = eval_at(Up), m = eval_at(Um);
    const auto sj = static_cast<std::size_t>(j);
    for (int i = 0; i < nd; ++i) {
      const auto si = static_cast<std::size_t>(i);
      f.kmax = std::max(f.kmax, std::abs(e.K[si][sj]));
      f.kerr = std::max(f.kerr, std::abs(e.K[si][sj] - (p.r[si] - m.r[si]) / (2 * h)));
    }
    f.rmax = std::max(f.rmax, std::abs(e.r[sj]));
    f.rerr = std::max(f.rerr, std::abs(e.r[sj] - (p.energy - m.energy) / (2 * h)));
  }
  return f;
}

// max |K - FD(r)| / max |K| and max |r - FD(E)| / max |r| at U (U0 = u_n when et.has_old);
// the largest of each is kept in `worst` (tangent, residual).
void expect_consistent(const Cell& c, const ElementTime& et, const char* what, double* worst) {
  double U[kMaxCellNodes][3], U0[kMaxCellNodes][3];
  displacement(c, 1.0, 0.03, U);
  displacement(c, 0.7, -0.02, U0);
  const Eval e = eval(c, U, U0, et);
  ASSERT_EQ(e.status, kElementOk) << what;
  const auto [kmax, kerr, rmax, rerr] = fd_errors(2 * c.nn, U, e, [&](const double (*V)[3]) { return eval(c, V, U0, et); });
  EXPECT_GT(kmax, 0.1) << what;
  EXPECT_LT(kerr / kmax, 1e-7) << what << ": tangent against FD of the residual";
  worst[0] = std::max(worst[0], kerr / kmax);
  if (!et.has_old) worst[1] = std::max(worst[1], rerr / rmax);
  // The residual is dE/du only for a stress that is the energy's derivative at the end point.
  if (!et.has_old) {
    EXPECT_GT(rmax, 1e-3) << what;
    EXPECT_LT(rerr / rmax, 1e-7) << what << ": residual against FD of the stored energy";
  }
}

const CellType kTypes[] = {CellType::Tri3, CellType::Tri6, CellType::Quad4};

}  // namespace

TEST(AxisymmetricElement, ResidualAndTangentAgainstFiniteDifferences) {
  double worst[2] = {0.0, 0.0};
  for (CellType t : kTypes)
    for (double r0 : {0.6, 0.0}) {
      const Cell c = make_cell(t, r0);
      SCOPED_TRACE(std::string(cell_name(t)) + (r0 == 0.0 ? " on the axis" : " off the axis"));
      expect_consistent(c, ElementTime{}, "end point", worst);
      ElementTime g;
      g.eval = StressEval::Gonzalez;
      g.has_old = true;
      g.dt = 0.1;
      g.eta = 0.05;
      expect_consistent(c, g, "Gonzalez with viscosity", worst);
      ElementTime mid = g;
      mid.eval = StressEval::Midpoint;
      mid.eta = 0.0;
      expect_consistent(c, mid, "midpoint", worst);
    }
  std::printf("[axisymmetric element] tri3/tri6/quad4, on and off the axis: max |K - FD(r)|/max|K| %.1e, "
              "max |r - FD(E)|/max|r| %.1e\n",
              worst[0], worst[1]);
}

// A cell whose edge lies on the axis: the nodes there carry no hoop strain of their own
// (their N_a/R stays bounded at the Gauss points), the values are finite.
TEST(AxisymmetricElement, CellOnTheAxisIsFinite) {
  for (CellType t : kTypes) {
    const Cell c = make_cell(t, 0.0);
    double U[kMaxCellNodes][3];
    displacement(c, 1.0, 0.0, U);
    const Eval e = eval(c, U, U, ElementTime{});
    ASSERT_EQ(e.status, kElementOk) << cell_name(t);
    for (double v : e.r) EXPECT_TRUE(std::isfinite(v)) << cell_name(t);
    for (const auto& row : e.K)
      for (double v : row) EXPECT_TRUE(std::isfinite(v)) << cell_name(t);
    EXPECT_TRUE(std::isfinite(e.energy));
  }
}

// Homogeneous u_r = a r, u_z = b z: F = diag(1 + a, 1 + b, 1 + a) at every point, so the
// energy is W(F) times the revolved volume, and the mass matrix sums to rho times that
// volume per direction (Pappus: 2 pi times the centroid's radius times the area).
TEST(AxisymmetricElement, HomogeneousStateAndRevolvedVolume) {
  const NeoHookean law{1.0, 3.0};
  const double a = 0.08, b = -0.04, rho = 2.5;
  for (CellType t : kTypes) {
    const Cell c = make_cell(t, 0.3);
    double U[kMaxCellNodes][3];
    for (int n = 0; n < c.nn; ++n) U[n][0] = a * c.X[n][0], U[n][1] = b * c.X[n][1], U[n][2] = 0.0;
    // Area and first moment by the shoelace formula over the straight-sided outline.
    const int corners = t == CellType::Quad4 ? 4 : 3;
    double A = 0, Sr = 0;
    for (int i = 0; i < corners; ++i) {
      const double* p = c.X[i];
      const double* q = c.X[(i + 1) % corners];
      const double cr = p[0] * q[1] - q[0] * p[1];
      A += 0.5 * cr;
      Sr += cr * (p[0] + q[0]) / 6.0;
    }
    const double volume = 2 * kPi * Sr;
    ASSERT_GT(A, 0.0);
    const Eval e = eval(c, U, U, ElementTime{});
    ASSERT_EQ(e.status, kElementOk);
    Mat3 F = Mat3::identity();
    F(0, 0) = 1 + a, F(1, 1) = 1 + b, F(2, 2) = 1 + a;
    const double W = law.energy(tmul(F, F));
    // Tri3 integrates the energy with one point (exact here: the integrand is W times R).
    EXPECT_NEAR(e.energy, W * volume, 1e-13 * W * volume) << cell_name(t);
    double M[kMaxCellDofs][kMaxCellDofs];
    mass_element(2, Kinematics::Axisymmetric, t, c.nn, c.X, rho, make_rule(t, default_quadrature_degree(t)), M);
    double total = 0;
    for (int i = 0; i < 2 * c.nn; i += 2)
      for (int j = 0; j < 2 * c.nn; j += 2) total += M[i][j];
    EXPECT_NEAR(total, rho * volume, 1e-13 * rho * volume) << cell_name(t);
  }
}

// Follower pressure on a revolved edge: the residual is p times the current ring's normal
// area, and the tangent (theta = 1/2) matches finite differences of it.
TEST(AxisymmetricElement, PressureTangentAgainstFiniteDifferences) {
  for (CellType t : {CellType::Line2, CellType::Line3}) {
    const int nn = cell_num_nodes(t);
    double X[kMaxCellNodes][3] = {{0.7, 0.2, 0}, {1.3, 0.9, 0}, {1.05, 0.5, 0}};
    double U[kMaxCellNodes][3] = {{0.05, -0.02, 0}, {0.11, 0.03, 0}, {0.09, 0.02, 0}};
    const QuadRule q = make_rule(t, 2 * cell_order(t) + 1);
    const double p = 1.7, theta = 0.5;
    double re[kMaxCellDofs], ke[kMaxCellDofs][kMaxCellDofs];
    pressure_element(2, Kinematics::Axisymmetric, t, nn, X, U, p, theta, q, re, ke);
    const double h = 1e-6;
    double err = 0, kmax = 0;
    for (int j = 0; j < 2 * nn; ++j) {
      double rp[kMaxCellDofs], rm[kMaxCellDofs], kd[kMaxCellDofs][kMaxCellDofs];
      U[j / 2][j % 2] += h;
      pressure_element(2, Kinematics::Axisymmetric, t, nn, X, U, p, theta, q, rp, kd);
      U[j / 2][j % 2] -= 2 * h;
      pressure_element(2, Kinematics::Axisymmetric, t, nn, X, U, p, theta, q, rm, kd);
      U[j / 2][j % 2] += h;
      for (int i = 0; i < 2 * nn; ++i) {
        kmax = std::max(kmax, std::abs(ke[i][j]));
        err = std::max(err, std::abs(ke[i][j] - theta * (rp[i] - rm[i]) / (2 * h)));
      }
    }
    EXPECT_GT(kmax, 0.1);
    EXPECT_LT(err / kmax, 1e-8) << cell_name(t);
    std::printf("[axisymmetric element] pressure on a revolved %s: |K - theta FD(r)|/max|K| %.1e\n", cell_name(t), err / kmax);
    if (t == CellType::Line2) {
      // Straight edge from x0 to x1: sum_a r_a = p 2 pi int x_r (dz, -dr) = p pi (r0 + r1) (z1 - z0, -(r1 - r0)).
      const double r0 = X[0][0] + U[0][0], z0 = X[0][1] + U[0][1], r1 = X[1][0] + U[1][0], z1 = X[1][1] + U[1][1];
      EXPECT_NEAR(re[0] + re[2], p * kPi * (r0 + r1) * (z1 - z0), 1e-13);
      EXPECT_NEAR(re[1] + re[3], -p * kPi * (r0 + r1) * (r1 - r0), 1e-13);
    }
  }
}

// ---------------------------------------------------------------------------------------
// The other laws in axisymmetry, through the same kernel as the assembler runs them:
// Ciarlet-Geymonat and Mooney-Rivlin as the device-side ElasticLaw, and the neo-Hookean
// damage law with its Gauss-point history (CellHistory). For each:
//  - the homogeneous state u = (a r, b z): F = diag(1 + a, 1 + b, 1 + a), the energy is
//    W(F) times the revolved volume (damage: (1 - g(W0)) W0, g(W0) = d_inf (1 - exp(-W0/beta))
//    from a virgin state, and every point's history holds alpha = W0 and d = g(W0));
//  - the tangent against central differences of the residual, and the residual against
//    central differences of the energy, tri3/tri6/quad4 on and off the axis. For damage the
//    residual is dE/du only where the damage does not grow (a history whose alpha exceeds
//    every W0 reached: the elastic (1 - d) W0 branch); the loading branch's tangent
//    (with -g' S0 (x) S0) is checked against the residual from a virgin state.
namespace {

// The ElasticLaw of a deck's Ciarlet-Geymonat and Mooney-Rivlin with mu = 1, lambda = 3
// (docs/deck.md: CG C1 = mu/2 - C2, D = lambda/4 - C2; MR C1 = mu/2 - C2, lam = lambda - 4 C2).
const ElasticLaw kCiarletGeymonat = ElasticLaw::ciarlet_geymonat(CiarletGeymonat{0.4, 0.1, 0.65});
const ElasticLaw kMooneyRivlin = ElasticLaw::mooney_rivlin(MooneyRivlin{0.35, 0.15, 2.4});
const IsotropicDamage<NeoHookean> kDamage{NeoHookean{1.0, 3.0}, 0.6, 0.02};

template <class Law>
struct LawEval {
  std::vector<double> r;
  std::vector<std::vector<double>> K;
  std::vector<double> h1;  // trial history, kNumHist per Gauss point (laws with history)
  double energy = 0.0, dissipation = 0.0, damage_dissipation = 0.0;
  int status = 0;
};

// One end-point evaluation of the cell with `law`; hn: the committed history row per point
// (laws with history; the same row at every point).
template <class Law>
LawEval<Law> eval_law(const Law& law, const Cell& c, const double (*U)[3], const std::vector<double>& hn_row) {
  const QuadRule q = make_rule(c.type, stiffness_quadrature_degree(c.type));
  double re[kMaxCellDofs], ke[kMaxCellDofs][kMaxCellDofs];
  LawEval<Law> e;
  if constexpr (std::is_same_v<Law, ElasticLaw>) {
    e.status = solid_element<true>(2, Kinematics::Axisymmetric, ElementTechnology::Full, c.type, c.nn, c.X, U, U, law, ElementTime{}, q,
                                   re, ke, e.energy, e.dissipation);
  } else {
    const int nh = Law::kNumHist;
    std::vector<double> hn;
    for (int g = 0; g < q.n; ++g) hn.insert(hn.end(), hn_row.begin(), hn_row.end());
    e.h1.assign(static_cast<std::size_t>(q.n * nh), -1.0);
    const CellHistory hist{hn.data(), e.h1.data(), nh};
    e.status = solid_element<true>(2, Kinematics::Axisymmetric, ElementTechnology::Full, c.type, c.nn, c.X, U, U, law, ElementTime{}, q,
                                   re, ke, e.energy, e.dissipation, hist, &e.damage_dissipation);
  }
  const int nd = 2 * c.nn;
  e.r.assign(re, re + nd);
  for (int i = 0; i < nd; ++i) e.K.emplace_back(ke[i], ke[i] + nd);
  return e;
}

// Worst relative errors (tangent vs FD(r), residual vs FD(E)) over the cells; check_residual:
// whether the residual is the energy's derivative for this history.
template <class Law>
void law_fd(const Law& law, const std::vector<double>& hn_row, bool check_residual, const char* name) {
  double worst_k = 0, worst_r = 0;
  for (CellType t : kTypes)
    for (double r0 : {0.6, 0.0}) {
      const Cell c = make_cell(t, r0);
      SCOPED_TRACE(std::string(name) + ", " + cell_name(t) + (r0 == 0.0 ? " on the axis" : " off the axis"));
      double U[kMaxCellNodes][3];
      displacement(c, 1.0, 0.03, U);
      const LawEval<Law> e = eval_law(law, c, U, hn_row);
      ASSERT_EQ(e.status, kElementOk);
      const auto [kmax, kerr, rmax, rerr] = fd_errors(2 * c.nn, U, e, [&](const double (*V)[3]) { return eval_law(law, c, V, hn_row); });
      EXPECT_GT(kmax, 0.1);
      EXPECT_LT(kerr / kmax, 1e-7) << "tangent against FD of the residual";
      worst_k = std::max(worst_k, kerr / kmax);
      if (check_residual) {
        EXPECT_GT(rmax, 1e-3);
        EXPECT_LT(rerr / rmax, 1e-7) << "residual against FD of the stored energy";
        worst_r = std::max(worst_r, rerr / rmax);
      }
    }
  std::printf("[axisymmetric element] %s, tri3/tri6/quad4 on and off the axis: max |K - FD(r)|/max|K| %.1e", name, worst_k);
  if (check_residual) std::printf(", max |r - FD(E)|/max|r| %.1e", worst_r);
  std::printf("\n");
}

// The homogeneous state's energy against W(F) V (the law's W from its own closed form, w).
template <class Law, class W>
void law_homogeneous(const Law& law, const std::vector<double>& hn_row, W w, const char* name) {
  const double a = 0.08, b = -0.04;
  Mat3 F = Mat3::identity();
  F(0, 0) = 1 + a, F(1, 1) = 1 + b, F(2, 2) = 1 + a;
  const double Wf = w(F);
  ASSERT_GT(Wf, 0.0);
  double worst = 0;
  for (CellType t : kTypes) {
    const Cell c = make_cell(t, 0.3);
    double U[kMaxCellNodes][3];
    for (int n = 0; n < c.nn; ++n) U[n][0] = a * c.X[n][0], U[n][1] = b * c.X[n][1], U[n][2] = 0.0;
    const int corners = t == CellType::Quad4 ? 4 : 3;
    double Sr = 0;
    for (int i = 0; i < corners; ++i) {
      const double* p = c.X[i];
      const double* q = c.X[(i + 1) % corners];
      Sr += (p[0] * q[1] - q[0] * p[1]) * (p[0] + q[0]) / 6.0;
    }
    const double volume = 2 * kPi * Sr;
    const LawEval<Law> e = eval_law(law, c, U, hn_row);
    ASSERT_EQ(e.status, kElementOk) << cell_name(t);
    EXPECT_NEAR(e.energy, Wf * volume, 1e-13 * Wf * volume) << name << ", " << cell_name(t);
    worst = std::max(worst, std::abs(e.energy - Wf * volume) / (Wf * volume));
    if constexpr (!std::is_same_v<Law, ElasticLaw>) {
      // Every point loads from the virgin state: alpha = W0(F), d = g(W0), dissipation d W0 V.
      const double W0 = law.elastic.energy(tmul(F, F)), d = law.d_inf * (1.0 - std::exp(-W0 / law.beta));
      EXPECT_GT(d, 0.1) << "the state must damage the law noticeably";
      for (std::size_t g = 0; g < e.h1.size(); g += Law::kNumHist) {
        EXPECT_NEAR(e.h1[g + Law::kMaxEnergy], W0, 1e-14) << cell_name(t);
        EXPECT_NEAR(e.h1[g + Law::kDamage], d, 1e-14) << cell_name(t);
      }
      EXPECT_NEAR(e.damage_dissipation, d * W0 * volume, 1e-13 * W0 * volume) << cell_name(t);
    }
  }
  std::printf("[axisymmetric element] %s, homogeneous u = (%.2f r, %.2f z): W(F) = %.10e, max |E - W V|/(W V) %.1e\n", name, a, b, Wf,
              worst);
}

}  // namespace

TEST(AxisymmetricElement, CiarletGeymonatHomogeneousStateAndTangent) {
  // W = C1 (I1 - 3) + C2 (I2 - 3) + D (I3 - 1) - (C1 + 2 C2 + D) ln I3 at C = F^T F.
  law_homogeneous(kCiarletGeymonat, {}, [](const Mat3& F) {
    const double l[3] = {F(0, 0) * F(0, 0), F(1, 1) * F(1, 1), F(2, 2) * F(2, 2)};  // eigenvalues of C
    const double I1 = l[0] + l[1] + l[2], I2 = l[0] * l[1] + l[1] * l[2] + l[2] * l[0], I3 = l[0] * l[1] * l[2];
    const double C1 = 0.4, C2 = 0.1, D = 0.65;
    return C1 * (I1 - 3) + C2 * (I2 - 3) + D * (I3 - 1) - (C1 + 2 * C2 + D) * std::log(I3);
  }, "Ciarlet-Geymonat");
  law_fd(kCiarletGeymonat, {}, true, "Ciarlet-Geymonat");
}

TEST(AxisymmetricElement, MooneyRivlinHomogeneousStateAndTangent) {
  // W = C1 (I1 - 3) + C2 (I2 - 3) - 2 (C1 + 2 C2) ln J + lam/2 (ln J)^2.
  law_homogeneous(kMooneyRivlin, {}, [](const Mat3& F) {
    const double l[3] = {F(0, 0) * F(0, 0), F(1, 1) * F(1, 1), F(2, 2) * F(2, 2)};
    const double I1 = l[0] + l[1] + l[2], I2 = l[0] * l[1] + l[1] * l[2] + l[2] * l[0], lnJ = 0.5 * std::log(l[0] * l[1] * l[2]);
    const double C1 = 0.35, C2 = 0.15, lam = 2.4;
    return C1 * (I1 - 3) + C2 * (I2 - 3) - 2 * (C1 + 2 * C2) * lnJ + 0.5 * lam * lnJ * lnJ;
  }, "Mooney-Rivlin");
  law_fd(kMooneyRivlin, {}, true, "Mooney-Rivlin");
}

TEST(AxisymmetricElement, DamageHomogeneousStateAndTangent) {
  using D = IsotropicDamage<NeoHookean>;
  const std::vector<double> virgin(D::kNumHist, 0.0);
  // Psi = (1 - g(W0)) W0, W0 = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2 (mu = 1, lambda = 3).
  law_homogeneous(kDamage, virgin, [](const Mat3& F) {
    const double l[3] = {F(0, 0) * F(0, 0), F(1, 1) * F(1, 1), F(2, 2) * F(2, 2)};
    const double lnJ = 0.5 * std::log(l[0] * l[1] * l[2]);
    const double W0 = 0.5 * (l[0] + l[1] + l[2] - 3) - lnJ + 1.5 * lnJ * lnJ;
    return (1.0 - 0.6 * (1.0 - std::exp(-W0 / 0.02))) * W0;
  }, "neo-Hookean damage");
  // Loading from a virgin state at every point (tangent with the -g' S0 (x) S0 term).
  law_fd(kDamage, virgin, false, "neo-Hookean damage, loading");
  // Unloading below a past maximum alpha = 1: the (1 - d) W0 branch, a potential.
  std::vector<double> past(D::kNumHist, 0.0);
  past[D::kMaxEnergy] = 1.0, past[D::kDamage] = kDamage.damage(1.0);
  law_fd(kDamage, past, true, "neo-Hookean damage, unloading");
}

// Ciarlet-Geymonat plasticity (the deck's `Ciarlet-Geymonat plasticity`, mu = 1, lambda = 3,
// yield stress 0.02, hardening 0.1) from its virgin history (the law's initial values): every
// point of the deformed cell flows, and the tangent of the return map matches central
// differences of the residual (the residual is not dE/du: the step dissipates).
TEST(AxisymmetricElement, CiarletGeymonatPlasticityTangent) {
  using P = CiarletGeymonatPlasticity;
  const P law{CiarletGeymonat{0.4, 0.1, 0.65}, 0.02, 0.1, stentor::PlasticDynamicStep::kIncrementalPotential, NonlinearHardening{}};
  std::vector<double> virgin;
  for (int i = 0; i < P::kNumHist; ++i) virgin.push_back(P::kHistory[i].initial);
  law_fd(law, virgin, false, "Ciarlet-Geymonat plasticity");
  // The same cells flow: positive plastic dissipation on each.
  for (CellType t : kTypes) {
    const Cell c = make_cell(t, 0.0);
    double U[kMaxCellNodes][3];
    displacement(c, 1.0, 0.03, U);
    const LawEval<P> e = eval_law(law, c, U, virgin);
    ASSERT_EQ(e.status, kElementOk);
    EXPECT_GT(e.damage_dissipation, 0.0) << cell_name(t) << ": the cell must flow";
  }
}
