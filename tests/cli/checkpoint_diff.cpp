// checkpoint_diff A.h5 B.h5 TOL: compares two Stentor checkpoints (the complete state of
// two runs at the same step), for the restart tests. Per table (u, velocity, contact
// history, Gauss-point state, ...): the same ids, and max |a - b| over the table divided by
// max |a| over it; per real scalar: |a - b| / max(|a|, |b|), energy terms relative to the
// largest energy term; integers (counters, step, stage) must be equal, except `ranks` and
// the iteration totals (reported). Prints one line per item and the largest difference;
// exit 0 when it is <= TOL, 1 otherwise, 2 when a file cannot be read.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "io/Checkpoint.hpp"

using stentor::CheckpointData;

namespace {

double table_diff(const stentor::CheckpointTable& a, const stentor::CheckpointTable& b, bool& same_layout) {
  same_layout = a.ncols == b.ncols && a.ids == b.ids && a.values.size() == b.values.size();
  if (!same_layout) return INFINITY;
  double scale = 0.0, diff = 0.0;
  for (std::size_t i = 0; i < a.values.size(); ++i) {
    scale = std::fmax(scale, std::fabs(a.values[i]));
    diff = std::fmax(diff, std::fabs(a.values[i] - b.values[i]));
  }
  return scale > 0.0 ? diff / scale : diff;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: checkpoint_diff A.h5 B.h5 TOL\n");
    return 2;
  }
  CheckpointData a, b;
  try {
    a = stentor::read_checkpoint_file(argv[1]);
    b = stentor::read_checkpoint_file(argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "checkpoint_diff: %s\n", e.what());
    return 2;
  }
  const double tol = std::atof(argv[3]);
  double worst = 0.0;
  std::string where = "-";
  auto note = [&](const std::string& name, double d) {
    std::printf("  %-28s %.3e\n", name.c_str(), d);
    if (!(d <= worst)) worst = d, where = name;
  };
  for (const auto& [name, ta] : a.tables) {
    const auto it = b.tables.find(name);
    bool same = false;
    const double d = it == b.tables.end() ? INFINITY : table_diff(ta, it->second, same);
    note("table " + name + (same ? "" : " (layout differs)"), d);
  }
  if (a.tables.size() != b.tables.size()) note("number of tables", INFINITY);
  // Energy terms (some are sums of nearly cancelling terms, e.g. the contact work of a
  // frictionless impact) relative to the largest of them.
  auto is_energy = [](const std::string& n) { return n.rfind("energy_", 0) == 0 || n == "mechanical_energy_n"; };
  double energy_scale = 0.0;
  for (const auto& [name, va] : a.reals)
    if (is_energy(name)) energy_scale = std::fmax(energy_scale, std::fabs(va));
  for (const auto& [name, va] : a.reals) {
    const auto it = b.reals.find(name);
    const double vb = it == b.reals.end() ? NAN : it->second;
    const double s = is_energy(name) ? energy_scale : std::fmax(std::fabs(va), std::fabs(vb));
    note(name, s > 0.0 ? std::fabs(va - vb) / s : std::fabs(va - vb));
  }
  for (const auto& [name, va] : a.ints) {
    if (name == "ranks") continue;
    const auto it = b.ints.find(name);
    if (name == "newton_iterations" || name == "linear_iterations") {  // may differ by one on another partition: reported only
      if (it != b.ints.end() && it->second != va) std::printf("  note: %s %lld vs %lld\n", name.c_str(), va, it->second);
      continue;
    }
    if (it == b.ints.end() || it->second != va) note(name + " (integer differs)", INFINITY);
  }
  std::printf("max relative difference %.3e (%s), tolerance %.1e\n", worst, where.c_str(), tol);
  return worst <= tol ? 0 : 1;
}
