// Global residual and tangent of the (static) finite-strain problem.
//
// Assembly follows Tpetra's FE pattern: every rank loops over its own cells in Kokkos
// kernels and sums element contributions into an *overlap* matrix/vector (rows of all
// nodes its cells touch, purely local), which is then exported (ADD) into the owned,
// one-to-one matrix/vector the solver sees. Both graphs are built once.
//
// Dirichlet dofs: their values are imposed on u before each solve; their residual rows
// are zeroed and their matrix rows replaced by the identity, so Newton increments
// vanish there. Reactions are read from those rows before zeroing. Nodes on `normal`
// sets (planes at any angle) keep u on their planes; their rows are projected on the
// planes with one constraint row per plane (PlaneConstraints.cpp).
//
// Threads: element kernels run in Kokkos' default execution space (OpenMP threads on an
// OpenMP build). Two cells on different threads may sum into the same rows; by default
// those sums are atomic (Problem->assembly = atomic); `coloring` instead launches one
// kernel per colour of cells that share no node and sums without atomics.
// docs/performance.md compares the two.
#pragma once
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "bc/Loads.hpp"
#include "bc/PlaneDirections.hpp"
#include "deck/Config.hpp"
#include "assembly/HyperelasticElement.hpp"
#include "material/MaterialRegistry.hpp"
#include "parallel/Distribution.hpp"

namespace stentor {

class Assembler {
 public:
  // The law of each material from the deck (make_material, material/MaterialRegistry.hpp).
  Assembler(const Mesh& mesh, const Distribution& dist, const Config& cfg, const Loads& loads,
            const std::vector<int>& block_material);
  // laws[i] is the law of cfg.materials[i] (any registered law, also one no deck names);
  // the rest of cfg.materials[i] (density, viscosity) is used as above.
  Assembler(const Mesh& mesh, const Distribution& dist, const Config& cfg, const Loads& loads,
            const std::vector<int>& block_material, const std::vector<Material>& laws);

  struct Stats {
    double energy = 0.0;       // stored elastic energy int W(C_{n+1}) (global)
    double dissipation = 0.0;  // viscous energy dissipated over the step (global; 0 without viscosity)
    double plastic_dissipation = 0.0;  // plastic dissipation int D_p of the step t_n -> t_{n+1} (global; trial state)
    long inverted = 0;         // cells with det F <= 0 at a Gauss point, or whose local return map failed (global)
    // With inverted > 0: the failed cell of smallest global id, e.g. "cell 812 of 'stent'
    // (centre 0.1, 0.95, 0)" (the same on every rank).
    std::string first_failed;
  };

  // What a time step adds to the static residual. The defaults give statics:
  //   r = s * (f_int(u) - f_ext(t)) + c M (u - u_tilde) + extra,   K = dr/du.
  struct StepInput {
    double load_time = 0.0, end_time = 1.0;  // ramps are evaluated at load_time
    StressEval eval = StressEval::EndPoint;
    const la::Vector* u_old = nullptr;       // u_n: Midpoint/Gonzalez stress, viscosity, midpoint pressure
    double dt = 0.0;
    double pressure_theta = 1.0;             // follower pressure on the configuration u_n + theta (u - u_n)
    double scale = 1.0;                      // s (HHT: 1 + alpha)
    double mass_coeff = 0.0;                 // c
    const la::Vector* u_tilde = nullptr;
    const la::Vector* extra = nullptr;       // owned, all rows
  };

  // After an assemble() that found inadmissible cells: the k cells of smallest det F (over
  // the stiffness quadrature points, all ranks) at its state, each as "cell <id> of
  // '<block>' (det F <value>, reference centre x, y[, z])", the smallest first; collective.
  std::string smallest_det_f(int k) const;

  // Residual on owned rows (Dirichlet rows zeroed after reactions are read) and, if
  // with_tangent, the tangent in matrix().
  Stats assemble(const la::Vector& u, const StepInput& in, la::Vector& r, bool with_tangent);
  // Statics shorthand.
  Stats assemble(const la::Vector& u, double t, double end_time, la::Vector& r, bool with_tangent) {
    StepInput in;
    in.load_time = t;
    in.end_time = end_time;
    return assemble(u, in, r, with_tangent);
  }

  // After assemble(): f_int - f_ext of the last call (unscaled, no inertia, all owned rows)
  // and f_ext alone (owned, all rows).
  const la::Vector& static_residual() const { return *r_static_; }
  const la::Vector& external_force() const { return *f_ext_; }
  // Consistent mass matrix (owned rows, Dirichlet rows included); built on first use.
  const la::RCP<la::CrsMatrix>& mass();
  // Work of the supports: sum over owned constrained dofs of r_i du_i (global), with r the
  // full residual (inertia included) of the last assemble(). On a constrained row the
  // support supplies exactly the force r_i = (f_int + M a - f_ext)_i that the free rows
  // balance to zero, so this is the work the Dirichlet reactions did on the body over a step
  // whose increment is du (summing r.du over all rows gives the scheme's identity
  // dE + D - W_ext = W_sup; with the opposite sign, invisible with fixed supports, a moving
  // one would show a balance error of 2 W_sup). A node on `normal` planes adds
  // sum_i (e_i . r)(e_i . du): zero for a fixed plane.
  double support_work(const la::Vector& du) const;
  // Dirichlet flag of each owned dof (on `normal` planes: the dofs that carry the planes'
  // constraint rows, plane_normals()).
  bool is_dirichlet(la::LO owned_dof) const;
  // ... by a Cartesian set only (not a plane's constraint row): the dof keeps its value.
  bool is_cartesian_dirichlet(la::LO owned_dof) const { return owned_cartesian_flag_[static_cast<std::size_t>(owned_dof)] != 0; }
  // An owned node on `normal` Dirichlet sets (planes at any angle): the number m of its
  // orthonormal constraint directions e[0..m-1] (the planes' normals with the Cartesian-
  // prescribed components removed, Gram-Schmidt); 0 elsewhere. Its rows: m of them
  // (is_dirichlet) are the constraints e_i . du = 0, the others those of the residual
  // projected on the planes, (I - sum e_i e_i^T) r (PlaneConstraints.cpp).
  // j: the components whose rows carry the constraints.
  int plane_normals(la::LO owned_node, double e[3][3], int j[3]) const;
  // Nodes on `normal` planes only: u moved to the closest point of their planes at time t
  // (apply_dirichlet does this and sets the Cartesian dofs too).
  void apply_planes(la::Vector& u, double t, double end_time) const;
  // v less its components along the planes' normals at the nodes on `normal` planes (an
  // initial velocity).
  void project_on_planes(la::Vector& v) const;
  // The rows of the plane nodes of M (owned rows in fill, the tangent's graph: the mass
  // matrix) and of the right-hand side b made the tangent's: the projection on the planes
  // and the constraint rows e_i . x = 0 (TimeIntegrator::solve_mass).
  void constrain_planes(la::CrsMatrix& M, la::Vector& b) const;

  const la::RCP<la::CrsMatrix>& matrix() const { return K_; }

  // Fluid cavities (bc/Loads.hpp, assembly/FluidCavity.hpp), as at the last assemble(): on
  // (the load active at its time), the volume V (V0 in the mesh), the pressure p; after one
  // with the tangent, the rank-one term c left right^T that matrix() leaves out of dr/du:
  // c = K / V, right = dV/du (owned rows; 0 on Cartesian Dirichlet rows), left = right with
  // the rows of Dirichlet and plane constraints made those of matrix() (zero, projected).
  struct Cavity {
    FluidCavitySpec spec;
    double V0 = 0.0, V = 0.0, p = 0.0, c = 0.0;
    bool on = false;
    double tangent_c = 0.0;  // c at the last assemble() with the tangent (0: off then)
    la::RCP<la::Vector> left, right;
  };
  const std::vector<Cavity>& cavities() const { return cavities_; }

  // Colours of the largest local block when Problem->assembly = coloring (0: atomic sums).
  int num_colors() const;
  // Colour of each cell of local block b (Distribution::blocks() order); empty with atomics.
  std::vector<int> cell_colors(std::size_t b) const;

  // Gauss-point history (laws with internal state, material/MaterialState.hpp: e.g.
  // the plasticity and damage models), per local block in Kokkos views: `committed` (h_n, read by the kernels) and `trial`
  // (h_{n+1}, written by every assemble() at the state it assembles). A deck without such
  // a law allocates nothing and these are no-ops.
  bool has_history() const { return !history_.empty(); }
  // The step is accepted: trial -> committed. Call after the Newton solve converged (its
  // last assemble() was at the accepted state).
  void commit_history();
  // The step is cut back: the trial copy is reset to the committed state (which no
  // assemble() ever writes).
  void rollback_history();
  // Per local block b (Distribution::blocks() order): rows cell * ngp + g, the kNumHist
  // columns of the block's law; empty views for blocks without history.
  using HistoryView = Kokkos::View<double**, Kokkos::LayoutRight, la::ExecSpace>;
  HistoryView committed_history(std::size_t b) const;
  HistoryView trial_history(std::size_t b) const;

  // Sets the prescribed values at time t on the owned Dirichlet dofs of u.
  void apply_dirichlet(la::Vector& u, double t, double end_time) const;

  // Reaction force per Dirichlet set from the last assemble(): the residual summed over the
  // dofs the set constrains (its nodes' listed components only; the other components are
  // 0). A dof constrained by several sets counts once, for the first of them in deck order
  // (the prescribed value is the last one's), so the sets' reactions add up to the total.
  const std::vector<std::array<double, 3>>& reactions() const { return reactions_; }
  const std::vector<DirichletSet>& dirichlet_sets() const { return loads_.dirichlet; }

  // Per local cell: Cauchy stress (xx, yy, zz, xy, yz, xz) averaged over Gauss points,
  // von Mises of that average, mean J. Order: Distribution::blocks() order.
  // With Gauss-point history (has_history()): per cell the average over its Gauss points
  // of each history variable marked for output (the laws' kHistory), named in extra_names
  // (the output names of the deck's laws with history, in block order, a name shared by
  // two laws once; 0 in blocks whose law lacks it); `extra` holds extra_names.size()
  // values per cell. The stress of a block with history is that of the committed state
  // (the law's frozen_potential at the committed row).
  // `volume`: reference volume of each cell (the Gauss weights' sum; 2D: per unit thickness;
  // axisymmetric: the ring the cell sweeps, 2 pi int R dA). Axisymmetric stress and strains are
  // in (r, z, theta): the third diagonal entry (zz of the output) is the hoop component.
  // On request (a deck pays only for what it asks): per Gauss point, averaged as the stress,
  //   green_lagrange: E = (C - I)/2, 6 per cell in the stress order (xx, yy, zz, xy, yz, xz);
  //   log_strain: the spatial Hencky strain ln V = ln(b)/2, b = F F^T (material/SymEigen.hpp), 6 per cell;
  //   principal: the eigenvalues of the cell's (averaged) Cauchy stress, largest first, 3 per cell.
  // Points with det F <= 0 are left out of the averages of stress and strains (as before).
  struct CellFieldRequest {
    bool green_lagrange = false, log_strain = false, principal = false;
  };
  struct CellFields {
    std::vector<GId> cell_ids;
    std::vector<double> stress, von_mises, J, volume;
    std::vector<std::string> extra_names;
    std::vector<double> extra;
    std::vector<double> green_lagrange, log_strain, principal;  // empty unless requested
  };
  CellFields cell_fields(const la::Vector& u, const CellFieldRequest& req);
  CellFields cell_fields(const la::Vector& u) { return cell_fields(u, CellFieldRequest()); }

  // The reactions node by node, from the last assemble(): per owned constrained dof its
  // global node id, component and the residual there (the values reactions() sums).
  struct DofReactions {
    std::vector<GId> nodes;
    std::vector<int> components;
    std::vector<double> values;
  };
  DofReactions dof_reactions() const;

 private:
  void build_graph();
  void setup_loads(const Mesh& mesh);
  // FluidCavity.cpp: the volume of cavity k at u_overlap_ (or at u = 0), summed over the
  // ranks; the pressures at the start of assemble(); the rank-one terms at its end.
  double cavity_volume(std::size_t k, bool reference) const;
  void update_cavities(const StepInput& in);
  void update_cavity_gradients();
  // project_plane_rows' projection of rows on a vector, without its reactions.
  void project_plane_vector(la::Vector& v) const;
  void color_cells();

  const Distribution& dist_;
  const Loads& loads_;
  int dim_;
  Kinematics kin_;                          // Problem->kinematics (axisymmetric: 2 pi R weights, hoop strain)
  std::vector<Material> block_law_;         // per mesh volume block (material/MaterialRegistry.hpp)
  std::vector<double> block_density_, block_eta_;
  std::vector<ElementTechnology> block_tech_;  // per mesh volume block: its body's element technology
  std::vector<int> quad_degree_;            // per mesh volume block: mass, body force, output
                                            // (the stiffness uses stiffness_quadrature_degree)

  // Problem->assembly = coloring: per local block (Distribution::blocks() order), its
  // cells permuted so that colour k is cells(offsets[k] .. offsets[k+1]-1). Empty: atomics.
  static constexpr int kMaxColors = 256;
  struct BlockColors {
    std::vector<std::size_t> offsets;
    Kokkos::View<int*, la::ExecSpace> cells;
  };
  std::vector<BlockColors> colors_;

  // Gauss-point history per local block (empty when no block has a law with history).
  struct BlockHistory {
    int ngp = 0;                 // Gauss points per cell (stiffness rule)
    HistoryView committed, trial;  // empty for blocks without history
  };
  std::vector<BlockHistory> history_;
  void init_history();

  la::RCP<const la::Export> exporter_;       // overlap -> owned
  la::RCP<la::CrsMatrix> K_overlap_, K_;
  // overlap -> owned matrix: positions in K_'s values of the overlap's owned-row entries;
  // the ghost rows as a matrix of their own, exported (ADD) into K_.
  Kokkos::View<std::size_t*, la::ExecSpace> owned_value_pos_;
  la::RCP<const la::Map> ghost_map_;
  la::RCP<la::CrsMatrix> K_ghost_;
  la::RCP<const la::Export> ghost_exporter_;
  la::RCP<la::Vector> u_overlap_, u0_overlap_, r_overlap_, rext_overlap_;
  la::RCP<la::Vector> r_static_, f_ext_, work_;  // owned
  la::RCP<la::CrsMatrix> M_;
  std::vector<char> owned_dirichlet_flag_, owned_cartesian_flag_;
  std::vector<double> dirichlet_r_;  // full residual at owned constrained dofs, last assemble()
  Kokkos::View<int*, la::ExecSpace> dirichlet_flag_;   // per overlap dof
  Kokkos::View<int*, la::ExecSpace> failures_;
  Kokkos::View<int*, la::ExecSpace> bad_cell_;  // per block: smallest local index of a failed cell
  std::vector<std::string> block_names_;        // per mesh volume block: its physical name
  // The failed cell of smallest global id over the ranks (Stats::first_failed); collective.
  std::string describe_failed(GId gid, std::size_t block, int cell) const;

  // assemble()'s parts (Assembler.cpp): the solid cells, the follower pressures, the owned
  // residual's constrained rows and reactions, the owned tangent.
  using DeviceMatrix = la::CrsMatrix::local_matrix_device_type;
  struct CellSums {
    double energy = 0.0, dissipation = 0.0, plastic = 0.0;
    GId bad_gid = std::numeric_limits<GId>::max();  // the failed cell of smallest global id
    std::size_t bad_block = 0;
    int bad_local = -1;
  };
  CellSums assemble_cells(const StepInput& in, bool has_old, bool with_tangent, const DeviceMatrix& Kl);
  void assemble_pressures(const StepInput& in, bool has_old, bool with_tangent, const DeviceMatrix& Kl);
  void constrain_residual(la::Vector& r);
  void finish_tangent(const StepInput& in, const DeviceMatrix& Kl);
  std::vector<la::LO> owned_dirichlet_dofs_;
  std::vector<double> owned_dirichlet_value_;           // full value (times ramp of its set)
  std::vector<int> owned_dirichlet_set_;                // the set whose value is prescribed (the last)
  std::vector<int> owned_reaction_set_;                 // the set its reaction counts for (the first)

  // Owned nodes on `normal` Dirichlet sets (PlaneConstraints.cpp). The residual and tangent
  // rows of such a node are projected after assembly; apply_dirichlet keeps u on its planes.
  // PlaneDirections' m, e, j, set, n: the node's constraint directions and planes.
  struct PlaneNode : PlaneDirections {
    la::LO lid = 0;                 // owned node
    la::LO self[3] = {-1, -1, -1};  // K_'s local columns of the node's own dofs
  };
  std::vector<PlaneNode> planes_;
  Kokkos::View<PlaneNode*, la::ExecSpace> planes_dev_;
  std::vector<std::array<double, 3>> plane_r_;  // e_i . r per plane node at the last assemble()
  void setup_planes();
  // Reactions along e into loc (3 per set), the projection of r; the tangent's rows.
  void project_plane_rows(la::Vector& r, std::vector<double>& loc);
  void project_plane_matrix();
  static void project_plane_rows_of(const Kokkos::View<PlaneNode*, la::ExecSpace>& planes, int dim,
                                    const la::CrsMatrix::local_matrix_device_type& Kl);

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
    int cavity;  // FluidCavity: index into cavities_ (whose p replaces pressure x ramp); else -1
    CellType type;
    int nn;
    Kokkos::View<int**, Kokkos::LayoutRight, la::ExecSpace> conn;
    Kokkos::View<double*, la::ExecSpace> orientation;
  };
  std::vector<PressureLoad> pressures_;
  std::vector<Cavity> cavities_;
  std::vector<std::array<double, 3>> reactions_;
};

}  // namespace stentor
