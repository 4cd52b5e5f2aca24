// The linear solver's fallback chain is used up (LinearSolver.hpp): thrown by setup() and
// solve() on every rank alike. Newton turns it into a failed iteration (cut-back); where
// it escapes (the initial-acceleration solve), the run ends with exit status 3.
#pragma once
#include <stdexcept>

namespace stentor {

struct LinearSolverFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace stentor
