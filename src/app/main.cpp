// stentor: command-line entry point.
#include <Kokkos_Macros.hpp>
#include <Tpetra_Core.hpp>
#include <Trilinos_version.h>
#include <hdf5.h>
#include <mpi.h>

#include <chrono>
#include <csignal>
#include <unistd.h>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "deck/Config.hpp"
#include "deck/InputLimits.hpp"
#include "io/LogCopy.hpp"
#include "io/WriteError.hpp"
#include "mesh/GmshReader.hpp"
#include "run/Simulation.hpp"
#include "run/StopRequest.hpp"
#include "solver/SolverFailure.hpp"

namespace {

const char* kUsage =
    "usage: stentor [options] DECK.xml\n"
    "       mpirun -np N stentor [options] DECK.xml\n"
    "\n"
    "Runs the simulation an XML input deck describes (see docs/deck.md).\n"
    "\n"
    "options:\n"
    "  --check        validate the deck, its mesh and everything set up before the first\n"
    "                 step (groups, materials, loads, contact pairs, initial state); write nothing\n"
    "  --output DIR   write results to DIR (overrides Output->directory)\n"
    "  --overwrite    write into DIR even when it is not empty and holds no Stentor results\n"
    "                 (files with the names of the results are replaced, no other file)\n"
    "  --restart FILE continue from checkpoint FILE (Output->checkpoint every), on any number of ranks\n"
    "  --max-input-size SIZE  refuse a deck or .geo (or a file it includes) larger than SIZE,\n"
    "                 unread (bytes, or with k, M, G: 64M, 1G; default 64M)\n"
    "  --max-mesh-size SIZE   the same for .msh and CAD files (default 16G)\n"
    "  --verbose      print every Newton iteration\n"
    "  --version      print Stentor's version and the library versions it was built with\n"
    "  --help         this text\n"
    "  --kokkos-...   Kokkos's own options (--kokkos-help lists them)\n"
    "\n"
    "exit status: 0 success, 1 internal error, 2 invalid input (or an output folder that\n"
    "may not be used), 3 the solve or writing a result file failed, 4 out of memory;\n"
    "under MPI an error on any one rank ends every rank with that status;\n"
    "SIGTERM or SIGINT (a batch time limit, Ctrl-C) ends the step in progress, writes its\n"
    "fields and a checkpoint and exits 143 or 130 (128 + the signal); a second signal\n"
    "ends the run at once\n";

#ifndef STENTOR_VERSION
#define STENTOR_VERSION "unknown"
#endif
// STENTOR_GIT_DESCRIBE: `git describe` of the sources at build time (cmake/GitDescribe.cmake).
#include "stentor_git.h"

std::string version_text() {
  const std::string git = STENTOR_GIT_DESCRIBE;
  return std::string("stentor ") + STENTOR_VERSION + (git.empty() ? "" : " (git " + git + ")") + "\n" +
         "Trilinos " + TRILINOS_VERSION_STRING + ", Kokkos " + std::to_string(KOKKOS_VERSION / 10000) + "." +
         std::to_string(KOKKOS_VERSION / 100 % 100) + "." + std::to_string(KOKKOS_VERSION % 100) + ", HDF5 " +
         std::to_string(H5_VERS_MAJOR) + "." + std::to_string(H5_VERS_MINOR) + "." + std::to_string(H5_VERS_RELEASE) + "\n";
}

// --help and --version are Stentor's: taken out of the arguments before Kokkos sees
// them (Kokkos::initialize answers --help with its own 40 lines; --kokkos-help still
// reaches it). The argument after --output/--restart is a value, never an option.
struct EarlyOptions {
  bool help = false, version = false;
  std::vector<char*> rest;  // argv without them, null-terminated
};
EarlyOptions early_options(int argc, char** argv) {
  EarlyOptions e;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (i > 0 && (a == "--help" || a == "-h")) {
      e.help = true;
      continue;
    }
    if (i > 0 && a == "--version") {
      e.version = true;
      continue;
    }
    e.rest.push_back(argv[i]);
    if ((a == "--output" || a == "-o" || a == "--restart" || a == "--max-input-size" || a == "--max-mesh-size") &&
        i + 1 < argc)
      e.rest.push_back(argv[++i]);
  }
  e.rest.push_back(nullptr);
  return e;
}

// A communicator of its own for agreeing on failures (duplicated at start-up, so that
// it never mixes with the collectives of the run).
MPI_Comm g_fail_comm = MPI_COMM_NULL;

// Ends the run after an error caught on this rank; rank 0 explains. On one rank:
// returns `code`. On several, the other ranks may not have seen the error and would wait
// for this one in their next collective forever: the failing ranks meet in a barrier on
// g_fail_comm for up to 3 s; when every rank arrives (a deck error that every rank sees)
// each returns `code`, else this rank explains and ends every rank with
// MPI_Abort(code) (mpirun then exits with `code`).
int fail_all_ranks(int rank, int size, int code, const std::string& msg) {
  if (rank == 0) std::cerr << msg << std::flush;
  if (size == 1 || g_fail_comm == MPI_COMM_NULL) return code;
  MPI_Request req;
  int done = 0;
  if (MPI_Ibarrier(g_fail_comm, &req) == MPI_SUCCESS) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(3);
    while (!done && std::chrono::steady_clock::now() < deadline) {
      MPI_Test(&req, &done, MPI_STATUS_IGNORE);
      if (!done) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  if (done) return code;
  if (rank != 0) std::cerr << "[rank " << rank << "] " << msg << std::flush;
  std::cerr << "stentor: the error above happened on rank " << rank << " only; ending all " << size
            << " ranks (exit status " << code << ")\n" << std::flush;
  MPI_Abort(MPI_COMM_WORLD, code);
  return code;
}

// Test hook (documented in tests/cli/CMakeLists.txt): STENTOR_TEST_FAIL_RANK=R[:input|:alloc]
// makes rank R alone throw after reading the deck, an internal error (exit 1), with
// ":input" an input error (exit 2), with ":alloc" std::bad_alloc (out of memory, exit 4),
// to check that one rank's failure ends every rank.
void test_failure_hook(int rank) {
  const char* v = std::getenv("STENTOR_TEST_FAIL_RANK");
  if (!v || !*v) return;
  const std::string s = v;
  const auto ends_with = [&s](const std::string& tail) {
    return s.size() > tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
  };
  if (std::atoi(s.c_str()) != rank) return;
  if (ends_with(":alloc")) throw std::bad_alloc();
  const std::string what = "failure injected on rank " + std::to_string(rank) + " (STENTOR_TEST_FAIL_RANK)";
  if (ends_with(":input")) throw stentor::InputError(what);
  throw std::runtime_error(what);
}

}  // namespace

int main(int argc, char** argv) {
  // gmsh's own process (mesh/GmshReader.hpp): no MPI, no Kokkos, only gmsh.
  if (argc > 1 && std::strcmp(argv[1], "--gmsh-helper") == 0) return stentor::gmsh_helper_main(argc, argv);
  // The log is line-buffered even when redirected to a file: a killed batch job keeps
  // every line written so far (the progress line is also flushed every step).
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  // A file size limit (ulimit -f) makes a write fail with EFBIG, reported like a full
  // disk, instead of killing the process with SIGXFSZ.
  std::signal(SIGXFSZ, SIG_IGN);
  EarlyOptions early = early_options(argc, argv);
  argc = static_cast<int>(early.rest.size()) - 1;
  argv = early.rest.data();
  Tpetra::ScopeGuard guard(&argc, &argv);
  const int rank = Tpetra::getDefaultComm()->getRank();
  stentor::install_stop_handlers();
  if (early.help || early.version) {
    if (rank == 0) std::cout << (early.help ? kUsage : "") << (early.help && early.version ? "\n" : "")
                             << (early.version ? version_text() : "") << std::flush;
    return 0;
  }
  // Rank 0's log, copied into the results (<basename>.log) once the folder exists.
  struct LogCopyGuard {
    explicit LogCopyGuard(bool on) { if (on) stentor::log_copy::start(); }
    ~LogCopyGuard() { stentor::log_copy::stop(); }
  } log_copy_guard(rank == 0);
  MPI_Comm_dup(MPI_COMM_WORLD, &g_fail_comm);
  {
    // gmsh reads and meshes in a child process of this executable (a crash, hang or exit
    // in gmsh becomes an input error naming the file).
    char exe[4096];
    const ssize_t n = ::readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
      exe[n] = '\0';
      stentor::enable_gmsh_process(exe);
    }
  }
  stentor::RunOptions opts;
  {  // "stentor X (git Y); Trilinos ..., Kokkos ..., HDF5 ...": version_text() on one line
    std::string v = version_text();
    v.pop_back();
    v.replace(v.find('\n'), 1, "; ");
    opts.version = v;
  }
  std::string deck;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--check") {
      opts.check_only = true;
    } else if (a == "--overwrite") {
      opts.overwrite = true;
    } else if (a == "--verbose" || a == "-v") {
      opts.verbose = true;
    } else if (a == "--output" || a == "-o") {
      if (i + 1 >= argc) {
        if (rank == 0) std::cerr << "stentor: error: --output needs a directory\n" << kUsage;
        return 2;
      }
      opts.output_dir = argv[++i];
    } else if (a == "--max-input-size" || a == "--max-mesh-size") {
      std::uint64_t& limit = a == "--max-input-size" ? stentor::input_limits().text : stentor::input_limits().mesh;
      if (i + 1 >= argc || !stentor::parse_size(argv[i + 1], limit)) {
        if (rank == 0)
          std::cerr << "stentor: error: " << a << " needs a size > 0 in bytes, or with k, M, G or T (e.g. 512M), got '"
                    << (i + 1 < argc ? argv[i + 1] : "") << "'\n";
        return 2;
      }
      ++i;
    } else if (a == "--restart") {
      if (i + 1 >= argc) {
        if (rank == 0) std::cerr << "stentor: error: --restart needs a checkpoint file\n" << kUsage;
        return 2;
      }
      opts.restart_file = argv[++i];
    } else if (!a.empty() && a[0] == '-') {
      if (rank == 0) std::cerr << "stentor: error: unknown option '" << a << "'\n" << kUsage;
      return 2;
    } else if (deck.empty()) {
      deck = a;
    } else {
      if (rank == 0) std::cerr << "stentor: error: more than one deck given ('" << deck << "', '" << a << "')\n";
      return 2;
    }
  }
  if (deck.empty()) {
    if (rank == 0) std::cerr << "stentor: error: no input deck given\n" << kUsage;
    return 2;
  }
  const int size = Tpetra::getDefaultComm()->getSize();
  try {
    stentor::current_phase() = "reading the deck " + deck;
    const stentor::Config cfg = stentor::read_deck(deck);
    stentor::current_phase() = "setting up the run";
    test_failure_hook(rank);
    return stentor::run_simulation(cfg, opts);
  } catch (const stentor::InputError& e) {
    return fail_all_ranks(rank, size, 2, std::string("stentor: error: ") + e.what() + "\n");
  } catch (const stentor::WriteError& e) {
    const int code = fail_all_ranks(rank, size, 3, std::string("stentor: error: ") + e.what() +
                                                       "; the run stopped (results written so far are kept in the .partial folder)\n");
    // No MPI_Finalize: it shuts HDF5 down, and HDF5 1.10 crashes (SIGSEGV) closing a file
    // whose last write failed. Nothing is left to write.
    stentor::log_copy::stop();
    std::fflush(nullptr);
    std::_Exit(code);
  } catch (const stentor::LinearSolverFailure& e) {
    return fail_all_ranks(rank, size, 3, std::string("stentor: error: the linear solver failed: ") + e.what() + "\n");
  } catch (const std::bad_alloc&) {
    return fail_all_ranks(rank, size, 4, "stentor: error: out of memory on rank " + std::to_string(rank) + " while " +
                                             stentor::current_phase() + " (exit status 4); give the run more memory "
                                             "(more ranks or nodes, a higher ulimit -v), or make the model smaller\n");
  } catch (const std::exception& e) {
    return fail_all_ranks(rank, size, 1, "stentor: internal error on rank " + std::to_string(rank) + ": " + e.what() + "\n");
  } catch (...) {
    return fail_all_ranks(rank, size, 1, "stentor: internal error on rank " + std::to_string(rank) + ": unknown exception\n");
  }
}
