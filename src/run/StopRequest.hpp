// Stopping a run cleanly on SIGTERM or SIGINT: a batch system's time limit (Slurm, PBS
// send SIGTERM some time before SIGKILL) or Ctrl-C. The first signal only records itself;
// the time loop looks at it between steps (every rank agrees on it there), ends the step
// in progress, writes the fields and a checkpoint of the last accepted step and stops with
// exit status 128 + the signal (143 for SIGTERM, 130 for SIGINT), the results in the
// `.partial` folder. A second signal of either kind ends the process at once (the default
// action): the checkpoint written before it stays valid (checkpoints are replaced by
// rename, io/Checkpoint.hpp).
#pragma once

namespace Teuchos {
template <typename Ordinal>
class Comm;
}

namespace stentor {

// Installs the handlers (main, once, after MPI is up).
void install_stop_handlers();

// The signal this rank received (0: none). Async-signal-safe to set, cheap to read.
int stop_signal();

// Collective, once per step: the largest signal any rank received (0: none), so that every
// rank stops after the same step (the ranks of an mpirun or srun job receive a signal at
// slightly different times).
int agreed_stop_signal(const Teuchos::Comm<int>& comm);

// Test hook (tests/cli/stop_signal.sh): STENTOR_TEST_SIGNAL_AT_STEP=N[:R] makes rank R
// (default 0) send itself SIGTERM after accepted step N, through the real handler.
void test_signal_hook(int step, int rank);

}  // namespace stentor
