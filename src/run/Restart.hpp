// Checkpoints and restart (docs/deck.md, "Checkpoints and restart").
//
// A checkpoint holds everything the next step depends on, so that a restarted run takes
// the same steps as the run that wrote it: time, step and attempt counters, stage, the
// step-size controller, u_n and u_{n-1} (static predictor), the time scheme's carried
// vectors (v_n; a_n and the t_n residual/force for newmark/hht) and E_n, the energy-audit
// totals, Newton's force-scale mean, the contact history per slave node and the committed
// Gauss-point state. Node data are keyed by global node id, Gauss-point data by global cell
// id and contact data by slave node id, so a checkpoint written on R ranks is read on any
// number of ranks. Layout: io/Checkpoint.hpp; the names are in Restart.cpp.
#pragma once
#include <ostream>
#include <map>
#include <string>
#include <vector>

#include "io/Checkpoint.hpp"

namespace stentor {

struct Model;
struct RunOptions;
struct RunState;
class Reporter;
class Stepper;

// `<staging folder>/<basename>_checkpoint.h5`, on every rank (after Reporter::open()).
std::string checkpoint_path(const Reporter& reporter, const Model& model);

// Writes the state after an accepted step to `path` atomically, every rank its rows
// (collective; the same `path` on every rank), and returns true. Throws WriteError on
// every rank when the file could not be written on any one (the ranks agree before
// closing it; the run then stops with exit status 3, as for any failed result write;
// rank 0 notes on `log` that the previous checkpoint stays).
// `extra`: more scalars for /reals (the stent metrics' state, Reporter::metrics_state()).
bool write_checkpoint(const Model& model, const Stepper& stepper, const RunState& s, const std::string& path, std::ostream& log,
                      const std::map<std::string, double>& extra = {});

// A checkpoint read for a restart, on every rank.
struct Restart {
  std::string path;
  CheckpointData data;
  // Rank 0: the lines of the interrupted run's <basename>_history.csv and _energy.csv (found
  // next to the checkpoint), header first, rows up to the checkpoint's step only.
  std::vector<std::string> history_lines, energy_lines;
};

// Reads `path` (rank 0, then broadcast) and checks it against the model: mesh dimension,
// node and cell counts, analysis and scheme, stages, contact pairs, Gauss-point layout, and
// every value's range and cross-reference (run/CheckpointCheck.hpp). First, a run still
// writing into the output folder (its lock held) is an InputError: nothing is touched.
// A mismatch is an InputError naming the file; a checkpoint written by another deck (other
// file contents) is only a warning on `log`. Collective. Call before Reporter::open(): when
// the checkpoint lies in the staging folder that open() would replace (<dir>.partial of an
// interrupted run), that folder is first renamed to <dir>.interrupted (an existing one is an
// InputError: nothing is removed).
Restart read_restart(const std::string& path, const Model& model, const RunOptions& opts, std::ostream& log);

// Sets the run's state from the checkpoint (instead of the initial conditions). Collective;
// an InputError when a node, cell or slave node of this rank is not in the file.
void restore(const Restart& r, Model& model, Stepper& stepper, RunState& s);

// Rank 0, after Reporter::open(): the interrupted run's CSV rows up to the checkpoint into
// the new files, when their columns are the same (else a warning on `log`).
void carry_rows(const Restart& r, Reporter& reporter, std::ostream& log);

}  // namespace stentor
