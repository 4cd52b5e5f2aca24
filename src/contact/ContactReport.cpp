// Contact::most_changed_nodes: the slave nodes whose contact state changed most often in a
// failed attempt at a step, for the failure message (a pass over the slave nodes and one
// gather, run only then).
#include <algorithm>
#include <sstream>

#include <Teuchos_CommHelpers.hpp>

#include "contact/Contact.hpp"

namespace stentor {

namespace {
// gid, pair, normal flips, tangent flips, held, reference position (3): doubles for one gather.
constexpr int kNodeRecord = 8;

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
      if (nd.normal_flips + nd.tangent_flips > 0)
        mine.push_back({static_cast<double>(nd.gid), static_cast<double>(ip), static_cast<double>(nd.normal_flips),
                        static_cast<double>(nd.tangent_flips), nd.hold_active || nd.hold_inactive || nd.hold_tangent ? 1.0 : 0.0,
                        nd.X[0], nd.X[1], nd.X[2]});
  // Most changes first; ties by pair and node id, so every rank count gives the same list.
  const auto before = [](const std::array<double, kNodeRecord>& a, const std::array<double, kNodeRecord>& b) {
    const double fa = a[2] + a[3], fb = b[2] + b[3];
    if (fa != fb) return fa > fb;
    return a[1] != b[1] ? a[1] < b[1] : a[0] < b[0];
  };
  std::sort(mine.begin(), mine.end(), before);
  mine.resize(std::min(kk, mine.size()));
  std::vector<double> send(kk * kNodeRecord, -1.0);
  for (std::size_t i = 0; i < mine.size(); ++i) std::copy(mine[i].begin(), mine[i].end(), send.begin() + static_cast<long>(i * kNodeRecord));
  const auto& comm = *dist_.comm();
  std::vector<double> all(send.size() * static_cast<std::size_t>(comm.getSize()));
  Teuchos::gatherAll(comm, static_cast<int>(send.size()), send.data(), static_cast<int>(all.size()), all.data());
  std::vector<std::array<double, kNodeRecord>> recs;
  for (std::size_t i = 0; i + kNodeRecord <= all.size(); i += kNodeRecord) {
    if (all[i] < 0.0) continue;
    std::array<double, kNodeRecord> r;
    std::copy(all.begin() + static_cast<long>(i), all.begin() + static_cast<long>(i + kNodeRecord), r.begin());
    recs.push_back(r);
  }
  std::sort(recs.begin(), recs.end(), before);
  std::ostringstream os;
  os.precision(4);
  for (std::size_t i = 0; i < std::min(kk, recs.size()); ++i) {
    const auto& r = recs[i];
    if (i > 0) os << ", ";
    os << "node " << static_cast<long long>(r[0]) << " of 'Contact->" << pairs_[static_cast<std::size_t>(r[1])].cfg.name
       << "' (reference position " << r[5] << ", " << r[6];
    if (dim_ == 3) os << ", " << r[7];
    os << "; entered or left contact " << times(r[2]) << ", stick/slip " << times(r[3]) << (r[4] > 0.0 ? ", held" : "") << ")";
  }
  return os.str();
}

}  // namespace stentor
