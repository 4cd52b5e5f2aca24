// A fluid cavity's volume, facet by facet (LoadConfig::FluidCavity).
//
// The cavity is bounded by its wall (the load's facets), by planes normal to the axis (its
// ends) and by planes through the axis (symmetry cuts). With x_perp = (x - x0) - ((x - x0).a) a
// the part of x - x0 normal to the axis (x0 a point of the axis, a its unit direction),
// div(x_perp / 2) = 1 and x_perp . n = 0 on every plane of the two kinds, so the divergence
// theorem leaves the wall alone:
//     V = 1/2 int_wall x_perp . n_c da,
// n_c the normal out of the cavity, which is minus the wall's outward normal n (the body's:
// n da = orient (x_,xi x x_,eta) dxi deta). As the end and cut planes' edges slide in their
// planes (held axially, symmetry conditions), the volume's derivative is the wall's alone,
//     dV/dx_a = int_wall N_a n_c da,
// which is minus the residual of a unit follower pressure (assembly/PressureElement.hpp):
// the cavity's pressure p = K ln(V_fluid / V) adds r = -p dV/du, whose tangent is the
// follower pressure's at p plus (K / V) (dV/du) (dV/du)^T, a rank-one term that couples
// every wall dof (Newton solves it by Sherman-Morrison, solver/Newton.hpp). For bilinear
// facets the integrand is of degree 2 in each parameter: the pressure's rule (degree 3) is
// exact, and the volume and its derivative agree to round-off.
#pragma once
#include "assembly/HyperelasticElement.hpp"

namespace stentor {

KOKKOS_INLINE_FUNCTION double cavity_facet_volume(CellType type, int nn, const double (*X)[3], const double (*U)[3],
                                                  double orient, const double* x0, const double* a, const QuadRule& q) {
  double N[kMaxCellNodes], dN[kMaxCellNodes][3], v = 0.0;
  for (int g = 0; g < q.n; ++g) {
    shape_functions(type, q.xi[g], N, dN);
    double t1[3] = {0, 0, 0}, t2[3] = {0, 0, 0}, x[3] = {0, 0, 0};
    for (int b = 0; b < nn; ++b)
      for (int d = 0; d < 3; ++d) {
        const double xb = X[b][d] + U[b][d];
        t1[d] += dN[b][0] * xb;
        t2[d] += dN[b][1] * xb;
        x[d] += N[b] * xb;
      }
    double y[3] = {x[0] - x0[0], x[1] - x0[1], x[2] - x0[2]};
    const double ya = y[0] * a[0] + y[1] * a[1] + y[2] * a[2];
    for (int d = 0; d < 3; ++d) y[d] -= ya * a[d];
    const double n[3] = {t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2], t1[0] * t2[1] - t1[1] * t2[0]};
    v += q.w[g] * (y[0] * n[0] + y[1] * n[1] + y[2] * n[2]);
  }
  return -0.5 * orient * v;
}

}  // namespace stentor
