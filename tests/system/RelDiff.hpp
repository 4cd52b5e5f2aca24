// |a - b|_2 / |b|_2 of two result vectors (e.g. RunResult::displacement): the relative
// difference the system tests compare solver variants by.
#pragma once
#include <cmath>
#include <cstddef>
#include <vector>

namespace stentor::testing {

inline double rel_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double d2 = 0.0, n2 = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    d2 += (a[i] - b[i]) * (a[i] - b[i]);
    n2 += b[i] * b[i];
  }
  return std::sqrt(d2 / n2);
}

}  // namespace stentor::testing
