// One run of a deck, start to finish: mesh -> partition -> assembly -> load steps
// (Newton, cut-back on failure) -> results. The loop in Simulation.cpp reads like the
// algorithm; each step's pieces live in their own folders.
#pragma once
#include <string>

#include "deck/Config.hpp"

namespace stentor {

struct RunOptions {
  std::string output_dir;   // overrides Output->directory when not empty
  bool verbose = false;     // per-Newton-iteration lines
  bool check_only = false;  // validate deck + mesh + groups, then stop
};

// Exit status: 0 success, 2 bad input (InputError thrown), 3 the solve failed
// (results written so far stay in <output>.partial).
int run_simulation(const Config& cfg, const RunOptions& opts);

}  // namespace stentor
