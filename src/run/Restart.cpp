#include "run/Restart.hpp"

#include <mpi.h>

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/OutputDir.hpp"
#include "io/SafeFile.hpp"
#include "io/WriteError.hpp"
#include "mesh/MeshComm.hpp"
#include "parallel/Agreement.hpp"
#include "parallel/RawComm.hpp"
#include "run/CheckpointCheck.hpp"
#include "run/OutputRows.hpp"
#include "run/Reporter.hpp"
#include "run/RunState.hpp"
#include "run/Stepper.hpp"

namespace stentor {

namespace fs = std::filesystem;

namespace {

// FNV-1a of the deck file's bytes: tells whether a checkpoint came from the same deck.
std::string deck_hash(const std::string& deck_path) {
  std::ifstream in(deck_path, std::ios::binary);
  Fnv1a f;
  char buf[4096];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) f.add(buf, static_cast<std::size_t>(in.gcount()));
  return f.hex();
}

// The analysis of the run: "static" or the scheme; with stages of several analyses or
// schemes, one per stage ("static, gonzalez, newmark").
std::string scheme_name(const Model& m) {
  const Config& c = m.cfg;
  std::string all = c.analysis_in(0);
  if (c.one_analysis()) return all;
  for (int k = 1; k < c.interval_count(); ++k) all += ", " + c.analysis_in(k);
  return all;
}

// Records of every rank as one table sorted by id, spread over the ranks: rank r gets the
// r-th range of the ids 0..id_space-1 (block_rows), sorted, which is how the parallel
// checkpoint writer takes them (io/Checkpoint.hpp). ncols: the largest over the ranks, so
// that ranks without such records may pass 0. Collective.
CheckpointTable rows_table(const Model& m, const std::vector<long long>& ids, const std::vector<double>& values, int ncols,
                           std::size_t id_space) {
  int k = 0;
  Teuchos::reduceAll(*m.comm, Teuchos::REDUCE_MAX, 1, &ncols, &k);
  const Records got = route_to_rows(raw_mpi_comm(*m.comm), id_space, ids, values, k);
  CheckpointTable t;
  t.ncols = k;
  t.ids = got.ids;
  t.values = got.values;
  t.sort_rows();
  return t;
}

// An owned-dof vector as rows (node id, dim values).
CheckpointTable node_table(const Model& m, const la::Vector& v) {
  const Distribution& d = *m.dist;
  std::vector<long long> ids;
  std::vector<double> vals;
  auto h = v.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (la::LO n = 0; n < d.num_owned_nodes(); ++n) {
    ids.push_back(d.global_node(n));
    for (int c = 0; c < m.dim; ++c) vals.push_back(h(n * m.dim + c, 0));
  }
  return rows_table(m, ids, vals, m.dim, m.mesh.num_nodes());
}

// The committed Gauss-point state of mesh volume block b: rows (cell id, ngp x nhist values).
CheckpointTable history_table(const Model& m, std::size_t b) {
  std::vector<long long> ids;
  std::vector<double> vals;
  int ncols = 0;
  const auto& blocks = m.dist->blocks();
  for (std::size_t lb = 0; lb < blocks.size(); ++lb) {
    if (static_cast<std::size_t>(blocks[lb].volume_block) != b) continue;
    const auto view = m.assembler->committed_history(lb);
    const std::size_t nc = blocks[lb].cell_ids.size();
    if (view.extent(0) == 0 || nc == 0) continue;
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), view);
    const std::size_t per_cell = view.extent(0) / nc * view.extent(1);
    ncols = static_cast<int>(per_cell);
    for (std::size_t c = 0; c < nc; ++c) {
      ids.push_back(blocks[lb].cell_ids[c]);
      const double* row = &h(c * (view.extent(0) / nc), 0);
      vals.insert(vals.end(), row, row + per_cell);
    }
  }
  return rows_table(m, ids, vals, ncols, m.mesh.num_volume_cells());
}

void put_scalars(const Model& m, const Stepper& st, const RunState& s, CheckpointData& d) {
  d.strings = {{"deck", m.cfg.deck_path}, {"deck_hash", deck_hash(m.cfg.deck_path)}, {"scheme", scheme_name(m)}, {"mesh", m.mesh.source}};
  const auto c = s.control.saved();
  const auto sc = st.scale_history();
  d.ints = {{"dim", m.dim}, {"num_nodes", static_cast<long long>(m.mesh.num_nodes())},
            {"num_cells", static_cast<long long>(m.mesh.num_volume_cells())}, {"num_stages", static_cast<long long>(m.cfg.stages.size())},
            {"ranks", m.nranks}, {"step", s.step}, {"attempts", s.attempts}, {"stage", s.stage},
            {"cuts_in_a_row", c.consecutive}, {"cuts_total", c.total}, {"newton_iterations", s.newton_iterations},
            {"linear_iterations", s.linear_iterations}, {"force_scale_count", sc.second}};
  const EnergyTotals& e = s.energy;
  d.reals = {{"time", s.t}, {"dt_last", s.dt_last}, {"dt_target", c.target}, {"dt_next", c.dt}, {"dt_min", c.min_dt},
             {"energy_external", e.external}, {"energy_support", e.support}, {"energy_dissipation", e.dissipation},
             {"energy_contact", e.contact}, {"energy_friction", e.friction}, {"energy_plastic", e.plastic},
             {"energy_max_balance", e.max_balance}, {"force_scale_sum", sc.first}, {"energy_stabilization", e.stabilization}};
  if (m.integrator) d.reals["mechanical_energy_n"] = m.integrator->energy_n();
  if (m.contact) {
    d.reals["contact_dt_last"] = m.contact->last_step();
    for (std::size_t p = 0; p < m.contact->num_pairs(); ++p) {
      const auto h = m.contact->normal_force_history(p);
      d.reals["contact_" + m.contact->pair_name(p) + "_normal_force_n"] = h[0];
      d.reals["contact_" + m.contact->pair_name(p) + "_normal_force_dt"] = h[1];
    }
  }
}

// The state to checkpoint: the scalars on every rank, each table's rows spread over the
// ranks in id order (rows_table). Collective.
CheckpointData collect(const Model& m, const Stepper& st, const RunState& s) {
  CheckpointData d;
  put_scalars(m, st, s, d);
  d.tables["u"] = node_table(m, s.u);
  d.tables["u_before_last"] = node_table(m, s.u_before_last);
  if (m.integrator)
    for (const auto& [name, v] : m.integrator->carried()) d.tables[name] = node_table(m, *v);
  if (m.contact)
    for (std::size_t p = 0; p < m.contact->num_pairs(); ++p) {
      const Contact::NodalFields h = m.contact->step_history(p);
      d.tables["contact_" + m.contact->pair_name(p)] = rows_table(m, h.nodes, h.values, Contact::kHistoryValues, m.mesh.num_nodes());
    }
  // A rank without cells of a plastic block has no history views: decide together.
  int local = m.assembler->has_history() ? 1 : 0, any = 0;
  Teuchos::reduceAll(*m.comm, Teuchos::REDUCE_MAX, 1, &local, &any);
  if (any)
    for (std::size_t b = 0; b < m.mesh.volumes.size(); ++b) {
      CheckpointTable t = history_table(m, b);
      if (t.ncols > 0) d.tables["gauss_points_" + std::to_string(b)] = std::move(t);
    }
  return d;
}

// Rank 0's error (or "") on every rank, then an InputError everywhere when there is one.
void agree(const Model& m, std::string err) {
  long long n = static_cast<long long>(err.size());
  Teuchos::broadcast(*m.comm, 0, &n);
  if (n == 0) return;
  err.resize(static_cast<std::size_t>(n));
  MPI_Bcast(err.data(), static_cast<int>(n), MPI_CHAR, 0, MPI_COMM_WORLD);
  throw InputError(err);
}

// Whether this rank keeps row `id` of table `name`: node tables the rows of its owned
// nodes (restore_vector), Gauss-point tables those of its cells (restore_gauss_points),
// contact tables all of them (a surface's worth).
struct RowFilter {
  std::vector<long long> cells;  // this rank's cells, sorted
  explicit RowFilter(const Model& m) {
    for (const auto& b : m.dist->blocks()) cells.insert(cells.end(), b.cell_ids.begin(), b.cell_ids.end());
    std::sort(cells.begin(), cells.end());
  }
  bool keep(const Model& m, const std::string& name, long long id) const {
    if (name.rfind("contact_", 0) == 0) return true;
    if (name.rfind("gauss_points_", 0) == 0) return std::binary_search(cells.begin(), cells.end(), id);
    return m.dist->owns_node(static_cast<GId>(id));
  }
};

// Rank 0 reads the file; every rank gets the scalars and, of each table, the rows it needs
// (RowFilter), or the same error. The tables go out in chunks of rows, so that no rank but
// 0 holds a whole table of the model's size.
CheckpointData read_everywhere(const Model& m, const std::string& path) {
  CheckpointData whole;
  std::string err;
  if (m.rank == 0) {
    try {
      whole = read_checkpoint_file(path);
    } catch (const std::exception& e) {
      err = std::string("cannot restart from ") + e.what();
    }
  }
  agree(m, err);
  CheckpointData outline;  // the scalars, and each table's columns without rows
  outline.reals = whole.reals, outline.ints = whole.ints, outline.strings = whole.strings;
  std::vector<long long> rows;
  for (const auto& [name, t] : whole.tables) {
    outline.tables[name].ncols = t.ncols;
    rows.push_back(static_cast<long long>(t.ids.size()));
  }
  std::vector<char> bytes = m.rank == 0 ? pack_checkpoint(outline) : std::vector<char>{};
  broadcast_bytes(bytes, raw_mpi_comm(*m.comm));
  CheckpointData d = unpack_checkpoint(bytes);
  rows.resize(d.tables.size());
  Teuchos::broadcast(*m.comm, 0, static_cast<int>(rows.size()), rows.data());
  const RowFilter filter(m);
  const long long chunk = 1 << 20;
  std::size_t k = 0;
  for (auto& [name, t] : d.tables) {
    const auto nc = static_cast<std::size_t>(t.ncols);
    const CheckpointTable* src = m.rank == 0 ? &whole.tables.at(name) : nullptr;
    for (long long first = 0; first < rows[k]; first += chunk) {
      const auto n = static_cast<std::size_t>(std::min(chunk, rows[k] - first)), at = static_cast<std::size_t>(first);
      std::vector<long long> ids(n);
      std::vector<double> values(n * nc);
      if (src) {
        std::copy_n(src->ids.begin() + static_cast<std::ptrdiff_t>(at), n, ids.begin());
        std::copy_n(src->values.begin() + static_cast<std::ptrdiff_t>(at * nc), n * nc, values.begin());
      }
      MPI_Bcast(ids.data(), static_cast<int>(n), MPI_LONG_LONG, 0, MPI_COMM_WORLD);
      MPI_Bcast(values.data(), static_cast<int>(n * nc), MPI_DOUBLE, 0, MPI_COMM_WORLD);
      for (std::size_t i = 0; i < n; ++i)
        if (filter.keep(m, name, ids[i])) {
          t.ids.push_back(ids[i]);
          t.values.insert(t.values.end(), values.begin() + static_cast<std::ptrdiff_t>(i * nc), values.begin() + static_cast<std::ptrdiff_t>((i + 1) * nc));
        }
    }
    ++k;
  }
  return d;
}

// Gauss-point values per cell of mesh volume block b on this rank (0: no history here).
int history_cols(const Model& m, std::size_t b) {
  const auto& blocks = m.dist->blocks();
  for (std::size_t lb = 0; lb < blocks.size(); ++lb) {
    const auto view = m.assembler->committed_history(lb);
    const std::size_t nc = blocks[lb].cell_ids.size();
    if (static_cast<std::size_t>(blocks[lb].volume_block) == b && view.extent(0) > 0 && nc > 0)
      return static_cast<int>(view.extent(0) / nc * view.extent(1));
  }
  return 0;
}

// The checkpoint's tables for contact pairs and Gauss points against the model. Collective.
void check_tables(const Model& m, const CheckpointData& d, const std::string& path) {
  std::vector<std::string> expected;
  if (m.contact)
    for (std::size_t p = 0; p < m.contact->num_pairs(); ++p) {
      const std::string name = "contact_" + m.contact->pair_name(p);
      const auto it = d.tables.find(name);
      if (it == d.tables.end() || it->second.ncols != Contact::kHistoryValues)
        throw InputError(path + ": no contact history for 'Contact->" + m.contact->pair_name(p) + "' (the checkpoint's run had other contact pairs)");
      expected.push_back(name);
    }
  for (std::size_t b = 0; b < m.mesh.volumes.size(); ++b) {
    int local = history_cols(m, b), cols = 0;
    Teuchos::reduceAll(*m.comm, Teuchos::REDUCE_MAX, 1, &local, &cols);
    if (cols == 0) continue;
    const std::string name = "gauss_points_" + std::to_string(b);
    const auto it = d.tables.find(name);
    if (it == d.tables.end() || it->second.ncols != cols)
      throw InputError(path + ": no Gauss-point state of " + std::to_string(cols) + " values per cell for block '" + m.mesh.volumes[b].name +
                       "' (the checkpoint's run had another material or mesh order there)");
    expected.push_back(name);
  }
  for (const auto& [name, t] : d.tables)
    if ((name.rfind("contact_", 0) == 0 || name.rfind("gauss_points_", 0) == 0) && std::find(expected.begin(), expected.end(), name) == expected.end())
      throw InputError(path + ": holds '" + name + "', which this deck has no use for (another contact pair or material?)");
}

// Every value the restart uses in its range (run/CheckpointCheck.hpp); a problem on any
// rank (each checks its rows of the node tables) is an InputError on every rank. Collective.
void check_values(const Model& m, const CheckpointData& d, const std::string& path) {
  std::string bad;
  try {
    bad = checkpoint_problem(m, d, path);
  } catch (const std::exception& e) {
    bad = path + ": " + e.what();
  }
  const Agreement a = agree_on_failure(*m.comm, bad);
  if (a.failed()) throw InputError(a.failure);
}

// Mesh, analysis, stages and tables against the model; the deck hash only warns.
void validate(const Model& m, const CheckpointData& d, const std::string& path, std::ostream& log) {
  try {
    std::ostringstream mine, theirs;
    mine << m.dim << "D, " << m.mesh.num_nodes() << " nodes, " << m.mesh.num_volume_cells() << " cells";
    theirs << d.integer("dim") << "D, " << d.integer("num_nodes") << " nodes, " << d.integer("num_cells") << " cells";
    if (mine.str() != theirs.str())
      throw InputError(path + ": checkpoint of a mesh with " + theirs.str() + " (" + d.string("mesh") + "); the deck's mesh " + m.mesh.source +
                       " has " + mine.str());
    if (d.string("scheme") != scheme_name(m))
      throw InputError(path + ": checkpoint of a '" + d.string("scheme") + "' run; the deck asks for '" + scheme_name(m) +
                       "' (Problem->analysis, Time Integration->scheme, the stages' analysis and scheme)");
    if (d.integer("num_stages") != static_cast<long long>(m.cfg.stages.size()))
      throw InputError(path + ": checkpoint of a run with " + std::to_string(d.integer("num_stages")) + " stages; the deck has " +
                       std::to_string(m.cfg.stages.size()) + " ('Stages')");
    check_tables(m, d, path);
    check_values(m, d, path);
    if (d.string("deck_hash") != deck_hash(m.cfg.deck_path))
      log << "warning: " << path << " was written by another deck (" << d.string("deck") << ", or it changed since); continuing with "
          << m.cfg.deck_path << "'s parameters\n";
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path + ": incomplete checkpoint: " + e.what());
  }
}

// The header and the rows with step <= `step` of a CSV file next to the checkpoint.
// `rows_at_step`: how many rows with step == `step` to take (-1: all). The energy CSV's
// row that opens a dynamic stage after a static one carries the static stage's last step
// number and is written after that step's checkpoint: the restart writes it again when it
// enters the stage, so it is not carried.
std::vector<std::string> csv_lines_until(const std::string& file, long long step, int rows_at_step = -1) {
  std::vector<std::string> lines;
  std::ifstream in(file);
  std::string line;
  int at_step = 0;
  while (std::getline(in, line)) {
    if (!lines.empty()) {
      const long long k = std::strtoll(line.c_str(), nullptr, 10);
      if (k > step || (k == step && rows_at_step >= 0 && at_step >= rows_at_step)) break;
      if (k == step) ++at_step;
    }
    lines.push_back(line);
  }
  return lines;
}

// A restart into the output folder of a run still running would move its staging folder
// away under it: refused before anything is read or moved. Rank 0 looks.
void refuse_running_output(const Model& m, const RunOptions& opts) {
  std::string err;
  if (m.rank == 0) {
    const std::string out = opts.output_dir.empty() ? m.cfg.output.directory : opts.output_dir;
    try {
      const std::string who = OutputDir::running_in(out);
      if (!who.empty())
        err = "cannot restart into '" + out + "': another run is writing into it: " + who +
              ". Wait for it to end, or choose another folder with --output DIR";
    } catch (const std::exception& e) {
      err = e.what();
    }
  }
  agree(m, err);
}

// The staging folder Reporter::open() would replace, when it is the checkpoint's folder:
// renamed to <dir>.interrupted first. Rank 0 acts; every rank gets the verdict.
void keep_interrupted_output(const Model& m, const std::string& path, const RunOptions& opts, std::ostream& log) {
  std::string err;
  if (m.rank == 0) {
    fs::path out(opts.output_dir.empty() ? m.cfg.output.directory : opts.output_dir);
    while (!out.has_filename() && out.has_parent_path() && out != out.parent_path()) out = out.parent_path();
    const std::string staging = out.string() + ".partial", kept = out.string() + ".interrupted";
    std::error_code ec;
    fs::path dir = fs::path(path).parent_path();
    if (dir.empty()) dir = ".";
    if (fs::exists(staging, ec) && fs::equivalent(dir, staging, ec)) {
      if (fs::exists(fs::symlink_status(kept, ec)))
        err = path + ": this run would replace " + staging + ", which holds the checkpoint, and " + kept +
              " already exists; remove or rename it, or restart with --output DIR";
      else if (fs::rename(staging, kept, ec); ec)
        err = path + ": cannot move " + staging + " to " + kept + ": " + ec.message();
      else
        log << "  restart  moved the interrupted run's " << staging << " to " << kept << "\n";
    }
  }
  agree(m, err);
}

}  // namespace

std::string checkpoint_path(const Reporter& reporter, const Model& model) {
  const std::string dir = reporter.staging_path();
  return dir.empty() ? std::string() : dir + "/" + model.cfg.output.basename + "_checkpoint.h5";
}

bool write_checkpoint(const Model& model, const Stepper& stepper, const RunState& s, const std::string& path, std::ostream& log,
                      const std::map<std::string, double>& extra) {
  CheckpointData d = collect(model, stepper, s);
  for (const auto& [key, value] : extra) d.reals[key] = value;
  try {  // every rank writes its rows; a failure anywhere is thrown on every rank
    write_checkpoint_file(path, d, raw_mpi_comm(*model.comm));
  } catch (const std::exception& e) {
    log << "  checkpoint at step " << s.step << " not written; the previous one stays\n" << std::flush;
    throw WriteError(std::string("writing the checkpoint at step ") + std::to_string(s.step) + " failed: " + e.what());
  }
  return true;
}

Restart read_restart(const std::string& path, const Model& model, const RunOptions& opts, std::ostream& log) {
  refuse_running_output(model, opts);
  Restart r;
  r.path = path;
  r.data = read_everywhere(model, path);
  validate(model, r.data, path, log);
  if (model.rank == 0) {
    const fs::path dir = fs::path(path).parent_path();
    const std::string stem = (dir.empty() ? fs::path(".") : dir).string() + "/" + model.cfg.output.basename;
    r.history_lines = csv_lines_until(stem + "_history.csv", r.data.integer("step"));
    if (model.any_dynamic) {
      // The checkpoint's step wrote an energy row if its stage is dynamic (and it is a step).
      const long long step = r.data.integer("step"), stage = r.data.integer("stage");
      const bool known = stage >= 0 && stage < model.cfg.interval_count();
      const bool row = step > 0 && (!known || model.cfg.dynamic_in(static_cast<int>(stage)));
      r.energy_lines = csv_lines_until(stem + "_energy.csv", step, row ? 1 : 0);
    }
  }
  keep_interrupted_output(model, path, opts, log);
  return r;
}

namespace {

// Rows of `t` into the owned entries of v (dim per node). Returns the owned nodes it lacks.
long restore_vector(const Model& m, const CheckpointTable& t, la::Vector& v) {
  long missing = 0;
  auto h = v.getLocalViewHost(Tpetra::Access::ReadWrite);
  for (la::LO n = 0; n < m.dist->num_owned_nodes(); ++n) {
    const double* row = t.find(m.dist->global_node(n));
    if (!row) {
      ++missing;
      continue;
    }
    for (int c = 0; c < m.dim; ++c) h(n * m.dim + c, 0) = row[c];
  }
  return missing;
}

// The committed (and trial) Gauss-point state of this rank's cells. Returns the cells it lacks.
long restore_gauss_points(Model& m, const CheckpointData& d) {
  long missing = 0;
  const auto& blocks = m.dist->blocks();
  for (std::size_t lb = 0; lb < blocks.size(); ++lb) {
    const auto view = m.assembler->committed_history(lb);
    const std::size_t nc = blocks[lb].cell_ids.size();
    if (view.extent(0) == 0 || nc == 0) continue;
    const CheckpointTable& t = d.table("gauss_points_" + std::to_string(blocks[lb].volume_block));
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), view);
    const std::size_t ngp = view.extent(0) / nc, per_cell = ngp * view.extent(1);
    for (std::size_t c = 0; c < nc; ++c) {
      const double* row = t.find(blocks[lb].cell_ids[c]);
      if (!row) {
        ++missing;
        continue;
      }
      std::copy(row, row + per_cell, &h(c * ngp, 0));
    }
    Kokkos::deep_copy(view, h);
  }
  m.assembler->rollback_history();  // trial = committed
  return missing;
}

// The deck's step and minimum step of the interval the run resumes in: a deck that
// changed them (a continued run with other steps) takes effect at once; the step size
// of the controller is the checkpoint's, at most the deck's.
StepControl::Saved step_control(const Config& cfg, const CheckpointData& d, int stage) {
  const SteppingConfig& st = cfg.stepping;
  double target = st.end_time / st.num_steps, min_dt = st.min_step();
  if (!cfg.stages.empty()) {
    target = cfg.stages[static_cast<std::size_t>(stage)].step();
    min_dt = st.min_dt > 0.0 ? st.min_dt : 1e-6 * target;
  }
  return {target, std::min(target, d.real("dt_next")), min_dt, static_cast<int>(d.integer("cuts_in_a_row")),
          static_cast<int>(d.integer("cuts_total"))};
}

void restore_scalars(const Config& cfg, const CheckpointData& d, Stepper& stepper, RunState& s) {
  s.t = d.real("time");
  s.dt_last = d.real("dt_last");
  s.step = static_cast<int>(d.integer("step"));
  s.attempts = d.integer("attempts");
  s.stage = static_cast<int>(d.integer("stage"));
  s.newton_iterations = static_cast<int>(d.integer("newton_iterations"));
  s.linear_iterations = static_cast<int>(d.integer("linear_iterations"));
  if (s.stage < 0 || (cfg.stages.empty() ? s.stage != 0 : s.stage >= static_cast<int>(cfg.stages.size())))
    throw std::runtime_error("stage " + std::to_string(s.stage) + " does not exist in the deck");
  s.control.restore(step_control(cfg, d, s.stage));
  EnergyTotals& e = s.energy;
  e.external = d.real("energy_external");
  e.support = d.real("energy_support");
  e.dissipation = d.real("energy_dissipation");
  e.contact = d.real("energy_contact");
  e.friction = d.real("energy_friction");
  e.plastic = d.real("energy_plastic");
  e.max_balance = d.real("energy_max_balance");
  // Checkpoints written before the static stabilisation existed do not hold it: none was absorbed.
  e.stabilization = d.reals.count("energy_stabilization") ? d.real("energy_stabilization") : 0.0;
  stepper.restore_scale_history(d.real("force_scale_sum"), static_cast<long>(d.integer("force_scale_count")));
}

}  // namespace

void restore(const Restart& r, Model& m, Stepper& stepper, RunState& s) {
  const CheckpointData& d = r.data;
  long missing = 0;
  try {
    restore_scalars(m.cfg, d, stepper, s);
    missing += restore_vector(m, d.table("u"), s.u);
    missing += restore_vector(m, d.table("u_before_last"), s.u_before_last);
    if (m.integrator) {
      for (const auto& [name, v] : m.integrator->carried()) missing += restore_vector(m, d.table(name), *v);
      m.integrator->set_energy_n(d.real("mechanical_energy_n"));
    }
    if (m.contact) {
      stepper.attach_contact(s);  // end time, master positions at u_n
      for (std::size_t p = 0; p < m.contact->num_pairs(); ++p) {
        const CheckpointTable& t = d.table("contact_" + m.contact->pair_name(p));
        missing += m.contact->restore_step_history(p, Contact::NodalFields{t.ids, t.values});
      }
      m.contact->set_last_step(d.real("contact_dt_last"));
      // The two-step mean of the contact force (a checkpoint written before it had none: the
      // first step after the restart then reports its own force).
      for (std::size_t p = 0; p < m.contact->num_pairs(); ++p) {
        const std::string key = "contact_" + m.contact->pair_name(p) + "_normal_force_";
        if (d.reals.count(key + "n") && d.reals.count(key + "dt"))
          m.contact->restore_normal_force_history(p, d.real(key + "n"), d.real(key + "dt"));
      }
    }
    missing += restore_gauss_points(m, d);
  } catch (const std::runtime_error& e) {  // the same data on every rank: every rank throws
    throw InputError(r.path + ": incomplete checkpoint: " + e.what());
  }
  long total = 0;
  Teuchos::reduceAll(*m.comm, Teuchos::REDUCE_SUM, 1, &missing, &total);
  if (total > 0)
    throw InputError(r.path + ": " + std::to_string(total) + " nodes, cells or contact nodes of the deck's mesh are not in the checkpoint");
}

namespace {

// `lines` (header first) into `csv` when the header names its columns.
void carry(const std::vector<std::string>& lines, CsvWriter* csv, const std::string& path, std::ostream& log) {
  if (!csv || lines.empty()) return;
  std::string header;
  for (const auto& c : csv->columns()) header += (header.empty() ? "" : ",") + c;
  if (lines[0] != header) {
    log << "warning: " << path << " next to the checkpoint has other columns; the rows before the restart are not copied\n";
    return;
  }
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::vector<double> row;
    std::istringstream in(lines[i]);
    std::string cell;
    while (std::getline(in, cell, ',')) row.push_back(std::strtod(cell.c_str(), nullptr));
    if (row.size() != csv->columns().size()) break;  // a row cut short by the crash
    csv->row(row);
  }
}

}  // namespace

void carry_rows(const Restart& r, Reporter& reporter, std::ostream& log) {
  const std::string dir = fs::path(r.path).parent_path().string();
  const std::string stem = (dir.empty() ? std::string(".") : dir) + "/" + reporter.basename();
  carry(r.history_lines, reporter.history_csv(), stem + "_history.csv", log);
  carry(r.energy_lines, reporter.energy_csv(), stem + "_energy.csv", log);
}

}  // namespace stentor
