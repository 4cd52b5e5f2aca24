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
