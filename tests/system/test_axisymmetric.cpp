// Axisymmetric analysis (Problem->kinematics = axisymmetric, docs/axisymmetric.md): meshes in
// the (r, z) half plane, x = r, y = z, forces and energies of the full revolution.
//  a. The global residual and tangent (follower pressure, dead traction, body force included)
//     against central finite differences, and the internal force against those of the energy.
//  b. Patch test: u_r = a r, u_z = b z + c on distorted tri3/tri6/quad4 meshes touching the axis.
//  c. Uniaxial stretch of a solid cylinder with a free mantle: the lateral stretch of the
//     closed form at every node, the end reaction P_zz pi R^2 (the whole ring).
//  d. Thick-walled cylinder (u_z = 0: plane strain along the axis) and sphere under internal
//     follower pressure at finite strain, against shooting solutions of the radial equilibrium
//     ODE; the error falls under mesh refinement.
//  e. An impulsively loaded ring (Gonzalez): the energy identity per step to 1e-12 of E0, and
//     E0 = 1/2 rho v^2 2 pi r_c A.
//  f. The hoop stress in the output's third column, cell volumes of the revolution.
//  g. Contact pressure on a rigid plane normal to the axis (revolved areas).
//  h. A ring bouncing on a rigid plane: the energy identity with contact.
//  i. Node-to-segment contact between two bodies: the contact pressure of a stacked pair.
//     Dual mortar between two bodies: the patch test of stacked annuli with non-matching
//     meshes (tri3, quad4), and a tube pressed into a tube (cylindrical interface, non-matching)
//     against node-to-segment on matching meshes.
//  j. Plasticity and fibres in the axisymmetric kernel: global tangents against differences.
//  k. A spinning cylinder (centrifugal body force field) against linear elasticity.
//  l. Output->Stent Metrics of a homogeneously expanded tube: radii, recoil, foreshortening
//     and the hoop stress against the closed form.
//  m. The scene S4-axi, coarse: the balloon's radius and the thin ring's elastic spring-back.
//  n. The dynamic S4-axi, coarse: the energy identity with a moving rigid balloon, frictional
//     node-to-segment contact between bodies and plasticity, per step and over the run.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "AssemblerFixture.hpp"
#include "CsvSeries.hpp"
#include "H5Results.hpp"
#include "run/Simulation.hpp"
#include "TestDir.hpp"

using namespace stentor;
using stentor::testing::AssemblerFixture;
using stentor::testing::read_csv;
using stentor::testing::Series;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;
fs::path work_dir() { return stentor::testing::test_dir("axisymmetric"); }

std::string write_file(const std::string& name, const std::string& text) {
  fs::create_directories(work_dir());
  const fs::path p = work_dir() / name;
  std::ofstream(p) << text;
  return p.string();
}

// A rectangle [r0, r1] x [z0, z1] with groups inner (r = r0), outer, bottom, top; body "wall".
std::string rectangle_geo(const std::string& name, double r0, double r1, double z0, double z1) {
  std::ostringstream g;
  g.precision(17);
  g << "Point(1) = {" << r0 << ", " << z0 << ", 0, 1};\nPoint(2) = {" << r1 << ", " << z0 << ", 0, 1};\n"
    << "Point(3) = {" << r1 << ", " << z1 << ", 0, 1};\nPoint(4) = {" << r0 << ", " << z1 << ", 0, 1};\n"
    << "Line(1) = {1, 2};\nLine(2) = {2, 3};\nLine(3) = {3, 4};\nLine(4) = {4, 1};\n"
    << "Curve Loop(1) = {1, 2, 3, 4};\nPlane Surface(1) = {1};\n"
    << "Physical Surface(\"wall\") = {1};\nPhysical Curve(\"bottom\") = {1};\nPhysical Curve(\"outer\") = {2};\n"
    << "Physical Curve(\"top\") = {3};\nPhysical Curve(\"inner\") = {4};\n";
  return write_file(name, g.str());
}

// What a deck needs besides its mesh and material (neo-Hookean mu, lambda; every body's).
struct DeckSpec {
  std::string mesh;
  double size = 0.0;
  int order = 1;
  bool recombine = false;
  double mu = 1.0, lambda = 3.0, rho = 0.0;
  std::string bcs, initial, contact;  // raw XML of "Boundary Conditions" / "Initial Conditions" / "Contact" entries
  bool fields = false;
  std::vector<std::string> bodies{"wall"};  // the mesh's surface groups
  std::string model = "neo-Hookean", material_xml;  // the law and its parameters besides mu, lambda, density
  bool dynamic = false;
  double end_time = 1.0;
  int steps = 1;
  std::string kinematics = "axisymmetric";  // "plane strain" for a 3D mesh (the parameter is not read there)
};

Config make_deck(const DeckSpec& s, const std::string& tag) {
  std::ostringstream x;
  x.precision(17);
  auto P = [&](const char* n, const char* t, const auto& v) {
    x << "<Parameter name=\"" << n << "\" type=\"" << t << "\" value=\"" << v << "\"/>";
  };
  x << "<ParameterList name=\"stentor\">\n<ParameterList name=\"Problem\">";
  P("kinematics", "string", s.kinematics);
  P("analysis", "string", s.dynamic ? "dynamic" : "static");
  x << "</ParameterList>\n<ParameterList name=\"Mesh\">";
  P("file", "string", s.mesh);
  P("size", "double", s.size);
  P("order", "int", s.order);
  P("recombine", "bool", s.recombine ? "true" : "false");
  x << "</ParameterList>\n<ParameterList name=\"Materials\"><ParameterList name=\"m\">";
  P("model", "string", s.model);
  P("mu", "double", s.mu);
  P("lambda", "double", s.lambda);
  P("density", "double", s.rho);
  x << s.material_xml << "</ParameterList></ParameterList>\n<ParameterList name=\"Bodies\">";
  for (const std::string& b : s.bodies) {
    x << "<ParameterList name=\"" << b << "\">";
    P("material", "string", "m");
    x << "</ParameterList>";
  }
  x << "</ParameterList>\n";
  if (!s.bcs.empty()) x << "<ParameterList name=\"Boundary Conditions\">" << s.bcs << "</ParameterList>\n";
  if (!s.initial.empty()) x << "<ParameterList name=\"Initial Conditions\">" << s.initial << "</ParameterList>\n";
  if (!s.contact.empty()) x << "<ParameterList name=\"Contact\">" << s.contact << "</ParameterList>\n";
  x << "<ParameterList name=\"Stepping\">";
  P("end time", "double", s.end_time);
  P("steps", "int", s.steps);
  x << "</ParameterList>\n<ParameterList name=\"Newton\">";
  P("relative residual tolerance", "double", 1e-13);
  P("absolute residual tolerance", "double", 1e-14);
  P("max iterations", "int", 30);
  x << "</ParameterList>\n<ParameterList name=\"Linear Solver\">";
  P("method", "string", "direct");
  x << "</ParameterList>\n<ParameterList name=\"Output\">";
  P("fields", "bool", s.fields ? "true" : "false");
  P("basename", "string", "run");
  x << "</ParameterList>\n</ParameterList>\n";
  return read_deck(write_file(tag + ".xml", x.str()));
}

std::string dirichlet(const std::string& name, const std::string& group, const std::string& comps, const std::string& values) {
  return "<ParameterList name=\"" + name + "\"><Parameter name=\"type\" type=\"string\" value=\"Dirichlet\"/>" +
         "<Parameter name=\"boundary\" type=\"string\" value=\"" + group + "\"/>" +
         "<Parameter name=\"components\" type=\"string\" value=\"" + comps + "\"/>" +
         (values.empty() ? "" : "<Parameter name=\"values\" type=\"Array(double)\" value=\"{" + values + "}\"/>") +
         "</ParameterList>";
}

RunResult run(const Config& cfg, const std::string& tag) {
  RunOptions opts;
  opts.output_dir = (work_dir() / tag).string();
  RunResult res;
  EXPECT_EQ(run_simulation(cfg, opts, &res), 0) << tag;
  EXPECT_TRUE(res.converged) << tag;
  return res;
}

// Reaction of the Dirichlet set named `name` (the run's sets: the deck's, then "axis").
std::array<double, 3> reaction(const Config& cfg, const RunResult& res, const std::string& name) {
  std::size_t d = 0;
  for (const auto& l : cfg.loads)
    if (l.type == LoadConfig::Type::Dirichlet) {
      if (l.name == name) return res.reactions[d];
      ++d;
    }
  if (name == "axis") return res.reactions[d];
  ADD_FAILURE() << "no Dirichlet set " << name;
  return {0, 0, 0};
}

}  // namespace

// ---------------------------------------------------------------------------------------
// a. Ring section r in [0.5, 1.5], z in [0, 1] (P2 triangles): follower pressure 0.3 on the
// inner side, a dead traction on the top, a body force; u a smooth finite deformation.
namespace {

struct FdCheck {
  double rel = 0, dE = 0, fv = 0, plastic = 0;  // |K v - FD|/|K v|, dE/dv, f_int.v, the trial state's plastic dissipation
};

// Tangent and internal force at a smooth finite deformation u (times amp) along v,
// against central differences (h = 1e-6) of the residual and of the stored energy.
FdCheck global_fd(const AssemblerFixture& f, double amp) {
  const auto map = f.dist->owned_map();
  la::Vector u(map), v(map), up(map), um(map), r(map), rp(map), rm(map), Kv(map), fint(map), fd(map);
  {
    auto uh = u.getLocalViewHost(Tpetra::Access::OverwriteAll);
    auto vh = v.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (la::LO l = 0; l < f.dist->num_owned_nodes(); ++l) {
      const double* X = f.mesh.coord(f.dist->global_node(l));
      uh(2 * l, 0) = amp * (0.1 * X[0] + 0.05 * X[0] * X[1] - 0.03 * X[1] * X[1]);
      uh(2 * l + 1, 0) = amp * (-0.04 * X[1] + 0.06 * std::sin(X[0] + 2 * X[1]));
      vh(2 * l, 0) = std::cos(3 * X[0] + X[1]);
      vh(2 * l + 1, 0) = std::sin(X[0] - 2 * X[1]);
    }
  }
  FdCheck c;
  const Assembler::Stats st = f.as->assemble(u, 1.0, 1.0, r, true);
  EXPECT_EQ(st.inverted, 0);
  c.plastic = st.plastic_dissipation;
  fint.update(1.0, f.as->static_residual(), 1.0, f.as->external_force(), 0.0);
  f.as->matrix()->apply(v, Kv);
  const double h = 1e-6;
  up.update(1.0, u, h, v, 0.0);
  um.update(1.0, u, -h, v, 0.0);
  const double Ep = f.as->assemble(up, 1.0, 1.0, rp, false).energy, Em = f.as->assemble(um, 1.0, 1.0, rm, false).energy;
  fd.update(0.5 / h, rp, -0.5 / h, rm, 0.0);
  fd.update(-1.0, Kv, 1.0);
  c.rel = fd.normInf() / Kv.normInf();
  c.dE = (Ep - Em) / (2 * h);
  c.fv = fint.dot(v);
  return c;
}

const char* kRingFdLoads =
    "<ParameterList name=\"p\"><Parameter name=\"type\" type=\"string\" value=\"pressure\"/>"
    "<Parameter name=\"boundary\" type=\"string\" value=\"inner\"/><Parameter name=\"pressure\" type=\"double\" value=\"0.3\"/></ParameterList>"
    "<ParameterList name=\"t\"><Parameter name=\"type\" type=\"string\" value=\"traction\"/>"
    "<Parameter name=\"boundary\" type=\"string\" value=\"top\"/><Parameter name=\"traction\" type=\"Array(double)\" value=\"{0.1, 0.2}\"/></ParameterList>"
    "<ParameterList name=\"g\"><Parameter name=\"type\" type=\"string\" value=\"body force\"/>"
    "<Parameter name=\"force\" type=\"Array(double)\" value=\"{0.05, -0.3}\"/></ParameterList>";

}  // namespace

TEST(Axisymmetric, GlobalTangentAndForcesAgainstFiniteDifferences) {
  DeckSpec s;
  s.mesh = rectangle_geo("ring_fd.geo", 0.5, 1.5, 0.0, 1.0);
  s.size = 0.35;
  s.order = 2;
  s.bcs = kRingFdLoads;
  const AssemblerFixture f(make_deck(s, "ring_fd"));
  const auto map = f.dist->owned_map();
  la::Vector r(map);
  const FdCheck c = global_fd(f, 1.0);
  std::printf("[axisymmetric] global FD: |K v - FD|/|K v| = %.2e; dE/dv %.12e, f_int.v %.12e\n", c.rel, c.dE, c.fv);
  EXPECT_LT(c.rel, 1e-7);
  EXPECT_NEAR(c.dE, c.fv, 1e-8 * std::abs(c.fv));
  // The external force's z sum at u = 0: the traction 0.2 on the top ring (area
  // pi (1.5^2 - 0.5^2)) and the body force -0.3 on the volume (pi (1.5^2 - 0.5^2) 1); the
  // pressure on the straight inner cylinder has no z component.
  double fz = 0.0;
  const double ring = kPi * (1.5 * 1.5 - 0.5 * 0.5);
  la::Vector zero(map);
  f.as->assemble(zero, 1.0, 1.0, r, false);
  {
    auto fh = f.as->external_force().getLocalViewHost(Tpetra::Access::ReadOnly);
    fz = 0.0;
    for (la::LO l = 0; l < f.dist->num_owned_nodes(); ++l) fz += fh(2 * l + 1, 0);
  }
  EXPECT_NEAR(fz, 0.2 * ring - 0.3 * ring, 1e-12);
}

// ---------------------------------------------------------------------------------------
// b. A distorted section touching the axis (curved top, embedded points of very different
// sizes), u = (a r, b z + c) prescribed on its whole boundary: F = diag(1 + a, 1 + b, 1 + a)
// everywhere, P constant with P_rr = P_thth, so the radial equilibrium
// dP_rr/dR + (P_rr - P_thth)/R = 0 holds and u is the exact solution, in every element space.
TEST(Axisymmetric, PatchTestOnDistortedMeshesTouchingTheAxis) {
  const std::string geo = write_file("patch.geo", R"(
Point(1) = {0, 0, 0, 0.22};
Point(2) = {1, 0.1, 0, 0.3};
Point(3) = {1.1, 0.9, 0, 0.12};
Point(4) = {0, 0.8, 0, 0.25};
Point(5) = {0.55, 1.05, 0, 0.2};
Point(6) = {0.31, 0.43, 0, 0.03};
Point(7) = {0.74, 0.27, 0, 0.06};
Point(8) = {0.62, 0.71, 0, 0.04};
Line(1) = {1, 2};
Line(2) = {2, 3};
Spline(3) = {3, 5, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point{6, 7, 8} In Surface{1};
Physical Surface("wall") = {1};
Physical Curve("bottom") = {1};
Physical Curve("outer") = {2};
Physical Curve("top") = {3};
Physical Curve("axis_side") = {4};
)");
  const double a = 0.07, b = -0.05, c = 0.02;
  auto exact = [=](const double* X) { return std::array<double, 3>{a * X[0], b * X[1] + c, 0.0}; };
  struct Case {
    int order;
    bool recombine;
  };
  for (const Case k : {Case{1, false}, Case{2, false}, Case{1, true}}) {
    DeckSpec s;
    s.mesh = geo;
    s.order = k.order;
    s.recombine = k.recombine;
    for (const char* g : {"bottom", "outer", "top", "axis_side"}) s.bcs += dirichlet(std::string("u_") + g, g, "x y", "");
    const std::string tag = "patch_p" + std::to_string(k.order) + (k.recombine ? "_quad" : "_tri");
    Config cfg = make_deck(s, tag);
    for (auto& l : cfg.loads) l.field = exact;
    const RunResult res = run(cfg, tag);
    double err = 0, scale = 0;
    std::size_t on_axis = 0;
    for (std::size_t n = 0; n < res.mesh.num_nodes(); ++n) {
      const auto ue = exact(&res.mesh.x[3 * n]);
      on_axis += res.mesh.x[3 * n] == 0.0;
      for (int d = 0; d < 2; ++d) {
        err = std::max(err, std::abs(res.displacement[3 * n + d] - ue[d]));
        scale = std::max(scale, std::abs(ue[d]));
      }
    }
    std::printf("[axisymmetric] patch %s: %zu nodes (%zu on the axis), max |u - u_exact| / max |u_exact| = %.2e\n", tag.c_str(),
                res.mesh.num_nodes(), on_axis, err / scale);
    EXPECT_GT(on_axis, 3u);
    EXPECT_LT(err / scale, 1e-11) << tag;
  }
}

// ---------------------------------------------------------------------------------------
// c. Solid cylinder R = 1, H = 1 (nodes on the axis), bottom u_z = 0, top u_z = delta, mantle
// free: the homogeneous state F = diag(s, l, s), l = 1 + delta, with the mantle stress-free,
//   P_rr = mu (s - 1/s) + lambda ln(s^2 l)/s = 0  (solved by Newton below),
// and the end force P_zz pi R^2, P_zz = mu (l - 1/l) + lambda ln(s^2 l)/l: the full ring.
TEST(Axisymmetric, UniaxialStretchOfASolidCylinder) {
  const double mu = 1.0, lambda = 3.0, delta = 0.2, l = 1 + delta;
  double sl = 1.0;
  for (int i = 0; i < 50; ++i) {
    const double lnJ = std::log(sl * sl * l);
    const double g = mu * (sl - 1 / sl) + lambda * lnJ / sl;
    const double dg = mu * (1 + 1 / (sl * sl)) + lambda * (2 - lnJ) / (sl * sl);
    sl -= g / dg;
  }
  const double Pzz = mu * (l - 1 / l) + lambda * std::log(sl * sl * l) / l;
  for (const bool quads : {true, false}) {
    DeckSpec s;
    s.mesh = rectangle_geo("solid.geo", 0.0, 1.0, 0.0, 1.0);
    s.size = 0.25;
    s.order = quads ? 1 : 2;
    s.recombine = quads;
    s.steps = 2;
    s.bcs = dirichlet("base", "bottom", "y", "") + dirichlet("pull", "top", "y", "0.2");
    const std::string tag = quads ? "solid_quad4" : "solid_tri6";
    const Config cfg = make_deck(s, tag);
    const RunResult res = run(cfg, tag);
    double err = 0;
    for (std::size_t n = 0; n < res.mesh.num_nodes(); ++n) {
      const double R = res.mesh.x[3 * n], Z = res.mesh.x[3 * n + 1];
      err = std::max({err, std::abs(res.displacement[3 * n] - (sl - 1) * R), std::abs(res.displacement[3 * n + 1] - delta * Z)});
    }
    const double F = reaction(cfg, res, "pull")[1], F_exact = Pzz * kPi;
    std::printf("[axisymmetric] uniaxial %s: lateral stretch %.12f, max |u - u_exact| %.2e; end force %.12e (P_zz pi R^2 %.12e), "
                "axis reaction %.1e\n",
                tag.c_str(), sl, err, F, F_exact, reaction(cfg, res, "axis")[0]);
    EXPECT_LT(err, 1e-11);
    EXPECT_NEAR(F, F_exact, 1e-10 * F_exact);
    EXPECT_NEAR(reaction(cfg, res, "base")[1], -F_exact, 1e-10 * F_exact);
    EXPECT_LT(std::abs(reaction(cfg, res, "axis")[0]), 1e-10 * F_exact);
  }
}

// ---------------------------------------------------------------------------------------
// d. Thick-walled cylinder and sphere, ri = 1, ro = 2, under internal follower pressure p on
// the bore, compressible neo-Hookean (mu = 1, lambda = 3), at finite strain. The cylinder has
// u_z = 0 on its ends (plane strain along z, p = 0.3); the sphere (p = 0.5) is the quarter
// annulus x, y >= 0 of the (r, z) plane with u_z = 0 on the equator and its poles on the axis.
// The reference: the radial deformation r(R), stretches l_r = r', l_t = r/R (n = 1 hoop
// direction for the cylinder, where l_z = 1; n = 2 for the sphere), J = l_r l_t^n,
//   P_r = mu (l_r - 1/l_r) + lambda ln J / l_r,  P_t = mu (l_t - 1/l_t) + lambda ln J / l_t,
//   dP_r/dR = n (P_t - P_r)/R,  P_r(ri) = -p l_t(ri)^n (Cauchy sigma_rr = -p),  P_r(ro) = 0,
// shot from r(ri) = a (l_r from P_r by safeguarded Newton, RK4 with 4000 steps, a by bisection).
namespace {

struct RadialSolution {
  double a = 0, b = 0;  // deformed inner and outer radius
};

struct Shell {
  int n;  // hoop directions: 1 cylinder, 2 sphere
  double mu, lambda, p, ri, ro;
  double radial_stress(double lr, double lt) const { return mu * (lr - 1 / lr) + lambda * std::log(lr * std::pow(lt, n)) / lr; }
  double hoop_stress(double lr, double lt) const { return mu * (lt - 1 / lt) + lambda * std::log(lr * std::pow(lt, n)) / lt; }
  // l_r with P_r(l_r, lt) = P: P_r increases with l_r while ln J < 1 + mu/lambda; Newton
  // safeguarded by the bracket [lo, hi] (bisection when a Newton step leaves it).
  double radial_stretch(double P, double lt) const {
    double lo = 1e-8, hi = 1.0;
    while (radial_stress(hi, lt) < P) hi *= 2;
    double lr = 0.5 * (lo + hi);
    for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
      const double g = radial_stress(lr, lt) - P;
      if (g == 0.0) break;
      (g > 0 ? hi : lo) = lr;
      const double dg = mu * (1 + 1 / (lr * lr)) + lambda * (1 - std::log(lr * std::pow(lt, n))) / (lr * lr);
      const double next = lr - g / dg;
      lr = (dg > 0 && next > lo && next < hi) ? next : 0.5 * (lo + hi);
    }
    return lr;
  }
  // Integrates the ODE from ri (r = a) to ro; returns (r(ro), P_r(ro)).
  std::array<double, 2> shoot(double a) const {
    auto rhs = [&](double R, const std::array<double, 2>& y) {
      const double lt = y[0] / R, lr = radial_stretch(y[1], lt);
      return std::array<double, 2>{lr, n * (hoop_stress(lr, lt) - y[1]) / R};
    };
    const int steps = 4000;
    const double h = (ro - ri) / steps;
    std::array<double, 2> y{a, -p * std::pow(a / ri, n)};
    for (int i = 0; i < steps; ++i) {
      const double R = ri + i * h;
      const auto k1 = rhs(R, y);
      const auto k2 = rhs(R + h / 2, {y[0] + h / 2 * k1[0], y[1] + h / 2 * k1[1]});
      const auto k3 = rhs(R + h / 2, {y[0] + h / 2 * k2[0], y[1] + h / 2 * k2[1]});
      const auto k4 = rhs(R + h, {y[0] + h * k3[0], y[1] + h * k3[1]});
      for (int k = 0; k < 2; ++k) y[k] += h / 6 * (k1[k] + 2 * k2[k] + 2 * k3[k] + k4[k]);
    }
    return y;
  }
  RadialSolution solve() const {
    double lo = ri, hi = 3 * ri;
    for (int i = 0; i < 60; ++i) {
      const double m = 0.5 * (lo + hi);
      (shoot(m)[1] < 0 ? lo : hi) = m;
    }
    RadialSolution s;
    s.a = 0.5 * (lo + hi);
    s.b = shoot(s.a)[0];
    return s;
  }
};

std::string pressure_on(const std::string& group, double p) {
  std::ostringstream x;
  x.precision(17);
  x << "<ParameterList name=\"p\"><Parameter name=\"type\" type=\"string\" value=\"pressure\"/>"
    << "<Parameter name=\"boundary\" type=\"string\" value=\"" << group << "\"/><Parameter name=\"pressure\" type=\"double\" value=\""
    << p << "\"/></ParameterList>";
  return x.str();
}

struct MeshChoice {
  int order;
  bool recombine;
  double size;
};

// Largest relative error of the deformed (cylindrical or spherical) radius of the nodes on the
// inner and outer boundaries, with the deck of `s` on each mesh choice.
std::vector<double> shell_errors(const Shell& sh, DeckSpec s, const std::vector<MeshChoice>& meshes, const std::string& name) {
  const RadialSolution ref = sh.solve();
  std::printf("[axisymmetric] thick %s p = %.2f: ODE inner radius %.10f, outer radius %.10f\n", name.c_str(), sh.p, ref.a, ref.b);
  EXPECT_GT(ref.a, 1.2);  // a finite strain: the bore grows by more than 20 %
  std::vector<double> err;
  for (const MeshChoice m : meshes) {
    s.size = m.size, s.order = m.order, s.recombine = m.recombine;
    const std::string tag = name + "_p" + std::to_string(m.order) + "_" + std::to_string(m.size);
    const Config cfg = make_deck(s, tag);
    const RunResult res = run(cfg, tag);
    double e = 0;
    for (std::size_t k = 0; k < res.mesh.num_nodes(); ++k) {
      const double* X = &res.mesh.x[3 * k];
      const double R = sh.n == 1 ? X[0] : std::hypot(X[0], X[1]);
      const double r = sh.n == 1 ? X[0] + res.displacement[3 * k] : std::hypot(X[0] + res.displacement[3 * k], X[1] + res.displacement[3 * k + 1]);
      if (std::abs(R - sh.ri) < 1e-9) e = std::max(e, std::abs(r - ref.a) / (ref.a - sh.ri));
      if (std::abs(R - sh.ro) < 1e-9) e = std::max(e, std::abs(r - ref.b) / (ref.b - sh.ro));
    }
    std::printf("[axisymmetric] thick %s: max rel. error of the deformed radius at R = %g, %g: %.3e\n", tag.c_str(), sh.ri, sh.ro, e);
    err.push_back(e);
  }
  return err;
}

}  // namespace

TEST(Axisymmetric, ThickCylinderAgainstTheRadialODE) {
  const Shell sh{1, 1.0, 3.0, 0.3, 1.0, 2.0};
  DeckSpec s;
  s.mesh = rectangle_geo("thick.geo", sh.ri, sh.ro, 0.0, 0.25);
  s.steps = 4;
  s.bcs = dirichlet("base", "bottom", "y", "") + dirichlet("lid", "top", "y", "") + pressure_on("inner", sh.p);
  const auto err = shell_errors(sh, s, {{1, true, 0.125}, {1, true, 0.0625}, {2, false, 0.25}, {2, false, 0.125}}, "cylinder");
  // Measured: Q1 2.8e-3 -> 1.2e-3, P2 9.6e-5 -> 2.3e-5 as h is halved.
  EXPECT_LT(err[0], 0.01);
  EXPECT_LT(err[1], 0.5 * err[0]);
  EXPECT_LT(err[2], 1e-3);
  EXPECT_LT(err[3], 0.3 * err[2]);
  EXPECT_LT(err[3], 1e-4);
}

// The same thick cylinder as a 3D wedge: its section revolved about the axis by 15 degrees
// in 4 layers of hex8, held on the planes theta = 0 and theta = 15 deg along their normals
// (Dirichlet components = normal) and in z on its ends. Axisymmetric quad4 and the wedge, on
// the same section size, both against the ODE and against each other: equal to the
// discretisation error (the wedge's facets add the chords of the hoop direction).
TEST(Axisymmetric, RevolvedWedgeWithSymmetryPlanesEqualsTheSection) {
  const Shell sh{1, 1.0, 3.0, 0.3, 1.0, 2.0};
  const RadialSolution ref = sh.solve();
  std::ostringstream g;
  g << "Point(1) = {1, 0, 0, 1};\nPoint(2) = {2, 0, 0, 1};\nPoint(3) = {2, 0, 0.25, 1};\nPoint(4) = {1, 0, 0.25, 1};\n"
    << "Line(1) = {1, 2};\nLine(2) = {2, 3};\nLine(3) = {3, 4};\nLine(4) = {4, 1};\n"
    << "Curve Loop(1) = {1, 2, 3, 4};\nPlane Surface(1) = {1};\nRecombine Surface{1};\n"
    << "out[] = Extrude {{0, 0, 1}, {0, 0, 0}, Pi / 12} { Surface{1}; Layers{4}; Recombine; };\n"
    << "Physical Volume(\"wall\") = {out[1]};\nPhysical Surface(\"plane0\") = {1};\nPhysical Surface(\"plane1\") = {out[0]};\n"
    << "Physical Surface(\"bottom\") = {out[2]};\nPhysical Surface(\"outer\") = {out[3]};\nPhysical Surface(\"top\") = {out[4]};\n"
    << "Physical Surface(\"inner\") = {out[5]};\n";
  auto bore_error = [&](const RunResult& res, bool axi) {
    double e = 0.0;
    std::size_t nodes = 0;
    for (std::size_t k = 0; k < res.mesh.num_nodes(); ++k) {
      const double* X = &res.mesh.x[3 * k];
      const double* u = &res.displacement[3 * k];
      const double R = axi ? X[0] : std::hypot(X[0], X[1]);
      if (std::abs(R - sh.ri) > 1e-9) continue;
      const double r = axi ? X[0] + u[0] : std::hypot(X[0] + u[0], X[1] + u[1]);
      e = std::max(e, std::abs(r - ref.a) / (ref.a - sh.ri));
      ++nodes;
    }
    EXPECT_GT(nodes, 2u);
    return e;
  };
  DeckSpec a;
  a.mesh = rectangle_geo("wedge_section.geo", sh.ri, sh.ro, 0.0, 0.25);
  a.size = 0.125, a.recombine = true, a.steps = 4;
  a.bcs = dirichlet("base", "bottom", "y", "") + dirichlet("lid", "top", "y", "") + pressure_on("inner", sh.p);
  const RunResult ra = run(make_deck(a, "wedge_axi"), "wedge_axi");
  DeckSpec w = a;
  w.kinematics = "plane strain";
  w.mesh = write_file("wedge.geo", g.str());
  w.bcs = dirichlet("base", "bottom", "z", "") + dirichlet("lid", "top", "z", "") + dirichlet("s0", "plane0", "normal", "") +
          dirichlet("s1", "plane1", "normal", "") + pressure_on("inner", sh.p);
  const RunResult rw = run(make_deck(w, "wedge_3d"), "wedge_3d");
  ASSERT_TRUE(ra.converged && rw.converged);
  const double ea = bore_error(ra, true), ew = bore_error(rw, false);
  // The wedge's bore, node by node, against the section's at the same height.
  std::printf("[axisymmetric] revolved wedge (hex8, 4 layers over 15 deg) against the ODE's bore %.6f: axisymmetric quad4 %.3e, wedge %.3e\n",
              ref.a, ea, ew);
  EXPECT_LT(ea, 0.01);
  EXPECT_LT(ew, 0.01);
  EXPECT_LT(std::abs(ew - ea), 0.005);
}

TEST(Axisymmetric, ThickSphereAgainstTheRadialODE) {
  const Shell sh{2, 1.0, 3.0, 0.5, 1.0, 2.0};
  DeckSpec s;
  s.mesh = write_file("sphere.geo", R"(
Point(1) = {0, 0, 0, 1};
Point(2) = {1, 0, 0, 1};
Point(3) = {2, 0, 0, 1};
Point(4) = {0, 2, 0, 1};
Point(5) = {0, 1, 0, 1};
Line(1) = {2, 3};
Circle(2) = {3, 1, 4};
Line(3) = {4, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("wall") = {1};
Physical Curve("equator") = {1};
Physical Curve("outer") = {2};
Physical Curve("axis_side") = {3};
Physical Curve("inner") = {4};
)");
  s.steps = 5;
  s.bcs = dirichlet("equator", "equator", "y", "") + pressure_on("inner", sh.p);
  const auto err = shell_errors(sh, s, {{1, true, 0.125}, {2, false, 0.25}, {2, false, 0.125}}, "sphere");
  // Measured: Q1 1.3e-2 at h = 0.125; P2 2.2e-3 -> 3.1e-4 as h is halved.
  EXPECT_LT(err[0], 0.02);
  EXPECT_LT(err[1], 0.005);
  EXPECT_LT(err[2], 0.2 * err[1]);
}

// ---------------------------------------------------------------------------------------
// e. Ring r in [1, 1.2], z in [0, 0.2], no support, given a uniform radial velocity v = 0.3 at
// t = 0: it expands, the hoop stiffness pulls it back, it oscillates. Gonzalez, 40 steps.
TEST(Axisymmetric, ImpulsivelyLoadedRingConservesEnergy) {
  DeckSpec s;
  s.mesh = rectangle_geo("ring.geo", 1.0, 1.2, 0.0, 0.2);
  s.size = 0.05;
  s.recombine = true;
  s.rho = 1.0;
  s.dynamic = true;
  s.end_time = 2.0;
  s.steps = 40;
  s.initial = "<Parameter name=\"velocity\" type=\"Array(double)\" value=\"{0.3, 0}\"/>";
  const Config cfg = make_deck(s, "ring_dyn");
  RunOptions opts;
  opts.output_dir = (work_dir() / "ring_dyn").string();
  RunResult res;
  ASSERT_EQ(run_simulation(cfg, opts, &res), 0);
  const Series e = read_csv(work_dir() / "ring_dyn" / "run_energy.csv");
  const double E0 = e["total"][0], E0_exact = 0.5 * 0.3 * 0.3 * 2 * kPi * 1.1 * 0.04;
  double bal = 0, drift = 0, strain = 0;
  for (std::size_t i = 0; i < e.rows(); ++i) {
    bal = std::max(bal, std::abs(e["balance_residual"][i]));
    drift = std::max(drift, std::abs(e["total"][i] - E0));
    strain = std::max(strain, e["strain"][i]);
  }
  std::printf("[axisymmetric] ring: E0 %.15e (1/2 rho v^2 2 pi r_c A = %.15e), max strain energy %.3e E0, max |balance| %.2e E0, "
              "max |E - E0| %.2e E0\n",
              E0, E0_exact, strain / E0, bal / E0, drift / E0);
  EXPECT_NEAR(E0, E0_exact, 1e-13 * E0_exact);
  EXPECT_GT(strain, 0.5 * E0);  // the kinetic energy is turned into hoop strain and back
  EXPECT_LT(bal, 1e-12 * E0);
  EXPECT_LT(drift, 1e-11 * E0);
}

// ---------------------------------------------------------------------------------------
// f. The output of a homogeneous state: a solid cylinder (R = H = 1, quad4) at
// u = (a r, b z), F = diag(1 + a, 1 + b, 1 + a), J = (1 + a)^2 (1 + b). The neo-Hookean
// Cauchy stress sigma = mu/J (F F^T - I) + lambda ln J / J I has the hoop component
// sigma_thth = sigma_rr (plane strain would give lambda ln J / J there, F_33 = 1), in the
// output's third column; the cells' volumes sum to pi R^2 H.
TEST(Axisymmetric, CellFieldsGiveTheHoopStressAndRevolvedVolumes) {
  DeckSpec s;
  s.mesh = rectangle_geo("solid_fields.geo", 0.0, 1.0, 0.0, 1.0);
  s.size = 0.25;
  s.recombine = true;
  const AssemblerFixture f(make_deck(s, "solid_fields"));
  const double a = 0.06, b = -0.03, mu = 1.0, lambda = 3.0;
  la::Vector u(f.dist->owned_map());
  {
    auto uh = u.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (la::LO l = 0; l < f.dist->num_owned_nodes(); ++l) {
      const double* X = f.mesh.coord(f.dist->global_node(l));
      uh(2 * l, 0) = a * X[0];
      uh(2 * l + 1, 0) = b * X[1];
    }
  }
  const Assembler::CellFields cf = f.as->cell_fields(u);
  const double J = (1 + a) * (1 + a) * (1 + b), lnJ = std::log(J);
  const double s_rr = mu / J * ((1 + a) * (1 + a) - 1) + lambda * lnJ / J, s_zz = mu / J * ((1 + b) * (1 + b) - 1) + lambda * lnJ / J;
  double err = 0, volume = 0;
  for (std::size_t c = 0; c < cf.cell_ids.size(); ++c) {
    const double* sig = &cf.stress[6 * c];
    err = std::max({err, std::abs(sig[0] - s_rr), std::abs(sig[1] - s_zz), std::abs(sig[2] - s_rr), std::abs(sig[3]),
                    std::abs(sig[4]), std::abs(sig[5])});
    volume += cf.volume[c];
  }
  std::printf("[axisymmetric] fields: %zu cells, sigma_rr = sigma_thth = %.12f, sigma_zz = %.12f, max error %.1e; "
              "volume %.15f (pi %.15f)\n",
              cf.cell_ids.size(), s_rr, s_zz, err, volume, kPi);
  EXPECT_GT(cf.cell_ids.size(), 8u);
  EXPECT_LT(err, 1e-13);
  EXPECT_NEAR(volume, kPi, 1e-13);
}

// ---------------------------------------------------------------------------------------
// g. Contact with rigid obstacles (2D profiles: surfaces of revolution). A solid cylinder
// (R = H = 1, nodes on the axis) pressed by a dead traction p = 0.2 on its top onto the
// rigid plane z = 0 (frictionless): the homogeneous state of uniaxial compression, so the
// contact pressure (the force per revolved reference area, mesh/SurfaceProjection.hpp) is
// p at every node of the base.
namespace {

std::string plane_obstacle(const std::string& name, const std::string& slave, double z) {
  std::ostringstream x;
  x << "<ParameterList name=\"" << name << "\"><Parameter name=\"slave\" type=\"string\" value=\"" << slave << "\"/>"
    << "<Parameter name=\"obstacle\" type=\"string\" value=\"plane\"/>"
    << "<Parameter name=\"point\" type=\"Array(double)\" value=\"{0, " << z << "}\"/>"
    << "<Parameter name=\"normal\" type=\"Array(double)\" value=\"{0, 1}\"/></ParameterList>";
  return x.str();
}

}  // namespace

TEST(Axisymmetric, ContactPressureOnARigidPlaneIsTheTraction) {
  const double p = 0.2;
  for (const bool quads : {true, false}) {
    DeckSpec s;
    s.mesh = rectangle_geo("solid_contact.geo", 0.0, 1.0, 0.0, 1.0);
    s.size = 0.25;
    s.order = quads ? 1 : 2;
    s.recombine = quads;
    s.fields = true;
    s.bcs = "<ParameterList name=\"press\"><Parameter name=\"type\" type=\"string\" value=\"traction\"/>"
            "<Parameter name=\"boundary\" type=\"string\" value=\"top\"/>"
            "<Parameter name=\"traction\" type=\"Array(double)\" value=\"{0, -0.2}\"/></ParameterList>";
    s.contact = plane_obstacle("floor", "bottom", 0.0);
    const std::string tag = quads ? "contact_quad4" : "contact_tri6";
    const Config cfg = make_deck(s, tag);
    run(cfg, tag);
    stentor::testing::H5Results h5(work_dir() / tag / "run.h5");
    const std::string step = "/step_" + std::to_string(h5.times().size() - 1) + "/";
    const auto X = h5.read("/mesh/coordinates"), pr = h5.read(step + "contact_pressure");
    ASSERT_EQ(3 * pr.size(), X.size());
    double err = 0;
    std::size_t on_base = 0;
    for (std::size_t n = 0; n < pr.size(); ++n)
      if (X[3 * n + 1] == 0.0) ++on_base, err = std::max(err, std::abs(pr[n] - p) / p);
    std::printf("[axisymmetric] %s on a rigid plane: %zu base nodes, max |contact_pressure - p|/p %.1e\n", tag.c_str(), on_base, err);
    EXPECT_GT(on_base, 4u);
    EXPECT_LT(err, 1e-9) << tag;
  }
}

// h. A ring (r in [1, 1.2], z in [0.05, 0.25], quad4) thrown at v = 1 onto the rigid plane
// z = 0, bouncing off it: Gonzalez with the persistence condition, the energy identity per step.
TEST(Axisymmetric, RingImpactOnARigidPlaneConservesEnergy) {
  DeckSpec s;
  s.mesh = rectangle_geo("ring_impact.geo", 1.0, 1.2, 0.05, 0.25);
  s.size = 0.05;
  s.recombine = true;
  s.rho = 1.0;
  s.dynamic = true;
  s.end_time = 0.6;
  s.steps = 60;
  s.initial = "<Parameter name=\"velocity\" type=\"Array(double)\" value=\"{0, -1}\"/>";
  s.contact = plane_obstacle("floor", "bottom", 0.0);
  const Config cfg = make_deck(s, "ring_impact");
  RunOptions opts;
  opts.output_dir = (work_dir() / "ring_impact").string();
  RunResult res;
  ASSERT_EQ(run_simulation(cfg, opts, &res), 0);
  const Series e = read_csv(work_dir() / "ring_impact" / "run_energy.csv");
  const double E0 = e["total"][0];
  double bal = 0, drift = 0, vz_end = 0;
  for (std::size_t i = 0; i < e.rows(); ++i) {
    bal = std::max(bal, std::abs(e["balance_residual"][i]));
    drift = std::max(drift, std::abs(e["total"][i] + e["friction_dissipation"][i] - e["contact_work"][i] - E0));
  }
  vz_end = e["momentum_y"][e.rows() - 1];
  std::printf("[axisymmetric] ring impact: E0 %.6e, max |balance| %.2e E0, max |E - E0 - W_contact| %.2e E0, contact work at the end "
              "%.2e E0, axial momentum %.4e -> %.4e\n",
              E0, bal / E0, drift / E0, e["contact_work"][e.rows() - 1] / E0, e["momentum_y"][0], vz_end);
  EXPECT_LT(bal, 1e-12 * E0);
  EXPECT_GT(vz_end, 0.0);  // it bounced
}

// i. Two solid cylinders (R = 1, heights 1) stacked on the axis, the lower one's base held
// axially, a dead traction p = 0.2 pressing the upper one's top (matching P1 meshes): the
// node-to-segment pair carries the homogeneous compression, so the upper body's
// contact_pressure is p at every node of its base and the lower body's
// contact_master_traction is (0, -p) at every node of its top.
TEST(Axisymmetric, NodeToSegmentContactBetweenStackedCylinders) {
  DeckSpec s;
  s.mesh = write_file("stacked.geo", R"(
Point(1) = {0, 0, 0, 0.25};
Point(2) = {1, 0, 0, 0.25};
Point(3) = {1, 1, 0, 0.25};
Point(4) = {0, 1, 0, 0.25};
Point(5) = {0, 1, 0, 0.25};
Point(6) = {1, 1, 0, 0.25};
Point(7) = {1, 2, 0, 0.25};
Point(8) = {0, 2, 0, 0.25};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Physical Surface("lower") = {1};
Physical Surface("upper") = {2};
Physical Curve("base") = {1};
Physical Curve("lower_top") = {3};
Physical Curve("upper_base") = {5};
Physical Curve("upper_top") = {7};
)");
  s.recombine = true;
  s.fields = true;
  s.bodies = {"lower", "upper"};
  s.bcs = dirichlet("hold", "base", "y", "") +
          "<ParameterList name=\"press\"><Parameter name=\"type\" type=\"string\" value=\"traction\"/>"
          "<Parameter name=\"boundary\" type=\"string\" value=\"upper_top\"/>"
          "<Parameter name=\"traction\" type=\"Array(double)\" value=\"{0, -0.2}\"/></ParameterList>";
  s.contact = "<ParameterList name=\"stack\"><Parameter name=\"slave\" type=\"string\" value=\"upper_base\"/>"
              "<Parameter name=\"master\" type=\"string\" value=\"lower_top\"/></ParameterList>";
  run(make_deck(s, "stacked"), "stacked");
  stentor::testing::H5Results h5(work_dir() / "stacked" / "run.h5");
  const std::string step = "/step_" + std::to_string(h5.times().size() - 1) + "/";
  const auto X = h5.read("/mesh/coordinates"), pr = h5.read(step + "contact_pressure"), st = h5.read(step + "contact_status"),
             tm = h5.read(step + "contact_master_traction");
  ASSERT_EQ(3 * pr.size(), X.size());
  ASSERT_EQ(tm.size(), X.size());
  const double p = 0.2;
  double err = 0;
  std::size_t slave = 0, master = 0;
  for (std::size_t n = 0; n < pr.size(); ++n) {
    if (X[3 * n + 1] != 1.0) continue;
    if (st[n] >= 0.0) ++slave, err = std::max(err, std::abs(pr[n] - p) / p);  // a slave node: on the upper body's base
    else ++master, err = std::max({err, std::abs(tm[3 * n]) / p, std::abs(tm[3 * n + 1] + p) / p});
  }
  std::printf("[axisymmetric] stacked cylinders: %zu slave, %zu master nodes, max relative error of contact_pressure and "
              "contact_master_traction %.1e\n",
              slave, master, err);
  EXPECT_GT(slave, 4u);
  EXPECT_GT(master, 4u);
  EXPECT_LT(err, 1e-9);
}

// i2. Dual mortar, patch test: two annular blocks r in [0.5, 1.5] (and two solid cylinders,
// r in [0, 1.5]) stacked at z = 1 (lower
// z in [0, 1], mesh size 0.25; upper z in [1, 2], size 0.2: non-matching interface meshes),
// the lower base held axially, a dead traction p on the upper top. The homogeneous state
// (P_zz = -p, u = (a r, b z)) is the exact discrete solution when the mortar integrals carry
// 2 pi r and the dual basis is biorthogonal in that measure: the slave side's
// contact_pressure is p and the master side's contact_master_traction (0, -p) at every
// interface node, and the axial reaction is p pi (ro^2 - ri^2), the force on the whole ring.
namespace {

std::string two_rectangles_geo(const std::string& name, const std::array<double, 4>& lower, const std::array<double, 4>& upper,
                               double h_lower, double h_upper, const std::array<std::string, 8>& groups) {
  // lower/upper: r0, r1, z0, z1; groups: lower's bottom, outer, top, inner, then upper's.
  std::ostringstream g;
  g.precision(17);
  const std::array<double, 4>* b[2] = {&lower, &upper};
  const double h[2] = {h_lower, h_upper};
  for (int k = 0; k < 2; ++k) {
    const auto& q = *b[k];
    const int o = 4 * k;
    g << "Point(" << o + 1 << ") = {" << q[0] << ", " << q[2] << ", 0, " << h[k] << "};\n"
      << "Point(" << o + 2 << ") = {" << q[1] << ", " << q[2] << ", 0, " << h[k] << "};\n"
      << "Point(" << o + 3 << ") = {" << q[1] << ", " << q[3] << ", 0, " << h[k] << "};\n"
      << "Point(" << o + 4 << ") = {" << q[0] << ", " << q[3] << ", 0, " << h[k] << "};\n";
    for (int l = 0; l < 4; ++l) g << "Line(" << o + l + 1 << ") = {" << o + l + 1 << ", " << o + (l + 1) % 4 + 1 << "};\n";
    g << "Curve Loop(" << k + 1 << ") = {" << o + 1 << ", " << o + 2 << ", " << o + 3 << ", " << o + 4 << "};\n"
      << "Plane Surface(" << k + 1 << ") = {" << k + 1 << "};\n";
    for (int l = 0; l < 4; ++l) g << "Physical Curve(\"" << groups[static_cast<std::size_t>(o + l)] << "\") = {" << o + l + 1 << "};\n";
  }
  g << "Physical Surface(\"lower\") = {1};\nPhysical Surface(\"upper\") = {2};\n";
  return write_file(name, g.str());
}

std::string contact_pair(const std::string& name, const std::string& slave, const std::string& master, const std::string& disc) {
  return "<ParameterList name=\"" + name + "\"><Parameter name=\"slave\" type=\"string\" value=\"" + slave + "\"/>" +
         "<Parameter name=\"master\" type=\"string\" value=\"" + master + "\"/>" +
         "<Parameter name=\"discretization\" type=\"string\" value=\"" + disc + "\"/></ParameterList>";
}

}  // namespace

TEST(Axisymmetric, MortarPatchTestOfStackedAnnuliWithNonMatchingMeshes) {
  const double p = 0.2, ro = 1.5;
  // Annuli (ri = 0.5) in quad4 and tri3, and solid cylinders (ri = 0: a slave and a master
  // facet end on the axis, the slave node there keeps u_r = 0 and contact in z) in quad4.
  for (const auto& [quads, ri] : {std::pair<bool, double>{true, 0.5}, {false, 0.5}, {true, 0.0}}) {
    const std::string mesh = two_rectangles_geo(ri > 0 ? "mortar_annuli.geo" : "mortar_solids.geo", {ri, ro, 0.0, 1.0}, {ri, ro, 1.0, 2.0}, 0.25,
                                                0.2, {"base", "lower_outer", "lower_top", "lower_inner", "upper_base", "upper_outer",
                                                      "upper_top", "upper_inner"});
    DeckSpec s;
    s.mesh = mesh;
    s.recombine = quads;
    s.fields = true;
    s.bodies = {"lower", "upper"};
    s.bcs = dirichlet("hold", "base", "y", "") +
            "<ParameterList name=\"press\"><Parameter name=\"type\" type=\"string\" value=\"traction\"/>"
            "<Parameter name=\"boundary\" type=\"string\" value=\"upper_top\"/>"
            "<Parameter name=\"traction\" type=\"Array(double)\" value=\"{0, -0.2}\"/></ParameterList>";
    s.contact = contact_pair("stack", "upper_base", "lower_top", "mortar");
    const std::string tag = ri == 0.0 ? "mortar_solids_quad4" : quads ? "mortar_annuli_quad4" : "mortar_annuli_tri3";
    const Config cfg = make_deck(s, tag);
    const RunResult res = run(cfg, tag);
    stentor::testing::H5Results h5(work_dir() / tag / "run.h5");
    const std::string step = "/step_" + std::to_string(h5.times().size() - 1) + "/";
    const auto X = h5.read("/mesh/coordinates"), pr = h5.read(step + "contact_pressure"), st = h5.read(step + "contact_status"),
               tm = h5.read(step + "contact_master_traction");
    ASSERT_EQ(3 * pr.size(), X.size());
    ASSERT_EQ(tm.size(), X.size());
    double err_s = 0, err_m = 0;
    std::size_t slave = 0, master = 0;
    for (std::size_t n = 0; n < pr.size(); ++n) {
      if (X[3 * n + 1] != 1.0) continue;
      if (st[n] >= 0.0) ++slave, err_s = std::max(err_s, std::abs(pr[n] - p) / p);
      else ++master, err_m = std::max({err_m, std::abs(tm[3 * n]) / p, std::abs(tm[3 * n + 1] + p) / p});
    }
    const double F = reaction(cfg, res, "hold")[1], F_exact = p * kPi * (ro * ro - ri * ri);
    std::printf("[axisymmetric] mortar patch test %s: %zu slave, %zu master nodes; max |contact_pressure - p|/p %.1e, "
                "max |contact_master_traction - (0, -p)|/p %.1e; axial reaction %.15f, p pi (ro^2 - ri^2) = %.15f (rel. %.1e), "
                "%d Newton iterations\n",
                tag.c_str(), slave, master, err_s, err_m, F, F_exact, std::abs(std::abs(F) - F_exact) / F_exact, res.newton_iterations);
    EXPECT_GT(slave, 4u);
    EXPECT_GT(master, 3u);
    EXPECT_NE(slave, master);  // non-matching interface meshes
    EXPECT_LT(err_s, 1e-10) << tag;
    EXPECT_LT(err_m, 1e-10) << tag;
    EXPECT_LT(std::abs(std::abs(F) - F_exact), 1e-10 * F_exact) << tag;
  }
}

// i3. Dual mortar on a cylindrical interface: an inner tube r in [1, 1.2] inside an outer
// tube r in [1.2, 1.5], z in [0, 1], u_z = 0 on all four ends, a follower pressure 0.1 on the
// bore: the tubes are pressed together on the cylinder r = 1.2. Structured quad4 meshes with
// the same radial divisions, so the z-independent state is the exact discrete solution of
// both discretizations: mortar with non-matching axial divisions (7 against 5) must give the
// interface pressure and radial displacement of node-to-segment on matching ones (5 and 5),
// uniform along z.
namespace {

std::string tubes_geo(const std::string& name, int nz_inner, int nz_outer) {
  std::ostringstream g;
  const double r[3] = {1.0, 1.2, 1.5};
  const int nz[2] = {nz_inner, nz_outer}, nr[2] = {4, 5};
  const char* grp[2][4] = {{"in_bottom", "in_out", "in_top", "bore"}, {"out_bottom", "mantle", "out_top", "out_in"}};
  for (int k = 0; k < 2; ++k) {
    const int o = 4 * k;
    g << "Point(" << o + 1 << ") = {" << r[k] << ", 0, 0, 1};\nPoint(" << o + 2 << ") = {" << r[k + 1] << ", 0, 0, 1};\n"
      << "Point(" << o + 3 << ") = {" << r[k + 1] << ", 1, 0, 1};\nPoint(" << o + 4 << ") = {" << r[k] << ", 1, 0, 1};\n";
    for (int l = 0; l < 4; ++l) g << "Line(" << o + l + 1 << ") = {" << o + l + 1 << ", " << o + (l + 1) % 4 + 1 << "};\n";
    g << "Transfinite Curve{" << o + 1 << ", " << o + 3 << "} = " << nr[k] + 1 << ";\n"
      << "Transfinite Curve{" << o + 2 << ", " << o + 4 << "} = " << nz[k] + 1 << ";\n"
      << "Curve Loop(" << k + 1 << ") = {" << o + 1 << ", " << o + 2 << ", " << o + 3 << ", " << o + 4 << "};\n"
      << "Plane Surface(" << k + 1 << ") = {" << k + 1 << "};\nTransfinite Surface{" << k + 1 << "};\n";
    for (int l = 0; l < 4; ++l) g << "Physical Curve(\"" << grp[k][l] << "\") = {" << o + l + 1 << "};\n";
  }
  g << "Physical Surface(\"inner\") = {1};\nPhysical Surface(\"outer\") = {2};\n";
  return write_file(name, g.str());
}

struct TubeResult {
  double pressure = 0, pressure_spread = 0, ur = 0, ur_spread = 0;
  int slave = 0, iterations = 0;
};

TubeResult tubes(const std::string& disc, int nz_inner, int nz_outer) {
  DeckSpec s;
  const std::string tag = "tubes_" + disc + "_" + std::to_string(nz_inner) + "_" + std::to_string(nz_outer);
  s.mesh = tubes_geo(tag + ".geo", nz_inner, nz_outer);
  s.recombine = true;
  s.fields = true;
  s.bodies = {"inner", "outer"};
  s.bcs = dirichlet("e1", "in_bottom", "y", "") + dirichlet("e2", "in_top", "y", "") + dirichlet("e3", "out_bottom", "y", "") +
          dirichlet("e4", "out_top", "y", "") +
          "<ParameterList name=\"p\"><Parameter name=\"type\" type=\"string\" value=\"pressure\"/>"
          "<Parameter name=\"boundary\" type=\"string\" value=\"bore\"/><Parameter name=\"pressure\" type=\"double\" value=\"0.1\"/></ParameterList>";
  s.contact = contact_pair("fit", "in_out", "out_in", disc);
  const RunResult res = run(make_deck(s, tag), tag);
  stentor::testing::H5Results h5(work_dir() / tag / "run.h5");
  const std::string step = "/step_" + std::to_string(h5.times().size() - 1) + "/";
  const auto X = h5.read("/mesh/coordinates"), pr = h5.read(step + "contact_pressure"), st = h5.read(step + "contact_status"),
             u = h5.read(step + "displacement");
  TubeResult t;
  t.iterations = res.newton_iterations;
  double pmin = 1e300, pmax = -1e300, umin = 1e300, umax = -1e300;
  for (std::size_t n = 0; n < pr.size(); ++n) {
    if (X[3 * n] != 1.2 || st[n] < 0.0) continue;  // slave nodes: the inner tube's outer surface
    ++t.slave;
    pmin = std::min(pmin, pr[n]), pmax = std::max(pmax, pr[n]);
    umin = std::min(umin, u[3 * n]), umax = std::max(umax, u[3 * n]);
  }
  t.pressure = 0.5 * (pmin + pmax), t.pressure_spread = pmax - pmin;
  t.ur = 0.5 * (umin + umax), t.ur_spread = umax - umin;
  return t;
}

}  // namespace

TEST(Axisymmetric, MortarTubeInTubeEqualsNodeToSegmentOnMatchingMeshes) {
  const TubeResult nts = tubes("node-to-segment", 5, 5), mortar = tubes("mortar", 7, 5);
  std::printf("[axisymmetric] tube in tube: node-to-segment (matching 5/5) interface pressure %.15f, u_r %.15f (spread along z %.1e, %.1e); "
              "mortar (7/5) %.15f, u_r %.15f (spread %.1e, %.1e); relative differences %.1e, %.1e; %d slave nodes, %d Newton iterations\n",
              nts.pressure, nts.ur, nts.pressure_spread, nts.ur_spread, mortar.pressure, mortar.ur, mortar.pressure_spread, mortar.ur_spread,
              std::abs(mortar.pressure - nts.pressure) / nts.pressure, std::abs(mortar.ur - nts.ur) / nts.ur, mortar.slave, mortar.iterations);
  EXPECT_EQ(nts.slave, 6);
  EXPECT_EQ(mortar.slave, 8);
  EXPECT_GT(nts.pressure, 0.01);  // in contact, carrying a good part of the bore's 0.1
  EXPECT_LT(nts.pressure, 0.1);
  EXPECT_LT(nts.pressure_spread, 1e-10 * nts.pressure);
  EXPECT_LT(mortar.pressure_spread, 1e-10 * nts.pressure);
  EXPECT_LT(mortar.ur_spread, 1e-10 * nts.ur);
  EXPECT_LT(std::abs(mortar.pressure - nts.pressure), 1e-10 * nts.pressure);
  EXPECT_LT(std::abs(mortar.ur - nts.ur), 1e-10 * nts.ur);
}

// j. The laws with Gauss-point history and with fibres through the same axisymmetric kernel:
// the ring section of a. with neo-Hookean plasticity (yield stress 0.02: the deformation
// flows) and with Holzapfel-Gasser-Ogden fibres at +-30 deg to the hoop direction about the
// axis of revolution; the global tangent against central differences of the residual.
TEST(Axisymmetric, PlasticityAndFibresTangentAgainstFiniteDifferences) {
  const std::vector<std::pair<std::string, std::string>> laws = {
      {"neo-Hookean plasticity",
       "<Parameter name=\"yield stress\" type=\"double\" value=\"0.02\"/><Parameter name=\"hardening\" type=\"double\" value=\"0.1\"/>"},
      {"Holzapfel-Gasser-Ogden",
       "<Parameter name=\"k1\" type=\"double\" value=\"2\"/><Parameter name=\"k2\" type=\"double\" value=\"0.8\"/>"
       "<Parameter name=\"fibre angle\" type=\"double\" value=\"30\"/>"
       "<Parameter name=\"axis\" type=\"Array(double)\" value=\"{0, 1, 0}\"/>"
       "<Parameter name=\"axis point\" type=\"Array(double)\" value=\"{0, 0}\"/>"}};
  for (const auto& [model, params] : laws) {
    DeckSpec s;
    s.mesh = rectangle_geo("ring_fd.geo", 0.5, 1.5, 0.0, 1.0);
    s.size = 0.35;
    s.order = 2;
    s.model = model;
    s.material_xml = params;
    s.bcs = kRingFdLoads;
    const AssemblerFixture f(make_deck(s, "ring_fd_law"));
    const FdCheck c = global_fd(f, 1.0);
    std::printf("[axisymmetric] global FD, %s: |K v - FD|/|K v| = %.2e, plastic dissipation of the trial state %.3e\n",
                model.c_str(), c.rel, c.plastic);
    EXPECT_LT(c.rel, 1e-6) << model;
    if (model == "neo-Hookean plasticity") EXPECT_GT(c.plastic, 0.0);
  }
}

// ---------------------------------------------------------------------------------------
// k. A long solid cylinder (radius b = 1, u_z = 0 on its ends) spinning about its axis,
// loaded by the centrifugal body force rho omega^2 r e_r (a field, dead), small strain
// (rho omega^2 b^2 / mu = 1e-4): linear elasticity gives, with M = lambda + 2 mu,
//   u_r = rho omega^2 r / (8 M) [(2 lambda + 3 mu)/(lambda + mu) b^2 - r^2], u_z = 0
// (sigma_rr(b) = 0 holds only with the hoop term lambda u_r/r); P2 meshes touching the axis,
// h halved. u_z is 0 up to the discretisation error of the unstructured triangles.
TEST(Axisymmetric, SpinningCylinderAgainstLinearElasticity) {
  const double mu = 1.0, lambda = 3.0, rw2 = 1e-4, b = 1.0, M = lambda + 2 * mu;
  auto ur = [=](double r) { return rw2 * r / (8 * M) * ((2 * lambda + 3 * mu) / (lambda + mu) * b * b - r * r); };
  std::vector<double> err;
  for (const double h : {0.25, 0.125}) {
    DeckSpec s;
    s.mesh = rectangle_geo("spin.geo", 0.0, b, 0.0, 0.25);
    s.size = h;
    s.order = 2;
    s.bcs = dirichlet("base", "bottom", "y", "") + dirichlet("lid", "top", "y", "") +
            "<ParameterList name=\"spin\"><Parameter name=\"type\" type=\"string\" value=\"body force\"/>"
            "<Parameter name=\"force\" type=\"Array(double)\" value=\"{1, 0}\"/></ParameterList>";
    const std::string tag = "spin_" + std::to_string(h);
    Config cfg = make_deck(s, tag);
    for (auto& l : cfg.loads)
      if (l.type == LoadConfig::Type::BodyForce) l.field = [=](const double* X) { return std::array<double, 3>{rw2 * X[0], 0.0, 0.0}; };
    const RunResult res = run(cfg, tag);
    double e = 0, uz = 0;
    for (std::size_t n = 0; n < res.mesh.num_nodes(); ++n) {
      e = std::max(e, std::abs(res.displacement[3 * n] - ur(res.mesh.x[3 * n])));
      uz = std::max(uz, std::abs(res.displacement[3 * n + 1]));
    }
    std::printf("[axisymmetric] spinning cylinder P2 h = %.3f: u_r(b) %.6e, max |u_r - u_r,exact| / u_r(b) %.2e, max |u_z| / u_r(b) %.1e\n", h,
                ur(b), e / ur(b), uz / ur(b));
    err.push_back(e / ur(b));
    EXPECT_LT(uz, 1e-3 * ur(b));
  }
  EXPECT_LT(err[0], 1e-3);
  EXPECT_LT(err[1], 0.5 * err[0]);
}

// ---------------------------------------------------------------------------------------
// l. Output->Stent Metrics in axisymmetry: a tube section r in [1.5, 2.25], z in [0, 1]
// (quad4) driven through the homogeneous state u = f (a r, b z) by Dirichlet sets on its
// four sides (u_r = f a R on the bore and the mantle, u_z = f b on the top), f = 1 at the
// end of stage "expand", f2 = 0.9 at the end of stage "recoil". F = diag(1 + a f, 1 + b f,
// 1 + a f) everywhere, so with the bore as the lumen and the mantle as the "stent":
// lumen radius 1.5 (1 + a f), stent radius 2.25 (1 + a f) (middle = ends, dogboning 0),
// stent length 1 + b f (foreshortening -b f), the hoop stress sigma_thth = sigma_rr of the
// neo-Hookean law (the plane-strain metric would report sigma_zz out of the plane, here the
// axial stress), von Mises |sigma_rr - sigma_zz|, and the radial recoil of stage 2
// a (1 - f2) / (1 + a).
namespace {

std::string stent_metrics_tube_deck(double a, double b, double f2) {
  const std::string geo = rectangle_geo("metrics_tube.geo", 1.5, 2.25, 0.0, 1.0);
  std::ostringstream x;
  x.precision(17);
  auto load = [&](const std::string& name, const std::string& group, const char* comp, double v) {
    x << "<ParameterList name=\"" << name << "\"><Parameter name=\"type\" type=\"string\" value=\"Dirichlet\"/>"
      << "<Parameter name=\"boundary\" type=\"string\" value=\"" << group << "\"/>"
      << "<Parameter name=\"components\" type=\"string\" value=\"" << comp << "\"/>"
      << "<Parameter name=\"values\" type=\"Array(double)\" value=\"{" << v << "}\"/></ParameterList>\n";
  };
  x << "<ParameterList name=\"stentor\">\n"
    << "<ParameterList name=\"Problem\"><Parameter name=\"kinematics\" type=\"string\" value=\"axisymmetric\"/></ParameterList>\n"
    << "<ParameterList name=\"Mesh\"><Parameter name=\"file\" type=\"string\" value=\"" << geo << "\"/>"
    << "<Parameter name=\"size\" type=\"double\" value=\"0.25\"/><Parameter name=\"recombine\" type=\"bool\" value=\"true\"/></ParameterList>\n"
    << "<ParameterList name=\"Materials\"><ParameterList name=\"m\"><Parameter name=\"model\" type=\"string\" value=\"neo-Hookean\"/>"
    << "<Parameter name=\"mu\" type=\"double\" value=\"1\"/><Parameter name=\"lambda\" type=\"double\" value=\"3\"/></ParameterList></ParameterList>\n"
    << "<ParameterList name=\"Bodies\"><ParameterList name=\"wall\"><Parameter name=\"material\" type=\"string\" value=\"m\"/></ParameterList></ParameterList>\n"
    << "<ParameterList name=\"Boundary Conditions\">\n";
  load("bore", "inner", "x", a * 1.5);
  load("mantle", "outer", "x", a * 2.25);
  load("bottom", "bottom", "y", 0.0);
  load("top", "top", "y", b);
  x << "</ParameterList>\n<ParameterList name=\"Stages\">\n"
    << "<ParameterList name=\"expand\"><Parameter name=\"duration\" type=\"double\" value=\"1\"/><Parameter name=\"steps\" type=\"int\" value=\"2\"/></ParameterList>\n"
    << "<ParameterList name=\"recoil\"><Parameter name=\"duration\" type=\"double\" value=\"1\"/><ParameterList name=\"Ramps\">";
  for (const char* l : {"bore", "mantle", "top"})
    x << "<ParameterList name=\"" << l << "\"><Parameter name=\"ramp\" type=\"string\" value=\"table\"/>"
      << "<Parameter name=\"ramp times\" type=\"Array(double)\" value=\"{0, 1}\"/>"
      << "<Parameter name=\"ramp factors\" type=\"Array(double)\" value=\"{1, " << f2 << "}\"/></ParameterList>";
  x << "</ParameterList></ParameterList>\n</ParameterList>\n"
    << "<ParameterList name=\"Newton\"><Parameter name=\"relative residual tolerance\" type=\"double\" value=\"1e-13\"/>"
    << "<Parameter name=\"absolute residual tolerance\" type=\"double\" value=\"1e-14\"/></ParameterList>\n"
    << "<ParameterList name=\"Linear Solver\"><Parameter name=\"method\" type=\"string\" value=\"direct\"/></ParameterList>\n"
    << "<ParameterList name=\"Output\"><Parameter name=\"fields\" type=\"bool\" value=\"false\"/>"
    << "<Parameter name=\"basename\" type=\"string\" value=\"tube\"/><ParameterList name=\"Stent Metrics\">"
    << "<Parameter name=\"axis point\" type=\"Array(double)\" value=\"{0, 0}\"/>"
    << "<Parameter name=\"axis\" type=\"Array(double)\" value=\"{0, 1, 0}\"/>"
    << "<Parameter name=\"stent\" type=\"string\" value=\"outer\"/><Parameter name=\"lumen\" type=\"string\" value=\"inner\"/>"
    << "<Parameter name=\"artery\" type=\"string\" value=\"wall\"/></ParameterList></ParameterList>\n</ParameterList>\n";
  return write_file("metrics_tube.xml", x.str());
}

}  // namespace

TEST(Axisymmetric, StentMetricsOfAHomogeneouslyExpandedTube) {
  const double a = 0.2, b = -0.05, f2 = 0.9, mu = 1.0, lambda = 3.0;
  const Config cfg = read_deck(stent_metrics_tube_deck(a, b, f2));
  run(cfg, "metrics_tube");
  const Series s = read_csv(work_dir() / "metrics_tube" / "tube_metrics.csv");
  const Series st = read_csv(work_dir() / "metrics_tube" / "tube_stages.csv");
  ASSERT_EQ(s.rows(), 4u);  // t = 0, 2 steps of "expand", 1 of "recoil"
  ASSERT_EQ(st.rows(), 2u);
  double err = 0.0;
  auto check = [&](double got, double want) { err = std::max(err, std::abs(got - want) / std::max(1.0, std::abs(want))); };
  for (std::size_t i = 0; i < s.rows(); ++i) {
    const double f = i == 0 ? 0.0 : i == 1 ? 0.5 : i == 2 ? 1.0 : f2;
    const double lr = 1 + a * f, lz = 1 + b * f, J = lr * lr * lz, lnJ = std::log(J);
    const double s_rr = mu / J * (lr * lr - 1) + lambda * lnJ / J, s_zz = mu / J * (lz * lz - 1) + lambda * lnJ / J;
    check(s["lumen_radius_mean"][i], 1.5 * lr);
    check(s["lumen_radius_min"][i], 1.5 * lr);
    for (const char* c : {"stent_radius_mean", "stent_radius_middle", "stent_radius_ends"}) check(s[c][i], 2.25 * lr);
    check(s["dogboning"][i], 0.0);
    check(s["stent_length"][i], lz);
    check(s["foreshortening"][i], -b * f);
    check(s["artery_hoop_stress_max"][i], s_rr);
    check(s["artery_von_mises_max"][i], std::abs(s_rr - s_zz));
    check(s["contact_pressure_max"][i], 0.0);
    if (i == 2) std::printf("[axisymmetric] stent metrics at f = 1: lumen radius %.15f (1.5 (1 + a) = %.15f), hoop stress %.15f "
                            "(closed form %.15f)\n", s["lumen_radius_mean"][i], 1.5 * lr, s["artery_hoop_stress_max"][i], s_rr);
  }
  check(st["lumen_gain"][0], a);
  check(st["lumen_gain"][1], a * f2);
  check(st["stent_radius_max"][1], 2.25 * (1 + a));
  check(st["radial_recoil"][0], 0.0);
  check(st["radial_recoil"][1], a * (1 - f2) / (1 + a));
  std::printf("[axisymmetric] stent metrics: radial recoil %.15f (a (1 - f2)/(1 + a) = %.15f), largest error over every "
              "column and row %.1e\n", st["radial_recoil"][1], a * (1 - f2) / (1 + a), err);
  EXPECT_LT(err, 1e-12);
}

// ---------------------------------------------------------------------------------------
// m. The scene S4-axi (inputs/s4_axi.xml) on a coarse section (tests/cli/decks/
// s4_axi_coarse.geo: 2 wire turns, 209 cells): the rigid balloon (radius 1.25 + 0.35)
// holds the rings' inner faces at r = 1.6 at the end of inflation (stent radius 1.6, no
// dogboning), and the radial recoil after deflation is the elastic spring-back of a thin
// 316L ring that unloads from the yield stress, (Y + H alpha)/E with alpha = ln(r_m/r_m0)
// the plastic hoop strain of its mid radius (r_m0 = 1.40; r_m = 1.6 + w'/2 with the side
// w' = w / sqrt(r_m/r_m0) of an isochoric section). The estimate neglects the radial stress
// (the balloon's pressure, about sigma w / r, 6 % of sigma at the inner face, 3 % on
// average) and the artery's small residual load: 10 % tolerance.
TEST(Axisymmetric, S4AxiCoarseRecoilIsTheElasticSpringBack) {
  Config cfg = read_deck(std::string(STENTOR_SOURCE_DIR) + "/inputs/s4_axi.xml");
  cfg.mesh.file = std::string(STENTOR_SOURCE_DIR) + "/tests/cli/decks/s4_axi_coarse.geo";
  cfg.output.fields = false;
  run(cfg, "s4_axi_coarse");
  const Series st = read_csv(work_dir() / "s4_axi_coarse" / "s4_axi_stages.csv");
  ASSERT_EQ(st.rows(), 3u);  // inflation, deflation, withdrawal
  const double E = 196000.0, Y = 205.0, H = 694.45, w = 0.1, rm0 = 1.40;
  double rm = 1.65;
  for (int k = 0; k < 50; ++k) rm = 1.6 + 0.5 * w / std::sqrt(rm / rm0);
  const double recoil = (Y + H * std::log(rm / rm0)) / E;
  std::printf("[axisymmetric] S4-axi coarse: stent radius %.12f after inflation, dogboning %.1e; lumen gain %.4f; "
              "radial recoil %.5f against the thin-ring spring-back %.5f (r_m %.4f)\n",
              st["stent_radius_mean"][0], st["dogboning"][0], st["lumen_gain"][1], st["radial_recoil"][1], recoil, rm);
  EXPECT_NEAR(st["stent_radius_mean"][0], 1.6, 1e-9);
  EXPECT_NEAR(st["dogboning"][0], 0.0, 1e-9);
  EXPECT_NEAR(st["radial_recoil"][1], recoil, 0.1 * recoil);
  EXPECT_NEAR(st["radial_recoil"][2], st["radial_recoil"][1], 1e-3 * recoil);  // the withdrawn balloon touches nothing
  EXPECT_GT(st["lumen_gain"][1], 0.1);                          // the stent holds the lumen open
}

// ---------------------------------------------------------------------------------------
// n. The dynamic S4-axi (inputs/s4_axi_dynamic.xml: the procedure of m with every stage
// dynamic, Gonzalez, the persistence condition on both pairs) on the coarse section of m.
// The energy CSV's identity E_{n+1} - E_n = W_contact - D_plastic - D_friction (no external
// load, supports at rest) is checked per step and over the run, relative to the largest total
// energy E = K + W; the terms it balances are all present (the inflating balloon's work, the
// turns' plastic flow, friction on the lumen, inertia). The balloon's inner-face contact starts
// on a step end (28 steps, touch at 2/7 of the inflation), so the persistence condition holds
// the turns on the balloon at radius 1.6 without the overlap of a mid-step touch.
TEST(Axisymmetric, S4AxiDynamicCoarseKeepsTheEnergyIdentity) {
  Config cfg = read_deck(std::string(STENTOR_SOURCE_DIR) + "/inputs/s4_axi_dynamic.xml");
  cfg.mesh.file = std::string(STENTOR_SOURCE_DIR) + "/tests/cli/decks/s4_axi_coarse.geo";
  cfg.output.fields = false;
  run(cfg, "s4_axi_dynamic_coarse");
  const Series e = read_csv(work_dir() / "s4_axi_dynamic_coarse" / "s4_axi_dynamic_energy.csv");
  const Series st = read_csv(work_dir() / "s4_axi_dynamic_coarse" / "s4_axi_dynamic_stages.csv");
  ASSERT_GT(e.rows(), 30u);
  ASSERT_EQ(st.rows(), 3u);
  double Emax = 0, bal = 0, Kmax = 0;
  for (std::size_t i = 0; i < e.rows(); ++i) {
    Emax = std::max(Emax, std::abs(e["total"][i]));
    bal = std::max(bal, std::abs(e["balance_residual"][i]));
    Kmax = std::max(Kmax, e["kinetic"][i]);
  }
  const std::size_t n = e.rows() - 1;
  const double Wc = e["contact_work"][n], Dp = e["plastic_dissipation"][n], Df = e["friction_dissipation"][n];
  const double run_defect = e["total"][n] - e["total"][0] -
                            (e["external_work"][n] + e["support_work"][n] - e["dissipation"][n] + Wc - Df);
  std::printf("[axisymmetric] S4-axi dynamic coarse: %zu rows, largest E %.6e, max |balance| per step %.2e E, over the run "
              "%.2e E; W_contact %.4e, D_plastic %.4e, D_friction %.3e, max kinetic %.2e E; stent radius %.12f after "
              "inflation, radial recoil %.5f, lumen gain %.4f\n",
              e.rows(), Emax, bal / Emax, run_defect / Emax, Wc, Dp, Df, Kmax / Emax, st["stent_radius_mean"][0],
              st["radial_recoil"][1], st["lumen_gain"][1]);
  EXPECT_LT(bal, 1e-10 * Emax);
  EXPECT_LT(std::abs(run_defect), 1e-10 * Emax);
  EXPECT_EQ(e["external_work"][n], 0.0);
  EXPECT_GT(Wc, Emax);                  // the balloon's work: stored in the wall and the turns, and dissipated
  EXPECT_GT(Dp, 0.5 * Emax);            // the turns yield
  EXPECT_GT(Df, 0.0);                   // the lumen slides on the turns
  EXPECT_NEAR(e["dissipation"][n], Dp, 1e-12 * Emax);  // no viscosity: the dissipation is plastic
  EXPECT_GT(Kmax, 0.0);                 // inertia is present,
  EXPECT_LT(Kmax, 1e-6 * Emax);         // and small: a 1 s inflation is quasi-static
  EXPECT_NEAR(st["stent_radius_mean"][0], 1.6, 1e-9);
  EXPECT_GT(st["radial_recoil"][1], 0.0);
  EXPECT_GT(st["lumen_gain"][1], 0.1);  // the stent holds the lumen open
}
