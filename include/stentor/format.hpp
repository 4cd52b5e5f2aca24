// Pi and numbers in messages: one definition for every file that needs them.
#pragma once
#include <sstream>
#include <string>

namespace stentor {

constexpr double kPi = 3.14159265358979323846;

// v with `precision` significant digits in the stream's default notation ("0.1", "1e-08").
inline std::string format_number(double v, int precision = 6) {
  std::ostringstream os;
  os.precision(precision);
  os << v;
  return os.str();
}

}  // namespace stentor
