#include "run/Model.hpp"

#include <algorithm>
#include <iterator>
#include <climits>
#include <cmath>
#include <sstream>
#include <string>

#include "bc/Axisymmetry.hpp"
#include "geometry/Generators.hpp"
#include "mesh/GmshReader.hpp"
#include "mesh/MeshComm.hpp"
#include "mesh/MeshPart.hpp"
#include "mesh/MeshQuery.hpp"
#include "run/ArteryMetrics.hpp"
#include "run/RingMetrics.hpp"
#include "run/Supports.hpp"
#include "solver/SolverParams.hpp"

namespace stentor {

namespace {

// The mesh node nearest to each probe point (the smallest id among equally near ones),
// over the nodes stored on each rank. Collective.
std::vector<GId> nearest_nodes(const Mesh& mesh, const std::vector<ProbeConfig>& probes, MPI_Comm comm) {
  std::vector<GId> nodes;
  for (const auto& p : probes) {
    double bd = 1e300;
    long long best = LLONG_MAX, first = LLONG_MAX;  // the first stored node (smallest id) at bd
    for (std::size_t i = 0; i < mesh.num_stored_nodes(); ++i) {
      double d = 0.0;
      for (int k = 0; k < 3; ++k) d += std::pow(mesh.x[3 * i + static_cast<std::size_t>(k)] - p.point[static_cast<std::size_t>(k)], 2);
      if (d < bd) bd = d, best = mesh.stored_node(i);
    }
    double all = bd;
    MPI_Allreduce(&bd, &all, 1, MPI_DOUBLE, MPI_MIN, comm);
    if (bd != all) best = LLONG_MAX;  // another rank has a nearer node
    MPI_Allreduce(&best, &first, 1, MPI_LONG_LONG, MPI_MIN, comm);
    nodes.push_back(static_cast<GId>(first));
  }
  return nodes;
}

// Every contact pair's slave and master name a boundary group of the mesh (so that
// `--check` finds a misspelled group as the run would).
// A fluid cavity's wall shares no node with a contact slave surface: the slave rows that
// contact rewrites would need the cavity's rank-one term rewritten too (Newton.hpp).
void check_contact_groups(const Config& cfg, const Mesh& mesh) {
  for (const auto& c : cfg.contact) {
    require_group(mesh, c.slave, true, "Contact->" + c.name + "->slave");
    if (!c.master.empty()) require_group(mesh, c.master, true, "Contact->" + c.name + "->master");
    for (const auto& l : cfg.loads) {
      if (l.type != LoadConfig::Type::FluidCavity) continue;
      const std::vector<GId> wall = boundary_nodes(mesh, l.group), slaves = boundary_nodes(mesh, c.slave);
      std::vector<GId> both;
      std::set_intersection(wall.begin(), wall.end(), slaves.begin(), slaves.end(), std::back_inserter(both));
      if (!both.empty())
        throw InputError(cfg.deck_path + ": 'Boundary Conditions->" + l.name + "': node " + std::to_string(both.front()) + " of the cavity's wall '" +
                         l.group + "' is a slave node of 'Contact->" + c.name + "' (group '" + c.slave +
                         "'); a fluid cavity's wall may not be a contact slave surface (make the other side the slave, or "
                         "use a `pressure` load)");
    }
  }
}

// The elastic constants of a material as its law uses them (for messages), and the
// largest of them in magnitude (inf/nan first).
std::string elastic_constants_text(const MaterialConfig& m) {
  std::ostringstream os;
  os.precision(3);
  if (m.ciarlet_geymonat() || m.model == "Mooney-Rivlin") {
    os << "C1 = " << m.C1 << ", C2 = " << m.C2;
    if (m.ciarlet_geymonat()) os << ", D = " << m.D;
    os << "; small-strain ";
  }
  os << "mu = " << m.mu << ", lambda = " << m.lambda;
  if (m.model == "Holzapfel-Gasser-Ogden") os << ", k1 = " << m.k1;
  return os.str();
}
double largest_modulus(const MaterialConfig& m) {
  double big = 0.0;
  for (double v : {m.C1, m.C2, m.D, m.mu, m.lambda, m.k1}) big = std::isfinite(v) ? std::max(big, std::abs(v)) : HUGE_VAL;
  return big;
}

}  // namespace

Model::Model(const Config& c, const RunOptions& opts, Timers& timers) : cfg(c), comm(Tpetra::getDefaultComm()) {
  rank = comm->getRank();
  nranks = comm->getSize();
  {
    Timers::Scope s{timers, "mesh"};
    // One rank reads (and meshes) the whole mesh; on several ranks it then sends each its
    // part (cells, their neighbours, the boundary groups: mesh/MeshPart.hpp).
    check_axisymmetric_deck(cfg);
    set_mesh_generator(&generate_mesh);
    if (nranks == 1) {
      mesh = read_mesh_on_root(cfg.mesh, MPI_COMM_WORLD, true, opts.verbose);
      prepare_axisymmetric_mesh(cfg, mesh);
    } else {
      mesh = read_mesh_on_root_only(cfg.mesh, MPI_COMM_WORLD, true, opts.verbose);
      on_root([&] { prepare_axisymmetric_mesh(cfg, mesh); }, MPI_COMM_WORLD);
      double whole_mb = static_cast<double>(mesh.bytes()) / 1e6;
      MPI_Bcast(&whole_mb, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
      // Boundary groups read whole on every rank: contact surfaces, the stent metrics' groups.
      std::vector<std::string> whole_groups;
      for (const auto& c : cfg.contact) whole_groups.insert(whole_groups.end(), {c.slave, c.master});
      for (const auto& l : cfg.loads)  // a plane's normal is computed from the whole group, the same on every rank
        if (l.normal || l.type == LoadConfig::Type::FluidCavity) whole_groups.push_back(l.group);  // a cavity: checked against the slaves
      if (cfg.output.metrics.enabled && cfg.mesh.generator == "stent") {
        const auto g = RingMetrics::whole_groups(cfg);
        whole_groups.insert(whole_groups.end(), g.begin(), g.end());
        if (ArteryMetrics::applies(cfg)) {
          const auto a = ArteryMetrics::whole_groups();
          whole_groups.insert(whole_groups.end(), a.begin(), a.end());
        }
      } else if (cfg.output.metrics.enabled) {
        whole_groups.insert(whole_groups.end(), {cfg.output.metrics.stent, cfg.output.metrics.lumen});
      }
      distribute_mesh(mesh, MPI_COMM_WORLD, whole_groups);
      // The largest part's share of the whole mesh (own cells, ghost layer and boundaries).
      std::size_t cells = 0;
      for (const auto& b : mesh.volumes) cells += b.num_cells();
      double share[3] = {static_cast<double>(cells) / static_cast<double>(mesh.num_volume_cells()),
                         static_cast<double>(mesh.num_stored_nodes()) / static_cast<double>(mesh.num_nodes()),
                         static_cast<double>(mesh.bytes()) / 1e6};
      MPI_Allreduce(share, largest_part, 3, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
      largest_part[3] = whole_mb;
    }
  }
  check_vector_dimensions(cfg, mesh.dim);
  block_mat = block_materials(cfg, mesh);
  loads = resolve_loads(cfg, mesh);
  dim = mesh.dim;
  dynamic = cfg.dynamic_in(0);
  stabilization = cfg.stabilization_in(0);
  any_dynamic = cfg.any_dynamic();
  probe_node = nearest_nodes(mesh, cfg.output.probes, MPI_COMM_WORLD);
  check_contact_groups(cfg, mesh);
  warnings = unsupported_bodies(cfg, mesh, loads, MPI_COMM_WORLD);
  if (cfg.any_static()) bodies = connected_bodies(cfg, mesh, loads, MPI_COMM_WORLD);
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
  if (any_dynamic) integrator = std::make_unique<TimeIntegrator>(cfg, *assembler, *dist, mesh);
}

void Model::set_stage(int stage) {
  dynamic = cfg.dynamic_in(stage);
  stabilization = cfg.stabilization_in(stage);
  if (contact) contact->set_analysis(dynamic);
}

// Three Frobenius norms, each of which overflows at entries of about 1e154 (where the
// residual and solver norms overflow too): the stiffness at u = 0, t = 0 (the tangent the
// first step starts from, loads aside); in dynamics the mass times 4/dt^2 (Newmark's
// coefficient, the largest of the schemes'), and with viscosity the whole step tangent.
void Model::check_numeric_range(double dt) {
  la::Vector u0(dist->owned_map()), r(dist->owned_map());
  assembler->assemble(u0, 0.0, cfg.stepping.end_time, r, true);
  const double k = assembler->matrix()->getFrobeniusNorm();
  const double m = any_dynamic ? assembler->mass()->getFrobeniusNorm() * 4.0 / (dt * dt) : 0.0;
  double v = 0.0;
  if (any_dynamic && std::isfinite(k) && std::isfinite(m)) {
    Assembler::StepInput in;
    in.end_time = cfg.stepping.end_time;
    in.u_old = in.u_tilde = &u0;
    in.dt = dt;
    in.mass_coeff = 4.0 / (dt * dt);
    assembler->assemble(u0, in, r, true);
    v = assembler->matrix()->getFrobeniusNorm();
  }
  if (std::isfinite(k) && std::isfinite(m) && std::isfinite(v)) return;
  enum class What { Stiffness, Mass, Viscosity } what = !std::isfinite(k) ? What::Stiffness : !std::isfinite(m) ? What::Mass : What::Viscosity;
  auto key = [what](const MaterialConfig& mc) {
    const double x = what == What::Stiffness ? largest_modulus(mc) : what == What::Mass ? mc.density : mc.viscosity;
    return std::isfinite(x) ? std::abs(x) : HUGE_VAL;
  };
  const MaterialConfig* worst = nullptr;  // the culprit named: the largest of the materials used
  for (int b : block_mat) {
    const MaterialConfig& mc = cfg.materials[static_cast<std::size_t>(b)];
    if (!worst || key(mc) > key(*worst)) worst = &mc;
  }
  const double norm = what == What::Stiffness ? k : what == What::Mass ? m : v;
  std::ostringstream os;
  os.precision(3);
  os << cfg.deck_path << ": the " << (what == What::Stiffness ? "stiffness of the undeformed model" : what == What::Mass ? "mass over the step squared (4 M / dt^2)" : "tangent of the first step")
     << " overflows double precision (Frobenius norm " << (std::isnan(norm) ? "nan" : "inf") << (what == What::Stiffness ? "" : ", dt = ");
  if (what != What::Stiffness) os << dt;
  os << "): 'Materials->" << worst->name;
  if (what == What::Stiffness)
    os << "' (" << elastic_constants_text(*worst) << ") is the stiffest material; expected smaller elastic constants";
  else if (what == What::Mass)
    os << "->density' = " << worst->density << " is the largest; expected a smaller density or a larger step";
  else
    os << "->viscosity' = " << worst->viscosity << " is the largest; expected a smaller viscosity or a larger step";
  os << ", so that the matrix entries stay below about 1e150 (a deck in smaller units, e.g. mm-N-s with moduli in MPa, helps)";
  throw InputError(os.str());
}

std::vector<double> current_positions(const Model& m, const std::vector<GId>& nodes, const la::Vector& u) {
  const Distribution& d = *m.dist;
  std::vector<double> loc(3 * nodes.size(), 0.0), x(loc.size(), 0.0);
  {
    auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (d.owns_node(nodes[i]))
        for (int k = 0; k < m.dim; ++k) loc[3 * i + static_cast<std::size_t>(k)] = uh(static_cast<std::size_t>(d.local_node(nodes[i]) * m.dim + k), 0);
  }
  if (!loc.empty()) Teuchos::reduceAll(*m.comm, Teuchos::REDUCE_SUM, static_cast<int>(loc.size()), loc.data(), x.data());
  for (std::size_t i = 0; i < nodes.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k) x[3 * i + k] += m.mesh.coord(nodes[i])[k];
  return x;
}

}  // namespace stentor
