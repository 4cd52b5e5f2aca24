// Size limits on input files, checked before a file is read, and the phase a run is in
// (named when it runs out of memory). Header-only: the deck, mesh and app code share one
// instance of each (inline functions with static locals).
//
// Limits (docs/robustness.md, "Input size limits"): decks and .geo text (every file a .geo
// includes or merges as .geo) at most input_limits().text bytes (default 64 MiB, set with
// --max-input-size), .msh and CAD files at most input_limits().mesh bytes (default 16 GiB,
// set with --max-mesh-size). A larger file is an input error naming it, its size and the limit.
#pragma once
#include <sys/stat.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "deck/Config.hpp"

namespace stentor {

struct InputLimits {
  std::uint64_t text = 64ull << 20;  // decks, .geo
  std::uint64_t mesh = 16ull << 30;  // .msh, CAD data
};

inline InputLimits& input_limits() {
  static InputLimits limits;
  return limits;
}

// "64 MiB", "1.5 GiB", "300 B": a size for messages.
inline std::string size_text(std::uint64_t bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  double v = static_cast<double>(bytes);
  int u = 0;
  while (v >= 1024.0 && u < 4) v /= 1024.0, ++u;
  char buf[48];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", v, units[u]);
  return buf;
}

// A size given on the command line: a whole number of bytes, or with a suffix k, M, G, T
// (powers of 1024). Returns false when `text` is not such a size or is 0.
inline bool parse_size(const std::string& text, std::uint64_t& out) {
  if (text.empty() || text[0] < '0' || text[0] > '9') return false;
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (errno != 0 || v == 0) return false;
  const std::string unit(end);
  int shift = 0;
  if (unit == "k" || unit == "K") shift = 10;
  else if (unit == "M") shift = 20;
  else if (unit == "G") shift = 30;
  else if (unit == "T") shift = 40;
  else if (!unit.empty()) return false;
  if (shift && v > (~0ull >> shift)) return false;
  out = static_cast<std::uint64_t>(v) << shift;
  return true;
}

// Throws InputError when `file` is a regular file larger than the limit for its kind
// (`mesh_data`: .msh or CAD, else deck or .geo text). `what` names the kind in the message.
inline void check_input_size(const std::string& file, bool mesh_data, const char* what) {
  struct stat st;
  if (::stat(file.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return;  // the reader says why
  const std::uint64_t size = static_cast<std::uint64_t>(st.st_size);
  const std::uint64_t limit = mesh_data ? input_limits().mesh : input_limits().text;
  if (size <= limit) return;
  throw InputError(file + ": " + what + " of " + std::to_string(size) + " bytes (" + size_text(size) +
                   "), larger than the limit of " + size_text(limit) + "; refused before reading it (raise the limit with " +
                   (mesh_data ? "--max-mesh-size" : "--max-input-size") + " SIZE, e.g. " +
                   (mesh_data ? "64G" : "1G") + ", to read it anyway)");
}

// What the run is doing, for the out-of-memory message ("reading the deck", ...).
inline std::string& current_phase() {
  static std::string phase = "starting";
  return phase;
}

}  // namespace stentor
