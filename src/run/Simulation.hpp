// One run of a deck, start to finish: mesh -> partition -> assembly -> load steps
// (Newton, cut-back on failure) -> results. The loop in Simulation.cpp reads like the
// algorithm; each step's pieces live in their own folders.
#pragma once
#include <string>

#include <array>
#include <vector>

#include "deck/Config.hpp"
#include "mesh/Mesh.hpp"

namespace stentor {

struct RunOptions {
  std::string output_dir;   // overrides Output->directory when not empty
  bool verbose = false;     // per-Newton-iteration lines
  bool check_only = false;  // validate deck + mesh + groups, then stop
  bool overwrite = false;   // write into a non-empty output folder that is not Stentor's (see io/OutputDir.hpp)
  std::string restart_file; // continue from this checkpoint (Output->checkpoint every) instead of t = 0
  std::string version;      // the program's version (stentor --version), printed in the run's header
};

// What a run leaves in memory, for tests and programs that embed Stentor.
struct RunResult {
  Mesh mesh;                          // as read: whole on one rank, this rank's part on several (mesh/Mesh.hpp)
  std::vector<double> displacement;   // final state, 3 per mesh node (z = 0 in 2D), on every rank
  std::vector<std::array<double, 3>> reactions;  // final, per Dirichlet set (deck order)
  double energy = 0.0;                // final stored energy
  int steps = 0, cutbacks = 0, newton_iterations = 0, linear_iterations = 0;
  bool converged = false;
};

// Exit status: 0 success, 2 bad input (InputError thrown), 3 the solve failed
// (results written so far stay in <output>.partial; a failed write throws WriteError).
int run_simulation(const Config& cfg, const RunOptions& opts, RunResult* result = nullptr);

}  // namespace stentor
