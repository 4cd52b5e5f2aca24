// Wall-clock timers by name, printed in the end-of-run summary.
#pragma once
#include <chrono>
#include <map>
#include <string>
#include <vector>

namespace stentor {

class Timers {
 public:
  // Adds the time from its construction to its destruction to timer `name`.
  struct Scope {
    Timers& t;
    std::string name;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    ~Scope() { t.add(name, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()); }
  };
  void add(const std::string& n, double s) {
    if (!acc_.count(n)) order_.push_back(n);
    acc_[n] += s;
  }
  double get(const std::string& n) const {
    auto it = acc_.find(n);
    return it == acc_.end() ? 0.0 : it->second;
  }
  // In the order they were first used.
  const std::vector<std::string>& names() const { return order_; }

 private:
  std::map<std::string, double> acc_;
  std::vector<std::string> order_;
};

}  // namespace stentor
