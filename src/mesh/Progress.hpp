// A progress line for long work that reports nothing itself (gmsh's meshing): while the
// object lives, a helper thread prints "<what>: <s> s so far<detail>" every `interval`
// seconds (the first after one interval, so quick work prints nothing), and on
// destruction, if it printed anything, one line with the total time. The helper thread
// only writes to `out`; the work itself runs undisturbed in the calling thread.
#pragma once
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <ostream>
#include <string>
#include <thread>

namespace stentor {

class Progress {
 public:
  Progress(std::ostream& out, std::string what, std::string detail, double interval_s);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

 private:
  void run();
  std::ostream& out_;
  const std::string what_, detail_;
  const std::chrono::duration<double> interval_;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  int lines_ = 0;
  std::thread thread_;
};

}  // namespace stentor
