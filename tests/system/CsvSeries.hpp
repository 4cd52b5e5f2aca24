// Reading a run's CSV output (history, energy) in system tests: columns by name.
#pragma once
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace stentor::testing {

struct Series {
  std::map<std::string, std::vector<double>> col;
  const std::vector<double>& operator[](const std::string& name) const {
    auto it = col.find(name);
    if (it == col.end()) throw std::runtime_error("no column " + name);
    return it->second;
  }
  bool has(const std::string& name) const { return col.count(name) != 0; }
  std::size_t rows() const { return col.empty() ? 0 : col.begin()->second.size(); }
  // (stem_x, stem_y, stem_z) at row i.
  std::array<double, 3> vec(const std::string& stem, std::size_t i) const {
    return {(*this)[stem + "_x"][i], (*this)[stem + "_y"][i], (*this)[stem + "_z"][i]};
  }
};

inline Series read_csv(const std::filesystem::path& path) {
  Series s;
  std::ifstream in(path);
  if (!in) {
    ADD_FAILURE() << "cannot read " << path;
    return s;
  }
  std::string line, cell;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::istringstream h(line); std::getline(h, cell, ',');) names.push_back(cell);
  while (std::getline(in, line)) {
    std::istringstream r(line);
    for (const auto& n : names) {
      std::getline(r, cell, ',');
      s.col[n].push_back(std::stod(cell));
    }
  }
  return s;
}

}  // namespace stentor::testing
