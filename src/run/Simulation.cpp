#include "run/Simulation.hpp"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "assembly/Assembler.hpp"
#include "bc/Loads.hpp"
#include "io/Csv.hpp"
#include "io/OutputDir.hpp"
#include "io/Plot.hpp"
#include "io/XdmfWriter.hpp"
#include "mesh/MeshComm.hpp"
#include "parallel/Distribution.hpp"
#include "solver/LinearSolver.hpp"
#include "solver/Newton.hpp"
#include "contact/Contact.hpp"
#include "run/TimeIntegrator.hpp"

namespace stentor {
namespace {

// Wall-clock timers, printed in the end-of-run summary.
class Timers {
 public:
  struct Scope {
    Timers& t;
    std::string name;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    ~Scope() { t.add(name, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()); }
  };
  void add(const std::string& n, double s) {
    if (!acc_.count(n)) order_.push_back(n);
    acc_[n] += s;
  }
  double get(const std::string& n) const {
    auto it = acc_.find(n);
    return it == acc_.end() ? 0.0 : it->second;
  }
  const std::vector<std::string>& names() const { return order_; }

 private:
  std::map<std::string, double> acc_;
  std::vector<std::string> order_;
};

// Records (a global id and k values each) of every rank, gathered on rank 0 (empty
// elsewhere); `from` is the rank each record came from.
struct Gathered {
  std::vector<long long> ids;
  std::vector<double> values;
  std::vector<int> from;
};
Gathered gather_on_root(const std::vector<long long>& ids, const std::vector<double>& values, int k, int nranks) {
  const int n = static_cast<int>(ids.size());
  std::vector<int> counts(static_cast<std::size_t>(nranks)), displs(static_cast<std::size_t>(nranks));
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  int total = 0;
  for (int r = 0; r < nranks; ++r) {
    displs[static_cast<std::size_t>(r)] = total;
    total += counts[static_cast<std::size_t>(r)];
  }
  Gathered g;
  g.ids.resize(static_cast<std::size_t>(total));
  g.values.resize(static_cast<std::size_t>(total) * static_cast<std::size_t>(k));
  MPI_Gatherv(ids.data(), n, MPI_LONG_LONG, g.ids.data(), counts.data(), displs.data(), MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  std::vector<int> counts_k(counts), displs_k(displs);
  for (auto& c : counts_k) c *= k;
  for (auto& d : displs_k) d *= k;
  MPI_Gatherv(values.data(), k * n, MPI_DOUBLE, g.values.data(), counts_k.data(), displs_k.data(), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  for (int r = 0; r < nranks; ++r) g.from.insert(g.from.end(), static_cast<std::size_t>(counts[static_cast<std::size_t>(r)]), r);
  return g;
}

// The residual of one step (static equilibrium, or a time scheme's), for Newton.
class StepSystem : public NewtonSystem {
 public:
  StepSystem(Assembler& a, Timers& timers) : a_(a), timers_(timers) {}
  Assembler::StepInput input;
  Assembler::Stats last;
  Contact* contact = nullptr;         // null without a "Contact" sublist
  std::ostream* contact_log = nullptr;  // --verbose: active/stick/slip sets per evaluation
  bool evaluate(const la::Vector& u, la::Vector& r, bool tangent) override {
    Timers::Scope s{timers_, "assembly"};
    last = a_.assemble(u, input, r, tangent);
    if (contact) {
      Timers::Scope sc{timers_, "contact"};
      auto K = contact->apply(u, r, tangent ? a_.matrix() : la::RCP<la::CrsMatrix>());
      if (tangent) K_ = K;
      if (contact_log) {
        const std::string line = contact->iteration_summary();
        *contact_log << line << "\n";
      }
    }
    return last.inverted == 0;
  }
  // The assembler's tangent, or with contact on master surfaces the coupled one.
  la::RCP<la::CrsMatrix> matrix() override { return K_.is_null() ? a_.matrix() : K_; }
  // Newton may stop only once the contact active set did not change in the last evaluation.
  bool settled() const override { return contact == nullptr || !contact->active_set_changed(); }
  // |f_ext| and |f_int - f_ext| over all rows (reactions included): the forces in play.
  // After unloading (a deflated balloon, a body at rest) both are round-off, and so would
  // be the target: the mean force scale of the accepted steps so far is kept as a floor
  // (Abaqus' time-averaged force plays the same role).
  double force_scale() const override {
    return std::max({a_.external_force().norm2(), a_.static_residual().norm2(), accepted_ ? scale_sum_ / accepted_ : 0.0});
  }
  // After an accepted step: its force scale joins the mean.
  void record_scale() {
    const double s = std::max(a_.external_force().norm2(), a_.static_residual().norm2());
    if (!(s > 0.0) || !std::isfinite(s)) return;
    scale_sum_ += s;
    ++accepted_;
  }

 private:
  Assembler& a_;
  Timers& timers_;
  la::RCP<la::CrsMatrix> K_;
  double scale_sum_ = 0.0;
  long accepted_ = 0;
};

const char* kAxes[3] = {"x", "y", "z"};

// Contact fields on all nodes: status -1 marks nodes that are no slave node (then the
// other fields are 0); 0 free, 1 inactive, 2 stick, 3 slip.
// Master surfaces: contact_master_traction = the reaction force on each master node
// (summed over ranks) divided by its tributary area (zero on other nodes).
void write_contact_fields(XdmfWriter& xdmf, std::size_t nn, const Gathered& slaves, const Gathered* masters) {
  constexpr int kv = Contact::kNodalValues;
  std::vector<double> status(nn, -1.0), gap(nn, 0.0), lambda_n(nn, 0.0), pressure(nn, 0.0), lambda_t(3 * nn, 0.0), slip(3 * nn, 0.0);
  for (std::size_t i = 0; i < slaves.ids.size(); ++i) {
    const auto g = static_cast<std::size_t>(slaves.ids[i]);
    const double* v = &slaves.values[kv * i];
    status[g] = v[0];
    gap[g] = v[1];
    lambda_n[g] = v[2];
    pressure[g] = v[3];
    for (int k = 0; k < 3; ++k) {
      lambda_t[3 * g + k] = v[4 + k];
      slip[3 * g + k] = v[7 + k];
    }
  }
  xdmf.node_field("contact_status", 1, status);
  xdmf.node_field("contact_gap", 1, gap);
  xdmf.node_field("contact_lambda_normal", 1, lambda_n);
  xdmf.node_field("contact_pressure", 1, pressure);
  xdmf.node_field("contact_lambda_tangent", 3, lambda_t);
  xdmf.node_field("contact_slip", 3, slip);
  if (!masters) return;  // no master surface in the deck
  constexpr int km = Contact::kMasterValues;
  std::vector<double> traction(3 * nn, 0.0), area(nn, 0.0);
  for (std::size_t i = 0; i < masters->ids.size(); ++i) {
    const auto g = static_cast<std::size_t>(masters->ids[i]);
    for (int k = 0; k < 3; ++k) traction[3 * g + k] += masters->values[km * i + k];
    area[g] = masters->values[km * i + 3];
  }
  for (std::size_t g = 0; g < nn; ++g)
    for (int k = 0; k < 3; ++k) traction[3 * g + k] = area[g] > 0.0 ? traction[3 * g + k] / area[g] : 0.0;
  xdmf.node_field("contact_master_traction", 3, traction);
}

std::string fmt(double v, int prec = 4) {
  std::ostringstream os;
  os << std::scientific << std::setprecision(prec) << v;
  return os.str();
}

}  // namespace

int run_simulation(const Config& cfg, const RunOptions& opts, RunResult* result) {
  auto comm = Tpetra::getDefaultComm();
  const int rank = comm->getRank();
  const int nranks = comm->getSize();
  std::ostringstream null_stream;
  std::ostream& out = (rank == 0) ? std::cout : null_stream;
  Timers timers;
  const auto t_start = std::chrono::steady_clock::now();

  // ---- Mesh, bodies, loads: everything the deck names must exist in the mesh.
  Mesh mesh;
  {
    Timers::Scope s{timers, "mesh"};
    mesh = read_mesh_on_root(cfg.mesh, MPI_COMM_WORLD, true, opts.verbose);
  }
  const std::vector<int> block_mat = block_materials(cfg, mesh);
  const Loads loads = resolve_loads(cfg, mesh);
  const int dim = mesh.dim;
  std::vector<GId> probe_node;
  for (const auto& p : cfg.output.probes) {
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
    probe_node.push_back(best);
  }

  out << "Stentor: " << (cfg.problem.title.empty() ? cfg.deck_path : cfg.problem.title) << "\n"
      << "  deck     " << cfg.deck_path << "\n"
      << "  mesh     " << mesh.source << ": " << dim << "D, " << mesh.num_nodes() << " nodes, " << mesh.num_volume_cells()
      << " cells (";
  for (std::size_t b = 0; b < mesh.volumes.size(); ++b)
    out << (b ? ", " : "") << mesh.volumes[b].name << ": " << mesh.volumes[b].num_cells() << " " << cell_name(mesh.volumes[b].type);
  out << ")\n";
  out << "  parallel " << nranks << " MPI rank(s), Kokkos " << la::ExecSpace::name() << " x " << la::ExecSpace().concurrency()
      << " thread(s), " << cfg.problem.assembly << " assembly\n";
  if (opts.check_only) {
    out << "deck and mesh are valid: " << cfg.bodies.size() << " bodies, " << cfg.materials.size() << " materials, " << cfg.loads.size()
        << " boundary conditions\n";
    return 0;
  }

  // ---- Parallel layout, assembly, solver.
  std::unique_ptr<Distribution> dist;
  std::unique_ptr<Assembler> assembler;
  {
    Timers::Scope s{timers, "setup"};
    dist = std::make_unique<Distribution>(mesh, comm);
    assembler = std::make_unique<Assembler>(mesh, *dist, cfg, loads, block_mat);
  }
  LinearSolver linear(cfg.linear, comm);
  {
    std::vector<double> xyz(3 * static_cast<std::size_t>(dist->num_owned_nodes()));
    for (la::LO n = 0; n < dist->num_owned_nodes(); ++n)
      for (int k = 0; k < 3; ++k) xyz[3 * static_cast<std::size_t>(n) + k] = mesh.x[3 * static_cast<std::size_t>(dist->global_node(n)) + k];
    linear.set_node_coordinates(dim, xyz);
  }
  const bool dynamic = cfg.problem.dynamic();
  std::unique_ptr<Contact> contact = Contact::create(cfg, mesh, *dist, *assembler);
  std::unique_ptr<TimeIntegrator> integrator;
  if (dynamic) integrator = std::make_unique<TimeIntegrator>(cfg, *assembler, *dist, mesh);
  out << "  dofs     " << dist->owned_map()->getGlobalNumElements() << "\n"
      << "  analysis " << (dynamic ? "dynamic: " + integrator->description() : std::string("static (load stepping)")) << "\n"
      << "  solver   " << linear.description() << "\n";
  if (contact) {
    const std::string d = contact->description();  // collective
    out << "  contact  " << d << "\n";
  }

  // ---- Output: staged in <dir>.partial, moved into place only when the run succeeds.
  const std::string out_dir = opts.output_dir.empty() ? cfg.output.directory : opts.output_dir;
  std::unique_ptr<OutputDir> staging;
  std::unique_ptr<XdmfWriter> xdmf;
  std::unique_ptr<CsvWriter> history, energy_csv;
  const std::vector<std::string> energy_columns = {"step", "time", "kinetic", "strain", "total", "external_work", "support_work",
                                                   "dissipation", "balance_residual", "momentum_x", "momentum_y", "momentum_z",
                                                   "angular_momentum_x", "angular_momentum_y", "angular_momentum_z"};
  std::vector<std::string> energy_cols = energy_columns;
  if (contact) energy_cols.insert(energy_cols.end(), {"contact_work", "friction_dissipation"});
  if (assembler->has_history()) energy_cols.push_back("plastic_dissipation");  // cumulative; also in "dissipation"
  std::vector<std::string> columns = {"step", "time", "dt", "newton_iterations", "linear_iterations", "cutbacks", "strain_energy"};
  for (const auto& d : assembler->dirichlet_sets())
    for (int k = 0; k < dim; ++k) columns.push_back("reaction_" + d.name + "_" + kAxes[k]);
  for (const auto& p : cfg.output.probes)
    for (int k = 0; k < dim; ++k) columns.push_back("u_" + p.name + "_" + kAxes[k]);
  if (contact)
    for (const auto& c : contact->history_columns()) columns.push_back(c);
  if (assembler->has_history()) columns.push_back("plastic_dissipation");  // of the step
  int io_error = 0;
  std::string io_message;
  if (rank == 0) {
    try {
      staging = std::make_unique<OutputDir>(out_dir);
      if (cfg.output.fields) xdmf = std::make_unique<XdmfWriter>(staging->path(), cfg.output.basename, mesh);
      history = std::make_unique<CsvWriter>(staging->path() + "/" + cfg.output.basename + "_history.csv", columns);
      if (dynamic) energy_csv = std::make_unique<CsvWriter>(staging->path() + "/" + cfg.output.basename + "_energy.csv", energy_cols);
    } catch (const std::exception& e) {
      io_error = 1;
      io_message = e.what();
    }
  }
  Teuchos::broadcast(*comm, 0, &io_error);
  if (io_error) {
    if (rank == 0) throw InputError("cannot create output in '" + out_dir + "': " + io_message);
    throw InputError("cannot create output");
  }

  // Gather map: every used dof on rank 0, for output in mesh node order.
  std::vector<la::GO> all_dofs;
  if (rank == 0) {
    std::vector<char> used(mesh.num_nodes(), 0);
    for (const auto& b : mesh.volumes)
      for (GId n : b.conn) used[static_cast<std::size_t>(n)] = 1;
    for (std::size_t n = 0; n < mesh.num_nodes(); ++n)
      if (used[n])
        for (int k = 0; k < dim; ++k) all_dofs.push_back(static_cast<la::GO>(n) * dim + k);
  }
  auto gather_map = Teuchos::rcp(new la::Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                             Teuchos::ArrayView<const la::GO>(all_dofs), 0, comm));
  la::Import gather(dist->owned_map(), gather_map);
  la::Vector u_all(gather_map);

  la::Vector u(dist->owned_map()), u_prev(dist->owned_map()), u_before_last(dist->owned_map());
  double dt_last = 0.0;
  StepSystem system(*assembler, timers);
  system.input.end_time = cfg.stepping.end_time;
  // Cumulative energy terms (dynamics), written per step to <basename>_energy.csv.
  double cum_ext = 0.0, cum_sup = 0.0, cum_diss = 0.0, max_balance = 0.0;
  double cum_contact = 0.0, cum_friction = 0.0;  // contact work on the body, frictional dissipation
  double cum_plastic = 0.0;
  auto energy_row = [&](int step_no, double time, const EnergyAudit& au) {
    if (rank != 0 || !energy_csv) return;
    std::vector<double> row = {double(step_no), time, au.kinetic, au.strain, au.kinetic + au.strain, cum_ext, cum_sup, cum_diss, au.balance,
                               au.momentum[0], au.momentum[1], au.momentum[2], au.angular_momentum[0], au.angular_momentum[1],
                               au.angular_momentum[2]};
    if (contact) row.insert(row.end(), {cum_contact, cum_friction});
    if (assembler->has_history()) row.push_back(cum_plastic);
    energy_csv->row(row);
  };
  // Non-finite values never reach the CSV or HDF5 files: the name of the first
  // non-finite quantity, or "". Every input is global (reduced), so all ranks agree.
  auto nonfinite = [&](const EnergyAudit* au) -> std::string {
    if (!std::isfinite(u.norm1())) return "displacement";
    if (!std::isfinite(system.last.energy)) return "stored energy";
    for (const auto& rf : assembler->reactions())
      for (double v : rf)
        if (!std::isfinite(v)) return "reaction force";
    if (!au) return "";
    const double vals[] = {au->kinetic, au->strain, au->external_work, au->support_work, au->dissipation, au->balance,
                           au->momentum[0], au->momentum[1], au->momentum[2], au->angular_momentum[0],
                           au->angular_momentum[1], au->angular_momentum[2], cum_ext, cum_sup, cum_diss};
    for (double v : vals)
      if (!std::isfinite(v)) return "energy or momentum";
    return "";
  };
  if (dynamic) {
    const EnergyAudit au0 = integrator->initialize(u, cfg.stepping.end_time);
    const std::string bad = nonfinite(&au0);
    if (!bad.empty() && rank == 0) {  // an input error: nothing worth keeping was written
      xdmf.reset();
      history.reset();
      energy_csv.reset();
      std::error_code ec;
      std::filesystem::remove_all(staging->path(), ec);
    }
    if (!bad.empty())
      throw InputError(cfg.deck_path + ": 'Initial Conditions' give a non-finite initial " + bad +
                       " (kinetic energy " + fmt(au0.kinetic, 3) + "); use smaller initial values");
    energy_row(0, 0.0, au0);
  }
  if (contact) {
    contact->initialize(u, cfg.stepping.end_time);
    system.contact = contact.get();
    if (opts.verbose) system.contact_log = (rank == 0) ? static_cast<std::ostream*>(&std::cout) : &null_stream;
  }

  auto write_fields = [&](double t) {
    Timers::Scope s{timers, "output"};
    u_all.doImport(u, gather, Tpetra::INSERT);
    Assembler::CellFields cf = assembler->cell_fields(u);
    const std::size_t nx = cf.extra_names.size(), kv = 8 + nx;  // + history fields (plasticity)
    std::vector<double> packed;  // per local cell: stress (6), von Mises, J, extra
    for (std::size_t c = 0; c < cf.cell_ids.size(); ++c) {
      packed.insert(packed.end(), cf.stress.begin() + static_cast<std::ptrdiff_t>(6 * c),
                    cf.stress.begin() + static_cast<std::ptrdiff_t>(6 * c + 6));
      packed.push_back(cf.von_mises[c]);
      packed.push_back(cf.J[c]);
      packed.insert(packed.end(), cf.extra.begin() + static_cast<std::ptrdiff_t>(nx * c), cf.extra.begin() + static_cast<std::ptrdiff_t>(nx * c + nx));
    }
    const Gathered cells = gather_on_root(std::vector<long long>(cf.cell_ids.begin(), cf.cell_ids.end()), packed, static_cast<int>(kv), nranks);
    // Contact fields at slave nodes.
    Gathered slaves, masters;
    if (contact) {
      const Contact::NodalFields nf = contact->nodal_fields();
      slaves = gather_on_root(nf.nodes, nf.values, Contact::kNodalValues, nranks);
      const Contact::NodalFields mf = contact->master_fields();
      masters = gather_on_root(mf.nodes, mf.values, Contact::kMasterValues, nranks);
    }
    if (rank != 0 || !xdmf) return;
    const std::size_t nc = mesh.num_volume_cells(), nn = mesh.num_nodes();
    std::vector<double> disp(3 * nn, 0.0), stress(6 * nc), vm(nc), J(nc), owner(nc), extra(nx * nc);
    auto uh = u_all.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (std::size_t i = 0; i < all_dofs.size(); ++i)
      disp[3 * static_cast<std::size_t>(all_dofs[i] / dim) + static_cast<std::size_t>(all_dofs[i] % dim)] = uh(i, 0);
    for (std::size_t i = 0; i < cells.ids.size(); ++i) {
      const auto id = static_cast<std::size_t>(cells.ids[i]);
      for (int k = 0; k < 6; ++k) stress[6 * id + k] = cells.values[kv * i + k];
      vm[id] = cells.values[kv * i + 6];
      J[id] = cells.values[kv * i + 7];
      for (std::size_t k = 0; k < nx; ++k) extra[k * nc + id] = cells.values[kv * i + 8 + k];
      owner[id] = cells.from[i];
    }
    xdmf->begin_step(t);
    xdmf->node_field("displacement", 3, disp);
    xdmf->cell_field("cauchy_stress", 6, stress);
    xdmf->cell_field("von_mises", 1, vm);
    xdmf->cell_field("J", 1, J);
    xdmf->cell_field("mpi_rank", 1, owner);
    for (std::size_t k = 0; k < nx; ++k)
      xdmf->cell_field(cf.extra_names[k], 1, std::vector<double>(extra.begin() + k * nc, extra.begin() + (k + 1) * nc));
    if (contact) write_contact_fields(*xdmf, nn, slaves, contact->has_master_surfaces() ? &masters : nullptr);
    xdmf->end_step();
  };

  auto probe_values = [&]() {
    std::vector<double> loc(probe_node.size() * 3, 0.0), glob(loc.size(), 0.0);
    auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (std::size_t p = 0; p < probe_node.size(); ++p)
      if (dist->owns_node(probe_node[p]))
        for (int k = 0; k < dim; ++k) loc[3 * p + k] = uh(dist->local_node(probe_node[p]) * dim + k, 0);
    if (!loc.empty()) Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, static_cast<int>(loc.size()), loc.data(), glob.data());
    return glob;
  };

  // ---- Load stepping with cut-back: a failed Newton solve halves the step and retries
  // from the last converged state; after a success the step grows back (x2) towards
  // the deck's step size.
  const double T = cfg.stepping.end_time;
  const double dt0 = T / cfg.stepping.num_steps;
  double t = 0.0, dt = dt0;
  int step = 0, consecutive_cuts = 0, total_cuts = 0, total_newton = 0, total_linear = 0;
  bool failed = false;
  std::string failure;
  if (cfg.output.fields) write_fields(0.0);
  std::ostream* newton_log = (opts.verbose && rank == 0) ? &std::cout : nullptr;
  while (t < T * (1.0 - 1e-12)) {
    dt = std::min(dt, T - t);
    const double t_new = t + dt;
    u_prev.update(1.0, u, 0.0);
    if (dynamic) {
      system.input = integrator->step_input(t, dt, T, u_prev);
    } else {
      system.input = Assembler::StepInput{};
      system.input.load_time = t_new;
      system.input.end_time = T;
    }
    // Initial guess. Statics: extrapolate the last converged increment, so a prescribed
    // boundary motion is spread into the interior instead of squeezing the boundary
    // layer of cells (which can invert them); fall back to u_n if that guess is inadmissible.
    if (contact) contact->begin_step(t, dt, u_prev);
    NewtonResult nr;
    bool predicted = false;
    if (!dynamic && step > 0 && dt_last > 0.0) {
      u.update(dt / dt_last, u_prev, -dt / dt_last, u_before_last, 1.0);
      predicted = true;
    }
    assembler->apply_dirichlet(u, t_new, T);
    {
      Timers::Scope s{timers, "newton"};
      nr = newton_solve(system, u, linear, cfg.newton, newton_log);
    }
    if (predicted && !nr.converged && nr.iterations == 0) {
      u.update(1.0, u_prev, 0.0);
      assembler->apply_dirichlet(u, t_new, T);
      Timers::Scope s{timers, "newton"};
      nr = newton_solve(system, u, linear, cfg.newton, newton_log);
    }
    total_newton += nr.iterations;
    total_linear += nr.linear_iterations;
    if (!nr.converged) {
      u.update(1.0, u_prev, 0.0);
      assembler->rollback_history();  // Gauss-point state: back to the last accepted step
      if (consecutive_cuts >= cfg.stepping.max_cutbacks) {
        std::ostringstream os;
        os << "Newton failed at t = " << t_new << " (" << nr.failure << ") after " << consecutive_cuts
           << " step halvings (dt = " << dt << "); see Stepping->max cutbacks, Newton->max iterations";
        failure = os.str();
        failed = true;
        break;
      }
      ++consecutive_cuts;
      ++total_cuts;
      out << "  step " << step + 1 << " t=" << fmt(t_new, 3) << ": " << nr.failure << "; cutting dt to " << fmt(dt / 2, 3) << "\n";
      dt *= 0.5;
      continue;
    }
    t = t_new;
    ++step;
    system.record_scale();
    assembler->commit_history();  // Newton's last assemble() was at the accepted u
    u_before_last.update(1.0, u_prev, 0.0);
    dt_last = dt;
    const auto& reac = assembler->reactions();
    out << "  step " << std::setw(4) << step << "  t " << fmt(t, 4) << "  dt " << fmt(dt, 2) << "  newton " << std::setw(2)
        << nr.iterations << "  linear " << std::setw(4) << nr.linear_iterations << "  |r| " << fmt(nr.residual, 2) << "  W "
        << fmt(system.last.energy, 6);
    Contact::StepStats cstats;
    if (contact) {
      cstats = contact->accept(u);
      out << contact->progress(cstats);
    }
    if (dynamic) {
      EnergyAudit au = integrator->accept(u_prev, u, dt, system.last);
      cum_ext += au.external_work;
      cum_sup += au.support_work;
      cum_diss += au.dissipation;
      cum_plastic += au.plastic_dissipation;
      if (contact) {
        // E_{n+1} - E_n = W_ext + W_sup - D + W_contact - D_friction.
        au.balance -= cstats.work - cstats.friction_dissipation;
        cum_contact += cstats.work;
        cum_friction += cstats.friction_dissipation;
      }
      const std::string bad = nonfinite(&au);
      if (!bad.empty()) {
        failure = "non-finite " + bad + " at t = " + fmt(t, 6) + " (loads, velocities or material constants too large?)";
        failed = true;
        out << "\n";
        break;
      }
      max_balance = std::max(max_balance, std::abs(au.balance));
      out << "  K " << fmt(au.kinetic, 6) << "  E " << fmt(au.kinetic + au.strain, 9) << "  balance " << fmt(au.balance, 2);
      energy_row(step, t, au);
    }
    out << "\n";
    if (const std::string bad = dynamic ? "" : nonfinite(nullptr); !bad.empty()) {
      failure = "non-finite " + bad + " at t = " + fmt(t, 6) + " (loads or material constants too large?)";
      failed = true;
      break;
    }
    if (rank == 0) {
      std::vector<double> row = {double(step), t, dt, double(nr.iterations), double(nr.linear_iterations), double(total_cuts),
                                 system.last.energy};
      for (const auto& rf : reac)
        for (int k = 0; k < dim; ++k) row.push_back(rf[static_cast<std::size_t>(k)]);
      const auto pv = probe_values();
      for (std::size_t p = 0; p < probe_node.size(); ++p)
        for (int k = 0; k < dim; ++k) row.push_back(pv[3 * p + k]);
      if (contact)
        for (double v : contact->history_values(cstats)) row.push_back(v);
      if (assembler->has_history()) row.push_back(system.last.plastic_dissipation);
      Timers::Scope s{timers, "output"};
      history->row(row);
    } else {
      probe_values();
    }
    const bool last = t >= T * (1.0 - 1e-12);
    if (cfg.output.fields && (step % cfg.output.every == 0 || last)) write_fields(t);
    if (consecutive_cuts > 0) dt = std::min(dt0, 2.0 * dt);
    consecutive_cuts = 0;
  }

  if (result) {
    result->displacement.assign(3 * mesh.num_nodes(), 0.0);
    u_all.doImport(u, gather, Tpetra::INSERT);
    if (rank == 0) {
      auto uh = u_all.getLocalViewHost(Tpetra::Access::ReadOnly);
      for (std::size_t i = 0; i < all_dofs.size(); ++i)
        result->displacement[3 * static_cast<std::size_t>(all_dofs[i] / dim) + static_cast<std::size_t>(all_dofs[i] % dim)] = uh(i, 0);
    }
    Teuchos::broadcast(*comm, 0, static_cast<int>(result->displacement.size()), result->displacement.data());
    result->reactions = assembler->reactions();
    result->energy = system.last.energy;
    result->steps = step;
    result->cutbacks = total_cuts;
    result->newton_iterations = total_newton;
    result->linear_iterations = total_linear;
    result->converged = !failed;
    result->mesh = mesh;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  if (dynamic)
    out << "Energy balance: max |E_{n+1} - E_n - (W_ext + W_sup - D" << (contact ? " + W_contact - D_friction" : "")
        << ")| per step = " << fmt(max_balance, 3) << "\n";
  out << (failed ? "FAILED: " + failure + "\n" : "") << "Summary: " << step << " steps, " << total_cuts << " cut-backs, " << total_newton
      << " Newton iterations, " << total_linear << " linear iterations, " << std::fixed << std::setprecision(2) << wall << " s\n";
  for (const auto& n : timers.names()) out << "  " << std::left << std::setw(10) << n << std::right << std::setw(10) << timers.get(n) << " s\n";
  out << std::defaultfloat;
  if (rank == 0) {
    history.reset();
    energy_csv.reset();
    xdmf.reset();
    if (!failed) {
      const std::string csv = staging->path() + "/" + cfg.output.basename + "_history.csv";
      std::vector<std::string> rcols;
      for (const auto& d : assembler->dirichlet_sets())
        for (int k = 0; k < dim; ++k) rcols.push_back("reaction_" + d.name + "_" + kAxes[k]);
      if (!rcols.empty())
        plot_csv_png(csv, staging->path() + "/" + cfg.output.basename + "_reactions.png", "time", rcols, "Reaction forces", "force");
      if (dynamic) {
        const std::string ecsv = staging->path() + "/" + cfg.output.basename + "_energy.csv";
        energy_csv.reset();
        plot_csv_png(ecsv, staging->path() + "/" + cfg.output.basename + "_energy.png", "time",
                     {"kinetic", "strain", "total", "dissipation", "external_work"}, "Energy (" + cfg.time.scheme + ")", "energy");
        plot_csv_png(ecsv, staging->path() + "/" + cfg.output.basename + "_balance.png", "time", {"balance_residual"},
                     "Energy balance residual per step", "E_{n+1} - E_n - (W_ext + W_sup - D)");
      } else {
        plot_csv_png(csv, staging->path() + "/" + cfg.output.basename + "_energy.png", "time", {"strain_energy"}, "Stored energy",
                     "energy");
      }
      staging->commit();
      out << "Results in " << std::filesystem::absolute(out_dir).string() << "/ (" << cfg.output.basename << ".xdmf for ParaView, "
          << cfg.output.basename << "_history.csv)\n";
    } else {
      out << "Partial results kept in " << staging->path() << "; earlier results in " << out_dir << " were not touched\n";
    }
  }
  return failed ? 3 : 0;
}

}  // namespace stentor
