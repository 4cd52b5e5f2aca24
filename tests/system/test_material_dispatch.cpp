// The material dispatch of the assembler (issue 11, "material dispatch"; docs/plasticity.md,
// "Adding a material"): two more laws with Gauss-point history, NeoHookeanDamage
// (material/Damage.hpp, its own history layout of 3 values) and NeoHookeanPlasticity
// (material/Plasticity.hpp), run through the same kernels, history views and cell output
// as CiarletGeymonatPlasticity without a line of src/assembly naming them. Checked through
// the global assembly: the tangent against central differences of the residual (damage
// growing at most points, and unloading; plastic flow at most points), d_inf = 0 against
// the stateless neo-Hookean kernel bit for bit, the exact energy identity of a Gonzalez
// step with damage, and a deck with two laws with history in two blocks (history widths,
// output columns, commit / roll back).
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "AssemblerFixture.hpp"
#include "assembly/Assembler.hpp"
#include "bc/Loads.hpp"
#include "deck/Config.hpp"
#include "mesh/MeshComm.hpp"
#include "parallel/Distribution.hpp"
#include "TestDir.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

fs::path work_dir() { return stentor::testing::test_dir("material_dispatch"); }
constexpr double kMu = 1.0e6, kLambda = 1.5e6;

std::string param(const std::string& name, const std::string& type, const std::string& value) {
  return "<Parameter name=\"" + name + "\" type=\"" + type + "\" value=\"" + value + "\"/>";
}

std::string dirichlet(const std::string& name, const std::string& boundary, const std::string& components) {
  return "<ParameterList name=\"" + name + "\">" + param("type", "string", "Dirichlet") + param("boundary", "string", boundary) +
         param("components", "string", components) + "</ParameterList>";
}

// The unit cube of inputs/block3d.geo (tet4, h = 0.5), neo-Hookean, symmetry supports.
std::string cube_deck() {
  return "<ParameterList name=\"stentor\"><ParameterList name=\"Mesh\">" +
         param("file", "string", std::string(STENTOR_SOURCE_DIR) + "/inputs/block3d.geo") + param("size", "double", "0.5") +
         "</ParameterList><ParameterList name=\"Materials\"><ParameterList name=\"tissue\">" +
         param("model", "string", "neo-Hookean") + param("mu", "double", std::to_string(kMu)) +
         param("lambda", "double", std::to_string(kLambda)) + param("density", "double", "1000") +
         "</ParameterList></ParameterList><ParameterList name=\"Bodies\"><ParameterList name=\"block\">" +
         param("material", "string", "tissue") + "</ParameterList></ParameterList><ParameterList name=\"Boundary Conditions\">" +
         dirichlet("left", "left", "x") + dirichlet("front", "front", "y") + dirichlet("bottom", "bottom", "z") +
         "</ParameterList><ParameterList name=\"Output\">" + param("fields", "bool", "false") + "</ParameterList></ParameterList>";
}

// inputs/two_blocks3d.geo: block "lower" of Ciarlet-Geymonat plasticity, "upper" of a
// neo-Hookean material (the test gives it the damage law).
std::string two_block_deck() {
  return "<ParameterList name=\"stentor\"><ParameterList name=\"Mesh\">" +
         param("file", "string", std::string(STENTOR_SOURCE_DIR) + "/inputs/two_blocks3d.geo") +
         "</ParameterList><ParameterList name=\"Materials\"><ParameterList name=\"metal\">" +
         param("model", "string", "Ciarlet-Geymonat plasticity") + param("C1", "double", "0.5e6") +
         param("D", "double", "0.35e6") + param("yield stress", "double", "0.05e6") +
         "</ParameterList><ParameterList name=\"tissue\">" + param("model", "string", "neo-Hookean") +
         param("mu", "double", std::to_string(kMu)) + param("lambda", "double", std::to_string(kLambda)) +
         "</ParameterList></ParameterList><ParameterList name=\"Bodies\"><ParameterList name=\"lower\">" +
         param("material", "string", "metal") + "</ParameterList><ParameterList name=\"upper\">" +
         param("material", "string", "tissue") + "</ParameterList></ParameterList><ParameterList name=\"Boundary Conditions\">" +
         dirichlet("base", "base", "x,y,z") + dirichlet("top", "upper_top", "x,y,z") +
         "</ParameterList><ParameterList name=\"Output\">" + param("fields", "bool", "false") + "</ParameterList></ParameterList>";
}

Config write_and_read(const std::string& text, const std::string& name) {
  fs::create_directories(work_dir());
  const fs::path p = work_dir() / (name + ".xml");
  std::ofstream(p) << text;
  return read_deck(p.string());
}

// An Assembler with the given law per deck material (deck laws when `laws` is empty).
using Fixture = stentor::testing::AssemblerFixture;

// The damage law of the tests: saturation 0.8, energy scale 2 kPa (W0 ~ 1-10 kPa at the
// fields above), so d is 0.2-0.8 and still growing.
NeoHookeanDamage damage_law(double d_inf = 0.8) { return NeoHookeanDamage{NeoHookean{kMu, kLambda}, d_inf, 2.0e3}; }

std::vector<double> host_copy(const Assembler::HistoryView& v) {
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
  return std::vector<double>(h.data(), h.data() + h.size());
}

// Gauss points of block b whose damage grew in the trial state (trial d > committed d).
int growing_points(const Assembler& as, std::size_t b) {
  const std::vector<double> h0 = host_copy(as.committed_history(b)), h1 = host_copy(as.trial_history(b));
  int n = 0;
  for (std::size_t i = NeoHookeanDamage::kDamage; i < h1.size(); i += NeoHookeanDamage::kNumHist) n += h1[i] > h0[i];
  return n;
}

// max |K du - central difference of r along du| / |K du|, on the free rows.
double tangent_error(Fixture& s, const la::Vector& u) {
  const auto map = s.dist->owned_map();
  la::Vector r(map), rp(map), rm(map), du(map), Kdu(map), up(map);
  s.as->assemble(u, 1.0, 1.0, r, true);
  du.randomize();
  for (la::LO i = 0; i < static_cast<la::LO>(map->getNodeNumElements()); ++i)
    if (s.as->is_dirichlet(i)) du.getLocalViewHost(Tpetra::Access::ReadWrite)(i, 0) = 0.0;
  s.as->matrix()->apply(du, Kdu);
  const double h = 1e-7;
  up.update(1.0, u, h, du, 0.0);
  s.as->assemble(up, 1.0, 1.0, rp, false);
  up.update(1.0, u, -h, du, 0.0);
  s.as->assemble(up, 1.0, 1.0, rm, false);
  rp.update(-0.5 / h, rm, 0.5 / h);
  double err = 0.0;
  auto a = rp.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto b = Kdu.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (std::size_t i = 0; i < a.extent(0); ++i)
    if (!s.as->is_dirichlet(static_cast<la::LO>(i))) err = std::max(err, std::abs(a(i, 0) - b(i, 0)));
  return err / Kdu.normInf();
}

}  // namespace

// The global tangent of the damage law against central differences, from a damaged
// committed state: loading further (damage grows at most points) and unloading.
TEST(MaterialDispatch, DamageTangentMatchesFiniteDifferences) {
  Fixture s(write_and_read(cube_deck(), "cube"), {damage_law()});
  ASSERT_TRUE(s.as->has_history());
  ASSERT_EQ(s.as->committed_history(0).extent(1), static_cast<std::size_t>(NeoHookeanDamage::kNumHist));
  const auto map = s.dist->owned_map();
  la::Vector u(map), r(map);
  s.fill(u, 0.6);
  s.as->assemble(u, 1.0, 1.0, r, false);
  s.as->commit_history();
  const int ngp = static_cast<int>(s.as->trial_history(0).extent(0));
  for (const double amp : {1.0, 0.3}) {
    s.fill(u, amp, 0.03);
    const double rel = tangent_error(s, u);
    const int grow = growing_points(*s.as, 0);
    std::cout << "[ damage ] amplitude " << amp << ": " << grow << "/" << ngp
              << " Gauss points with growing damage, |K du - FD|/|K du| = " << rel << "\n";
    if (amp > 0.6)
      EXPECT_GT(grow, ngp / 2);
    else
      EXPECT_EQ(grow, 0);
    EXPECT_LT(rel, 1e-6);
  }
}

// The second plasticity law (the return map over the neo-Hookean law) through the global
// assembly: tangent against central differences from a plastic committed state, most
// points flowing, perfect plasticity and hardening.
TEST(MaterialDispatch, NeoHookeanPlasticityTangentMatchesFiniteDifferences) {
  for (const double H : {0.0, 0.5e6}) {
    Fixture s(write_and_read(cube_deck(), "cube"), {NeoHookeanPlasticity{NeoHookean{kMu, kLambda}, 0.1e6, H}});
    ASSERT_EQ(s.as->committed_history(0).extent(1), static_cast<std::size_t>(NeoHookeanPlasticity::kNumHist));
    la::Vector u(s.dist->owned_map()), r(s.dist->owned_map());
    s.fill(u, 0.6);
    s.as->assemble(u, 1.0, 1.0, r, false);
    s.as->commit_history();
    s.fill(u, 1.0, 0.03);
    const double rel = tangent_error(s, u);
    s.as->assemble(u, 1.0, 1.0, r, false);
    const std::vector<double> h = host_copy(s.as->trial_history(0));
    int flowing = 0, ngp = 0;
    for (std::size_t i = NeoHookeanPlasticity::kYielding; i < h.size(); i += NeoHookeanPlasticity::kNumHist) flowing += h[i] > 0.0, ++ngp;
    std::cout << "[ nh-plastic ] H = " << H << ": " << flowing << "/" << ngp << " Gauss points flowing, |K du - FD|/|K du| = " << rel
              << "\n";
    EXPECT_GT(flowing, ngp / 2);
    EXPECT_LT(rel, 1e-6);
  }
}

// Nonlinear hardening (material/IsotropicHardening.hpp: Voce, and a table whose points the
// plastic strains of the field cross) through the global assembly, over both elastic parts:
// tangent against central differences from a plastic committed state, most points flowing.
TEST(MaterialDispatch, NonlinearHardeningTangentMatchesFiniteDifferences) {
  const double te[] = {0.0, 0.02, 0.06, 0.12}, ts[] = {0.1e6, 0.2e6, 0.26e6, 0.28e6};
  const NonlinearHardening hards[] = {NonlinearHardening::voce(0.1e6, 0.4e6, 20.0), NonlinearHardening::table(te, ts, 4)};
  for (const NonlinearHardening& hard : hards)
    for (const bool cg : {false, true}) {
      const double H = hard.kind == NonlinearHardening::kVoce ? 0.2e6 : 0.0;
      NeoHookeanPlasticity nh{NeoHookean{kMu, kLambda}, 0.1e6, H};
      CiarletGeymonatPlasticity cgp{CiarletGeymonat{0.5 * kMu, 0.0, 0.25 * kLambda}, 0.1e6, H};
      nh.nonlinear = cgp.nonlinear = hard;
      Fixture s(write_and_read(cube_deck(), "cube"), {cg ? Material{cgp} : Material{nh}});
      la::Vector u(s.dist->owned_map()), r(s.dist->owned_map());
      s.fill(u, 0.6);
      s.as->assemble(u, 1.0, 1.0, r, false);
      s.as->commit_history();
      s.fill(u, 1.0, 0.03);
      const double rel = tangent_error(s, u);
      s.as->assemble(u, 1.0, 1.0, r, false);
      const std::vector<double> h = host_copy(s.as->trial_history(0));
      int flowing = 0, ngp = 0;
      double amin = 1e300, amax = 0.0;
      for (std::size_t i = 0; i < h.size(); i += NeoHookeanPlasticity::kNumHist) {
        flowing += h[i + NeoHookeanPlasticity::kYielding] > 0.0, ++ngp;
        amin = std::min(amin, h[i + NeoHookeanPlasticity::kAlpha]), amax = std::max(amax, h[i + NeoHookeanPlasticity::kAlpha]);
      }
      std::cout << "[ hardening ] " << (hard.kind == NonlinearHardening::kVoce ? "Voce" : "table") << ", "
                << (cg ? "Ciarlet-Geymonat" : "neo-Hookean") << ": " << flowing << "/" << ngp << " Gauss points flowing, alpha in ["
                << amin << ", " << amax << "], |K du - FD|/|K du| = " << rel << "\n";
      EXPECT_GT(flowing, ngp / 2);
      EXPECT_LT(rel, 1e-6);
    }
}

// The Gonzalez step (incremental potential) with nonlinear hardening through the global
// assembly: the tangent of the step's residual against central differences, and the energy
// identity Psi_{n+1} - Psi_n = f_int . du - D_p with D_p > 0.
TEST(MaterialDispatch, GonzalezStepWithNonlinearHardening) {
  const double te[] = {0.0, 0.02, 0.06, 0.12}, ts[] = {0.1e6, 0.2e6, 0.26e6, 0.28e6};
  const NonlinearHardening hards[] = {NonlinearHardening::voce(0.1e6, 0.4e6, 20.0), NonlinearHardening::table(te, ts, 4)};
  for (const NonlinearHardening& hard : hards) {
    NeoHookeanPlasticity nh{NeoHookean{kMu, kLambda}, 0.1e6, 0.0};
    nh.nonlinear = hard;
    Fixture s(write_and_read(cube_deck(), "cube"), {nh});
    const auto map = s.dist->owned_map();
    la::Vector u0(map), u(map), r(map), rp(map), rm(map), du(map), Kdu(map), up(map);
    s.fill(u0, 0.6);
    s.as->assemble(u0, 1.0, 1.0, r, false);
    s.as->commit_history();
    const double psi_n = s.as->assemble(u0, 1.0, 1.0, r, false).energy;
    s.fill(u, 1.0, 0.03);
    Assembler::StepInput in;
    in.eval = StressEval::Gonzalez;
    in.u_old = &u0;
    in.dt = 1e-3;
    in.load_time = 1.0;
    const auto st = s.as->assemble(u, in, r, true);
    du.update(1.0, u, -1.0, u0, 0.0);
    const double work = s.as->static_residual().dot(du);
    const double gap = st.energy - psi_n - (work - st.plastic_dissipation);
    du.randomize();
    for (la::LO i = 0; i < static_cast<la::LO>(map->getNodeNumElements()); ++i)
      if (s.as->is_dirichlet(i)) du.getLocalViewHost(Tpetra::Access::ReadWrite)(i, 0) = 0.0;
    s.as->matrix()->apply(du, Kdu);
    const double h = 1e-7;
    up.update(1.0, u, h, du, 0.0);
    s.as->assemble(up, in, rp, false);
    up.update(1.0, u, -h, du, 0.0);
    s.as->assemble(up, in, rm, false);
    rp.update(-0.5 / h, rm, 0.5 / h);
    rp.update(-1.0, Kdu, 1.0);
    double err = 0.0;
    auto a = rp.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (std::size_t i = 0; i < a.extent(0); ++i)
      if (!s.as->is_dirichlet(static_cast<la::LO>(i))) err = std::max(err, std::abs(a(i, 0)));
    std::cout << "[ hardening ] Gonzalez step, " << (hard.kind == NonlinearHardening::kVoce ? "Voce" : "table")
              << ": |K du - FD|/|K du| = " << err / Kdu.normInf() << ", D_p = " << st.plastic_dissipation << " J of work "
              << work << " J, identity gap " << gap << " J\n";
    EXPECT_GT(st.plastic_dissipation, 1e-3 * std::abs(work));
    EXPECT_LT(std::abs(gap), 1e-11 * (std::abs(work) + st.energy));
    EXPECT_LT(err / Kdu.normInf(), 1e-6);
  }
}

// d_inf = 0: the history kernel of the damage law gives the stateless neo-Hookean kernel's
// residual, tangent and energy bit for bit (and zero dissipation).
TEST(MaterialDispatch, NoDamageIsTheElasticKernel) {
  const Config cfg = write_and_read(cube_deck(), "cube");
  Fixture e(cfg, {});
  Fixture d(cfg, {damage_law(0.0)});
  ASSERT_FALSE(e.as->has_history());
  ASSERT_TRUE(d.as->has_history());
  la::Vector u(e.dist->owned_map());
  e.fill(u, 1.0);
  stentor::testing::expect_same_assembly(e, d, u);
}

// A Gonzalez step u_n -> u_{n+1} with damage growing: the element energy and dissipation
// close Psi_{n+1} - Psi_n = f_int . (u_{n+1} - u_n) - D to round-off (f_int: the static
// residual of the step, i.e. the discrete gradient of the frozen potential; no loads).
TEST(MaterialDispatch, GonzalezStepEnergyIdentityWithDamage) {
  Fixture s(write_and_read(cube_deck(), "cube"), {damage_law()});
  const auto map = s.dist->owned_map();
  la::Vector u0(map), u1(map), r(map), du(map);
  s.fill(u0, 0.6);
  s.as->assemble(u0, 1.0, 1.0, r, false);
  s.as->commit_history();
  const double psi_n = s.as->assemble(u0, 1.0, 1.0, r, false).energy;  // at the committed state
  s.fill(u1, 0.9, 0.02);
  Assembler::StepInput gz;
  gz.eval = StressEval::Gonzalez;
  gz.u_old = &u0;
  gz.dt = 1e-3;
  gz.load_time = 1.0;
  const auto st = s.as->assemble(u1, gz, r, false);
  du.update(1.0, u1, -1.0, u0, 0.0);
  const double work = s.as->static_residual().dot(du);
  const double gap = st.energy - psi_n - (work - st.plastic_dissipation);
  std::cout << "[ damage ] Gonzalez step: Psi_n = " << psi_n << ", Psi_n+1 = " << st.energy << ", work = " << work
            << ", D = " << st.plastic_dissipation << ", identity gap = " << gap << " J\n";
  EXPECT_GT(growing_points(*s.as, 0), 0);
  EXPECT_GT(st.plastic_dissipation, 1e-3 * std::abs(work));
  EXPECT_LT(std::abs(gap), 1e-11 * (std::abs(work) + st.energy));
}

// Two laws with history in one deck: each block's views have its law's width, the output
// columns are the union of the laws' output names (0 where a block's law has none), and
// commit / roll back act on both blocks.
TEST(MaterialDispatch, TwoLawsWithHistoryInOneDeck) {
  const Config cfg = write_and_read(two_block_deck(), "two_blocks");
  std::vector<Material> laws;
  for (const MaterialConfig& m : cfg.materials) laws.push_back(m.name == "tissue" ? Material(damage_law()) : make_material(m));
  Fixture s(cfg, laws);
  ASSERT_EQ(s.dist->blocks().size(), 2u);
  std::size_t metal = 0, tissue = 1;
  if (cfg.materials[static_cast<std::size_t>(s.block_mat[static_cast<std::size_t>(s.dist->blocks()[0].volume_block)])].name == "tissue")
    std::swap(metal, tissue);
  EXPECT_EQ(s.as->committed_history(metal).extent(1), static_cast<std::size_t>(CiarletGeymonatPlasticity::kNumHist));
  EXPECT_EQ(s.as->committed_history(tissue).extent(1), static_cast<std::size_t>(NeoHookeanDamage::kNumHist));
  la::Vector u(s.dist->owned_map()), r(s.dist->owned_map());
  s.fill(u, 1.0);
  s.as->apply_dirichlet(u, 1.0, 1.0);
  const auto st = s.as->assemble(u, 1.0, 1.0, r, true);
  EXPECT_EQ(st.inverted, 0);
  EXPECT_GT(growing_points(*s.as, tissue), 0);
  s.as->commit_history();
  const Assembler::CellFields cf = s.as->cell_fields(u);
  // In block order: the plasticity law's four output names and the damage law's three.
  const std::vector<std::string> plastic = {"equivalent_plastic_strain", "mandel_hill_norm", "yielding", "plastic_dissipation"};
  const std::vector<std::string> damage = {"max_virgin_energy", "damage", "damage_dissipation"};
  std::vector<std::string> expect = metal == 0 ? plastic : damage;
  for (const auto& n : metal == 0 ? damage : plastic) expect.push_back(n);
  const std::vector<std::string>& names = cf.extra_names;
  ASSERT_EQ(names, expect);
  const std::size_t nx = names.size(), nc_metal = s.dist->blocks()[metal].cell_ids.size();
  const auto column = [&](const std::string& n) { return static_cast<std::size_t>(std::find(names.begin(), names.end(), n) - names.begin()); };
  double damage_metal = 0.0, damage_tissue = 0.0, alpha_tissue = 0.0, alpha_metal = 0.0;
  for (std::size_t c = 0; c < cf.cell_ids.size(); ++c) {
    const bool in_metal = (metal == 0) == (c < nc_metal);
    (in_metal ? damage_metal : damage_tissue) += std::abs(cf.extra[c * nx + column("damage")]);
    (in_metal ? alpha_metal : alpha_tissue) += std::abs(cf.extra[c * nx + column("equivalent_plastic_strain")]);
  }
  EXPECT_EQ(damage_metal, 0.0);
  EXPECT_EQ(alpha_tissue, 0.0);
  EXPECT_GT(damage_tissue, 0.0);
  EXPECT_GT(alpha_metal, 0.0);
  // A cut-back: a wild trial, then roll back, leaves both committed states as committed.
  const std::vector<double> m1 = host_copy(s.as->committed_history(metal)), t1 = host_copy(s.as->committed_history(tissue));
  s.fill(u, 2.0, 0.1);
  s.as->assemble(u, 1.0, 1.0, r, false);
  EXPECT_NE(host_copy(s.as->trial_history(tissue)), t1);
  s.as->rollback_history();
  EXPECT_EQ(host_copy(s.as->trial_history(metal)), m1);
  EXPECT_EQ(host_copy(s.as->trial_history(tissue)), t1);
  EXPECT_EQ(host_copy(s.as->committed_history(metal)), m1);
}
