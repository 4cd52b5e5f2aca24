#include "run/StopRequest.hpp"

#include <csignal>
#include <cstdlib>
#include <string>

#include <Teuchos_Comm.hpp>
#include <Teuchos_CommHelpers.hpp>

namespace stentor {

namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void record_stop(int sig) { g_signal = sig; }

}  // namespace

void install_stop_handlers() {
  struct sigaction sa {};
  sa.sa_handler = record_stop;
  sigemptyset(&sa.sa_mask);
  // The handler runs once per signal number; the next delivery takes the default action.
  sa.sa_flags = SA_RESETHAND | SA_RESTART;
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGINT, &sa, nullptr);
}

int stop_signal() { return static_cast<int>(g_signal); }

int agreed_stop_signal(const Teuchos::Comm<int>& comm) {
  const int mine = stop_signal();
  if (comm.getSize() == 1) return mine;
  int all = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, mine, Teuchos::outArg(all));
  return all;
}

void test_signal_hook(int step, int rank) {
  const char* v = std::getenv("STENTOR_TEST_SIGNAL_AT_STEP");
  if (!v || !*v) return;
  const std::string s = v;
  const auto colon = s.find(':');
  const int at = std::atoi(s.c_str());
  const int who = colon == std::string::npos ? 0 : std::atoi(s.c_str() + colon + 1);
  if (step == at && rank == who) std::raise(SIGTERM);
}

}  // namespace stentor
