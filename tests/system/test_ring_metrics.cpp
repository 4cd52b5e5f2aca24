// The metrics of a generated stent (Output->Stent Metrics with Mesh->generator = stent,
// run/RingMetrics.hpp) on a coarse ring (2 x 2 cells through width and thickness, elastic),
// at prescribed displacement fields with closed-form answers:
//  1. as cut: every diameter (stent, ring, crowns) = the generator's outer diameter and the
//     length = the ring length, to 1e-12; the metal-to-artery ratio against the unrolled
//     area (centreline length x strut width) x Ro / Rm over pi D L (chords of the crowns);
//  2. a uniform radial expansion x -> lambda x (in x, y) and an axial field z -> (1 - e) z:
//     D = lambda D0, foreshortening e, and after a smaller second state the radial recoil
//     (lambda1 - lambda2) / lambda1 and the longitudinal recoil (L1 - L2) / L1, to 1e-12;
//     after a crimp (lambda < 1) and its spring-back the recoil counts from the expansion's
//     peak, not from the as-cut diameter, and the stage table gives each stage's change;
//  3. a quarter ring and the full ring under the same field (symmetric about x = 0 and
//     y = 0, varying around the ring and along it): every metric equal to 1e-12 (the
//     symmetry weights and factors of RingMetrics); the same for the one-strut sector
//     (sector = period, 0 <= theta <= pi / 8) under a field symmetric about its planes;
//  4. two rings with links: the links' diameters and the stent length (2 rings + gap);
//  5. four rings with links: the quarter of the half length and the whole stent under
//     the same field (mirror-symmetric about the middle plane): every metric, dogboning
//     included, equal to 1e-12.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "deck/Config.hpp"
#include "run/Model.hpp"
#include "run/RingMetrics.hpp"
#include "TestDir.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

fs::path work_dir() { return stentor::testing::test_dir("ring_metrics"); }

std::string deck(const std::string& sector, const std::string& extra_stent = "") {
  return R"(<ParameterList name="stentor">
  <ParameterList name="Problem"><Parameter name="analysis" type="string" value="static"/>
    <Parameter name="units" type="string" value="mm-N-s"/></ParameterList>
  <ParameterList name="Mesh"><Parameter name="generator" type="string" value="stent"/>
    <ParameterList name="Stent">
      <Parameter name="crowns" type="int" value="8"/>
      <Parameter name="outer diameter" type="double" value="3.0"/>
      <Parameter name="thickness" type="double" value="0.1"/>
      <Parameter name="strut width" type="double" value="0.1"/>
      <Parameter name="ring length" type="double" value="1.0"/>
      <Parameter name="elements through width" type="int" value="2"/>
      <Parameter name="elements through thickness" type="int" value="2"/>
      <Parameter name="sector" type="string" value=")" + sector + R"("/>)" + extra_stent + R"(
    </ParameterList></ParameterList>
  <ParameterList name="Materials"><ParameterList name="steel">
    <Parameter name="model" type="string" value="neo-Hookean"/>
    <Parameter name="E" type="double" value="196000"/><Parameter name="nu" type="double" value="0.3"/>
    <Parameter name="density" type="double" value="8e-9"/>
  </ParameterList></ParameterList>
  <ParameterList name="Bodies"><ParameterList name="stent">
    <Parameter name="material" type="string" value="steel"/></ParameterList></ParameterList>
  <ParameterList name="Boundary Conditions"><ParameterList name="axial">
    <Parameter name="type" type="string" value="Dirichlet"/><Parameter name="boundary" type="string" value="anchor"/>
    <Parameter name="components" type="string" value="all"/></ParameterList></ParameterList>
  <ParameterList name="Stepping"><Parameter name="end time" type="double" value="1.0"/>
    <Parameter name="steps" type="int" value="1"/></ParameterList>
  <ParameterList name="Output"><ParameterList name="Stent Metrics"/></ParameterList>
</ParameterList>
)";
}

struct Rig {
  Config cfg;
  Timers timers;
  std::unique_ptr<Model> m;
  std::unique_ptr<RingMetrics> rm;
  explicit Rig(const std::string& text, const std::string& name) {
    fs::create_directories(work_dir());
    const fs::path p = work_dir() / (name + ".xml");
    std::ofstream(p) << text;
    cfg = read_deck(p.string());
    m = std::make_unique<Model>(cfg, RunOptions{}, timers);
    m->discretise(timers);
    rm = std::make_unique<RingMetrics>(*m);
  }
  // The metrics at the displacement field f(X) -> u (3 values).
  std::vector<double> at(const std::function<void(const double*, double*)>& f, double t = 0.0) {
    la::Vector u(m->dist->owned_map());
    {
      auto uh = u.getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (GId n = 0; n < static_cast<GId>(m->mesh.num_nodes()); ++n)
        if (m->dist->owns_node(n)) {
          double v[3];
          f(m->mesh.coord(n), v);
          for (int k = 0; k < 3; ++k) uh(static_cast<std::size_t>(m->dist->local_node(n) * 3 + k), 0) = v[k];
        }
    }
    return rm->evaluate(u, t);
  }
  double get(const std::vector<double>& v, const std::string& c) const {
    const auto cols = rm->columns();
    for (std::size_t i = 0; i < cols.size(); ++i)
      if (cols[i] == c) return v[i];
    ADD_FAILURE() << "no column " << c;
    return std::nan("");
  }
};

void zero(const double*, double* u) { u[0] = u[1] = u[2] = 0.0; }

}  // namespace

TEST(RingMetrics, AsCutDiametersAreTheGeneratorsAndTheRatioIsTheUnrolledArea) {
  Rig r(deck("full"), "as_cut");
  const auto v = r.at(zero);
  for (const char* c : {"D_mean [mm]", "D_min [mm]", "D_max [mm]", "ring0_D_mean [mm]", "ring0_D_min [mm]",
                        "ring0_D_max [mm]", "ring0_D_crown_mean [mm]", "ring0_D_crown_min [mm]", "ring0_D_crown_max [mm]"})
    EXPECT_NEAR(r.get(v, c), 3.0, 1e-12) << c;
  EXPECT_NEAR(r.get(v, "length [mm]"), 1.0, 1e-12);
  EXPECT_NEAR(r.get(v, "ring0_length [mm]"), 1.0, 1e-12);
  for (const char* c : {"foreshortening [-]", "radial_recoil [-]", "longitudinal_recoil [-]"}) EXPECT_EQ(r.get(v, c), 0.0) << c;
  const StentConfig& s = r.cfg.mesh.stent;
  const double unrolled = s.centreline_length() * s.strut_width * s.outer_radius() / s.mid_radius();
  const double expected = unrolled / (3.14159265358979323846 * 3.0 * 1.0);
  EXPECT_NEAR(r.get(v, "metal_to_artery_ratio [-]") / expected, 1.0, 1e-2);
}

TEST(RingMetrics, UniformExpansionAndAxialFieldGiveTheirDiametersRecoilAndForeshortening) {
  Rig r(deck("full"), "uniform");
  r.at(zero);
  auto field = [](double lambda, double e) {
    return [=](const double* x, double* u) { u[0] = (lambda - 1.0) * x[0], u[1] = (lambda - 1.0) * x[1], u[2] = -e * x[2]; };
  };
  const auto a = r.at(field(1.25, 0.1), 0.5);
  for (const char* c : {"D_mean [mm]", "D_min [mm]", "D_max [mm]", "ring0_D_crown_mean [mm]"})
    EXPECT_NEAR(r.get(a, c), 3.75, 1e-12) << c;
  EXPECT_NEAR(r.get(a, "length [mm]"), 0.9, 1e-12);
  EXPECT_NEAR(r.get(a, "foreshortening [-]"), 0.1, 1e-12);
  EXPECT_NEAR(r.get(a, "radial_recoil [-]"), 0.0, 1e-15);
  const auto b = r.at(field(1.2, 0.08), 1.0);
  EXPECT_NEAR(r.get(b, "D_mean [mm]"), 3.6, 1e-12);
  EXPECT_NEAR(r.get(b, "radial_recoil [-]"), (1.25 - 1.2) / 1.25, 1e-12);
  EXPECT_NEAR(r.get(b, "longitudinal_recoil [-]"), (0.9 - 0.92) / 0.9, 1e-12);
  EXPECT_NEAR(r.get(b, "foreshortening [-]"), 0.08, 1e-12);
  // Mass = density x metal volume, the volume (centreline length) x w x t up to the
  // crowns' chords.
  std::ostringstream log;
  r.rm->table(log);
  const std::string t = log.str();
  const auto at = t.find(", mass ");
  ASSERT_NE(at, std::string::npos) << t;
  const StentConfig& s = r.cfg.mesh.stent;
  EXPECT_NEAR(std::stod(t.substr(at + 7)) / (8e-9 * s.centreline_length() * s.strut_width * s.thickness), 1.0, 1e-2) << t;
}

// Crimp (lambda 0.7), spring-back (0.72), expansion (1.25), recoil (1.2): a crimp is no
// recoil (the peak follows the stent down), the recoil counts from the expansion's peak, and
// the stage table gives each stage's start and change.
TEST(RingMetrics, CrimpIsNoRecoilAndTheRecoilCountsFromTheExpansion) {
  Rig r(deck("full"), "crimp");
  r.at(zero);
  auto field = [](double lambda) {
    return [=](const double* x, double* u) { u[0] = (lambda - 1.0) * x[0], u[1] = (lambda - 1.0) * x[1], u[2] = 0.0; };
  };
  const auto crimped = r.at(field(0.7), 1.0);
  EXPECT_NEAR(r.get(crimped, "D_mean [mm]"), 2.1, 1e-12);
  EXPECT_EQ(r.get(crimped, "radial_recoil [-]"), 0.0);
  std::ostringstream crimp_log;
  r.rm->table(crimp_log);
  r.rm->begin_stage();
  const auto released = r.at(field(0.72), 1.25);
  EXPECT_EQ(r.get(released, "radial_recoil [-]"), 0.0);
  std::ostringstream release_log;
  r.rm->table(release_log);
  r.rm->begin_stage();
  EXPECT_EQ(r.get(r.at(field(1.25), 2.25), "radial_recoil [-]"), 0.0);
  r.rm->begin_stage();
  const auto recoiled = r.at(field(1.2), 2.75);
  EXPECT_NEAR(r.get(recoiled, "radial_recoil [-]"), (1.25 - 1.2) / 1.25, 1e-12);
  // The stage rows ("all": start, peak, now, change %, recoil %): the crimp from 3 to 2.1
  // (-30 %), the spring-back from 2.1 to 2.16 (+2.857 %, no recoil), the recoil 4 %.
  auto all_row = [](const std::string& t) { return t.substr(t.find("\n  all ")); };
  EXPECT_NE(all_row(crimp_log.str()).find("3.0000 |          2.1000 |          2.1000 |  -30.000 |           0.000"), std::string::npos)
      << crimp_log.str();
  EXPECT_NE(all_row(release_log.str()).find("2.1000 |          2.1600 |          2.1600 |    2.857 |           0.000"),
            std::string::npos)
      << release_log.str();
  std::ostringstream end_log;
  r.rm->table(end_log);
  EXPECT_NE(all_row(end_log.str()).find("3.7500 |          3.7500 |          3.6000 |   -4.000 |           4.000"), std::string::npos)
      << end_log.str();
}

// A stent that springs back to its as-cut diameter (elastic) shows its whole recoil: the
// return to D0 is not a new smallest diameter (that takes more than round-off below it).
TEST(RingMetrics, SpringingBackToTheAsCutDiameterIsTheWholeRecoil) {
  Rig r(deck("full"), "spring_back");
  r.at(zero);
  auto field = [](double lambda) {
    return [=](const double* x, double* u) { u[0] = (lambda - 1.0) * x[0], u[1] = (lambda - 1.0) * x[1], u[2] = 0.0; };
  };
  r.at(field(1.25), 0.5);
  EXPECT_NEAR(r.get(r.at(field(1.0 - 1e-13), 1.0), "radial_recoil [-]"), 0.2, 1e-12);
  EXPECT_EQ(r.get(r.at(field(0.99), 1.5), "radial_recoil [-]"), 0.0);  // below D0: a crimp
}

// The state a checkpoint carries (RingMetrics::save / restore): a second metrics object
// restored from the first's state after the crimp, the expansion's peak and a stage start
// gives the same row and table as the first at the recoiled state, where a fresh one
// would count from the recoiled state itself (recoil 0, foreshortening 0).
TEST(RingMetrics, SavedStateRestoresThePeakReferenceAndStageStart) {
  Rig a(deck("full"), "save_a");
  a.at(zero);
  auto field = [](double lambda, double e) {
    return [=](const double* x, double* u) { u[0] = (lambda - 1.0) * x[0], u[1] = (lambda - 1.0) * x[1], u[2] = -e * x[2]; };
  };
  a.at(field(0.7, -0.05), 1.0);
  a.at(field(1.25, 0.1), 2.0);
  a.rm->begin_stage();
  std::map<std::string, double> state;
  a.rm->save(state, "metrics_ring_");
  Rig b(deck("full"), "save_b");
  ASSERT_TRUE(b.rm->restore(state, "metrics_ring_"));
  const auto va = a.at(field(1.2, 0.08), 3.0), vb = b.at(field(1.2, 0.08), 3.0);
  ASSERT_EQ(va.size(), vb.size());
  for (std::size_t k = 0; k < va.size(); ++k) EXPECT_EQ(va[k], vb[k]) << a.rm->columns()[k];
  EXPECT_NEAR(a.get(vb, "radial_recoil [-]"), (1.25 - 1.2) / 1.25, 1e-12);
  EXPECT_NEAR(a.get(vb, "foreshortening [-]"), 0.08, 1e-12);
  std::ostringstream ta, tb;
  a.rm->table(ta);
  b.rm->table(tb);
  EXPECT_EQ(ta.str(), tb.str());
  std::map<std::string, double> partial = state;
  partial.erase("metrics_ring_D_min");
  Rig c(deck("full"), "save_c");
  EXPECT_FALSE(c.rm->restore(partial, "metrics_ring_"));  // all or nothing
}

TEST(RingMetrics, QuarterEqualsFullUnderASymmetricField) {
  Rig full(deck("full"), "full"), quarter(deck("quarter"), "quarter");
  // Symmetric about x = 0 and y = 0 (cos 4 theta, even in z): radial and axial.
  auto f = [](double s) {
    return [=](const double* x, double* u) {
      const double th = std::atan2(x[1], x[0]), r = std::hypot(x[0], x[1]);
      const double ur = s * (0.2 + 0.05 * std::cos(4.0 * th) + 0.03 * x[2] * x[2]);
      u[0] = ur * x[0] / r, u[1] = ur * x[1] / r, u[2] = -s * 0.05 * x[2] * x[2] * (1.0 + 0.2 * std::cos(8.0 * th));
    };
  };
  const auto cols = full.rm->columns();
  ASSERT_EQ(cols, quarter.rm->columns());
  for (double s : {0.0, 1.0, 0.6}) {
    const auto a = full.at(f(s), s), b = quarter.at(f(s), s);
    for (std::size_t i = 0; i < cols.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-12 * (1.0 + std::abs(a[i]))) << cols[i] << " at " << s;
  }
  std::ostringstream lf, lq;
  full.rm->table(lf), quarter.rm->table(lq);
  auto volume = [](const std::string& t) { return std::stod(t.substr(t.find("metal volume ") + 13)); };
  EXPECT_NEAR(volume(lq.str()) / volume(lf.str()), 1.0, 1e-10);
}

TEST(RingMetrics, OneStrutSectorEqualsFullUnderASymmetricField) {
  Rig full(deck("full"), "full_s"), sector(deck("period"), "sector");
  EXPECT_NEAR(sector.cfg.mesh.stent.sector_angle(), std::acos(-1.0) / 8.0, 1e-15);  // one strut of 8 crowns
  // Symmetric about theta = 0 and theta = pi / 8 (cos 8 theta, cos 16 theta), even in z.
  auto f = [](double s) {
    return [=](const double* x, double* u) {
      const double th = std::atan2(x[1], x[0]), r = std::hypot(x[0], x[1]);
      const double ur = s * (0.2 + 0.05 * std::cos(8.0 * th) + 0.03 * x[2] * x[2]);
      u[0] = ur * x[0] / r, u[1] = ur * x[1] / r, u[2] = -s * 0.05 * x[2] * x[2] * (1.0 + 0.2 * std::cos(16.0 * th));
    };
  };
  const auto cols = full.rm->columns();
  ASSERT_EQ(cols, sector.rm->columns());
  for (double s : {0.0, 1.0, 0.6}) {
    const auto a = full.at(f(s), s), b = sector.at(f(s), s);
    for (std::size_t i = 0; i < cols.size(); ++i) {
      if (cols[i].rfind("eps_p_max_", 0) == 0) continue;  // where: one of the symmetric copies
      EXPECT_NEAR(a[i], b[i], 1e-12 * (1.0 + std::abs(a[i]))) << cols[i] << " at " << s;
    }
  }
  std::ostringstream lf, ls;
  full.rm->table(lf), sector.rm->table(ls);
  auto volume = [](const std::string& t) { return std::stod(t.substr(t.find("metal volume ") + 13)); };
  EXPECT_NEAR(volume(ls.str()) / volume(lf.str()), 1.0, 1e-10);
}

TEST(RingMetrics, TwoRingsWithLinksMeasureTheLinksAndTheWholeLength) {
  const std::string two = R"(
      <Parameter name="rings" type="int" value="2"/><Parameter name="gap" type="double" value="0.3"/>
      <Parameter name="links per ring" type="int" value="4"/>)";
  Rig r(deck("full", two), "two_rings");
  const auto v = r.at([](const double* x, double* u) { u[0] = 0.1 * x[0], u[1] = 0.1 * x[1], u[2] = 0.0; });
  for (const char* c : {"links_D_mean [mm]", "links_D_min [mm]", "links_D_max [mm]", "ring1_D_crown_mean [mm]"})
    EXPECT_NEAR(r.get(v, c), 3.3, 1e-12) << c;
  EXPECT_NEAR(r.get(v, "length [mm]"), r.cfg.mesh.stent.total_length(), 1e-12);
  EXPECT_NEAR(r.get(v, "ring1_length [mm]"), 1.0, 1e-12);
}

TEST(RingMetrics, QuarterOfTheHalfLengthEqualsTheWholeStent) {
  const std::string four = R"(
      <Parameter name="rings" type="int" value="4"/><Parameter name="gap" type="double" value="0.3"/>
      <Parameter name="links per ring" type="int" value="8"/>)";
  Rig full(deck("full", four), "four_full"), part(deck("quarter", four + R"(
      <Parameter name="half length" type="bool" value="true"/>)"), "four_part");
  const double zc = 0.5 * full.cfg.mesh.stent.total_length();
  // Symmetric about x = 0, y = 0 and z = zc: the ends expand more than the middle.
  auto f = [=](double s) {
    return [=](const double* x, double* u) {
      const double th = std::atan2(x[1], x[0]), r = std::hypot(x[0], x[1]), d = x[2] - zc;
      const double ur = s * (0.2 + 0.05 * std::cos(4.0 * th) + 0.04 * d * d);
      u[0] = ur * x[0] / r, u[1] = ur * x[1] / r, u[2] = -s * 0.05 * d * (1.0 + 0.2 * std::cos(8.0 * th));
    };
  };
  const auto cols = full.rm->columns();
  ASSERT_EQ(std::count(cols.begin(), cols.end(), "dogboning [-]"), 1);
  // The part holds rings 0 and 1 of the four: its columns are the whole stent's less
  // rings 2 and 3.
  const auto pc = part.rm->columns();
  for (double s : {0.0, 1.0, 0.6}) {
    const auto a = full.at(f(s), s), b = part.at(f(s), s);
    for (std::size_t j = 0; j < pc.size(); ++j) {
      const auto i = static_cast<std::size_t>(std::find(cols.begin(), cols.end(), pc[j]) - cols.begin());
      ASSERT_LT(i, cols.size()) << pc[j];
      EXPECT_NEAR(a[i], b[j], 1e-12 * (1.0 + std::abs(a[i]))) << pc[j] << " at " << s;
    }
    EXPECT_GT(full.get(a, "dogboning [-]"), s > 0.0 ? 1e-3 : -1.0);
  }
}
