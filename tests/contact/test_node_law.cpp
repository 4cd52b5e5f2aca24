// The rows contact::law() writes for one active slave node against a rigid plane in 3D:
// the normal condition goes to the component most aligned with n and each tangential
// condition to the free component most aligned with its tangent, so every replaced row
// keeps its leading term on the diagonal of the node's block. (With the tangents in
// component order, a plane z = 0 put t1 = e_y on the x row: zero diagonals on stick rows,
// and GMRES with MueLu's Gauss-Seidel smoother stalled on 3D contact; docs/solvers.md.)
#include <gtest/gtest.h>

#include <cmath>

#include "contact/NodeLaw.hpp"

using namespace stentor;

namespace {

// A node 0.01 inside the plane through the origin with unit normal n, pressed (r = n):
// active; mu > 0 with no tangential motion or force: stick; mu = 0: slip.
contact::NodeOutput evaluate_on_plane(const double n[3], double mu) {
  contact::Obstacle o;
  o.kind = 0;
  for (int k = 0; k < 3; ++k) o.normal[k] = n[k];
  contact::NodeInput in;
  in.dim = 3;
  for (int k = 0; k < 3; ++k) {
    in.xs[k] = in.xs_n[k] = -0.01 * n[k];
    in.r[k] = n[k];
  }
  contact::LawParams p;
  p.persistence = false;
  p.mu = mu;
  contact::NodeOutput out;
  contact::evaluate(in, p, &o, out);
  return out;
}

}  // namespace

TEST(NodeLaw, EveryContactRowKeepsItsLeadingTermOnTheDiagonal) {
  const double s = 1.0 / std::sqrt(1.0 + 0.04 + 0.09);
  const double normals[][3] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0.2 * s, -0.3 * s, s},
                               {s, 0.2 * s, 0.3 * s}, {-0.3 * s, s, -0.2 * s}};
  for (const auto& n : normals) {
    for (double mu : {0.3, 0.0}) {
      const contact::NodeOutput out = evaluate_on_plane(n, mu);
      ASSERT_EQ(out.state, mu > 0 ? contact::Stick : contact::Slip) << "n " << n[0] << " " << n[1] << " " << n[2];
      // Stick and normal rows depend on the slave position (unknowns 0..2), slip rows on
      // its bulk residual r_p (unknowns 3..5; the assembled row is that times K_p).
      for (int k = 0; k < 3; ++k) {
        const bool normal_row = std::abs(n[k]) >= std::abs(n[(k + 1) % 3]) && std::abs(n[k]) >= std::abs(n[(k + 2) % 3]);
        const int off = (normal_row || mu > 0) ? 0 : 3;
        const double diag = std::abs(out.dres[k][off + k]);
        EXPECT_GT(diag, 0.9) << "row " << k << ", n " << n[0] << " " << n[1] << " " << n[2] << ", mu " << mu;
        for (int j = 0; j < 3; ++j)
          if (j != k)
            EXPECT_GT(diag, 2.0 * std::abs(out.dres[k][off + j]))
                << "row " << k << ", column " << j << ", n " << n[0] << " " << n[1] << " " << n[2] << ", mu " << mu;
      }
    }
  }
}

namespace {

// A node on the plane z = 0 (normal e_z), pressed (r_z = 1: lambda_nu = -1), with the bulk
// tangential residual rt and the tangential relative displacement rel over the step,
// held slipping with the fixed friction direction dir (null: not held).
contact::NodeOutput held_slip(const double rt[2], const double rel[2], const double* dir, double mu) {
  contact::Obstacle o;
  o.kind = 0;
  o.normal[2] = 1.0;
  contact::NodeInput in;
  in.dim = 3;
  in.xs[0] = rel[0], in.xs[1] = rel[1], in.xs[2] = -1e-3;
  in.r[0] = rt[0], in.r[1] = rt[1], in.r[2] = 1.0;
  contact::LawParams p;
  p.persistence = false;
  p.mu = mu;
  p.ct = 1.0;
  p.force_active = true;
  p.force_tangent = contact::Slip;
  if (dir) {
    p.has_slip_dir = true;
    for (int c = 0; c < 3; ++c) p.slip_dir[c] = dir[c];
  }
  contact::NodeOutput out;
  contact::evaluate(in, p, &o, out);
  return out;
}

}  // namespace

// A node held slipping keeps its friction direction: its rows vanish exactly when
// lambda_tau = mu |lambda_nu| s with the held s, whatever q = lambda_tau + c_tau v says;
// with the direction of q (not held) the same force and a reversed slip rate also
// vanish, the spurious solution the fixed direction excludes.
TEST(NodeLaw, HeldSlipKeepsItsFrictionDirection) {
  const double mu = 0.3, dir[3] = {1.0, 0.0, 0.0}, against[2] = {-0.1, 0.0};
  // lambda_tau = -r_t = mu e_x: on the cone along the held direction.
  const double rt[2] = {-mu, 0.0};
  const contact::NodeOutput held = held_slip(rt, against, dir, mu);
  ASSERT_EQ(held.state, contact::Slip);
  EXPECT_NEAR(held.res[0], 0.0, 1e-15);
  EXPECT_NEAR(held.res[1], 0.0, 1e-15);
  const contact::NodeOutput free_dir = held_slip(rt, against, nullptr, mu);
  EXPECT_NEAR(free_dir.res[0], 0.0, 1e-15);  // q = 0.3 - 0.1 along +x: the same rows, spurious
  // The opposite held direction does not accept that force: the row is 2 mu.
  const double back[3] = {-1.0, 0.0, 0.0};
  EXPECT_NEAR(std::abs(held_slip(rt, against, back, mu).res[0]), 2.0 * mu, 1e-14);
}

// The held rows' derivatives (Dual numbers) against central differences in every unknown.
TEST(NodeLaw, HeldSlipRowsMatchFiniteDifferences) {
  const double mu = 0.25, dir[3] = {0.6, 0.8, 0.05}, rel[2] = {0.02, -0.01}, rt[2] = {-0.1, 0.05};
  contact::Obstacle o;
  o.kind = 1;  // a sphere: the normal and the tangent plane move with the node
  o.radius = 2.0;
  o.point[2] = -2.0;
  auto eval = [&](const double* xs, const double* r) {
    contact::NodeInput in;
    in.dim = 3;
    for (int c = 0; c < 3; ++c) in.xs[c] = xs[c], in.r[c] = r[c];
    contact::LawParams p;
    p.persistence = false;
    p.mu = mu;
    p.force_active = true;
    p.force_tangent = contact::Slip;
    p.has_slip_dir = true;
    for (int c = 0; c < 3; ++c) p.slip_dir[c] = dir[c];
    contact::NodeOutput out;
    contact::evaluate(in, p, &o, out);
    return out;
  };
  double xs[3] = {rel[0], rel[1], -1e-3}, r[3] = {rt[0], rt[1], 1.0};
  const contact::NodeOutput out = eval(xs, r);
  ASSERT_EQ(out.state, contact::Slip);
  const double h = 1e-6;
  for (int j = 0; j < 6; ++j) {
    double* v = j < 3 ? &xs[j] : &r[j - 3];
    const double keep = *v;
    *v = keep + h;
    const contact::NodeOutput up = eval(xs, r);
    *v = keep - h;
    const contact::NodeOutput dn = eval(xs, r);
    *v = keep;
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(out.dres[k][j], (up.res[k] - dn.res[k]) / (2 * h), 1e-7) << "row " << k << ", unknown " << j;
  }
}

// A node on a symmetry plane y = 0 (its y component prescribed, its bulk r_y = 0) pressed
// against a rigid plane whose normal n = (cos a, sin a, 0) tilts towards y: it can slide
// only along t1 = e_y x n = -e_z, and its friction force is its component along t1. The
// normal force then has a tangential projection off the symmetry plane, -(n . r) n
// against r, which is no friction (the mirrored node's cancels it). With mu = 0.1, a
// force (1, 0, 0.05): |lambda_tau . t1| = 0.05 < mu |lambda_nu| = 0.0995, the node sticks;
// the same node off the plane (nothing prescribed) reads the whole tangential part,
// sqrt(sin^2 a + 0.05^2) = 0.112 > 0.0995, and slips.
TEST(NodeLaw, SymmetryPlaneNodeReadsFrictionAlongThePlaneOnly) {
  const double a = std::asin(0.1), n[3] = {std::cos(a), std::sin(a), 0.0};
  auto eval = [&](bool on_plane) {
    contact::Obstacle o;
    o.kind = 0;
    for (int k = 0; k < 3; ++k) o.normal[k] = n[k];
    contact::NodeInput in;
    in.dim = 3;
    in.xs[0] = in.xs_n[0] = -0.01;
    in.r[0] = 1.0, in.r[2] = 0.05;
    in.fixed[1] = on_plane;
    contact::LawParams p;
    p.persistence = false;
    p.mu = 0.1;
    contact::NodeOutput out;
    contact::evaluate(in, p, &o, out);
    return out;
  };
  const contact::NodeOutput plane = eval(true), free = eval(false);
  EXPECT_EQ(plane.state, contact::Stick);
  EXPECT_EQ(free.state, contact::Slip);
  // Sticking, the node's one tangential row is its slip along t1: zero here (no motion).
  EXPECT_NEAR(plane.res[2], 0.0, 1e-15);
}

// The force between the bodies at a slave on symmetry planes (contact::contact_force): in
// the directions the conditions act in, and equal to the bulk residual r along the node's
// free directions (the rest is the planes' reaction). 3D on the plane theta = 22.5 deg
// (e its normal, r completed onto it): F in span{n, t1}, t1 = e x n, and F - r along e.
// 2D with x prescribed (a node on the axis of an axisymmetric section): F = a n with
// F_y = r_y. Without prescribed components, F = r.
TEST(NodeLaw, ContactForceOnSymmetryPlanes) {
  const double th = 0.3926990816987241, e[3] = {-std::sin(th), std::cos(th), 0.0};
  contact::LawParams p;
  p.planes = 1;
  p.pj[0] = 1;
  for (int c = 0; c < 3; ++c) p.e[0][c] = e[c];
  double n[3] = {0.92, 0.38, 0.06};
  const double nl = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (double& v : n) v /= nl;
  double r[3] = {-0.8, 0.0, 0.03};
  contact::complete_on_planes(p, r);  // e . r = 0
  const bool fixed[3] = {false, true, false};
  double F[3];
  contact::contact_force(3, fixed, p, n, r, F);
  const double t[3] = {e[1] * n[2] - e[2] * n[1], e[2] * n[0] - e[0] * n[2], e[0] * n[1] - e[1] * n[0]};
  const double m[3] = {n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0]};
  EXPECT_NEAR(contact::dot3(F, m), 0.0, 1e-15);  // no component off span{n, t1}
  double d[3];
  for (int c = 0; c < 3; ++c) d[c] = F[c] - r[c];
  const double along = contact::dot3(d, e);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(d[c], along * e[c], 1e-15);  // F - r along e only
  EXPECT_GT(std::abs(along), 5e-4);  // and not zero: r itself has a part off span{n, t1}
  // 2D, x prescribed.
  const bool fx[3] = {true, false, false};
  contact::LawParams p2;
  const double n2[3] = {0.6, 0.8, 0.0}, r2[3] = {0.0, -0.5, 0.0};
  double F2[3];
  contact::contact_force(2, fx, p2, n2, r2, F2);
  EXPECT_NEAR(F2[1], -0.5, 1e-15);
  EXPECT_NEAR(F2[0] * n2[1] - F2[1] * n2[0], 0.0, 1e-15);  // along n
  const bool none[3] = {false, false, false};
  double F3[3];
  contact::contact_force(3, none, p, n, r, F3);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(F3[c], r[c]);
}
