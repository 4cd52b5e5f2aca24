// An assembler on a deck's mesh without the rest of a run, for the material tests that
// call assemble() directly (test_plasticity_fe, test_material_dispatch): the mesh, loads,
// layout and assembler, a smooth test displacement, and the bitwise comparison of two
// assemblers' residual, energy and tangent.
#pragma once
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "assembly/Assembler.hpp"
#include "bc/Loads.hpp"
#include "deck/Config.hpp"
#include "mesh/MeshComm.hpp"
#include "parallel/Distribution.hpp"

namespace stentor::testing {

struct AssemblerFixture {
  Config cfg;
  Mesh mesh;
  Loads loads;
  std::vector<int> block_mat;
  std::unique_ptr<Distribution> dist;
  std::unique_ptr<Assembler> as;
  // `laws`: one per deck material, replacing the deck's (empty: the deck's own).
  explicit AssemblerFixture(const Config& c, const std::vector<Material>& laws = {}) : cfg(c) {
    mesh = read_mesh_on_root(cfg.mesh, MPI_COMM_WORLD, true, false);
    loads = resolve_loads(cfg, mesh);
    block_mat = block_materials(cfg, mesh);
    dist = std::make_unique<Distribution>(mesh, Tpetra::getDefaultComm());
    as = laws.empty() ? std::make_unique<Assembler>(mesh, *dist, cfg, loads, block_mat)
                      : std::make_unique<Assembler>(mesh, *dist, cfg, loads, block_mat, laws);
  }
  // A smooth non-homogeneous displacement (stretch, shear, twist) of a 3D mesh, scaled by amp.
  void fill(la::Vector& u, double amp, double phase = 0.0) const {
    auto uh = u.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (la::LO l = 0; l < dist->num_owned_nodes(); ++l) {
      const double* X = &mesh.x[3 * static_cast<std::size_t>(dist->global_node(l))];
      uh(3 * l + 0, 0) = amp * (0.10 * X[0] + 0.05 * X[1] * X[2] + phase * X[1]);
      uh(3 * l + 1, 0) = amp * (-0.03 * X[1] + 0.04 * std::sin(X[0] + X[2]));
      uh(3 * l + 2, 0) = amp * (0.02 * X[0] * X[1] - 0.05 * X[2] * X[2] + phase * X[0] * X[2]);
    }
  }
};

// `b` assembles exactly what `a` does at u (statics, t = 1): energy, residual and every
// tangent entry bit for bit, and no dissipation (a law with history whose history cannot
// change, against the stateless kernel).
inline void expect_same_assembly(const AssemblerFixture& a, const AssemblerFixture& b, const la::Vector& u) {
  la::Vector r1(a.dist->owned_map()), r2(b.dist->owned_map());
  const auto s1 = a.as->assemble(u, 1.0, 1.0, r1, true);
  const auto s2 = b.as->assemble(u, 1.0, 1.0, r2, true);
  EXPECT_EQ(s1.energy, s2.energy);
  EXPECT_EQ(s2.plastic_dissipation, 0.0);
  r1.update(-1.0, r2, 1.0);
  EXPECT_EQ(r1.normInf(), 0.0);
  auto K1 = a.as->matrix()->getLocalMatrixHost();
  auto K2 = b.as->matrix()->getLocalMatrixHost();
  ASSERT_EQ(K1.values.extent(0), K2.values.extent(0));
  double diff = 0.0;
  for (std::size_t i = 0; i < K1.values.extent(0); ++i) diff = std::max(diff, std::abs(K1.values(i) - K2.values(i)));
  EXPECT_EQ(diff, 0.0);
}

}  // namespace stentor::testing
