// stentor: command-line entry point.
#include <Tpetra_Core.hpp>

#include <cstring>
#include <iostream>

#include "deck/Config.hpp"
#include "run/Simulation.hpp"

namespace {

const char* kUsage =
    "usage: stentor [options] DECK.xml\n"
    "       mpirun -np N stentor [options] DECK.xml\n"
    "\n"
    "Runs the simulation an XML input deck describes (see docs/deck.md).\n"
    "\n"
    "options:\n"
    "  --check        validate the deck and its mesh (groups, materials, loads), run nothing\n"
    "  --output DIR   write results to DIR (overrides Output->directory)\n"
    "  --verbose      print every Newton iteration\n"
    "  --help         this text\n"
    "\n"
    "exit status: 0 success, 1 internal error, 2 invalid input, 3 the solve failed\n";

}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  const int rank = Tpetra::getDefaultComm()->getRank();
  stentor::RunOptions opts;
  std::string deck;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      if (rank == 0) std::cout << kUsage;
      return 0;
    } else if (a == "--check") {
      opts.check_only = true;
    } else if (a == "--verbose" || a == "-v") {
      opts.verbose = true;
    } else if (a == "--output" || a == "-o") {
      if (i + 1 >= argc) {
        if (rank == 0) std::cerr << "stentor: error: --output needs a directory\n" << kUsage;
        return 2;
      }
      opts.output_dir = argv[++i];
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
  try {
    const stentor::Config cfg = stentor::read_deck(deck);
    return stentor::run_simulation(cfg, opts);
  } catch (const stentor::InputError& e) {
    if (rank == 0) std::cerr << "stentor: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "stentor: internal error on rank " << rank << ": " << e.what() << "\n";
    return 1;
  }
}
