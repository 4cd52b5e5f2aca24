// Contact verification cases (docs/verification.md, "Contact"; docs/scenes/README.md).
//  1. 1D Signorini bar (Doyen, Ern & Piperno 2011), inputs/signorini.xml: a strip of one row
//     of Q1 cells with nu -> 0 (exactly 1D), E = rho = 1, fixed at x = 1, persistence contact
//     at x = 0. Started from the reference solution's state at t = 1 (u = 0, v = -a/2: a
//     uniform velocity, the only initial field a deck can give; docs/verification.md), so
//     time here is t_ref - 1. Compared with the closed form over one period (3): u(0, t),
//     the contact impulse and mean contact stress, the energy; errors shrink under refinement.
//  2. Hertz line contact (plane strain), inputs/hertz.xml: half disk pressed on the plane by
//     its flat top; contact half-width and peak pressure (from the nodal contact forces)
//     against a = sqrt(4 P R / (pi E*)), p0 = 2 P / (pi a) at two refinements.
//  3. S1(a) coarse (inputs/s1_ring.xml, h = 0.1, 80 steps): frictionless persistence
//     conserves E through the impact; gap loses a measurable amount (all in contact_work);
//     with friction E_0 - E_T = friction dissipation to solver tolerance.
//  4. Semi-smooth Newton on S1 (frictionless and mu = 0.3): the active/stick/slip set sizes
//     printed per evaluation (--verbose) settle within a few iterations; Newton iterations
//     per step (median, max).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "assembly/Assembler.hpp"
#include "bc/Loads.hpp"
#include "parallel/Distribution.hpp"
#include "CsvSeries.hpp"
#include "run/Simulation.hpp"
#include "TestDir.hpp"

using namespace stentor;
using stentor::testing::read_csv;
using stentor::testing::Series;
namespace fs = std::filesystem;

namespace {

fs::path work_dir() { return stentor::testing::test_dir("contact_verification"); }
const std::string kInputs = std::string(STENTOR_SOURCE_DIR) + "/inputs/";


struct Outcome {
  int status = -1;
  RunResult res;
  Series history, energy;
  std::string log;  // stdout of the run (with verbose: per-iteration lines)
};

Outcome run(const Config& cfg, const std::string& tag, bool verbose = false) {
  RunOptions opts;
  const fs::path dir = work_dir() / tag;
  opts.output_dir = dir.string();
  opts.verbose = verbose;
  Outcome r;
  std::ostringstream capture;
  std::streambuf* old = std::cout.rdbuf(capture.rdbuf());
  try {
    r.status = run_simulation(cfg, opts, &r.res);
  } catch (...) {
    std::cout.rdbuf(old);
    throw;
  }
  std::cout.rdbuf(old);
  r.log = capture.str();
  EXPECT_EQ(r.status, 0) << tag << "\n" << r.log.substr(r.log.size() > 3000 ? r.log.size() - 3000 : 0);
  r.history = read_csv(dir / (cfg.output.basename + "_history.csv"));
  if (cfg.problem.dynamic()) r.energy = read_csv(dir / (cfg.output.basename + "_energy.csv"));
  return r;
}

// A copy of inputs/<geo> with the line starting with `key` (e.g. "N = DefineNumber[40")
// rewritten to `replacement`, in the test's output folder.
std::string geo_variant(const std::string& geo, const std::string& key, const std::string& replacement, const std::string& tag) {
  std::ifstream in(kInputs + geo);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const auto pos = s.find(key);
  if (pos == std::string::npos) throw std::runtime_error(geo + ": no '" + key + "'");
  s.replace(pos, key.size(), replacement);
  fs::create_directories(work_dir());
  const fs::path out = work_dir() / (tag + ".geo");
  std::ofstream(out) << s;
  return out.string();
}

// ---------------------------------------------------------------------------------------
// 1. Signorini bar.
const double kAmp = 1e-3, kThick = 0.025;

// Closed form in the shifted time s = t_ref - 1 (period 3), amplitude a = kAmp.
double signorini_u0(double s) {
  s = std::fmod(s, 3.0);
  if (s <= 1.0) return 0.0;
  return s <= 2.0 ? kAmp * (s - 1.0) / 2.0 : kAmp * (3.0 - s) / 2.0;
}

struct SignoriniErrors {
  int N = 0;
  double u_max = 0, u_l1 = 0, impulse = 0, mean_stress = 0, E0_ratio = 0, E_dev = 0, release = 0, min_gap = 0;
  double newton_median = 0;
};

SignoriniErrors signorini(int N) {
  Config cfg = read_deck(kInputs + "signorini.xml");
  cfg.mesh.file = geo_variant("signorini.geo", "N = DefineNumber[40", "N = DefineNumber[" + std::to_string(N), "signorini_N" + std::to_string(N));
  cfg.stepping.num_steps = 3 * N;  // dt = h (c = 1)
  cfg.output.basename = "signorini_N" + std::to_string(N);
  const Outcome r = run(cfg, "signorini_N" + std::to_string(N));
  const Series& h = r.history;
  const Series& e = r.energy;
  SignoriniErrors out;
  out.N = N;
  const double half = kAmp / 2;  // scale of u(0,t) and of the contact stress
  std::vector<int> its;
  for (std::size_t i = 0; i < h.rows(); ++i) {
    const double s = h["time"][i], dt = h["dt"][i], u = h["u_end_x"][i];
    out.u_max = std::max(out.u_max, std::abs(u - signorini_u0(s)) / half);
    out.u_l1 += dt * std::abs(u - signorini_u0(s)) / half / 3.0;
    const double F = h["contact_wall_force_x"][i];  // on the body, +x
    if (s < 1.5) out.impulse += dt * F / kThick / half;  // exact: (a/2) * 1
    if (h["contact_wall_active"][i] > 0 && s < 2.0) out.release = s;
    out.min_gap = std::min(out.min_gap, h["contact_wall_min_gap"][i] / half);
    its.push_back(static_cast<int>(h["newton_iterations"][i]));
  }
  // Mean contact stress over the middle of the contact phase (0.2 < s < 0.8), from the
  // contact force over the strip thickness; two-step means remove the midpoint rule's
  // odd-even oscillation of the multiplier.
  double sum = 0, T = 0;
  for (std::size_t i = 0; i < h.rows(); ++i)
    if (h["time"][i] > 0.2 && h["time"][i] <= 0.8) {
      sum += h["dt"][i] * h["contact_wall_force_x"][i] / kThick;
      T += h["dt"][i];
    }
  out.mean_stress = sum / T / half;
  const double E0 = e["total"][0];
  for (double v : e["total"]) out.E_dev = std::max(out.E_dev, std::abs(v - E0) / E0);
  out.E0_ratio = E0 / (kAmp * kAmp * kThick / 8.0);
  std::sort(its.begin(), its.end());
  out.newton_median = its[its.size() / 2];
  std::printf("[contact-verif] Signorini N=%3d dt=h: max|u(0)-exact|/(a/2) %.4f, L1 mean %.4f, impulse/exact %.4f, "
              "mean stress (0.2<t<0.8)/exact %.4f, release t %.4f (exact 1), min gap/(a/2) %.4f, E0/E_exact %.6f "
              "(1 - 2/(3N) = %.6f), max|E-E0|/E0 %.1e, Newton median %g\n",
              N, out.u_max, out.u_l1, out.impulse, out.mean_stress, out.release, out.min_gap, out.E0_ratio, 1.0 - 2.0 / (3.0 * N),
              out.E_dev, out.newton_median);
  return out;
}

TEST(ContactVerification, SignoriniBar) {
  std::vector<SignoriniErrors> r;
  for (int N : {20, 40, 80}) r.push_back(signorini(N));
  for (std::size_t k = 0; k < r.size(); ++k) {
    // Persistence + Gonzalez: energy conserved through impact and release to solver tolerance.
    EXPECT_LT(r[k].E_dev, 1e-8);
    // The discrete initial energy is the kinetic energy of v = -a/2 with the fixed end at
    // rest: consistent Q1 mass gives exactly (1 - 2/(3N)) of the continuum a^2 H / 8.
    EXPECT_NEAR(r[k].E0_ratio, 1.0 - 2.0 / (3.0 * r[k].N), 1e-6);
    EXPECT_LE(r[k].newton_median, 3);
  }
  for (std::size_t k = 1; k < r.size(); ++k) {
    EXPECT_LT(r[k].u_l1, 0.75 * r[k - 1].u_l1);                               // measured ratio ~0.58
    EXPECT_LT(std::abs(r[k].impulse - 1), 0.75 * std::abs(r[k - 1].impulse - 1));  // ~0.58
    EXPECT_LT(std::abs(r[k].release - 1), 0.75 * std::abs(r[k - 1].release - 1) + 1e-9);
  }
  const auto& f = r.back();  // N = 80
  EXPECT_LT(f.u_max, 0.05);
  EXPECT_LT(f.u_l1, 0.015);
  EXPECT_NEAR(f.impulse, 1.0, 0.025);
  EXPECT_NEAR(f.mean_stress, 1.0, 0.05);
  EXPECT_GT(f.min_gap, -0.01);  // transient penetration after release: O(h) (leapfrog)
}

// ---------------------------------------------------------------------------------------
// 2. Hertz. Nodal contact forces: f_int - f_ext at the final state on the slave nodes (the
// contact force on the body, as Contact computes it), re-assembled here from the result.
struct HertzResult {
  double hc = 0, P = 0, a_hertz = 0, p0_hertz = 0, a_edge = 0, a_moment = 0, p0 = 0;
  long active = 0;
};

HertzResult hertz(double hc) {
  Config cfg = read_deck(kInputs + "hertz.xml");
  char buf[64];
  std::snprintf(buf, sizeof buf, "hc = DefineNumber[%g", hc);
  const std::string tag = "hertz_" + std::to_string(static_cast<int>(std::lround(1e4 * hc)));
  cfg.mesh.file = geo_variant("hertz.geo", "hc = DefineNumber[0.004", buf, tag);
  cfg.output.basename = "hertz";
  const Outcome r = run(cfg, tag);
  HertzResult out;
  out.hc = hc;
  const std::size_t last = r.history.rows() - 1;
  out.P = r.history["contact_floor_force_y"][last];
  out.active = static_cast<long>(r.history["contact_floor_active"][last]);
  const double E = 1.0, nu = 0.3, R = 1.0, Es = E / (1 - nu * nu);
  out.a_hertz = std::sqrt(4 * out.P * R / (M_PI * Es));
  out.p0_hertz = 2 * out.P / (M_PI * out.a_hertz);

  // Internal forces at the final displacement.
  const Mesh& mesh = r.res.mesh;
  auto comm = Tpetra::getDefaultComm();
  Distribution dist(mesh, comm);
  const Loads loads = resolve_loads(cfg, mesh);
  Assembler as(mesh, dist, cfg, loads, block_materials(cfg, mesh));
  la::Vector u(dist.owned_map()), res(dist.owned_map());
  {
    auto uh = u.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (la::LO l = 0; l < dist.num_owned_nodes(); ++l)
      for (int c = 0; c < 2; ++c) uh(2 * l + c, 0) = r.res.displacement[3 * static_cast<std::size_t>(dist.global_node(l)) + c];
  }
  as.assemble(u, cfg.stepping.end_time, cfg.stepping.end_time, res, false);
  auto rh = as.static_residual().getLocalViewHost(Tpetra::Access::ReadOnly);
  // Contact nodes: on the arc, at the plane (gap below 1e-9 R); force f_y = r_y.
  struct CNode {
    double x, f;
  };
  std::vector<CNode> nodes;
  std::vector<double> arc_x;  // deformed x of all arc nodes near the contact, sorted
  for (la::LO l = 0; l < dist.num_owned_nodes(); ++l) {
    const auto g = static_cast<std::size_t>(dist.global_node(l));
    const double X = mesh.x[3 * g], Y = mesh.x[3 * g + 1];
    if (std::abs(std::hypot(X, Y - R) - R) > 1e-9 || Y > 0.5) continue;  // not on the lower arc
    const double x = X + r.res.displacement[3 * g], y = Y + r.res.displacement[3 * g + 1];
    arc_x.push_back(x);
    if (y < 1e-9 * R) nodes.push_back({x, rh(2 * l + 1, 0)});
  }
  std::sort(nodes.begin(), nodes.end(), [](const CNode& a, const CNode& b) { return a.x < b.x; });
  std::sort(arc_x.begin(), arc_x.end());
  double sumf = 0, m2 = 0;
  for (const auto& n : nodes) {
    sumf += n.f;
    m2 += n.f * n.x * n.x;
    out.a_edge = std::max(out.a_edge, std::abs(n.x));
  }
  // Hertz: int p x^2 dx = p0 pi a^3 / 8 and P = pi a p0 / 2, so a^2 = 4 <x^2>_p. Nodal
  // forces put each node's share of the pressure at the node: <x^2> is then biased by
  // +O(h^2) (the square of the tributary half-width): corrected for a uniform h_c.
  out.a_moment = 2 * std::sqrt(std::max(0.0, m2 / sumf - hc * hc / 12));
  // Peak pressure: the force of the node nearest x = 0 over its tributary length.
  std::size_t imid = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (std::abs(nodes[i].x) < std::abs(nodes[imid].x)) imid = i;
  const auto it = std::lower_bound(arc_x.begin(), arc_x.end(), nodes[imid].x);
  const std::size_t k = static_cast<std::size_t>(it - arc_x.begin());
  const double trib = 0.5 * (arc_x[k + 1] - arc_x[k - 1]);
  out.p0 = nodes[imid].f / trib;
  std::printf("[contact-verif] Hertz hc=%.4f: P %.6e (sum of nodal forces %.6e), active %ld, a: Hertz %.5f, edge of "
              "contact nodes %.5f (%+.2f %%), from <x^2>_p %.5f (%+.2f %%); p0: Hertz %.5e, centre node %.5e (%+.2f %%)\n",
              hc, out.P, sumf, out.active, out.a_hertz, out.a_edge, 100 * (out.a_edge - out.a_hertz) / out.a_hertz, out.a_moment,
              100 * (out.a_moment - out.a_hertz) / out.a_hertz, out.p0_hertz, out.p0, 100 * (out.p0 - out.p0_hertz) / out.p0_hertz);
  EXPECT_NEAR(sumf, out.P, 1e-8 * out.P);
  return out;
}

TEST(ContactVerification, HertzCylinderOnPlane) {
  const HertzResult c = hertz(0.008), f = hertz(0.004);
  for (const auto* r : {&c, &f}) {
    // The edge of the contact set is resolved to one element: a_edge in [a - h, a + h].
    EXPECT_NEAR(r->a_edge, r->a_hertz, 1.01 * r->hc);
  }
  const double ea_c = std::abs(c.a_moment - c.a_hertz) / c.a_hertz, ea_f = std::abs(f.a_moment - f.a_hertz) / f.a_hertz;
  const double ep_c = std::abs(c.p0 - c.p0_hertz) / c.p0_hertz, ep_f = std::abs(f.p0 - f.p0_hertz) / f.p0_hertz;
  EXPECT_LT(ea_f, 0.05);
  EXPECT_LT(ep_f, 0.05);
  EXPECT_LT(ea_f, ea_c + 0.005);
  EXPECT_LT(ep_f, ep_c + 0.005);
}

// ---------------------------------------------------------------------------------------
// 3./4. S1 coarse.
Config s1_coarse(const std::string& formulation, double mu) {
  Config cfg = read_deck(kInputs + "s1_ring.xml");
  cfg.mesh.size = 0.1;
  cfg.stepping.end_time = 0.16;
  cfg.stepping.num_steps = 80;
  cfg.contact[0].formulation = formulation;
  cfg.contact[0].friction = mu;
  return cfg;
}

struct NewtonStats {
  double median = 0, median_contact = 0;
  int max = 0, settle_max = 0, steps = 0, contact_steps = 0, settle_le2 = 0, settle_changed = 0;
};

// Per step: Newton iterations, and the settling of the contact sets. --verbose prints the
// set sizes "contact floor: active a (stick s, slip l)" after every evaluation: the first
// line of a step is the state at the initial guess u^0, the last one before each
// "newton k" line the state at u^k. settle = the first k from which the sizes no longer
// change (0: the sets predicted at u^0 were already the final ones). Sizes, not the sets
// themselves: a swap of two nodes would go unseen.
NewtonStats newton_stats(const Outcome& r) {
  NewtonStats st;
  std::vector<int> its, its_c;
  std::istringstream in(r.log);
  std::string line, last_sets;
  const std::regex set_re(R"(contact\s+floor: active (\d+) \(stick (\d+), slip (\d+)\))");
  const std::regex it_re(R"(^\s+newton\s+(\d+)\s+\|r\|)");
  const std::regex step_re(R"(^\s+step\s+\d+\s+t .* newton\s+(\d+) .* contact (\d+)/)");
  std::vector<std::string> sets_at;  // sets at u^0, u^1, ...
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_search(line, m, set_re)) {
      if (sets_at.empty()) sets_at.push_back(m.str(0));  // u^0
      last_sets = m.str(0);
    } else if (std::regex_search(line, m, it_re)) {
      sets_at.push_back(last_sets);
    } else if (std::regex_search(line, m, step_re)) {
      const int n = std::stoi(m.str(1)), act = std::stoi(m.str(2));
      its.push_back(n);
      st.max = std::max(st.max, n);
      bool any = act > 0;
      for (const auto& x : sets_at) any = any || x.find("active 0 ") == std::string::npos;
      if (any) {
        its_c.push_back(n);
        int settle = static_cast<int>(sets_at.size()) - 1;
        while (settle > 0 && sets_at[static_cast<std::size_t>(settle - 1)] == sets_at.back()) --settle;
        st.settle_max = std::max(st.settle_max, settle);
        st.settle_le2 += settle <= 2;
        st.settle_changed += settle > 0;
      }
      sets_at.clear();
    }
  }
  auto median = [](std::vector<int> v) { return v.empty() ? 0.0 : (std::sort(v.begin(), v.end()), double(v[v.size() / 2])); };
  st.median = median(its);
  st.median_contact = median(its_c);
  st.steps = static_cast<int>(its.size());
  st.contact_steps = static_cast<int>(its_c.size());
  return st;
}

TEST(ContactVerification, RingImpactEnergy) {
  const Outcome p = run(s1_coarse("persistence", 0.0), "s1_persistence", true);
  const Outcome g = run(s1_coarse("gap", 0.0), "s1_gap", true);
  const Outcome f = run(s1_coarse("persistence", 0.3), "s1_friction", true);
  const Series& ep = p.energy;
  const Series& eg = g.energy;
  const Series& ef = f.energy;
  const double E0 = ep["total"][0];
  double dev_p = 0, bal_p = 0, closure_f = 0, bal_f = 0, bal_g = 0;
  long contact_steps = 0;
  for (std::size_t i = 0; i < ep.rows(); ++i) {
    dev_p = std::max(dev_p, std::abs(ep["total"][i] - E0));
    bal_p = std::max(bal_p, std::abs(ep["balance_residual"][i]));
  }
  for (double a : p.history["contact_floor_active"]) contact_steps += a > 0;
  for (std::size_t i = 0; i < eg.rows(); ++i) bal_g = std::max(bal_g, std::abs(eg["balance_residual"][i]));
  for (std::size_t i = 0; i < ef.rows(); ++i) {
    closure_f = std::max(closure_f, std::abs(ef["total"][i] - E0 + ef["friction_dissipation"][i] - ef["contact_work"][i]));
    bal_f = std::max(bal_f, std::abs(ef["balance_residual"][i]));
  }
  const std::size_t lg = eg.rows() - 1, lf = ef.rows() - 1;
  const double loss_g = E0 - eg["total"][lg], loss_f = E0 - ef["total"][lf];
  std::printf("[contact-verif] S1 coarse: E0 %.6e, %ld steps with contact; persistence max|E-E0|/E0 %.2e (max |balance| %.2e, "
              "contact work %.2e); gap: E loss %.4f %% (contact work %.4e, max |balance| %.2e); mu = 0.3: E0 - E_T = %.6e, "
              "friction dissipation %.6e, contact work %.2e, max_t |E - E0 + D_f - W_c| %.2e (rel %.1e), max |balance| %.2e\n",
              E0, contact_steps, dev_p / E0, bal_p, ep["contact_work"].back(), 100 * loss_g / E0, eg["contact_work"][lg], bal_g, loss_f,
              ef["friction_dissipation"][lf], ef["contact_work"][lf], closure_f, closure_f / E0, bal_f);
  EXPECT_GT(contact_steps, 10);
  EXPECT_LT(dev_p, 1e-9 * E0);
  EXPECT_GT(loss_g, 1e-3 * E0);                                  // measurable impact loss
  EXPECT_NEAR(loss_g, -eg["contact_work"][lg], 1e-9 * E0);        // ... all of it in the contact work
  EXPECT_GT(ef["friction_dissipation"][lf], 1e-2 * E0);
  EXPECT_LT(closure_f, 1e-9 * E0);                                // E_0 - E_T = friction dissipation
  EXPECT_LT(std::abs(ef["contact_work"][lf]), 1e-9 * E0);         // persistence on a fixed plane: no normal work

  // 4. Semi-smooth Newton.
  for (const auto* o : {&p, &g, &f}) {
    const NewtonStats st = newton_stats(*o);
    const std::string name = o == &p ? "persistence" : o == &g ? "gap" : "persistence mu=0.3";
    std::printf("[contact-verif] S1 coarse Newton (%s): %d steps, median iterations %.0f (steps with contact: %d, median %.0f), max %d; "
                "contact set sizes changed after the initial guess on %d of %d contact steps, settled by iterate <= 2 on %d, worst %d\n",
                name.c_str(), st.steps, st.median, st.contact_steps, st.median_contact, st.max, st.settle_changed, st.contact_steps,
                st.settle_le2, st.settle_max);
    EXPECT_EQ(st.steps, 80);
    EXPECT_LE(st.median_contact, 4);
    EXPECT_LE(st.max, 12);
    EXPECT_LE(st.settle_max, 6);
    EXPECT_GE(st.settle_le2, st.contact_steps * 3 / 4);
  }
}

}  // namespace
