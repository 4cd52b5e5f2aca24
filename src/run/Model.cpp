#include "run/Model.hpp"

#include <cmath>

#include "mesh/MeshComm.hpp"
#include "mesh/MeshQuery.hpp"
#include "run/Supports.hpp"
#include "solver/SolverParams.hpp"

namespace stentor {

namespace {

std::vector<GId> nearest_nodes(const Mesh& mesh, const std::vector<ProbeConfig>& probes) {
  std::vector<GId> nodes;
  for (const auto& p : probes) {
    GId best = 0;
    double bd = 1e300;
    for (std::size_t n = 0; n < mesh.num_nodes(); ++n) {
      double d = 0.0;
      for (int k = 0; k < 3; ++k) d += std::pow(mesh.x[3 * n + k] - p.point[static_cast<std::size_t>(k)], 2);
      if (d < bd) {
        bd = d;
        best = static_cast<GId>(n);
      }
    }
    nodes.push_back(best);
  }
  return nodes;
}

// Every contact pair's slave and master name a boundary group of the mesh (so that
// `--check` finds a misspelled group as the run would).
void check_contact_groups(const Config& cfg, const Mesh& mesh) {
  for (const auto& c : cfg.contact) {
    require_group(mesh, c.slave, true, "Contact->" + c.name + "->slave");
    if (!c.master.empty()) require_group(mesh, c.master, true, "Contact->" + c.name + "->master");
  }
}

}  // namespace

Model::Model(const Config& c, const RunOptions& opts, Timers& timers) : cfg(c), comm(Tpetra::getDefaultComm()) {
  rank = comm->getRank();
  nranks = comm->getSize();
  {
    Timers::Scope s{timers, "mesh"};
    mesh = read_mesh_on_root(cfg.mesh, MPI_COMM_WORLD, true, opts.verbose);
  }
  check_vector_dimensions(cfg, mesh.dim);
  block_mat = block_materials(cfg, mesh);
  loads = resolve_loads(cfg, mesh);
  dim = mesh.dim;
  dynamic = cfg.problem.dynamic();
  probe_node = nearest_nodes(mesh, cfg.output.probes);
  check_contact_groups(cfg, mesh);
  warnings = unsupported_bodies(cfg, mesh, loads);
  validate_linear_solver(cfg.linear);  // the pass-through lists, before anything runs (and under --check)
}

void Model::discretise(Timers& timers) {
  {
    Timers::Scope s{timers, "setup"};
    dist = std::make_unique<Distribution>(mesh, comm);
    assembler = std::make_unique<Assembler>(mesh, *dist, cfg, loads, block_mat);
  }
  linear = std::make_unique<LinearSolver>(cfg.linear, comm);
  linear->set_node_coordinates(dim, dist->owned_coordinates());
  contact = Contact::create(cfg, mesh, *dist, *assembler);
  if (dynamic) integrator = std::make_unique<TimeIntegrator>(cfg, *assembler, *dist, mesh);
}

}  // namespace stentor
