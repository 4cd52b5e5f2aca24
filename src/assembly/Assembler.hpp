// Global residual and tangent of the (static) finite-strain problem.
//
// Assembly follows Tpetra's FE pattern: every rank loops over its own cells in Kokkos
// kernels and sums element contributions into an *overlap* matrix/vector (rows of all
// nodes its cells touch, purely local), which is then exported (ADD) into the owned,
// one-to-one matrix/vector the solver sees. Both graphs are built once.
//
// Dirichlet dofs: their values are imposed on u before each solve; their residual rows
// are zeroed and their matrix rows replaced by the identity, so Newton increments
// vanish there. Reactions are read from those rows before zeroing.
#pragma once
#include <array>
#include <vector>

#include "bc/Loads.hpp"
#include "deck/Config.hpp"
#include "material/CiarletGeymonat.hpp"
#include "parallel/Distribution.hpp"

namespace stentor {

class Assembler {
 public:
  Assembler(const Mesh& mesh, const Distribution& dist, const Config& cfg, const Loads& loads,
            const std::vector<int>& block_material);

  struct Stats {
    double energy = 0.0;     // stored elastic energy (global)
    long inverted = 0;       // cells with det F <= 0 at a Gauss point (global)
  };

  // r = f_int(u) - f_ext(u, t) on owned rows (Dirichlet rows zeroed); K = dr/du if with_tangent.
  // `t` and `end_time` evaluate the load ramps.
  Stats assemble(const la::Vector& u, double t, double end_time, la::Vector& r, bool with_tangent);

  const la::RCP<la::CrsMatrix>& matrix() const { return K_; }

  // Sets the prescribed values at time t on the owned Dirichlet dofs of u.
  void apply_dirichlet(la::Vector& u, double t, double end_time) const;

  // Reaction force (sum over each Dirichlet set's nodes, all components) from the last assemble().
  const std::vector<std::array<double, 3>>& reactions() const { return reactions_; }
  const std::vector<DirichletSet>& dirichlet_sets() const { return loads_.dirichlet; }

  // Per local cell: Cauchy stress (xx, yy, zz, xy, yz, xz) averaged over Gauss points,
  // von Mises of that average, mean J. Order: Distribution::blocks() order.
  struct CellFields {
    std::vector<GId> cell_ids;
    std::vector<double> stress, von_mises, J;
  };
  CellFields cell_fields(const la::Vector& u);

 private:
  void build_graph();
  void setup_loads(const Mesh& mesh);

  const Distribution& dist_;
  const Loads& loads_;
  int dim_;
  std::vector<CiarletGeymonat> block_mat_;  // per mesh volume block
  std::vector<int> quad_degree_;            // per mesh volume block

  la::RCP<const la::Export> exporter_;       // overlap -> owned
  la::RCP<la::CrsMatrix> K_overlap_, K_;
  la::RCP<la::Vector> u_overlap_, r_overlap_, f_dead_;  // f_dead_: unit-ramp dead loads per load (see loads below)
  Kokkos::View<int*, la::ExecSpace> dirichlet_flag_;   // per overlap dof
  Kokkos::View<int*, la::ExecSpace> failures_;
  std::vector<la::LO> owned_dirichlet_dofs_;
  std::vector<double> owned_dirichlet_value_;           // full value (times ramp of its set)
  std::vector<int> owned_dirichlet_set_;

  // Dead loads (traction, body force): assembled once for a unit ramp, scaled each step.
  struct DeadLoad {
    Ramp ramp;
    la::RCP<la::Vector> f;  // overlap
  };
  std::vector<DeadLoad> dead_;
  // Follower pressures: facets integrated by this rank (local node indices).
  struct PressureLoad {
    Ramp ramp;
    double pressure;
    CellType type;
    int nn;
    Kokkos::View<int**, Kokkos::LayoutRight, la::ExecSpace> conn;
    Kokkos::View<double*, la::ExecSpace> orientation;
  };
  std::vector<PressureLoad> pressures_;
  std::vector<std::array<double, 3>> reactions_;
  std::vector<std::vector<la::LO>> dirichlet_owned_nodes_;  // per set
};

}  // namespace stentor
