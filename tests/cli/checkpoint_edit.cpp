// checkpoint_edit IN OUT EDIT...: a hand-edited checkpoint, as a user or an attacker can
// make one with any HDF5 tool, written with a valid checksum (so that the restart's own
// checks, not the checksum, must find what is wrong). For the hostile-checkpoint tests.
// EDIT: real NAME VALUE | int NAME VALUE | string NAME VALUE | drop-real NAME | drop-int NAME
//     | cell TABLE ROW COL VALUE  (VALUE may be nan, inf, -inf)
//     | cols TABLE N              (the table's rows cut or padded with zeros to N columns)
//     | drop TABLE                (the table removed)
// Exit 0 when written, 2 when IN cannot be read or an edit is malformed.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "io/Checkpoint.hpp"

namespace {

void set_columns(stentor::CheckpointTable& t, int n) {
  std::vector<double> v;
  for (std::size_t r = 0; r < t.ids.size(); ++r)
    for (int c = 0; c < n; ++c) v.push_back(c < t.ncols ? t.values[r * static_cast<std::size_t>(t.ncols) + static_cast<std::size_t>(c)] : 0.0);
  t.values.swap(v);
  t.ncols = n;
}

// Applies the edit at argv[i]; returns the index after it.
int apply(stentor::CheckpointData& d, int argc, char** argv, int i) {
  const std::string op = argv[i];
  const auto arg = [&](int k) -> std::string {
    if (i + k >= argc) throw std::runtime_error("edit '" + op + "' needs more arguments");
    return argv[i + k];
  };
  if (op == "real") return d.reals[arg(1)] = std::strtod(arg(2).c_str(), nullptr), i + 3;
  if (op == "int") return d.ints[arg(1)] = std::strtoll(arg(2).c_str(), nullptr, 10), i + 3;
  if (op == "string") return d.strings[arg(1)] = arg(2), i + 3;
  if (op == "drop-real") return d.reals.erase(arg(1)), i + 2;
  if (op == "drop-int") return d.ints.erase(arg(1)), i + 2;
  if (op == "drop") return d.tables.erase(arg(1)), i + 2;
  if (op == "cols") return set_columns(d.tables.at(arg(1)), std::atoi(arg(2).c_str())), i + 3;
  if (op == "cell") {
    stentor::CheckpointTable& t = d.tables.at(arg(1));
    const std::size_t row = std::strtoul(arg(2).c_str(), nullptr, 10), col = std::strtoul(arg(3).c_str(), nullptr, 10);
    if (row >= t.ids.size() || col >= static_cast<std::size_t>(t.ncols)) throw std::runtime_error("no cell " + arg(2) + ", " + arg(3));
    t.values[row * static_cast<std::size_t>(t.ncols) + col] = std::strtod(arg(4).c_str(), nullptr);
    return i + 5;
  }
  throw std::runtime_error("unknown edit '" + op + "'");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: checkpoint_edit IN OUT EDIT...\n");
    return 2;
  }
  try {
    stentor::CheckpointData d = stentor::read_checkpoint_file(argv[1]);
    for (int i = 3; i < argc;) i = apply(d, argc, argv, i);
    stentor::write_checkpoint_file(argv[2], d);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "checkpoint_edit: %s\n", e.what());
    return 2;
  }
  return 0;
}
