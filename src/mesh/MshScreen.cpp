#include "mesh/MshScreen.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

#include "deck/Config.hpp"

namespace stentor {
namespace {

[[noreturn]] void bad_nodes(const std::string& file, const std::string& what) {
  throw InputError(file + ": $Nodes section: " + what);
}

// Reads the next whitespace-separated token as an integer (false at the end or on text).
bool next_int(std::istream& in, long long& v) {
  std::string t;
  if (!(in >> t)) return false;
  char* end = nullptr;
  v = std::strtoll(t.c_str(), &end, 10);
  return !t.empty() && *end == '\0';
}

bool next_finite(std::istream& in, double& v) {
  std::string t;
  if (!(in >> t)) return false;
  char* end = nullptr;
  v = std::strtod(t.c_str(), &end);
  return !t.empty() && *end == '\0' && std::isfinite(v);
}

// Checks one $Nodes section (the stream is just after its "$Nodes" line). Returns
// false, checking nothing more, at a parametric block (left to gmsh).
bool check_nodes(std::istream& in, const std::string& file) {
  long long blocks, nodes, lo, hi;
  if (!next_int(in, blocks) || !next_int(in, nodes) || !next_int(in, lo) || !next_int(in, hi) ||
      blocks < 0 || nodes < 0)
    bad_nodes(file, "the header must be 4 integers: blocks, nodes, min tag, max tag (>= 0)");
  long long seen = 0;
  for (long long b = 0; b < blocks; ++b) {
    long long dim, tag, parametric, n;
    if (!next_int(in, dim) || !next_int(in, tag) || !next_int(in, parametric) || !next_int(in, n) || n < 0)
      bad_nodes(file, "block " + std::to_string(b + 1) + " of " + std::to_string(blocks) +
                          " has no valid header (entity dim, entity tag, parametric, count)");
    if (parametric != 0) return false;
    if (n > nodes - seen)
      bad_nodes(file, "the header declares " + std::to_string(nodes) + " nodes, its blocks hold more");
    seen += n;
    for (long long i = 0; i < n; ++i) {
      long long t;
      if (!next_int(in, t) || t < lo || t > hi)
        bad_nodes(file, "a node tag in block " + std::to_string(b + 1) + " is missing or outside [" +
                            std::to_string(lo) + ", " + std::to_string(hi) + "]");
    }
    for (long long i = 0; i < 3 * n; ++i) {
      double x;
      if (!next_finite(in, x))
        bad_nodes(file, "a coordinate in block " + std::to_string(b + 1) + " is missing or not a finite number");
    }
  }
  if (seen != nodes)
    bad_nodes(file, "the header declares " + std::to_string(nodes) + " nodes, its blocks hold " + std::to_string(seen));
  std::string end;
  if (!(in >> end) || end != "$EndNodes")
    bad_nodes(file, "expected $EndNodes after " + std::to_string(blocks) + " blocks");
  return true;
}

}  // namespace

void screen_msh_file(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file + ": cannot open mesh file (missing or unreadable)");
  std::string line;
  bool ascii4 = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line == "$MeshFormat") {
      std::string version;
      long long binary = 1;
      ascii4 = (in >> version) && next_int(in, binary) && binary == 0 && version.rfind("4", 0) == 0;
      if (!ascii4) return;
    } else if (line == "$Nodes" && ascii4) {
      if (!check_nodes(in, file)) return;
    }
  }
}

}  // namespace stentor
