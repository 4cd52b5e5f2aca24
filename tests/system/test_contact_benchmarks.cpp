// Contact between deformable bodies against closed forms and conservation laws
// (docs/contact.md, "Verification"):
//  1. Hertz line contact of two deformable cylinders (plane strain), inputs/hertz_cylinders.xml:
//     node-to-segment on curved, non-matching interface meshes; contact half-width, peak
//     pressure and pressure profile from the run's contact_pressure / contact_status fields
//     against a = sqrt(4 P R* / (pi E*)), p0 = 2 P / (pi a), p(x) = p0 sqrt(1 - x^2 / a^2).
//  2. Ironing (inputs/ironing.xml, coarse): a stiff half-ring die pressed into a slab and
//     slid along it with Coulomb friction mu = 0.3: during steady sliding the tangential
//     and normal contact forces are in the ratio mu, and the frictional dissipation equals
//     the work of the die's horizontal contact force minus the change of stored energy.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "CsvSeries.hpp"
#include "run/Simulation.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

const fs::path kDir = fs::path(STENTOR_BINARY_DIR) / "system_tests" / "contact_benchmarks";
const std::string kInputs = std::string(STENTOR_SOURCE_DIR) + "/inputs/";

// A copy of inputs/<geo> with each `from` (e.g. "hc = DefineNumber[0.004") replaced by `to`,
// written to the test folder.
std::string geo_variant(const std::string& geo, const std::vector<std::pair<std::string, std::string>>& subs, const std::string& name) {
  std::ifstream in(kInputs + geo);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string t = ss.str();
  for (const auto& [from, to] : subs) {
    const auto at = t.find(from);
    if (at == std::string::npos) throw std::runtime_error(geo + ": no '" + from + "'");
    t.replace(at, from.size(), to);
  }
  fs::create_directories(kDir);
  const fs::path p = kDir / name;
  std::ofstream(p) << t;
  return p.string();
}

// Node field `name` of the last output step of an HDF5 result (all mesh nodes).
std::vector<double> last_node_field(const fs::path& h5, const std::string& name) {
  const hid_t f = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  std::vector<double> v;
  if (f < 0) return v;
  int last = -1;
  while (H5Lexists(f, ("/step_" + std::to_string(last + 1)).c_str(), H5P_DEFAULT) > 0) ++last;
  const std::string path = "/step_" + std::to_string(last) + "/" + name;
  if (last >= 0 && H5Lexists(f, path.c_str(), H5P_DEFAULT) > 0) {
    const hid_t d = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
    const hid_t sp = H5Dget_space(d);
    v.resize(static_cast<std::size_t>(H5Sget_simple_extent_npoints(sp)));
    H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    H5Sclose(sp);
    H5Dclose(d);
  }
  H5Fclose(f);
  return v;
}

// ---------------------------------------------------------------------------------------
// 1. Hertz, two cylinders.
struct HertzCylinders {
  double hc = 0, P = 0, a_hertz = 0, p0_hertz = 0;
  double a_edge = 0;     // half the distance between the first free nodes left and right, minus half a cell
  double a_moment = 0;   // 2 sqrt(<x^2>_f - hc^2/12) from the nodal normal forces
  double p0 = 0;         // the largest nodal contact pressure
  double profile_rms = 0;  // RMS over the active nodes of p - p0_H sqrt(1 - x^2/a_H^2), / p0_H
  double inner_rms = 0;    // the same over |x| < 0.8 a_H (away from the edge's square root)
  int active = 0, newton = 0;
};

// hc: mesh size at the contact on the slave side; ratio: master size / slave size there.
HertzCylinders hertz_cylinders(double hc, double ratio) {
  char buf[64], rbuf[64];
  std::snprintf(buf, sizeof buf, "hc = DefineNumber[%g", hc);
  std::snprintf(rbuf, sizeof rbuf, "ratio = DefineNumber[%g", ratio);
  const std::string tag = "hertz_cyl_" + std::to_string(static_cast<int>(std::lround(1e4 * hc))) + "_" +
                          std::to_string(static_cast<int>(std::lround(100 * ratio)));
  Config cfg = read_deck(kInputs + "hertz_cylinders.xml");
  cfg.mesh.file = geo_variant("hertz_cylinders.geo", {{"hc = DefineNumber[0.004", buf}, {"ratio = DefineNumber[1.3", rbuf}}, tag + ".geo");
  cfg.output.every = 1000;  // the last step only
  RunOptions opts;
  const fs::path dir = kDir / tag;
  opts.output_dir = dir.string();
  RunResult res;
  EXPECT_EQ(run_simulation(cfg, opts, &res), 0) << tag;
  HertzCylinders out;
  out.hc = hc;
  out.newton = res.newton_iterations;
  const auto hist = stentor::testing::read_csv(dir / "hertz_cylinders_history.csv");
  out.P = hist["contact_interface_force_y"].back();  // on the upper body, upwards
  const double E = 1.0, nu = 0.3, R = 1.0;
  const double Es = E / (2 * (1 - nu * nu)), Rs = R / 2;
  out.a_hertz = std::sqrt(4 * out.P * Rs / (M_PI * Es));
  out.p0_hertz = 2 * out.P / (M_PI * out.a_hertz);

  const fs::path h5 = dir / "hertz_cylinders.h5";
  const auto status = last_node_field(h5, "contact_status");
  const auto pressure = last_node_field(h5, "contact_pressure");
  const auto lambda = last_node_field(h5, "contact_lambda_normal");
  const std::size_t nn = res.mesh.num_nodes();
  EXPECT_EQ(status.size(), nn);
  EXPECT_EQ(pressure.size(), nn);
  // Slave nodes by deformed x; the active ones carry the pressure.
  struct SNode {
    double x, p, f;
    bool active;
  };
  std::vector<SNode> s;
  for (std::size_t n = 0; n < std::min(nn, status.size()); ++n)
    if (status[n] >= 0 && std::abs(res.mesh.x[3 * n]) < 0.3)
      s.push_back({res.mesh.x[3 * n] + res.displacement[3 * n], pressure[n], -lambda[n], status[n] >= 2});
  std::sort(s.begin(), s.end(), [](const SNode& a, const SNode& b) { return a.x < b.x; });
  double sumf = 0, m2 = 0, e2 = 0, e2i = 0, xl = 0, xr = 0;
  int inner = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s[i].active) continue;
    ++out.active;
    sumf += s[i].f;
    m2 += s[i].f * s[i].x * s[i].x;
    out.p0 = std::max(out.p0, s[i].p);
    const double ref = out.p0_hertz * std::sqrt(std::max(0.0, 1 - s[i].x * s[i].x / (out.a_hertz * out.a_hertz)));
    e2 += std::pow(s[i].p - ref, 2);
    if (std::abs(s[i].x) < 0.8 * out.a_hertz) e2i += std::pow(s[i].p - ref, 2), ++inner;
    // The edge lies between the outermost active node and the first free one.
    if (i > 0 && !s[i - 1].active) xl = 0.5 * (s[i - 1].x + s[i].x);
    if (i + 1 < s.size() && !s[i + 1].active) xr = 0.5 * (s[i].x + s[i + 1].x);
  }
  out.a_edge = 0.5 * (xr - xl);
  out.a_moment = 2 * std::sqrt(std::max(0.0, m2 / sumf - hc * hc / 12));
  out.profile_rms = std::sqrt(e2 / std::max(1, out.active)) / out.p0_hertz;
  out.inner_rms = std::sqrt(e2i / std::max(1, inner)) / out.p0_hertz;
  std::printf("[hertz-cyl] hc=%.4f ratio %.2f: P %.6e (sum of nodal forces %.6e), active %d, newton %d; a: Hertz %.5f, edge %.5f (%+.2f %%), "
              "moment %.5f (%+.2f %%); p0: Hertz %.5e, max nodal %.5e (%+.2f %%); profile RMS %.2f %% of p0 (%.2f %% within 0.8 a)\n",
              hc, ratio, out.P, sumf, out.active, out.newton, out.a_hertz, out.a_edge, 100 * (out.a_edge / out.a_hertz - 1), out.a_moment,
              100 * (out.a_moment / out.a_hertz - 1), out.p0_hertz, out.p0, 100 * (out.p0 / out.p0_hertz - 1), 100 * out.profile_rms, 100 * out.inner_rms);
  // Sum of the normal nodal forces against the vertical resultant: equal up to the tilt of
  // the normals across the contact (1 - cos(a/R) ~ 1e-3, weighted towards the centre).
  EXPECT_NEAR(sumf, out.P, 1e-5 * out.P);
  return out;
}

// Mesh sizes at the contact and the master/slave size ratio: STENTOR_HERTZ_LEVELS (e.g.
// "0.008 0.004 0.002") and STENTOR_HERTZ_RATIO (perf/scenes/run_hertz.sh sets them), else
// 0.008 and 0.004 with ratio 1.3 (non-matching interface meshes).
std::vector<double> hertz_levels() {
  std::vector<double> hc;
  if (const char* env = std::getenv("STENTOR_HERTZ_LEVELS")) {
    std::istringstream in(env);
    for (double v; in >> v;) hc.push_back(v);
  }
  if (hc.empty()) hc = {0.008, 0.004};
  return hc;
}
double hertz_ratio() {
  const char* env = std::getenv("STENTOR_HERTZ_RATIO");
  return env ? std::atof(env) : 1.3;
}

}  // namespace

// Measured (docs/contact.md, Hertz; ratio 1.3): hc = 0.008 / 0.004 / 0.002 / 0.001:
// half-width from the pressure moment -2.4 / -1.1 / -0.8 / -0.7 %, peak nodal pressure
// +0.4 / +1.6 / +2.4 / +2.4 %, profile RMS 2.8 / 3.1 / 3.1 / 2.9 % of p0. The moment
// half-width converges; the peak pressure and the profile keep a ~2.5 % / 3 % error, the
// one-pass node-to-segment error on non-matching meshes (the patch test's, docs/contact.md):
// with matching interface meshes (ratio 1) p0 is within 0.6 % and the inner profile within
// 0.5 % at every level. Tolerances: twice the measured error at hc = 0.004.
TEST(ContactBenchmarks, HertzTwoCylinders) {
  const double ratio = hertz_ratio();
  std::vector<HertzCylinders> r;
  for (double hc : hertz_levels()) r.push_back(hertz_cylinders(hc, ratio));
  for (std::size_t k = 0; k < r.size(); ++k) {
    const HertzCylinders& x = r[k];
    EXPECT_GT(x.active, 0.04 / x.hc) << x.hc;       // the contact (2a ~ 0.09) is resolved by ~2a/hc nodes
    EXPECT_LE(x.newton, 8 * 2) << x.hc;              // 2 load steps, at most 8 iterations each (measured 10-16 in all)
    EXPECT_NEAR(x.a_edge, x.a_hertz, x.hc) << x.hc;  // the edge of the contact set: within one cell
    if (x.hc > 0.005) continue;                      // tolerances for hc <= 0.004 (a/hc >= 11)
    EXPECT_NEAR(x.a_moment / x.a_hertz, 1.0, 0.02) << x.hc;
    EXPECT_NEAR(x.p0 / x.p0_hertz, 1.0, 0.05) << x.hc;
    EXPECT_LT(x.profile_rms, 0.06) << x.hc;
    if (k > 0) EXPECT_LT(std::abs(x.a_moment / x.a_hertz - 1), std::abs(r[k - 1].a_moment / r[k - 1].a_hertz - 1) + 1e-3) << x.hc;
  }
}

