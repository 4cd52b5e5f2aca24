#include "io/OutputDir.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "io/Checkpoint.hpp"
#include "io/WriteError.hpp"

namespace stentor {

namespace fs = std::filesystem;

namespace {

std::string normalized(const std::string& dir) {
  if (dir.empty()) throw std::runtime_error("OutputDir: empty output directory name");
  fs::path p(dir);
  while (!p.has_filename() && p.has_parent_path() && p != p.parent_path()) p = p.parent_path();
  if (!p.has_filename() || p.filename() == "." || p.filename() == "..")
    throw std::runtime_error("OutputDir: '" + dir + "' cannot be used as an output directory");
  return p.string();
}

[[noreturn]] void fail(const std::string& what, const std::error_code& ec) {
  throw std::runtime_error("OutputDir: " + what + ": " + ec.message());
}

// A name the manifest may list: a plain file name in the folder itself.
bool plain_name(const std::string& n) {
  return !n.empty() && n != "." && n != ".." && n.find('/') == std::string::npos && n[0] != '#';
}

// The files a manifest lists; `found` says whether <dir> has one.
std::set<std::string> read_manifest(const fs::path& dir, bool& found) {
  std::set<std::string> names;
  std::ifstream in(dir / OutputDir::kManifest);
  found = static_cast<bool>(in);
  for (std::string line; std::getline(in, line);)
    if (plain_name(line)) names.insert(line);
  return names;
}

// The names in `dir` (none when it cannot be read).
std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) names.push_back(it->path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string listing(const std::vector<std::string>& names) {
  std::string s;
  for (std::size_t i = 0; i < names.size() && i < 4; ++i) s += (i ? ", " : "") + names[i];
  if (names.size() > 4) s += ", ... (" + std::to_string(names.size()) + " in all)";
  return s;
}

// Whether `file` lies inside `dir` (at any depth), symbolic links resolved.
bool inside(const std::string& file, const fs::path& dir) {
  std::error_code ec;
  const fs::path f = fs::weakly_canonical(fs::absolute(file), ec), d = fs::weakly_canonical(fs::absolute(dir), ec);
  const auto rel = f.lexically_relative(d);
  return !rel.empty() && *rel.begin() != "..";
}

std::string host_name() {
  char h[256] = {0};
  if (::gethostname(h, sizeof h - 1) != 0) return "unknown";
  return h;
}

std::string now_text() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S %Z", std::localtime(&t));
  return buf;
}

// The run a lock file names (its lines "pid N", "host H", "started T", "deck D").
struct Holder {
  long pid = 0;
  std::string host, started, deck;
  bool empty() const { return pid == 0; }
  std::string describe() const {
    return "pid " + std::to_string(pid) + " on host " + host + ", started " + started + (deck.empty() ? "" : ", deck " + deck);
  }
  // Alive as far as this host can tell: another host's run counts as alive.
  bool alive() const { return host != host_name() || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM; }
};

Holder read_holder(int fd) {
  std::string text(4096, '\0');
  const ssize_t n = ::pread(fd, text.data(), text.size(), 0);
  text.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  Holder h;
  std::istringstream in(text);
  for (std::string key; in >> key;) {
    std::string value;
    std::getline(in >> std::ws, value);
    if (key == "pid") h.pid = std::atol(value.c_str());
    if (key == "host") h.host = value;
    if (key == "started") h.started = value;
    if (key == "deck") h.deck = value;
  }
  return h;
}

// "<dir>/<name>_checkpoint.h5 (t = 0.025, step 50)" for each complete checkpoint in `dir`
// (the one written last; not the .prev.h5 kept beside it nor a .tmp cut short).
std::vector<std::string> checkpoints_in(const fs::path& dir) {
  std::vector<std::string> found;
  const std::string tail = "_checkpoint.h5";
  for (const auto& n : entries(dir)) {
    if (n.size() <= tail.size() || n.compare(n.size() - tail.size(), tail.size(), tail) != 0) continue;
    const std::string path = (dir / n).string();
    std::string at;
    try {
      const CheckpointData d = read_checkpoint_file(path);
      std::ostringstream os;
      os << " (t = " << d.real("time") << ", step " << d.integer("step") << ")";
      at = os.str();
    } catch (const std::exception& e) {
      at = " (its time and step cannot be read: " + std::string(e.what()) + ")";
    }
    found.push_back(path + at);
  }
  return found;
}

}  // namespace

OutputDir::OutputDir(const std::string& final_dir, const Options& opts)
    : final_(normalized(final_dir)), staging_(final_ + ".partial"), deck_(opts.deck), overwrite_(opts.overwrite) {
  check_final(opts);
  lock(opts);
}

OutputDir::~OutputDir() { release(); }

void OutputDir::release() {
  if (lock_fd_ >= 0) ::close(lock_fd_);  // the kernel drops the flock()
  lock_fd_ = -1;
}

// <final> may be used: not a file, not holding the inputs, new, empty or Stentor's.
void OutputDir::check_final(const Options& opts) {
  for (const auto& in : opts.inputs)
    if (!in.empty() && (inside(in, final_) || inside(in, staging_)))
      throw std::runtime_error("the output folder '" + final_ + "' holds " + in +
                               ", a file this run reads; results never go into the deck's own folder: choose "
                               "another folder with --output DIR (or Output->directory), e.g. results/<deck name>");
  std::error_code ec;
  const auto st = fs::status(final_, ec);
  if (!fs::exists(st)) return;
  if (!fs::is_directory(st))
    throw std::runtime_error("the output folder '" + final_ + "' exists and is not a folder; choose another one with --output DIR");
  bool stentor = false;
  const std::set<std::string> listed = read_manifest(final_, stentor);
  std::vector<std::string> foreign, clashing;
  for (const auto& n : entries(final_))
    if (n != kManifest && !listed.count(n)) {
      foreign.push_back(n);
      if (!opts.prefix.empty() && n.rfind(opts.prefix, 0) == 0) clashing.push_back(n);
    }
  if (overwrite_) return;
  if (!stentor && !foreign.empty())
    throw std::runtime_error("the output folder '" + final_ + "' is not empty and holds no Stentor results (no " + kManifest +
                             "): " + listing(foreign) + ". A run never deletes or overwrites files it did not write: "
                             "choose a new or empty folder with --output DIR, or add --overwrite to write into it anyway "
                             "(files with the names of the results would then be replaced, no other file)");
  if (!clashing.empty())
    throw std::runtime_error("the output folder '" + final_ + "' holds files that its Stentor results do not list but that "
                             "this run would write: " + listing(clashing) + "; move them away, choose another folder with "
                             "--output DIR, or add --overwrite to replace them");
  if (stentor && !listed.empty()) notice_ = "the results in " + final_ + " will be replaced when this run succeeds";
}

// Takes the lock in the staging folder (creating it) and empties the folder but for the
// lock. Retries when the lock file it locked was removed meanwhile (a run ending).
void OutputDir::lock(const Options& opts) {
  const std::string file = staging_ + "/" + kLockFile;
  for (int attempt = 0; attempt < 20 && lock_fd_ < 0; ++attempt) {
    std::error_code ec;
    const bool existed = fs::exists(fs::symlink_status(staging_, ec));
    if (existed && (!fs::is_directory(fs::symlink_status(staging_, ec)) ||
                    (!fs::exists(file, ec) && !fs::is_empty(staging_, ec))))
      throw std::runtime_error("'" + staging_ + "' exists and is not a Stentor staging folder (no " + kLockFile +
                               "); a run stages its results there: move it away, or choose another folder with --output DIR");
    fs::create_directories(staging_, ec);
    if (ec) fail("cannot create " + staging_, ec);
    const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) fail("cannot create the lock file " + file, std::error_code(errno, std::generic_category()));
    const Holder before = read_holder(fd);
    // Without flock() (some network file systems) the pid in the file decides.
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0 && (errno == EWOULDBLOCK || (!before.empty() && before.alive()))) {
      ::close(fd);
      throw std::runtime_error("another run is writing into '" + final_ + "': " +
                               (before.empty() ? std::string("a run just starting") : before.describe()) + " (lock file " +
                               file + "). Wait for it to end, or choose another folder with --output DIR");
    }
    struct stat a, b;
    if (::fstat(fd, &a) != 0 || ::stat(file.c_str(), &b) != 0 || a.st_ino != b.st_ino || a.st_dev != b.st_dev) {
      ::close(fd);  // the file was removed after we opened it: lock the new one
      continue;
    }
    lock_fd_ = fd;
    if (!before.empty())
      notice_ = "took over " + staging_ + " from an earlier run that is no longer running (" + before.describe() + ")" +
                (notice_.empty() ? "" : "; " + notice_);
  }
  if (lock_fd_ < 0) throw std::runtime_error("cannot lock " + file + ": it keeps being removed by another run");
  keep_checkpoints();
  for (const auto& n : entries(staging_)) {
    std::error_code ec;
    if (n != kLockFile) fs::remove_all(fs::path(staging_) / n, ec);
    if (ec) fail("cannot remove the leftover " + staging_ + "/" + n, ec);
  }
  const std::string text = "pid " + std::to_string(::getpid()) + "\nhost " + host_name() + "\nstarted " + now_text() + "\n" +
                           (opts.deck.empty() ? "" : "deck " + opts.deck + "\n");
  const bool ok = ::ftruncate(lock_fd_, 0) == 0 && ::pwrite(lock_fd_, text.data(), text.size(), 0) == ssize_t(text.size());
  check_write(ok, "writing the lock file", file);
}

// An earlier run that is no longer running left a checkpoint in the staging folder: a
// plain run would empty the folder and lose it (hours of a killed run's work), so it
// stops and says how to go on; --overwrite discards it.
void OutputDir::keep_checkpoints() {
  if (overwrite_) return;
  const std::vector<std::string> found = checkpoints_in(staging_);
  if (found.empty()) return;
  release();
  std::string list;
  for (const auto& f : found) list += (list.empty() ? "" : "; ") + f;
  const std::string first = found.front().substr(0, found.front().find(" ("));
  throw std::runtime_error("'" + staging_ + "' holds the checkpoint " + list + " of an earlier run that is no longer "
                           "running; a new run would empty the folder and lose it. Resume that run with --restart " +
                           first + " (the same deck and --output), or start again from t = 0 and discard it with "
                           "--overwrite");
}

void OutputDir::copy_in(const std::string& file, const std::string& name) {
  const fs::path to = fs::path(staging_) / name;
  std::error_code ec;
  fs::copy_file(file, to, fs::copy_options::overwrite_existing, ec);
  errno = ec.value();
  check_write(!ec, "copying " + file + " to", to.string());
}

// The manifest, written to a temporary file in the staging folder and renamed over the
// old one (atomic; a failed write leaves <final> as it was).
void OutputDir::write_manifest(const std::vector<std::string>& names) const {
  const std::string path = final_ + "/" + kManifest, tmp = staging_ + "/" + kManifest + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << "# Stentor results folder: the files below were written by one run (" << (deck_.empty() ? "" : "deck " + deck_ + ", ")
        << "host " << host_name() << ", " << now_text() << ").\n"
        << "# The next Stentor run into this folder replaces them; it never touches a file not listed here.\n";
    for (const auto& n : names) out << n << "\n";
    out.flush();
    try {
      check_write(static_cast<bool>(out), "writing", tmp);
    } catch (const WriteError&) {
      std::error_code ec;
      fs::remove(tmp, ec);  // the folder as it was
      throw;
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  errno = ec.value();
  if (ec) fs::remove(tmp, ec);
  check_write(errno == 0, "renaming " + tmp + " to", path);
}

void OutputDir::commit() {
  if (committed_) throw std::runtime_error("OutputDir: " + final_ + " already committed");
  std::error_code ec;
  if (!fs::is_directory(staging_, ec)) throw std::runtime_error("OutputDir: staging directory " + staging_ + " vanished");
  std::vector<std::string> staged;
  for (const auto& n : entries(staging_))
    if (n != kLockFile && n != kManifest && fs::is_regular_file(fs::path(staging_) / n, ec)) staged.push_back(n);
  // The .xdmf last: it names the .h5, which is then already in place.
  std::stable_partition(staged.begin(), staged.end(), [](const std::string& n) { return fs::path(n).extension() != ".xdmf"; });
  fs::create_directories(final_, ec);
  if (ec) throw_write_error("creating", final_, ec.value());
  bool had = false;
  const std::set<std::string> old = read_manifest(final_, had);
  for (const auto& n : staged)
    if (!old.count(n) && fs::exists(fs::symlink_status(fs::path(final_) / n, ec)) && !overwrite_)
      throw WriteError("results kept in " + staging_ + ": " + final_ + "/" + n + " appeared during the run and is not a "
                       "Stentor result; move it away and move the files from " + staging_ + " yourself");
  std::set<std::string> both(old.begin(), old.end());
  both.insert(staged.begin(), staged.end());
  write_manifest({both.begin(), both.end()});  // an interrupted commit leaves every Stentor file listed
  for (const auto& n : old)
    if (!std::count(staged.begin(), staged.end(), n) && fs::is_regular_file(fs::symlink_status(fs::path(final_) / n, ec)))
      fs::remove(fs::path(final_) / n, ec);
  for (const auto& n : staged) {
    fs::rename(fs::path(staging_) / n, fs::path(final_) / n, ec);
    if (ec) throw_write_error("moving " + staging_ + "/" + n + " to", final_ + "/" + n, ec.value());
  }
  write_manifest(staged);
  committed_ = true;
  discard();
}

void OutputDir::discard() {
  std::error_code ec;
  for (const auto& n : entries(staging_))
    if (n != kLockFile) fs::remove_all(fs::path(staging_) / n, ec);
  fs::remove(fs::path(staging_) / kLockFile, ec);  // still locked: a run waiting for it re-checks the file
  fs::remove(staging_, ec);
  release();
}

}  // namespace stentor
