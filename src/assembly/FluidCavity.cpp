// Fluid cavities: their volume, pressure and the rank-one term of their tangent
// (assembly/FluidCavity.hpp has the formulas). Host loops over the cavity's wall facets
// this rank integrates (PressureLoad::conn): a balloon's wall is small beside the bulk.
#include <Teuchos_CommHelpers.hpp>

#include <cmath>
#include <limits>

#include "assembly/Assembler.hpp"
#include "assembly/FluidCavity.hpp"
#include "assembly/PressureElement.hpp"

namespace stentor {

namespace {
// Calls f(pl, conn, facet, Xe, Ue, orientation, rule) for every facet of cavity k's wall that this
// rank integrates (`pressures`: Assembler::pressures_), with its reference coordinates Xe and
// displacements Ue (overlap-local node indices; Ue = 0 without u).
template <class PressureLoads, class Coords, class UView, class F>
void each_wall_facet(const PressureLoads& pressures, std::size_t k, const Coords& X, const UView* u, F&& f) {
  for (const auto& pl : pressures) {
    if (pl.cavity != static_cast<int>(k)) continue;
    const QuadRule q = make_rule(pl.type, 2 * cell_order(pl.type) + 1);
    const auto conn = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), pl.conn);
    const auto orient = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), pl.orientation);
    for (std::size_t c = 0; c < conn.extent(0); ++c) {
      double Xe[kMaxCellNodes][3], Ue[kMaxCellNodes][3];
      for (int a = 0; a < pl.nn; ++a)
        for (int d = 0; d < 3; ++d) {
          Xe[a][d] = X(conn(c, a), d);
          Ue[a][d] = u ? (*u)(conn(c, a) * 3 + d, 0) : 0.0;
        }
      f(pl, conn, c, Xe, Ue, orient(c), q);
    }
  }
}
}  // namespace

double Assembler::cavity_volume(std::size_t k, bool reference) const {
  const auto X = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dist_.coords());
  const auto uh = u_overlap_->getLocalViewHost(Tpetra::Access::ReadOnly);
  const FluidCavitySpec& s = cavities_[k].spec;
  double loc = 0.0, glob = 0.0;
  each_wall_facet(pressures_, k, X, reference ? nullptr : &uh,
                  [&](const auto& pl, const auto&, std::size_t, const double(*Xe)[3], const double(*Ue)[3], double orient,
                      const QuadRule& q) { loc += cavity_facet_volume(pl.type, pl.nn, Xe, Ue, orient, s.point.data(), s.axis.data(), q); });
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, 1, &loc, &glob);
  return glob;
}

// p = K ln(V_fluid / V), V_fluid = V0 (1 + ramp (ratio - 1)); 0 in a stage without the load.
// A volume that is not positive (a wall turned through the axis) gives a NaN pressure: the
// residual is not finite and Newton cuts the step.
void Assembler::update_cavities(const StepInput& in) {
  for (std::size_t k = 0; k < cavities_.size(); ++k) {
    Cavity& c = cavities_[k];
    c.on = c.spec.ramp.on(in.load_time);
    c.p = c.c = 0.0;
    if (!c.on) continue;
    c.V = cavity_volume(k, false);
    const double fluid = c.V0 * (1.0 + c.spec.ramp(in.load_time, in.end_time) * (c.spec.volume_ratio - 1.0));
    if (!(c.V > 0.0) || !(fluid > 0.0)) {
      c.p = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    c.p = c.spec.bulk_modulus * std::log(fluid / c.V);
    c.c = c.spec.bulk_modulus / c.V;
  }
}

// right = dV/du: minus a unit follower pressure's residual on the wall; left: its rows
// constrained as matrix()'s are (Dirichlet rows 0, plane rows projected, their constraint
// rows 0).
void Assembler::update_cavity_gradients() {
  if (cavities_.empty()) return;
  const auto X = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), dist_.coords());
  la::Vector g_overlap(dist_.overlap_map());
  for (std::size_t k = 0; k < cavities_.size(); ++k) {
    Cavity& c = cavities_[k];
    c.tangent_c = c.on && std::isfinite(c.c) ? c.c : 0.0;
    if (c.tangent_c == 0.0) continue;
    g_overlap.putScalar(0.0);
    {
      const auto uh = u_overlap_->getLocalViewHost(Tpetra::Access::ReadOnly);
      auto gh = g_overlap.getLocalViewHost(Tpetra::Access::ReadWrite);
      each_wall_facet(pressures_, k, X, &uh,
                      [&](const auto& pl, const auto& conn, std::size_t f, const double(*Xe)[3], const double(*Ue)[3], double orient,
                          const QuadRule& q) {
                        double re[kMaxCellDofs], ke[kMaxCellDofs][kMaxCellDofs];
                        pressure_element(3, kin_, pl.type, pl.nn, Xe, Ue, -orient, 1.0, q, re, ke);
                        for (int a = 0; a < pl.nn; ++a)
                          for (int d = 0; d < 3; ++d) gh(conn(f, a) * 3 + d, 0) += re[a * 3 + d];
                      });
    }
    if (c.right.is_null()) c.right = Teuchos::rcp(new la::Vector(dist_.owned_map()));
    if (c.left.is_null()) c.left = Teuchos::rcp(new la::Vector(dist_.owned_map()));
    c.right->putScalar(0.0);
    c.right->doExport(g_overlap, *exporter_, Tpetra::ADD);
    c.left->assign(*c.right);
    {
      auto lh = c.left->getLocalViewHost(Tpetra::Access::ReadWrite);
      for (la::LO i : owned_dirichlet_dofs_) lh(i, 0) = 0.0;
    }
    project_plane_vector(*c.left);
  }
}

}  // namespace stentor
