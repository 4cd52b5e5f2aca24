#include "mesh/Progress.hpp"

#include <iomanip>
#include <sstream>

namespace stentor {

namespace {
std::string seconds(std::chrono::steady_clock::duration d) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(0) << std::chrono::duration<double>(d).count() << " s";
  return os.str();
}
}  // namespace

Progress::Progress(std::ostream& out, std::string what, std::string detail, double interval_s)
    : out_(out), what_(std::move(what)), detail_(std::move(detail)), interval_(interval_s), thread_([this] { run(); }) {}

Progress::~Progress() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  wake_.notify_all();
  thread_.join();
  if (lines_ > 0) out_ << "  " << what_ << ": done in " << seconds(std::chrono::steady_clock::now() - start_) << "\n" << std::flush;
}

void Progress::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (auto next = start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(interval_);;
       next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(interval_)) {
    if (wake_.wait_until(lock, next, [this] { return done_; })) return;
    out_ << "  " << what_ << ": " << seconds(std::chrono::steady_clock::now() - start_) << " so far" << detail_ << "\n" << std::flush;
    ++lines_;
  }
}

}  // namespace stentor
