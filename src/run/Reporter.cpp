#include "run/Reporter.hpp"

#include "io/WriteError.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <iostream>
#include <limits>

#include "geometry/Generators.hpp"
#include "geometry/MshWriter.hpp"
#include "io/LogCopy.hpp"
#include "io/SafeFile.hpp"
#include "parallel/Agreement.hpp"
#include "mesh/MeshComm.hpp"
#include "run/OutputRows.hpp"
#include "stentor/format.hpp"

namespace stentor {

namespace {

const char* kAxes[3] = {"x", "y", "z"};

std::string fmt(double v, int prec = 4) {
  std::ostringstream os;
  os << std::scientific << std::setprecision(prec) << v;
  return os.str();
}

// Times and step sizes in the log: 6 significant digits, no trailing zeros (0.15, 1e-05),
// so a time summed from steps (0.15000000000000002) reads as the deck's. The CSV and
// HDF5 files keep every digit.
std::string fmt_time(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Records (a global id and k values each) of every rank of comm (`nranks` of them),
// gathered on rank 0 (empty elsewhere); `from` is the rank each record came from.
struct Gathered {
  std::vector<long long> ids;
  std::vector<double> values;
  std::vector<int> from;
};
Gathered gather_on_root(MPI_Comm comm, const std::vector<long long>& ids, const std::vector<double>& values, int k, int nranks) {
  const int n = static_cast<int>(ids.size());
  std::vector<int> counts(static_cast<std::size_t>(nranks)), displs(static_cast<std::size_t>(nranks));
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  int total = 0;
  for (int r = 0; r < nranks; ++r) {
    displs[static_cast<std::size_t>(r)] = total;
    total += counts[static_cast<std::size_t>(r)];
  }
  Gathered g;
  g.ids.resize(static_cast<std::size_t>(total));
  g.values.resize(static_cast<std::size_t>(total) * static_cast<std::size_t>(k));
  MPI_Gatherv(ids.data(), n, MPI_LONG_LONG, g.ids.data(), counts.data(), displs.data(), MPI_LONG_LONG, 0, comm);
  std::vector<int> counts_k(counts), displs_k(displs);
  for (auto& c : counts_k) c *= k;
  for (auto& d : displs_k) d *= k;
  MPI_Gatherv(values.data(), k * n, MPI_DOUBLE, g.values.data(), counts_k.data(), displs_k.data(), MPI_DOUBLE, 0, comm);
  for (int r = 0; r < nranks; ++r) g.from.insert(g.from.end(), static_cast<std::size_t>(counts[static_cast<std::size_t>(r)]), r);
  return g;
}

// Contact fields on this rank's node rows: status -1 marks nodes that are no slave node
// (then the gap is NaN, the value without meaning that ParaView draws in its NaN colour, so
// that no node off the contact surfaces reads as touching; the forces, pressure and slip
// are 0); 0 free, 1 inactive, 2 stick, 3 slip. `slaves`: the slave nodes' values routed to
// their rows. Master surfaces (`traction` not null): contact_master_traction and
// contact_master_pressure = the reaction forces on the master nodes and their normal parts
// (summed over ranks) projected on the master surfaces like the contact pressure
// (mesh/SurfaceProjection.hpp; zero on other nodes), routed to their rows. Only the
// fields of Output->field list are written. Collective.
void write_contact_fields(XdmfWriter& xdmf, const OutputConfig& o, const Records& slaves, const Records* traction) {
  constexpr int kv = Contact::kNodalValues;
  const RowRange rows = xdmf.node_rows();
  const std::size_t nn = rows.size();
  std::vector<double> status(nn, double(contact::NotSlave)), gap(nn, std::numeric_limits<double>::quiet_NaN()), lambda_n(nn, 0.0),
      pressure(nn, 0.0), lambda_t(3 * nn, 0.0), slip(3 * nn, 0.0);
  for (std::size_t i = 0; i < slaves.ids.size(); ++i) {
    const auto g = static_cast<std::size_t>(slaves.ids[i]) - rows.begin;
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
  auto put = [&](const char* name, int k, const std::vector<double>& v) {
    if (o.wants(name)) xdmf.node_field(name, k, v);
  };
  put("contact_status", 1, status);
  put("contact_gap", 1, gap);
  put("contact_lambda_normal", 1, lambda_n);
  put("contact_pressure", 1, pressure);
  put("contact_lambda_tangent", 3, lambda_t);
  put("contact_slip", 3, slip);
  if (!traction) return;
  std::vector<double> t(3 * nn, 0.0), pm(nn, 0.0);
  for (std::size_t i = 0; i < traction->ids.size(); ++i) {
    const std::size_t g = static_cast<std::size_t>(traction->ids[i]) - rows.begin;
    for (std::size_t k = 0; k < 3; ++k) t[3 * g + k] = traction->values[4 * i + k];
    pm[g] = traction->values[4 * i + 3];
  }
  put("contact_master_traction", 3, t);
  put("contact_master_pressure", 1, pm);
}

// Rank 0: the master surfaces' traction and normal pressure (projected summed forces) at
// their nodes, 4 values each (x y z, p), from the gathered master records
// (write_contact_fields).
void master_traction(const Gathered& masters, const SurfaceProjection& s, std::vector<long long>& ids, std::vector<double>& values) {
  constexpr int km = Contact::kMasterValues;
  std::vector<double> force(4 * s.nodes().size(), 0.0);
  for (std::size_t i = 0; i < masters.ids.size(); ++i) {
    const long at = s.index(static_cast<GId>(masters.ids[i]));  // every master node is on a master surface
    if (at < 0) continue;
    for (std::size_t k = 0; k < 3; ++k) force[4 * static_cast<std::size_t>(at) + k] += masters.values[km * i + k];
    force[4 * static_cast<std::size_t>(at) + 3] += masters.values[km * i + 4];
  }
  values = s.project(force, 4);
  ids.assign(s.nodes().begin(), s.nodes().end());
}

// Cell fields on this rank's cell rows: `columns` (name, values per cell) of the local
// cells, packed per cell, routed to the ranks of their rows and unpacked into rows x k
// arrays (`owner`: the rank of each cell). Collective.
struct CellColumn {
  std::string name;
  int k;
  const std::vector<double>* local;
  std::vector<double> rows;
};
void cells_to_rows(MPI_Comm comm, const std::vector<GId>& ids, std::vector<CellColumn>& columns, std::size_t num_cells,
                   RowRange rows, std::vector<double>& owner) {
  int kc = 0;
  for (const auto& col : columns) kc += col.k;
  std::vector<double> packed;
  packed.reserve(ids.size() * static_cast<std::size_t>(kc));
  for (std::size_t c = 0; c < ids.size(); ++c)
    for (const auto& col : columns)
      for (int j = 0; j < col.k; ++j) packed.push_back((*col.local)[c * col.k + j]);
  const Records g = route_to_rows(comm, num_cells, std::vector<long long>(ids.begin(), ids.end()), packed, kc);
  owner.assign(rows.size(), 0.0);
  for (auto& col : columns) col.rows.assign(rows.size() * static_cast<std::size_t>(col.k), 0.0);
  for (std::size_t i = 0; i < g.ids.size(); ++i) {
    const auto id = static_cast<std::size_t>(g.ids[i]) - rows.begin;
    owner[id] = g.from[i];
    const double* v = &g.values[i * static_cast<std::size_t>(kc)];
    for (auto& col : columns)
      for (int j = 0; j < col.k; ++j) col.rows[id * col.k + j] = *v++;
  }
}

}  // namespace

Reporter::Reporter(const Model& model, const RunOptions& opts, Timers& timers, std::chrono::steady_clock::time_point start)
    : m_(model), cfg_(model.cfg), timers_(timers), out_(model.rank == 0 ? std::cout : null_stream_), start_(start) {
  out_dir_ = opts.output_dir.empty() ? cfg_.output.directory : opts.output_dir;
  overwrite_ = opts.overwrite;
  version_ = opts.version;
}

Reporter::~Reporter() = default;

void Reporter::print_model() {
  const Mesh& mesh = m_.mesh;
  out_ << "Stentor: " << (cfg_.problem.title.empty() ? cfg_.deck_path : cfg_.problem.title) << "\n"
       << "  deck     " << cfg_.deck_path << "\n"
       << (version_.empty() ? std::string() : "  version  " + version_ + "\n")
       << "  mesh     " << mesh.source << ": " << m_.dim << "D, " << mesh.num_nodes() << " nodes, " << mesh.num_volume_cells()
       << " cells (";
  for (std::size_t b = 0; b < mesh.volumes.size(); ++b)
    out_ << (b ? ", " : "") << mesh.volumes[b].name << ": " << mesh.block_cells(b) << " " << cell_name(mesh.volumes[b].type);
  out_ << ")\n";
  const StentConfig& st = cfg_.mesh.stent;
  if (cfg_.mesh.generator == "stent" && (st.sector != "full" || st.half_length)) {
    std::ostringstream os;
    os << "  model    ";
    if (st.sector != "full") os << "sector 0 <= theta <= " << std::setprecision(6) << st.sector_angle() * 180.0 / kPi << " deg";
    if (st.half_length) os << (st.sector != "full" ? " of " : "") << "half the length";
    os << ": 1/" << st.symmetry_copies() << " of the stent (its symmetry planes are to be held; the metrics count it "
       << st.symmetry_copies() << " times)\n";
    out_ << os.str();
  }
  if (cfg_.problem.axisymmetric())
    out_ << "  kinematics axisymmetric: x = r, y = z; forces, reactions and energies of the full revolution (2 pi r), "
            "u_r = 0 on the axis, stress zz = hoop\n";
  out_ << "  parallel " << m_.nranks << " MPI rank(s), Kokkos " << la::ExecSpace::name() << " x " << la::ExecSpace().concurrency()
       << " thread(s), " << cfg_.problem.assembly << " assembly\n";
  if (m_.nranks > 1) {
    std::ostringstream os;
    os << std::fixed << std::setprecision(1) << "  parts    each rank holds its cells, their neighbours and the surfaces it needs: at most "
       << 100.0 * m_.largest_part[0] << " % of the cells, " << 100.0 * m_.largest_part[1] << " % of the nodes, " << m_.largest_part[2]
       << " MB (the whole mesh: " << m_.largest_part[3] << " MB)\n";
    out_ << os.str();
  }
  for (const std::string& w : m_.warnings) out_ << "  " << w << "\n";
}

// "static (load stepping)", "dynamic: <scheme>", or with stages of several analyses or
// schemes the list "per stage: insertion static, inflation dynamic (gonzalez), ...".
namespace {
// "static" or "dynamic (<scheme>)" of a stage.
std::string stage_analysis(const StageConfig& st) { return st.dynamic() ? "dynamic (" + st.scheme + ")" : std::string("static"); }
}  // namespace

std::string Reporter::analysis_text() const {
  if (cfg_.one_analysis()) return m_.dynamic ? "dynamic: " + m_.integrator->description() : std::string("static (load stepping)");
  std::string text = "per stage:";
  for (const StageConfig& st : cfg_.stages) text += (&st == &cfg_.stages.front() ? " " : ", ") + st.name + " " + stage_analysis(st);
  return text;
}

void Reporter::print_solvers() {
  out_ << "  dofs     " << m_.dist->owned_map()->getGlobalNumElements() << "\n"
       << "  analysis " << analysis_text() << "\n"
       << "  solver   " << m_.linear->description() << "\n";
  if (m_.nranks > 1 && klu2())
    out_ << "warning: 'Linear Solver->method' = direct on " << m_.nranks
         << " ranks: KLU2 gathers the matrix and solves it on one rank at every Newton iteration, so more ranks "
            "make the run slower, not faster; on several ranks use 'direct solver' = mumps, or method = gmres (with "
            "the default MueLu or Schwarz preconditioner, docs/solvers.md)\n";
  if (m_.contact) {
    const std::string d = m_.contact->description();  // collective
    out_ << "  contact  " << d << "\n";
  }
}

std::vector<std::string> Reporter::history_columns() const {
  std::vector<std::string> columns = {"step", "time", "dt", "newton_iterations", "linear_iterations", "cutbacks", "strain_energy"};
  for (const auto& c : reaction_columns()) columns.push_back(c);
  for (const LoadConfig& l : cfg_.loads) {
    if (l.type == LoadConfig::Type::Pressure || l.type == LoadConfig::Type::FluidCavity) columns.push_back("pressure_" + l.name);
    if (l.type == LoadConfig::Type::FluidCavity) columns.push_back("volume_ratio_" + l.name);
  }
  for (const auto& p : cfg_.output.probes)
    for (int k = 0; k < m_.dim; ++k) columns.push_back("u_" + p.name + "_" + kAxes[k]);
  if (m_.contact)
    for (const auto& c : m_.contact->history_columns()) columns.push_back(c);
  if (m_.assembler->has_history()) columns.push_back("plastic_dissipation");  // of the step
  if (cfg_.any_stabilization()) columns.push_back("stabilization_energy");  // of the step
  if (!cfg_.stages.empty()) columns.push_back("stage");
  return columns;
}

std::vector<std::string> Reporter::reaction_columns() const {
  std::vector<std::string> columns;
  for (const auto& d : m_.assembler->dirichlet_sets())
    for (int k = 0; k < m_.dim; ++k)
      if (d.components[static_cast<std::size_t>(k)]) columns.push_back("reaction_" + d.name + "_" + kAxes[k]);
  return columns;
}

std::vector<std::string> Reporter::energy_columns() const {
  std::vector<std::string> cols = {"step", "time", "kinetic", "strain", "total", "external_work", "support_work",
                                   "dissipation", "balance_residual", "momentum_x", "momentum_y", "momentum_z",
                                   "angular_momentum_x", "angular_momentum_y", "angular_momentum_z"};
  if (m_.contact) cols.insert(cols.end(), {"contact_work", "friction_dissipation"});
  if (m_.assembler->has_history()) cols.push_back("plastic_dissipation");  // cumulative; also in "dissipation"
  return cols;
}

void Reporter::open() {
  if (cfg_.output.metrics.enabled) metrics_ = std::make_unique<MetricsReport>(m_);  // before any file: bad group names
  int io_error = 0;
  std::string io_message;
  if (m_.rank == 0) {
    try {
      const OutputDir::Options o{{cfg_.deck_path, cfg_.mesh.file}, cfg_.output.basename, cfg_.deck_path, overwrite_};
      staging_ = std::make_unique<OutputDir>(out_dir_, o);
      const std::string stem = staging_->path() + "/" + cfg_.output.basename;
      staging_->copy_in(cfg_.deck_path, cfg_.output.basename + "_deck.xml");
      if (cfg_.mesh.write_mesh) {  // generated again here: m_.mesh is this rank's part on several ranks
        const std::string msh = stem + "_mesh.msh";
        check_write(write_text_file(msh, mesh_to_msh(generate_mesh(cfg_.mesh))), "writing the generated mesh to", msh);
      }
      log_copy::attach(stem + ".log");
      if (!staging_->notice().empty()) out_ << "  output   " << staging_->notice() << "\n";
      if (metrics_) metrics_->open(stem);
      std::vector<std::string> master_groups;
      for (const ContactPairConfig& c : cfg_.contact)
        if (!c.master.empty()) master_groups.push_back(c.master);
      if (cfg_.output.fields && !master_groups.empty()) master_surface_ = std::make_unique<SurfaceProjection>(m_.mesh, master_groups, cfg_.problem.axisymmetric());
      std::vector<std::string> rigid;  // the rigid pairs, in Contact::rigid_obstacles() order
      for (const ContactPairConfig& c : cfg_.contact)
        if (c.master.empty()) rigid.push_back(c.name);
      if (cfg_.output.fields && m_.contact && !rigid.empty()) {
        const Mesh::Box box = m_.mesh.bounding_box();
        const std::array<double, 3> c{0.5 * (box.lo[0] + box.hi[0]), 0.5 * (box.lo[1] + box.hi[1]), 0.5 * (box.lo[2] + box.hi[2])};
        obstacles_ = std::make_unique<ObstacleWriter>(staging_->path(), cfg_.output.basename, m_.dim, box.diagonal(), c, rigid);
      }
      history_ = std::make_unique<CsvWriter>(stem + "_history.csv", history_columns());
      if (m_.any_dynamic) energy_csv_ = std::make_unique<CsvWriter>(stem + "_energy.csv", energy_columns());
    } catch (const WriteError& e) {
      // A failed write (a full disk, a file size limit) is a write failure like any later
      // one: exit 3, and no MPI_Finalize, whose HDF5 shut-down crashed (SIGSEGV) on the
      // file whose first flush failed (found by the corpus: a file size limit of 4 kB).
      io_error = 2;
      io_message = e.what();
    } catch (const std::exception& e) {
      io_error = 1;
      io_message = e.what();
    }
  }
  Teuchos::broadcast(*m_.comm, 0, &io_error);
  if (io_error == 2) {
    if (m_.rank == 0) throw WriteError("cannot create output in '" + out_dir_ + "': " + io_message);
    throw WriteError("cannot create output");
  }
  if (io_error) {
    if (m_.rank == 0) throw InputError("cannot create output in '" + out_dir_ + "': " + io_message);
    throw InputError("cannot create output");
  }
  {  // rank 0's staging folder on every rank (the field writer and checkpoints open files there)
    const std::string here = staging_ ? staging_->path() : std::string();
    std::vector<char> dir(here.begin(), here.end());
    broadcast_bytes(dir, raw_mpi_comm(*m_.comm));
    staging_dir_.assign(dir.begin(), dir.end());
  }
  if (cfg_.output.fields) open_fields();
}

// The HDF5/XDMF writer, on every rank (collective), in rank 0's staging folder.
void Reporter::open_fields() {
  xdmf_ = make_writer(cfg_.output.basename);
  node_rows_ = std::make_unique<NodeRows>(*m_.dist, m_.mesh.num_nodes(), m_.comm, xdmf_->node_rows());
  master_traction_ = false;
  for (const ContactPairConfig& c : cfg_.contact) master_traction_ = master_traction_ || !c.master.empty();
}

// An HDF5/XDMF writer <basename>.xdmf/.h5 in the staging folder, on every rank (collective).
std::unique_ptr<XdmfWriter> Reporter::make_writer(const std::string& basename) {
  const std::string& dir = staging_dir_;
  const MPI_Comm comm = raw_mpi_comm(*m_.comm);
  const XdmfMesh rows = xdmf_mesh_on_rows(m_.mesh, *m_.dist, comm);  // collective
  std::unique_ptr<XdmfWriter> w;
  std::string local;
  int code = 0;
  try {
    w = std::make_unique<XdmfWriter>(dir, basename, rows, comm);
  } catch (const WriteError& e) {
    code = 2, local = e.what();
  } catch (const std::exception& e) {
    code = 1, local = e.what();
  }
  const Agreement a = agree_on_failure(*m_.comm, local);
  if (a.failed()) {
    int worst = 0;
    Teuchos::reduceAll(*m_.comm, Teuchos::REDUCE_MAX, 1, &code, &worst);
    const std::string what = m_.rank == 0 ? "cannot create output in '" + out_dir_ + "': " + a.failure : "cannot create output";
    if (worst == 2) throw WriteError(what);
    throw InputError(what);
  }
  return w;
}

void Reporter::discard() {
  xdmf_.reset();  // collective
  if (m_.rank != 0) return;
  obstacles_.reset();
  history_.reset();
  energy_csv_.reset();
  staging_->discard();
}

// Every rank writes its rows of each dataset (io/XdmfWriter.hpp); a failed write on any
// rank stops every rank with WriteError (the ranks vote: parallel/Agreement.hpp).
void Reporter::write_fields(double t, const la::Vector& u) {
  Timers::Scope s{timers_, "output"};
  write_frame(*xdmf_, t, u, true);
}

void Reporter::write_failed_state(double t, const la::Vector& u) {
  if (!xdmf_) return;  // Output->fields = false
  Timers::Scope s{timers_, "output"};
  std::unique_ptr<XdmfWriter> w = make_writer(cfg_.output.basename + "_failed");
  write_frame(*w, t, u, false);
  const std::string path = w->xdmf_path();
  w.reset();  // collective
  out_ << "  the failed step's last iterate (t = " << t << ") is in " << path << "\n";
}

// One frame of the fields the deck asks for into `w` (collective); `obstacles`: the
// rigid obstacles' frame at t too.
void Reporter::write_frame(XdmfWriter& w, double t, const la::Vector& u, bool obstacles) {
  const OutputConfig& o = cfg_.output;
  Assembler::CellFieldRequest req;
  req.green_lagrange = o.wants("green_lagrange_strain");
  req.log_strain = o.wants("log_strain");
  req.principal = o.wants("principal_stress");
  const Assembler::CellFields cf = m_.assembler->cell_fields(u, req);
  // What goes to the cell rows: the wanted cell fields.
  std::vector<CellColumn> cols;
  auto want_cells = [&](const std::string& name, int k, const std::vector<double>& v) {
    if (o.wants(name)) cols.push_back({name, k, &v, {}});
  };
  // In the order written (the standard ones as before field lists; mpi_rank after J).
  want_cells("cauchy_stress", 6, cf.stress);
  want_cells("von_mises", 1, cf.von_mises);
  want_cells("J", 1, cf.J);
  const std::size_t nx = cf.extra_names.size();
  std::vector<std::vector<double>> extra(nx);  // history averages, one vector per name
  for (std::size_t k = 0; k < nx; ++k)
    for (std::size_t c = 0; c < cf.cell_ids.size(); ++c) extra[k].push_back(cf.extra[c * nx + k]);
  for (std::size_t k = 0; k < nx; ++k) want_cells(cf.extra_names[k], 1, extra[k]);
  want_cells("principal_stress", 3, cf.principal);
  want_cells("green_lagrange_strain", 6, cf.green_lagrange);
  want_cells("log_strain", 6, cf.log_strain);
  const MPI_Comm comm = raw_mpi_comm(*m_.comm);
  std::vector<double> owner;
  cells_to_rows(comm, cf.cell_ids, cols, m_.mesh.num_volume_cells(), w.cell_rows(), owner);
  std::vector<const std::vector<double>*> recovered;  // cauchy_stress_nodal, von_mises_nodal
  std::vector<int> rk;
  if (o.wants("cauchy_stress_nodal")) recovered.push_back(&cf.stress), rk.push_back(6);
  if (o.wants("von_mises_nodal")) recovered.push_back(&cf.von_mises), rk.push_back(1);
  // Collective, skipped alike on every rank when no recovered field is wanted (it would
  // still send every cell to the ranks of its nodes).
  const std::vector<std::vector<double>> nodal =
      recovered.empty() ? std::vector<std::vector<double>>{}
                        : recover_on_rows(m_.mesh, comm, w.node_rows(), cf.cell_ids, recovered, rk, cf.volume);
  // The malapposition map: every rank has the outer nodes' distances; each fills its rows.
  std::vector<double> wall_gap;
  std::vector<GId> outer;
  std::vector<double> gaps;
  if (o.wants("wall_gap") && metrics_ && metrics_->wall_gaps(u, outer, gaps)) {
    const RowRange rows = w.node_rows();
    wall_gap.assign(rows.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t i = 0; i < outer.size(); ++i) {
      const auto g = static_cast<std::size_t>(outer[i]);
      if (g >= rows.begin && g < rows.begin + rows.size()) wall_gap[g - rows.begin] = gaps[i];
    }
  }
  std::string failure;
  try {
    w.begin_step(t);
    write_node_fields(w, u, nodal);
    if (!wall_gap.empty()) w.node_field("wall_gap", 1, wall_gap);
    for (const CellColumn& c : cols) {
      w.cell_field(c.name, c.k, c.rows);
      if (c.name == "J" && o.wants("mpi_rank")) w.cell_field("mpi_rank", 1, owner);
    }
    if (!o.wants("J") && o.wants("mpi_rank")) w.cell_field("mpi_rank", 1, owner);
    if (m_.contact) write_contact(w, comm);
    w.end_step();
    if (obstacles) write_obstacles(t);
  } catch (const WriteError& e) {
    failure = e.what();
  }
  const Agreement a = agree_on_failure(*m_.comm, failure);
  if (a.failed()) throw WriteError(a.failure);
}

// The step's node fields but the contact ones: displacement, velocity, reaction_force,
// then the recovered ones (`nodal`: cauchy_stress_nodal, von_mises_nodal as wanted).
void Reporter::write_node_fields(XdmfWriter& w, const la::Vector& u, const std::vector<std::vector<double>>& nodal) {
  const OutputConfig& o = cfg_.output;
  const RowRange rows = w.node_rows();
  if (o.wants("displacement")) w.node_field("displacement", 3, node_rows_->values(u));
  if (o.wants("velocity")) w.node_field("velocity", 3, node_rows_->values(m_.integrator->velocity()));
  if (o.wants("reaction_force")) {
    const Assembler::DofReactions d = m_.assembler->dof_reactions();
    std::vector<long long> nodes;
    std::vector<double> vals;
    for (std::size_t i = 0; i < d.nodes.size(); ++i) {
      nodes.push_back(static_cast<long long>(d.nodes[i]));
      vals.push_back(static_cast<double>(d.components[i]));
      vals.push_back(d.values[i]);
    }
    const Records r = route_to_rows(raw_mpi_comm(*m_.comm), m_.mesh.num_nodes(), nodes, vals, 2);
    std::vector<double> rf(3 * rows.size(), 0.0);
    for (std::size_t i = 0; i < r.ids.size(); ++i)
      rf[3 * (static_cast<std::size_t>(r.ids[i]) - rows.begin) + static_cast<std::size_t>(r.values[2 * i])] = r.values[2 * i + 1];
    w.node_field("reaction_force", 3, rf);
  }
  std::size_t k = 0;
  if (o.wants("cauchy_stress_nodal")) w.node_field("cauchy_stress_nodal", 6, nodal[k++]);
  if (o.wants("von_mises_nodal")) w.node_field("von_mises_nodal", 1, nodal[k++]);
}

// The contact fields: the slave nodes' values routed to their rows; the master surfaces'
// forces gathered on rank 0 (few nodes), projected there and routed to their rows.
void Reporter::write_contact(XdmfWriter& w, MPI_Comm comm) {
  const Contact::NodalFields nf = m_.contact->nodal_fields();
  const Records slaves = route_to_rows(comm, m_.mesh.num_nodes(), nf.nodes, nf.values, Contact::kNodalValues);
  const Contact::NodalFields mf = m_.contact->master_fields();
  const Gathered masters = gather_on_root(comm, mf.nodes, mf.values, Contact::kMasterValues, m_.nranks);
  const bool traction = master_traction_ && m_.contact->has_master_surfaces() &&
                        (cfg_.output.wants("contact_master_traction") || cfg_.output.wants("contact_master_pressure"));
  Records t;
  if (traction) {
    std::vector<long long> ids;
    std::vector<double> values;
    if (m_.rank == 0) master_traction(masters, *master_surface_, ids, values);
    t = route_to_rows(comm, m_.mesh.num_nodes(), ids, values, 4);
  }
  write_contact_fields(w, cfg_.output, slaves, traction ? &t : nullptr);
}

// The rigid obstacles at t in <basename>_obstacles.xdmf/.h5 (rank 0, with the fields).
void Reporter::write_obstacles(double t) {
  if (!obstacles_) return;
  std::vector<ObstacleShape> shapes;
  for (const contact::Obstacle& o : m_.contact->rigid_obstacles(t)) {
    ObstacleShape s;
    s.kind = o.kind;
    for (std::size_t k = 0; k < 3; ++k) s.point[k] = o.point[k], s.normal[k] = o.normal[k], s.axis[k] = o.axis[k];
    s.radius = o.radius;
    s.length = o.length;
    shapes.push_back(s);
  }
  obstacles_->write(t, shapes);
}

void Reporter::energy_row(int step, double t, const EnergyAudit& au, const EnergyTotals& e) {
  total_energy_ = au.kinetic + au.strain;
  if (m_.rank != 0 || !energy_csv_) return;
  std::vector<double> row = {double(step), t, au.kinetic, au.strain, au.kinetic + au.strain, e.external, e.support, e.dissipation,
                             au.balance, au.momentum[0], au.momentum[1], au.momentum[2], au.angular_momentum[0],
                             au.angular_momentum[1], au.angular_momentum[2]};
  if (m_.contact) row.insert(row.end(), {e.contact, e.friction});
  if (m_.assembler->has_history()) row.push_back(e.plastic);
  energy_csv_->row(row);
}

std::vector<double> Reporter::probe_values(const la::Vector& u) const {
  const auto& probes = m_.probe_node;
  std::vector<double> loc(probes.size() * 3, 0.0), glob(loc.size(), 0.0);
  auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (std::size_t p = 0; p < probes.size(); ++p)
    if (m_.dist->owns_node(probes[p]))
      for (int k = 0; k < m_.dim; ++k) loc[3 * p + k] = uh(m_.dist->local_node(probes[p]) * m_.dim + k, 0);
  if (!loc.empty()) Teuchos::reduceAll(*m_.comm, Teuchos::REDUCE_SUM, static_cast<int>(loc.size()), loc.data(), glob.data());
  return glob;
}

void Reporter::initial_metrics(const RunState& s) {
  if (s.step == 0) {  // not after --restart: the plots' t = 0 (collective)
    initial_.probes = probe_values(s.u);
    const bool penetrating = m_.contact && !m_.contact->initial_penetrations().empty();
    initial_.at_rest_unloaded = !penetrating && deck_at_rest_unloaded(m_);
    initial_.known = true;
  }
  if (!metrics_) return;
  Timers::Scope sc{timers_, "output"};
  metrics_->step(s, s.u, m_.dynamic ? total_energy_ : 0.0);
}

std::map<std::string, double> Reporter::metrics_state() const {
  std::map<std::string, double> m;
  if (metrics_) metrics_->save(m);
  return m;
}

void Reporter::restore_metrics(const std::map<std::string, double>& state) {
  if (metrics_) metrics_->restore(state);
}

void Reporter::end_stage(const RunState& s, const std::string& name) {
  if (metrics_) metrics_->end_stage(s, name, out_);
}

void Reporter::history_row(const RunState& s, const StepRecord& rec, double energy) {
  if (metrics_) {
    Timers::Scope sc{timers_, "output"};
    metrics_->step(s, s.u, m_.dynamic ? total_energy_ : energy);
  }
  const auto pv = probe_values(s.u);
  strain_energy_ = energy;
  if (m_.rank != 0) return;
  const int dim = m_.dim;
  std::vector<double> row = {double(s.step), s.t, rec.dt, double(rec.newton.iterations), double(rec.newton.linear_iterations),
                             double(s.control.total_cuts()), energy};
  for (std::size_t i = 0; i < m_.assembler->reactions().size(); ++i)  // as reaction_columns()
    for (int k = 0; k < dim; ++k)
      if (m_.assembler->dirichlet_sets()[i].components[static_cast<std::size_t>(k)])
        row.push_back(m_.assembler->reactions()[i][static_cast<std::size_t>(k)]);
  std::size_t cavity = 0;
  for (const LoadConfig& l : cfg_.loads) {  // the pressure acting at s.t (its ramp in this stage); a cavity's at the last evaluation
    if (l.type == LoadConfig::Type::Pressure) row.push_back(l.value * l.ramp(s.t, cfg_.stepping.end_time));
    if (l.type != LoadConfig::Type::FluidCavity) continue;
    const Assembler::Cavity& c = m_.assembler->cavities()[cavity++];
    row.push_back(c.on ? c.p : 0.0);
    row.push_back(c.on ? c.V / c.V0 : 1.0);
  }
  for (std::size_t p = 0; p < m_.probe_node.size(); ++p)
    for (int k = 0; k < dim; ++k) row.push_back(pv[3 * p + k]);
  if (m_.contact)
    for (double v : m_.contact->history_values(rec.contact)) row.push_back(v);
  if (m_.assembler->has_history()) row.push_back(rec.plastic_dissipation);
  if (cfg_.any_stabilization()) row.push_back(rec.stabilization_energy);
  if (!cfg_.stages.empty()) row.push_back(double(s.stage + 1));
  Timers::Scope sc{timers_, "output"};
  history_->row(row);
  log_copy::check();  // a failed write of the log copy stops the run like any other
}

void Reporter::begin_stage(std::size_t k) {
  const StageConfig& st = cfg_.stages[k];
  out_ << "stage " << k + 1 << "/" << cfg_.stages.size() << " '" << st.name << "': t " << fmt_time(st.start) << " -> "
       << fmt_time(st.end) << ", " << st.num_steps << " step(s) of " << fmt_time(st.step()) << ", " << stage_analysis(st) << "\n";
}

void Reporter::begin_interval(double t0, double t1) {
  interval_start_ = std::chrono::steady_clock::now();
  interval_t0_ = t0;
  interval_t1_ = t1;
  // What the progress line's columns are (step_line).
  out_ << "  columns: t time, dt its step, Newton and linear iterations of the step, |r| final residual, W strain energy";
  if (m_.contact) {
    out_ << ", contact active/stick/slip nodes of";
    for (const ContactPairConfig& c : cfg_.contact) out_ << " '" << c.name << "'";
  }
  for (const Assembler::Cavity& c : m_.assembler->cavities())
    out_ << ", p pressure and V/V0 volume ratio of the fluid cavity '" << c.spec.name << "'";
  if (m_.any_dynamic) out_ << ", K kinetic and E total energy, balance E_{n+1} - E_n - (work - dissipation) of the step";
  out_ << "; [" << (cfg_.stages.empty() ? "" : "stage k/n: its time of its duration; ") << "wall time, time left]\n";
}

namespace {
std::string seconds(double s) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(s < 10.0 ? 1 : 0) << s << " s";
  return os.str();
}
}  // namespace

void Reporter::step_line(const RunState& s, const StepRecord& rec, double energy) {
  const NewtonResult& nr = rec.newton;
  out_ << "  step " << std::setw(4) << s.step << "  t " << std::left << std::setw(10) << fmt_time(s.t) << "  dt " << std::setw(8) << fmt_time(rec.dt)
       << std::right << "  newton " << std::setw(2)
       << nr.iterations << "  linear " << std::setw(4) << nr.linear_iterations << "  |r| " << fmt(nr.residual, 2) << "  W "
       << fmt(energy, 6);
  if (m_.contact) out_ << m_.contact->progress(rec.contact);
  for (const Assembler::Cavity& c : m_.assembler->cavities())
    if (c.on) out_ << "  p " << fmt(c.p, 4) << "  V/V0 " << fmt(c.V / c.V0, 5);
  if (m_.dynamic && rec.nonfinite.empty()) {
    const EnergyAudit& au = rec.audit;
    out_ << "  K " << fmt(au.kinetic, 6) << "  E " << fmt(au.kinetic + au.strain, 9) << "  balance " << fmt(au.balance, 2);
  }
  // Time left: the wall time per unit of simulated time so far in this interval.
  const auto now = std::chrono::steady_clock::now();
  const double wall = std::chrono::duration<double>(now - start_).count();
  const double spent = std::chrono::duration<double>(now - interval_start_).count();
  const double done = s.t - interval_t0_, left = std::max(0.0, interval_t1_ - s.t);
  out_ << "  [";
  if (!cfg_.stages.empty()) {  // the stage, its own clock and its duration: "inflation 2/3: 0.12 of 0.4 s; "
    const StageConfig& st = cfg_.stages[static_cast<std::size_t>(s.stage)];
    out_ << st.name << " " << s.stage + 1 << "/" << cfg_.stages.size() << ": " << fmt_time(s.t - st.start) << " of "
         << fmt_time(st.end - st.start) << " s; ";
  }
  out_ << seconds(wall);
  if (done > 0.0) out_ << ", ~" << seconds(spent * left / done) << " left";
  out_ << "]" << std::endl;
}

void Reporter::cutback_line(const RunState& s, double t_new, const NewtonResult& nr, double dt_new) {
  out_ << "  step " << s.step + 1 << " t=" << fmt_time(t_new) << ": " << nr.failure << "; cutting dt to " << fmt_time(dt_new) << std::endl;
}

void Reporter::step_size_line(double dt_old, double dt_new, const std::string& why) {
  out_ << "  dt " << fmt_time(dt_old) << " -> " << fmt_time(dt_new) << ": " << why << std::endl;
}

std::vector<double> Reporter::displacement_on_root(const la::Vector& u) {
  if (!gather_) {  // every dof (each owned once) on rank 0, in dof (= mesh node) order
    std::vector<long long> owned;  // the owned map's dofs
    for (la::LO l = 0; l < m_.dist->num_owned_nodes(); ++l)
      for (int k = 0; k < m_.dim; ++k) owned.push_back(static_cast<long long>(m_.dist->global_node(l)) * m_.dim + k);
    const Gathered all = gather_on_root(raw_mpi_comm(*m_.comm), owned, {}, 0, m_.nranks);
    all_dofs_.assign(all.ids.begin(), all.ids.end());
    std::sort(all_dofs_.begin(), all_dofs_.end());
    gather_map_ = Teuchos::rcp(new la::Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                           Teuchos::ArrayView<const la::GO>(all_dofs_), 0, m_.comm));
    gather_ = Teuchos::rcp(new la::Import(m_.dist->owned_map(), gather_map_));
    u_all_ = Teuchos::rcp(new la::Vector(gather_map_));
  }
  std::vector<double> d(3 * m_.mesh.num_nodes(), 0.0);
  u_all_->doImport(u, *gather_, Tpetra::INSERT);
  if (m_.rank == 0) {
    auto uh = u_all_->getLocalViewHost(Tpetra::Access::ReadOnly);
    for (std::size_t i = 0; i < all_dofs_.size(); ++i)
      d[3 * static_cast<std::size_t>(all_dofs_[i] / m_.dim) + static_cast<std::size_t>(all_dofs_[i] % m_.dim)] = uh(i, 0);
  }
  return d;
}

std::vector<double> Reporter::displacement(const la::Vector& u) {
  std::vector<double> d = displacement_on_root(u);
  Teuchos::broadcast(*m_.comm, 0, static_cast<int>(d.size()), d.data());
  return d;
}

void Reporter::summary(const RunState& s) {
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (cfg_.any_stabilization()) {
    // Abaqus' check of its static stabilisation (ALLSD against ALLIE), on the final state.
    out_ << "Static stabilisation: " << fmt(s.energy.stabilization, 4) << " J absorbed, "
         << fmt(strain_energy_ != 0.0 ? 100.0 * s.energy.stabilization / std::abs(strain_energy_) : 0.0, 3)
         << " % of the final strain energy\n";
    if (s.energy.stabilization > 0.01 * std::abs(strain_energy_))
      out_ << "warning: the static stabilisation absorbed more than 1 % of the strain energy: it is not a small "
              "perturbation of the equilibrium; lower 'Stepping->stabilization' (or the stages'), or take smaller steps\n";
  }
  if (m_.any_dynamic)
    out_ << "Energy balance" << (m_.cfg.any_static() ? " (dynamic stages)" : "") << ": max |E_{n+1} - E_n - (W_ext + W_sup - D" << (m_.contact ? " + W_contact - D_friction" : "")
         << ")| per step = " << fmt(s.energy.max_balance, 3) << "\n";
  out_ << (s.failed ? (s.stopped_by ? "STOPPED: " : "FAILED: ") + s.failure + "\n" : "") << "Summary: " << s.step << " steps, " << s.control.total_cuts()
       << " cut-backs, " << s.newton_iterations << " Newton iterations, " << s.linear_iterations << " linear iterations, "
       << std::fixed << std::setprecision(2) << wall << " s\n";
  for (const auto& n : timers_.names())
    out_ << "  " << std::left << std::setw(10) << n << std::right << std::setw(10) << timers_.get(n) << " s\n";
  if (m_.linear) {
    const LinearSolver::Times& lt = m_.linear->times();
    out_ << "    (newton: linear set-up " << lt.setup << " s in " << lt.setups << " calls, " << lt.builds
         << " preconditioner builds; linear solve " << lt.solve << " s in " << lt.solves << " calls)\n";
    if (lt.stale_rebuilds > 0)
      out_ << "    (" << lt.stale_rebuilds << " reused preconditioner(s) rebuilt: GMRES gained less than one digit in a cycle)\n";
    if (lt.fallbacks > 0) out_ << "    (linear solver fell back " << lt.fallbacks << " time(s): " << m_.linear->description() << " at the end)\n";
#ifdef STENTOR_HAVE_MUMPS
    // KLU2 has no supernodes: on a 3D mesh its factorizations can be most of the run, where
    // MUMPS is several times faster (docs/solvers.md, "The direct solvers").
    if (m_.dim == 3 && klu2() && lt.setup > 2.0 && 3.0 * lt.setup > wall)
      out_ << "note: KLU2's factorizations took " << lt.setup << " s of the run's " << wall
           << " s; on 3D meshes 'Linear Solver->direct solver' = mumps is usually several times faster "
              "(docs/solvers.md), or method = gmres\n";
#endif
  }
  out_ << std::defaultfloat;
}

void Reporter::plots() {
  const std::string stem = staging_->path() + "/" + cfg_.output.basename;
  write_result_plots(m_, stem, initial_, metrics_ ? metrics_->radius_columns() : std::vector<std::string>{},
                     metrics_ ? metrics_->stress_columns() : std::vector<std::string>{},
                     metrics_ ? metrics_->diameter_columns() : std::vector<std::string>{});
}

void Reporter::finish(bool failed) {
  xdmf_.reset();  // collective
  if (m_.rank != 0) return;
  history_.reset();
  energy_csv_.reset();
  const bool obstacles = obstacles_ != nullptr;
  obstacles_.reset();
  if (metrics_) metrics_->close();
  if (failed) {
    out_ << "Partial results kept in " << staging_->path() << "; earlier results in " << out_dir_ << " were not touched\n";
    return;
  }
  plots();
  log_copy::check();
  staging_->commit();
  // Name only what was written: a deck with Output->fields = false has no XDMF.
  out_ << "Results in " << std::filesystem::absolute(out_dir_).string() << "/ (";
  if (cfg_.output.fields)
    out_ << cfg_.output.basename << ".xdmf" << (obstacles ? " and " + cfg_.output.basename + "_obstacles.xdmf" : std::string())
         << " for ParaView, ";
  out_ << cfg_.output.basename << "_history.csv)\n";
}

}  // namespace stentor
