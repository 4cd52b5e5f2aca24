// The k best fixed-size records over all ranks, for diagnostics (the cells of smallest
// det F, the contact nodes that changed state most): every rank passes its own records and
// gets the same k best by `before`, in that order. One gatherAll of k records per rank.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <Teuchos_Comm.hpp>
#include <Teuchos_CommHelpers.hpp>

namespace stentor {

template <std::size_t N, class Before>
std::vector<std::array<double, N>> gather_best(const Teuchos::Comm<int>& comm, std::vector<std::array<double, N>> mine,
                                               std::size_t k, Before before) {
  std::sort(mine.begin(), mine.end(), before);
  mine.resize(std::min(k, mine.size()));
  // k rows per rank; rows a rank does not fill start with NaN.
  std::vector<double> send(k * N, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < mine.size(); ++i) std::copy(mine[i].begin(), mine[i].end(), send.begin() + static_cast<long>(i * N));
  std::vector<double> all(send.size() * static_cast<std::size_t>(comm.getSize()));
  Teuchos::gatherAll(comm, static_cast<int>(send.size()), send.data(), static_cast<int>(all.size()), all.data());
  std::vector<std::array<double, N>> best;
  for (std::size_t i = 0; i + N <= all.size(); i += N) {
    if (std::isnan(all[i])) continue;
    std::array<double, N> r;
    std::copy(all.begin() + static_cast<long>(i), all.begin() + static_cast<long>(i + N), r.begin());
    best.push_back(r);
  }
  std::sort(best.begin(), best.end(), before);
  best.resize(std::min(k, best.size()));
  return best;
}

}  // namespace stentor
