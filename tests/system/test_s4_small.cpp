// The small S4 (tests/cli/decks/par_s4.xml: 6 struts in two artery walls, a rigid capsule
// balloon inserted, inflated and extracted in three stages, mu = 0.2 between struts and
// artery; also run on 1 and 2 ranks by mpi.consistency.s4), checked from its output files:
//  1. The energy identity E_{n+1} - E_n = W_ext - D_visc + W_contact - D_fric per step in
//     every stage, recomputed here from the cumulative columns of <basename>_energy.csv
//     (E = kinetic + strain), to 1e-8 of the largest E (E_max = 333 J/m; measured
//     1.2e-7 J/m in the inflation, 4e-10 J/m in the extraction, 0 in the insertion: 4e-10
//     of E_max at most). No load acts and the clamps do not
//     move (W_ext = W_sup = 0), so the balloon's contact work is the external work: none
//     in the insertion (the balloon touches nothing, E stays 0), the inflation's energy
//     input, and nothing once it has been deflated and pulled out. The per-stage energy
//     terms of <basename>_stages.csv are the sums of the steps of their stage.
//  2. The stent metrics at the end of each stage (<basename>_stages.csv) against the same
//     quantities recomputed from the deformed nodes (mesh coordinates + the displacement of
//     the HDF5 output at that stage's end, gathered on rank 0 by the field writer, not by
//     the metrics' reduction): the mean stent radius (|y| of the struts' inner arcs), the
//     middle and end radii and dogboning, the stent length and foreshortening, the mean and
//     smallest lumen radius over the stent's span, the lumen gain and the radial recoil.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "CsvSeries.hpp"
#include "H5Results.hpp"
#include "deck/Config.hpp"
#include "mesh/MeshQuery.hpp"
#include "run/Simulation.hpp"
#include "TestDir.hpp"

using namespace stentor;
using stentor::testing::read_csv;
using stentor::testing::Series;
namespace fs = std::filesystem;

namespace {

fs::path work_dir() { return stentor::testing::test_dir("s4_small"); }
const std::string kDeck = std::string(STENTOR_SOURCE_DIR) + "/tests/cli/decks/par_s4.xml";

using H5 = stentor::testing::H5Results;

// The metrics of docs/deck.md ("Output->Stent Metrics") for the axis x through the origin
// of a 2D axial section, from the current node positions x (3 per mesh node) and the
// reference ones X.
struct Metrics {
  double stent_mean = 0, stent_middle = 0, stent_ends = 0, dogboning = 0, length = 0, foreshortening = 0;
  double lumen_mean = 0, lumen_min = 1e300;
};

Metrics metrics(const std::vector<GId>& stent, const std::vector<GId>& lumen, const std::vector<double>& X, const std::vector<double>& x,
                double end_fraction) {
  auto at = [](const std::vector<double>& v, GId n, int k) { return v[3 * static_cast<std::size_t>(n) + static_cast<std::size_t>(k)]; };
  double lo = 1e300, hi = -1e300;
  for (GId n : stent) lo = std::min(lo, at(X, n, 0)), hi = std::max(hi, at(X, n, 0));
  const double L0 = hi - lo, centre = 0.5 * (lo + hi), f = end_fraction * L0;
  Metrics m;
  double zmin = 1e300, zmax = -1e300;
  int nmid = 0, nends = 0;
  for (GId n : stent) {
    const double r = std::abs(at(x, n, 1)), z0 = at(X, n, 0);
    m.stent_mean += r / double(stent.size());
    zmin = std::min(zmin, at(x, n, 0)), zmax = std::max(zmax, at(x, n, 0));
    if (std::abs(z0 - centre) <= 0.5 * f) m.stent_middle += r, ++nmid;
    if (z0 - lo <= f || hi - z0 <= f) m.stent_ends += r, ++nends;
  }
  EXPECT_GT(nmid, 0);
  EXPECT_GT(nends, 0);
  m.stent_middle /= nmid, m.stent_ends /= nends;
  m.dogboning = (m.stent_ends - m.stent_middle) / m.stent_middle;
  m.length = zmax - zmin;
  m.foreshortening = (L0 - m.length) / L0;
  int nl = 0;
  for (GId n : lumen) {
    if (at(X, n, 0) < lo || at(X, n, 0) > hi) continue;
    const double r = std::abs(at(x, n, 1));
    m.lumen_mean += r, m.lumen_min = std::min(m.lumen_min, r), ++nl;
  }
  EXPECT_GT(nl, 0);
  m.lumen_mean /= nl;
  return m;
}

}  // namespace

TEST(S4Small, EnergyIdentityAndStentMetricsInEveryStage) {
  const Config cfg = read_deck(kDeck);
  ASSERT_EQ(cfg.stages.size(), 3u);
  RunOptions opts;
  opts.output_dir = (work_dir() / "out").string();
  opts.overwrite = true;
  RunResult res;
  ASSERT_EQ(run_simulation(cfg, opts, &res), 0);
  const fs::path out = work_dir() / "out";
  const std::string stem = (out / cfg.output.basename).string();
  const Series e = read_csv(stem + "_energy.csv"), h = read_csv(stem + "_history.csv");
  const Series st = read_csv(stem + "_stages.csv"), ms = read_csv(stem + "_metrics.csv");
  ASSERT_EQ(st.rows(), 3u);
  const std::size_t n = e.rows();  // step 0 .. last
  ASSERT_EQ(h.rows() + 1, n);
  ASSERT_EQ(ms.rows(), n);

  // 1. Energy identity per step, every stage.
  const auto& E = e["total"];
  double Emax = 0.0;
  for (double v : E) Emax = std::max(Emax, std::abs(v));
  ASSERT_GT(Emax, 10.0);  // the inflation puts energy in (about 330 J/m)
  const double tol = 1e-8 * Emax;
  auto inc = [&](const char* c, std::size_t k) { return e[c][k] - e[c][k - 1]; };
  double worst[3] = {0, 0, 0};
  std::vector<double> sum_dE(3, 0.0), sum_wc(3, 0.0), sum_dv(3, 0.0), sum_df(3, 0.0);
  for (std::size_t k = 1; k < n; ++k) {
    ASSERT_EQ(e["time"][k], h["time"][k - 1]);
    const auto s = static_cast<std::size_t>(h["stage"][k - 1]) - 1;
    ASSERT_LT(s, 3u);
    EXPECT_EQ(e["external_work"][k], 0.0) << "no load acts";
    EXPECT_EQ(e["support_work"][k], 0.0) << "the clamps do not move";
    const double dE = E[k] - E[k - 1], wc = inc("contact_work", k), dv = inc("dissipation", k), df = inc("friction_dissipation", k);
    const double balance = dE - (inc("external_work", k) + inc("support_work", k) - dv + wc - df);
    EXPECT_LE(std::abs(balance), tol) << "step " << k << " (stage " << s + 1 << ", t = " << e["time"][k] << ")";
    EXPECT_NEAR(balance, e["balance_residual"][k], 1e-10 * Emax) << "step " << k;  // the run's own audit says the same
    EXPECT_GE(dv, -1e-12 * Emax) << "viscous dissipation decreased at step " << k;
    EXPECT_GE(df, -1e-8 * Emax) << "frictional dissipation decreased at step " << k;
    worst[s] = std::max(worst[s], std::abs(balance));
    sum_dE[s] += dE, sum_wc[s] += wc, sum_dv[s] += dv, sum_df[s] += df;
  }
  std::printf("[s4_small] %zu steps, E_max %.4g J/m; max |balance| per step: insertion %.2e, inflation %.2e, extraction %.2e J/m\n",
              n - 1, Emax, worst[0], worst[1], worst[2]);
  // The balloon's work is the only input: none in the insertion (it touches nothing), the
  // inflation's, nothing after deflation and extraction.
  for (std::size_t k = 0; k < h.rows(); ++k)
    if (h["stage"][k] == 1.0) EXPECT_EQ(h["contact_balloon_active"][k], 0.0) << "the balloon touched a strut in the insertion";
  EXPECT_LE(std::abs(sum_wc[0]), tol);
  EXPECT_LE(std::abs(sum_dE[0]), tol);
  EXPECT_GT(sum_wc[1], 0.5 * Emax);
  EXPECT_NEAR(sum_wc[1], sum_dE[1] + sum_dv[1] + sum_df[1], 4.0 * tol);
  EXPECT_GT(sum_df[1], 0.0) << "mu = 0.2: the struts slide on the walls";
  EXPECT_LE(std::abs(sum_wc[2]), tol) << "the deflated balloon does no work in the extraction";
  // The stage rows are the sums of their steps.
  for (std::size_t s = 0; s < 3; ++s) {
    EXPECT_NEAR(st["stage_delta_energy"][s], sum_dE[s], 1e-10 * Emax) << "stage " << s + 1;
    EXPECT_NEAR(st["stage_contact_work"][s], sum_wc[s], 1e-10 * Emax) << "stage " << s + 1;
    EXPECT_NEAR(st["stage_dissipation"][s], sum_dv[s], 1e-10 * Emax) << "stage " << s + 1;
    EXPECT_NEAR(st["stage_friction_dissipation"][s], sum_df[s], 1e-10 * Emax) << "stage " << s + 1;
    EXPECT_EQ(st["stage_external_work"][s], 0.0);
  }

  // 2. Metrics from the deformed nodes at t = 0 and at the end of each stage.
  const H5 h5(out / (cfg.output.basename + ".h5"));
  const std::vector<double> times = h5.times();
  const std::vector<double> X = h5.read("/mesh/coordinates");
  ASSERT_EQ(X, res.mesh.x);
  const std::vector<GId> stent = boundary_nodes(res.mesh, cfg.output.metrics.stent);
  const std::vector<GId> lumen = boundary_nodes(res.mesh, cfg.output.metrics.lumen);
  ASSERT_FALSE(stent.empty());
  ASSERT_FALSE(lumen.empty());
  auto positions = [&](double t) {
    std::size_t k = 0;
    while (k < times.size() && std::abs(times[k] - t) > 1e-12) ++k;
    EXPECT_LT(k, times.size()) << "no field output at t = " << t;
    std::vector<double> x = k < times.size() ? h5.read("/step_" + std::to_string(k) + "/displacement") : std::vector<double>();
    if (x.size() != X.size()) {
      ADD_FAILURE() << "displacement at t = " << t << ": " << x.size() << " values";
      return X;
    }
    for (std::size_t i = 0; i < x.size(); ++i) x[i] += X[i];
    return x;
  };
  const double ef = cfg.output.metrics.end_fraction;
  const Metrics m0 = metrics(stent, lumen, X, positions(0.0), ef);
  EXPECT_NEAR(m0.lumen_mean, 1.0, 1e-12);  // the walls' inner surfaces at |y| = 1
  double stent_max = 0.0, largest_dogboning = 0.0;
  std::size_t row = 0;
  for (std::size_t s = 0; s < 3; ++s) {
    const double t = st["time"][s];
    SCOPED_TRACE("end of stage " + std::to_string(s + 1) + ", t = " + std::to_string(t));
    const Metrics m = metrics(stent, lumen, X, positions(t), ef);
    const double tol_r = 1e-12;
    EXPECT_NEAR(st["stent_radius_mean"][s], m.stent_mean, tol_r);
    EXPECT_NEAR(st["stent_radius_middle"][s], m.stent_middle, tol_r);
    EXPECT_NEAR(st["stent_radius_ends"][s], m.stent_ends, tol_r);
    EXPECT_NEAR(st["dogboning"][s], m.dogboning, tol_r);
    EXPECT_NEAR(st["stent_length"][s], m.length, tol_r);
    EXPECT_NEAR(st["foreshortening"][s], m.foreshortening, tol_r);
    EXPECT_NEAR(st["lumen_radius_mean"][s], m.lumen_mean, tol_r);
    EXPECT_NEAR(st["lumen_radius_min"][s], m.lumen_min, tol_r);
    EXPECT_NEAR(st["lumen_gain"][s], m.lumen_mean / m0.lumen_mean - 1.0, tol_r);
    // Recoil: from the largest mean stent radius of any step so far (the per-step metrics,
    // whose value at this stage's end is the one checked above).
    for (; row < ms.rows() && ms["time"][row] <= t + 1e-12; ++row) stent_max = std::max(stent_max, ms["stent_radius_mean"][row]);
    EXPECT_NEAR(ms["stent_radius_mean"][row - 1], m.stent_mean, tol_r);
    EXPECT_NEAR(st["stent_radius_max"][s], stent_max, 1e-15);
    EXPECT_NEAR(st["radial_recoil"][s], (stent_max - m.stent_mean) / stent_max, tol_r);
    if (s == 0) {  // nothing touched: the reference state
      EXPECT_NEAR(m.stent_mean, m0.stent_mean, 1e-12);
      EXPECT_NEAR(m.foreshortening, 0.0, 1e-12);
    }
    if (s == 1) {  // inflated: the struts pressed into the walls
      EXPECT_GT(m.stent_mean, m0.stent_mean + 0.03);
      EXPECT_GT(m.lumen_mean, 1.03);
    }
    largest_dogboning = std::max(largest_dogboning, std::abs(m.dogboning));
    std::printf("[s4_small] stage %zu: stent radius %.4f (middle %.4f, ends %.4f, dogboning %.2f %%), foreshortening %.2f %%, "
                "lumen radius %.4f (min %.4f), recoil %.2f %%\n",
                s + 1, m.stent_mean, m.stent_middle, m.stent_ends, 100 * m.dogboning, 100 * m.foreshortening, m.lumen_mean, m.lumen_min,
                100 * st["radial_recoil"][s]);
  }
  // The dogboning comparison above is not a comparison of zeros: some stage ends with the
  // ends and the middle apart. Which one depends on the steps' path on this coarse deck
  // (measured at the end of the inflation: -1.21 % and +0.01 % with two Newton globalisations
  // that take different cut-backs, -1.36 % and -1.35 % with both at 4 times the steps).
  EXPECT_GT(largest_dogboning, 1e-3);
}
