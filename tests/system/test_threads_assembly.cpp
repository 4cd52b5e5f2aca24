// Thread-safe assembly: the element kernels run on all Kokkos threads (OpenMP build) and
// sum into shared rows either atomically (default) or by colours of cells that share no
// node. Both must give the same residual, tangent and energy, and the colouring must be
// a real colouring. ctest runs this executable with OMP_NUM_THREADS=2, so on an OpenMP
// build the kernels below run on two threads.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <algorithm>
#include <memory>
#include <cmath>
#include <cstdlib>
#include <set>
#include <string>
#include <vector>

#include "assembly/Assembler.hpp"
#include "bc/Loads.hpp"
#include "deck/Config.hpp"
#include "mesh/MeshComm.hpp"
#include "parallel/Distribution.hpp"

using namespace stentor;

namespace {

const std::string kDeck = std::string(STENTOR_SOURCE_DIR) + "/tests/cli/decks/par3d.xml";

struct Fixture {
  Config cfg;
  Mesh mesh;
  Loads loads;
  std::vector<int> block_mat;
  std::unique_ptr<Distribution> dist;
};

// The 3D P2 consistency deck (pressure, traction, body force) on a finer mesh, so that
// each thread gets many cells and shared rows are hit concurrently. Built once; released
// by the environment below before main() finalizes Kokkos (its views must go first).
std::unique_ptr<Fixture> g_fixture;

class ReleaseFixture : public ::testing::Environment {
 public:
  void TearDown() override { g_fixture.reset(); }
};
const auto* const kRelease = ::testing::AddGlobalTestEnvironment(new ReleaseFixture);

Fixture& setup() {
  if (!g_fixture) {
    g_fixture = std::make_unique<Fixture>();
    Fixture& x = *g_fixture;
    x.cfg = read_deck(kDeck);
    x.cfg.mesh.size = 0.2;
    x.mesh = read_mesh_on_root(x.cfg.mesh, MPI_COMM_WORLD, true, false);
    x.loads = resolve_loads(x.cfg, x.mesh);
    x.block_mat = block_materials(x.cfg, x.mesh);
    x.dist = std::make_unique<Distribution>(x.mesh, Tpetra::getDefaultComm());
  }
  return *g_fixture;
}

// A smooth, non-trivial displacement (stretch + twist + bulge), scaled by amp.
void fill(const Fixture& s, la::Vector& u, double amp) {
  auto uh = u.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (la::LO l = 0; l < s.dist->num_owned_nodes(); ++l) {
    const double* X = &s.mesh.x[3 * static_cast<std::size_t>(s.dist->global_node(l))];
    uh(3 * l + 0, 0) = amp * (0.10 * X[0] + 0.05 * X[1] * X[2]);
    uh(3 * l + 1, 0) = amp * (-0.03 * X[1] + 0.04 * std::sin(X[0] + X[2]));
    uh(3 * l + 2, 0) = amp * (0.02 * X[0] * X[1] - 0.05 * X[2] * X[2]);
  }
}

struct Assembled {
  std::vector<double> r, K;
  double energy = 0.0, dissipation = 0.0;
};

Assembled assemble(Assembler& as, const Assembler::StepInput& in, double amp) {
  const Fixture& s = setup();
  la::Vector u(s.dist->owned_map()), r(s.dist->owned_map());
  fill(s, u, amp);
  const auto st = as.assemble(u, in, r, true);
  Assembled out;
  out.energy = st.energy;
  out.dissipation = st.dissipation;
  auto rh = r.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (std::size_t i = 0; i < rh.extent(0); ++i) out.r.push_back(rh(i, 0));
  auto K = as.matrix()->getLocalMatrixHost();
  for (std::size_t i = 0; i < K.values.extent(0); ++i) out.K.push_back(K.values(i));
  return out;
}

double rel_diff(const std::vector<double>& a, const std::vector<double>& b) {
  EXPECT_EQ(a.size(), b.size());
  double d = 0.0, m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    d = std::max(d, std::abs(a[i] - b[i]));
    m = std::max(m, std::abs(a[i]));
  }
  return m > 0 ? d / m : d;
}

// Atomic and coloured assembly of the same state: residual, tangent, energy, dissipation.
void expect_same(const Assembled& a, const Assembled& c) {
  EXPECT_LT(rel_diff(a.r, c.r), 1e-13);
  EXPECT_LT(rel_diff(a.K, c.K), 1e-13);
  EXPECT_NEAR(a.energy, c.energy, 1e-13 * std::abs(a.energy));
  EXPECT_NEAR(a.dissipation, c.dissipation, 1e-13 * std::abs(a.dissipation));
}

Config with_assembly(const std::string& how) {
  Config c = setup().cfg;
  c.problem.assembly = how;
  return c;
}

}  // namespace

TEST(Threads, KokkosRunsOnTheRequestedThreads) {
  const int conc = la::ExecSpace().concurrency();
  const std::string backend = la::ExecSpace::name();
  std::cout << "Kokkos " << backend << " x " << conc << " thread(s)\n";
  if (backend == "OpenMP") {
    const char* env = std::getenv("OMP_NUM_THREADS");
    ASSERT_NE(env, nullptr) << "ctest sets OMP_NUM_THREADS for this test";
    EXPECT_EQ(conc, std::atoi(env));
  } else {
    EXPECT_EQ(backend, "Serial");
    EXPECT_EQ(conc, 1);
  }
}

TEST(Threads, ColoringIsAProperColoring) {
  Fixture& s = setup();
  const Config cfg = with_assembly("coloring");
  Assembler as(s.mesh, *s.dist, cfg, s.loads, s.block_mat);
  ASSERT_GT(as.num_colors(), 1);
  EXPECT_LT(as.num_colors(), 100) << "greedy colouring of a tet10 mesh should need a few dozen colours";
  for (std::size_t b = 0; b < s.dist->blocks().size(); ++b) {
    const auto& lb = s.dist->blocks()[b];
    auto conn = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), lb.conn);
    const std::vector<int> color = as.cell_colors(b);
    ASSERT_EQ(color.size(), conn.extent(0));
    std::set<std::pair<int, int>> seen;  // (colour, node)
    for (std::size_t c = 0; c < color.size(); ++c) {
      ASSERT_GE(color[c], 0) << "cell " << c << " has no colour";
      for (int a = 0; a < lb.nodes_per_cell; ++a)
        EXPECT_TRUE(seen.insert(std::make_pair(color[c], static_cast<int>(conn(c, a)))).second)
            << "node " << conn(c, a) << " appears twice in colour " << color[c];
    }
  }
  Assembler atomic(s.mesh, *s.dist, with_assembly("atomic"), s.loads, s.block_mat);
  EXPECT_EQ(atomic.num_colors(), 0);
  EXPECT_TRUE(atomic.cell_colors(0).empty());
}

TEST(Threads, AtomicAndColoredAssemblyAgree) {
  Fixture& s = setup();
  Assembler a(s.mesh, *s.dist, with_assembly("atomic"), s.loads, s.block_mat);
  Assembler c(s.mesh, *s.dist, with_assembly("coloring"), s.loads, s.block_mat);
  Assembler::StepInput in;
  in.load_time = 0.7;
  const Assembled ra = assemble(a, in, 1.0), rc = assemble(c, in, 1.0);
  expect_same(ra, rc);
  EXPECT_GT(ra.energy, 0.0);

  // Time-step path: Gonzalez stress from u_n to u_{n+1}, Curnier viscosity, pressure at the midpoint.
  Config dyn = with_assembly("atomic");
  dyn.problem.analysis = "dynamic";
  for (auto& m : dyn.materials) m.viscosity = 50.0;
  Config dync = dyn;
  dync.problem.assembly = "coloring";
  Assembler ad(s.mesh, *s.dist, dyn, s.loads, s.block_mat), cd(s.mesh, *s.dist, dync, s.loads, s.block_mat);
  la::Vector u0(s.dist->owned_map());
  fill(s, u0, 0.6);
  Assembler::StepInput st;
  st.load_time = 0.5;
  st.eval = StressEval::Gonzalez;
  st.u_old = &u0;
  st.dt = 0.01;
  st.pressure_theta = 0.5;
  const Assembled da = assemble(ad, st, 1.0), dc = assemble(cd, st, 1.0);
  expect_same(da, dc);
  EXPECT_GT(da.dissipation, 0.0);
}

TEST(Threads, RepeatedAtomicAssemblyAgreesToRoundOff) {
  // Atomic sums arrive in a thread-dependent order: results may differ by round-off only.
  Fixture& s = setup();
  Assembler a(s.mesh, *s.dist, with_assembly("atomic"), s.loads, s.block_mat);
  Assembler::StepInput in;
  const Assembled first = assemble(a, in, 1.0);
  for (int k = 0; k < 3; ++k) {
    const Assembled again = assemble(a, in, 1.0);
    EXPECT_LT(rel_diff(first.r, again.r), 1e-14);
    EXPECT_LT(rel_diff(first.K, again.K), 1e-14);
  }
}
