// Contact::most_changed_nodes: the slave nodes whose contact state changed most often in a
// failed attempt at a step, for the failure message (a pass over the slave nodes and one
// gather, run only then).
#include <algorithm>
#include <array>
#include <sstream>

#include "contact/Contact.hpp"
#include "parallel/GatherBest.hpp"

namespace stentor {

namespace {
// gid, pair, normal flips, tangent flips, held, reference position (3), facet changes:
// gather_best's rows.
constexpr int kNodeRecord = 9;

std::string times(double n) {
  const int k = static_cast<int>(n);
  return k == 0 ? "never" : k == 1 ? "once" : k == 2 ? "twice" : std::to_string(k) + " times";
}
}  // namespace

std::string Contact::most_changed_nodes(int k) const {
  const std::size_t kk = static_cast<std::size_t>(std::max(k, 1));
  std::vector<std::array<double, kNodeRecord>> mine;
  for (std::size_t ip = 0; ip < pairs_.size(); ++ip)
    for (const auto& nd : pairs_[ip].nodes)
      if (nd.normal_flips + nd.tangent_flips + nd.facet_flips > 0)
        mine.push_back({static_cast<double>(nd.gid), static_cast<double>(ip), static_cast<double>(nd.normal_flips),
                        static_cast<double>(nd.tangent_flips),
                        nd.held() ? 1.0 : 0.0, nd.X[0], nd.X[1], nd.X[2], static_cast<double>(nd.facet_flips)});
  // Most changes first; ties by pair and node id, so every rank count gives the same list.
  const auto before = [](const std::array<double, kNodeRecord>& a, const std::array<double, kNodeRecord>& b) {
    const double fa = a[2] + a[3] + a[8], fb = b[2] + b[3] + b[8];
    if (fa != fb) return fa > fb;
    return a[1] != b[1] ? a[1] < b[1] : a[0] < b[0];
  };
  const auto recs = gather_best(*dist_.comm(), std::move(mine), kk, before);
  std::ostringstream os;
  os.precision(4);
  for (std::size_t i = 0; i < recs.size(); ++i) {
    const auto& r = recs[i];
    if (i > 0) os << ", ";
    os << "node " << static_cast<long long>(r[0]) << " of 'Contact->" << pairs_[static_cast<std::size_t>(r[1])].cfg.name
       << "' (reference position " << r[5] << ", " << r[6];
    if (dim_ == 3) os << ", " << r[7];
    os << "; entered or left contact " << times(r[2]) << ", stick/slip " << times(r[3]);
    if (r[8] > 0.0) os << ", changed master facet " << times(r[8]);
    os << (r[4] > 0.0 ? ", held" : "") << ")";
  }
  return os.str();
}

}  // namespace stentor
