// What a run computes with, built once from the deck: the mesh and what the deck names
// in it (materials per block, loads, probe nodes), then the parallel layout, the
// assembler, the linear solver, contact and the time scheme. Not movable: the assembler
// and contact keep references to the mesh and the loads.
#pragma once
#include <memory>
#include <vector>

#include "assembly/Assembler.hpp"
#include "bc/Loads.hpp"
#include "contact/Contact.hpp"
#include "deck/Config.hpp"
#include "mesh/Mesh.hpp"
#include "parallel/Distribution.hpp"
#include "run/Simulation.hpp"
#include "run/Supports.hpp"
#include "run/Timers.hpp"
#include "run/TimeIntegrator.hpp"
#include "solver/LinearSolver.hpp"

namespace stentor {

struct Model {
  // Reads the mesh (rank 0; on several ranks each then gets its part, mesh/MeshPart.hpp)
  // and resolves the deck's names against it.
  // Throws InputError naming the parameter.
  Model(const Config& cfg, const RunOptions& opts, Timers& timers);
  Model(const Model&) = delete;
  Model& operator=(const Model&) = delete;

  // Partition, assembler, linear solver (with the node coordinates multigrid needs),
  // contact pairs, time integrator. Collective.
  void discretise(Timers& timers);

  // Collective, after discretise(), before the first step: throws InputError naming the
  // material when the stiffness of the undeformed model (with a dynamic stage also its mass
  // over dt^2, dt = the smallest step of a dynamic stage) is not finite in double precision -- constants such as
  // C1 = 1e308, whose overflow would otherwise reach the linear solver first.
  void check_numeric_range(double dt);

  // The stage about to run (0 without stages): its analysis in `dynamic` and the formulation
  // of `auto` contact pairs. The time integrator changes scheme in its begin_stage() (which
  // needs the scheme before) or, on a restart, set_scheme().
  void set_stage(int stage);

  const Config& cfg;
  la::RCP<const la::Comm> comm;
  int rank = 0, nranks = 1;
  Mesh mesh;
  int dim = 0;
  bool dynamic = false;            // the analysis of the current stage (set_stage)
  double stabilization = 0.0;      // the current stage's static stabilisation factor (set_stage)
  bool any_dynamic = false;        // some stage is dynamic: mass, integrator, energy output
  std::vector<int> block_mat;     // material of each volume block
  Loads loads;
  std::vector<std::string> warnings;  // found reading the model (unsupported static bodies), printed with it
  std::vector<GId> probe_node;    // nearest mesh node of each Output->Probes entry
  // Several ranks: the largest share of the cells and of the nodes a rank's part of the
  // mesh holds, its largest size [MB], and the whole mesh's [MB].
  double largest_part[4] = {1.0, 1.0, 0.0, 0.0};
  ConnectedBodies bodies;         // bodies connected by shared nodes or master-surface contact, and their supports

  std::unique_ptr<Distribution> dist;
  std::unique_ptr<Assembler> assembler;
  std::unique_ptr<LinearSolver> linear;
  std::unique_ptr<Contact> contact;            // null without a Contact sublist
  std::unique_ptr<TimeIntegrator> integrator;  // null without a dynamic stage
};

// The current positions x = X + u of the global nodes `nodes` (3 values per node; 0 beyond
// the model's dimension for the displacement), each node's u from its owner, summed over
// the ranks: every rank gets the same array. Collective.
std::vector<double> current_positions(const Model& m, const std::vector<GId>& nodes, const la::Vector& u);

}  // namespace stentor
