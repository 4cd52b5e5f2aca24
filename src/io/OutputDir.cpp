#include "io/OutputDir.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "io/Checkpoint.hpp"
#include "io/SafeFile.hpp"
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
  return !n.empty() && n != "." && n != ".." && n.find('/') == std::string::npos && n.find('\0') == std::string::npos;
}

// Names in the manifest: bytes other than letters, digits and . _ - + as %XX, so that
// every name (a newline, a space, a '#' in it) is one unambiguous token.
bool plain_byte(unsigned char c) { return std::isalnum(c) && c < 128 ? true : c == '.' || c == '_' || c == '-' || c == '+'; }
std::string encode_name(const std::string& n) {
  static const char* hex = "0123456789ABCDEF";
  std::string e;
  for (const char ch : n) {
    const auto c = static_cast<unsigned char>(ch);
    if (plain_byte(c)) e += ch;
    else e += {'%', hex[c >> 4], hex[c & 15]};
  }
  return e;
}
// Text for the manifest's comment line: control bytes and '%' as %XX (one line).
std::string one_line(const std::string& t) {
  std::string e;
  for (const char ch : t) {
    const auto c = static_cast<unsigned char>(ch);
    e += c < 32 || c == 127 || c == '%' ? encode_name(std::string(1, ch)) : std::string(1, ch);
  }
  return e;
}
// False for a token that is not such an encoding.
bool decode_name(const std::string& e, std::string& n) {
  n.clear();
  for (std::size_t i = 0; i < e.size(); ++i) {
    const auto c = static_cast<unsigned char>(e[i]);
    if (plain_byte(c)) { n += e[i]; continue; }
    if (c != '%' || i + 2 >= e.size() || !std::isxdigit(static_cast<unsigned char>(e[i + 1])) || !std::isxdigit(static_cast<unsigned char>(e[i + 2])))
      return false;
    n += static_cast<char>(std::stoi(e.substr(i + 1, 2), nullptr, 16));
    i += 2;
  }
  return plain_name(n);
}

constexpr const char* kManifestHeader = "stentor-manifest 2";
constexpr std::size_t kManifestMaxBytes = 64u << 20;

// A file the manifest lists: its size and FNV-1a when the run wrote it. The log copy
// (<basename>.log) goes on growing after the commit (the run's last lines): its entry,
// marked by a '+' after the size, matches while its first `size` bytes are unchanged.
struct Entry {
  std::uint64_t size = 0;
  std::string hash;
  bool grows = false;
};
using Listing = std::map<std::string, Entry>;
bool grows(const std::string& name) { return fs::path(name).extension() == ".log"; }

// Whether `file` is still the regular file the entry describes (never a link).
bool matches(const fs::path& file, const Entry& e) {
  std::uint64_t size = 0;
  std::string hash;
  if (!hash_file(file.string(), size, hash, e.size)) return false;
  return hash == e.hash && (e.grows ? size >= e.size : size == e.size);
}

// A folder's manifest as read: `found` whether it has one; `files` the entries whose
// files still match (the only ones a run may replace or remove); `stale` the names it
// lists that do not (changed since, or a manifest not written by Stentor: none of its
// entries count then).
struct Manifest {
  bool found = false;
  Listing files;
  std::vector<std::string> stale;
};

// The entries of a manifest's text, or false when it is not a well-formed one (header,
// "<size> <hash> <name>" lines, "end <FNV-1a of the text before that line>").
bool parse_manifest(const std::string& text, Listing& out) {
  std::istringstream in(text);
  std::string line;
  std::size_t consumed = 0;
  bool header = false;
  while (std::getline(in, line)) {
    const std::size_t before = consumed;
    consumed += line.size() + 1;
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      if (line != kManifestHeader) return false;
      header = true;
      continue;
    }
    if (line.rfind("end ", 0) == 0) {
      Fnv1a f;
      f.add(text.data(), before);
      return line.substr(4) == f.hex() && consumed >= text.size();
    }
    std::istringstream l(line);
    std::string size, hash, enc, name, extra;
    if (!(l >> size >> hash >> enc) || (l >> extra)) return false;
    const bool plus = !size.empty() && size.back() == '+';
    if (plus) size.pop_back();
    if (size.empty() || size.find_first_not_of("0123456789") != std::string::npos || size.size() > 19 || hash.size() != 16 ||
        !decode_name(enc, name) || plus != grows(name))
      return false;
    out[name] = Entry{std::stoull(size), hash, plus};
  }
  return false;  // no "end" line: cut short
}

Manifest read_manifest(const fs::path& dir) {
  Manifest m;
  const int fd = ::open((dir / OutputDir::kManifest).c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  m.found = fd >= 0 || errno == ELOOP;
  if (fd < 0) return m;
  std::string text;
  char buf[65536];
  for (ssize_t n; (n = ::read(fd, buf, sizeof buf)) > 0 && text.size() < kManifestMaxBytes;) text.append(buf, static_cast<std::size_t>(n));
  ::close(fd);
  Listing listed;
  if (!parse_manifest(text, listed)) {  // not one Stentor wrote: its lines count for nothing
    std::istringstream in(text);
    for (std::string line; std::getline(in, line) && m.stale.size() < 1000;)
      if (plain_name(line) && line[0] != '#') m.stale.push_back(line);
    return m;
  }
  for (const auto& [name, e] : listed)
    if (matches(dir / name, e)) m.files[name] = e;
    else m.stale.push_back(name);
  return m;
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
  const Manifest manifest = read_manifest(final_);
  const bool stentor = manifest.found;
  const Listing& listed = manifest.files;
  std::vector<std::string> foreign, clashing;
  if (!manifest.stale.empty())
    notice_ = std::to_string(manifest.stale.size()) + " files that " + final_ + "/" + kManifest + " lists are not as the run that "
              "wrote them left them (changed, replaced, or listed by a manifest Stentor did not write): they stay, untouched: " +
              listing(manifest.stale);
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
  if (stentor && !listed.empty())
    notice_ = "the results in " + final_ + " will be replaced when this run succeeds" + (notice_.empty() ? "" : "; " + notice_);
}

namespace {

// The lock file in the staging folder: opened through the folder's descriptor, never
// through a symbolic link (the folder itself, or the lock file, being one is refused: a
// run must not write into a file outside its output folder), and only a regular file.
int open_lock_file(const std::string& staging, const std::string& file) {
  const int dir = ::open(staging.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (dir < 0) fail("cannot open the staging folder " + staging, std::error_code(errno, std::generic_category()));
  const int fd = ::openat(dir, OutputDir::kLockFile, O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
  const int err = errno;
  ::close(dir);
  struct stat st;
  if (fd >= 0 && ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) return fd;
  if (fd >= 0) ::close(fd);
  throw std::runtime_error("the lock file " + file + " " +
                           (fd >= 0 ? std::string("is not a regular file") : err == ELOOP ? "is a symbolic link" : std::strerror(err)) +
                           "; a run writes no file outside its output folder and never through a link: remove it, or "
                           "choose another folder with --output DIR");
}

// Whether `fd` (a lock file) is held by a running run: flock(), or where the file system
// has none, the pid it names alive. `exclusive`: take the lock when free.
bool held_elsewhere(int fd, const Holder& h, bool exclusive) {
  if (::flock(fd, (exclusive ? LOCK_EX : LOCK_SH) | LOCK_NB) == 0) {
    if (!exclusive) ::flock(fd, LOCK_UN);
    return false;
  }
  return errno == EWOULDBLOCK || (!h.empty() && h.alive());
}

}  // namespace

std::string OutputDir::running_in(const std::string& final_dir) {
  const std::string file = normalized(final_dir) + ".partial/" + kLockFile;
  const int fd = ::open(file.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return "";
  struct stat st;
  const Holder h = read_holder(fd);
  const bool busy = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && held_elsewhere(fd, h, false);
  ::close(fd);
  if (!busy) return "";
  return (h.empty() ? std::string("a run just starting") : h.describe()) + " (lock file " + file + ")";
}

// Takes the lock in the staging folder (creating it) and empties the folder but for the
// lock. Retries when the lock file it locked was removed meanwhile (a run ending).
void OutputDir::lock(const Options& opts) {
  const std::string file = staging_ + "/" + kLockFile;
  for (int attempt = 0; attempt < 20 && lock_fd_ < 0; ++attempt) {
    std::error_code ec;
    const auto st = fs::symlink_status(staging_, ec);
    if (fs::exists(st) && (!fs::is_directory(st) ||
                           (!fs::exists(fs::symlink_status(file, ec)) && !fs::is_empty(staging_, ec))))
      throw std::runtime_error("'" + staging_ + "' exists and is not a Stentor staging folder (no " + kLockFile +
                               "); a run stages its results there: move it away, or choose another folder with --output DIR");
    fs::create_directories(staging_, ec);
    if (ec) fail("cannot create " + staging_, ec);
    const int fd = open_lock_file(staging_, file);
    const Holder before = read_holder(fd);
    if (held_elsewhere(fd, before, true)) {
      ::close(fd);
      throw std::runtime_error("another run is writing into '" + final_ + "': " +
                               (before.empty() ? std::string("a run just starting") : before.describe()) + " (lock file " +
                               file + "). Wait for it to end, or choose another folder with --output DIR");
    }
    struct stat a, b;
    if (::fstat(fd, &a) != 0 || ::lstat(file.c_str(), &b) != 0 || a.st_ino != b.st_ino || a.st_dev != b.st_dev) {
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
    if (n != kLockFile) fs::remove_all(fs::path(staging_) / n, ec);  // a link is removed, never followed
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
  const std::string to = staging_ + "/" + name;
  std::ifstream in(file, std::ios::binary);
  const int fd = open_for_write(to);
  if (fd < 0) throw WriteError("copying " + file + " to " + to + " failed: " + open_error(errno));
  std::vector<char> buf(1 << 16);
  bool ok = static_cast<bool>(in);
  while (ok && in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    const auto n = static_cast<std::size_t>(in.gcount());
    ok = in.good() || in.eof();
    for (std::size_t done = 0; ok && done < n;) {
      const ssize_t w = ::write(fd, buf.data() + done, n - done);
      ok = w > 0;
      if (ok) done += static_cast<std::size_t>(w);
    }
  }
  const int err = errno;
  ok = ::close(fd) == 0 && ok;
  if (!ok && errno == 0) errno = err;
  check_write(ok, "copying " + file + " to", to);
}

// The manifest, written to a temporary file in the staging folder (never through a link)
// and renamed over the old one (atomic; a failed write leaves <final> as it was).
void OutputDir::write_manifest(const std::map<std::string, std::pair<std::uint64_t, std::string>>& files) const {
  const std::string path = final_ + "/" + kManifest, tmp = staging_ + "/" + kManifest + ".tmp";
  std::string text = "# Stentor results folder: the files below were written by one run (" +
                     (deck_.empty() ? std::string() : "deck " + one_line(deck_) + ", ") + "host " + one_line(host_name()) +
                     ", " + now_text() + ").\n"
                     "# The next Stentor run into this folder replaces those that still have the size and FNV-1a hash listed;\n"
                     "# it never touches any other file. Names: bytes other than letters, digits and . _ - + as %XX.\n" +
                     kManifestHeader + "\n";
  for (const auto& [name, e] : files)
    text += std::to_string(e.first) + (grows(name) ? "+ " : " ") + e.second + " " + encode_name(name) + "\n";
  Fnv1a f;
  f.add(text.data(), text.size());
  text += "end " + f.hex() + "\n";
  std::error_code ec;
  fs::remove(tmp, ec);  // a leftover (or a link) goes; the new file is created afresh
  const bool ok = write_text_file(tmp, text);
  try {
    check_write(ok, "writing", tmp);
  } catch (const WriteError&) {
    fs::remove(tmp, ec);  // the folder as it was
    throw;
  }
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
    if (n != kLockFile && n != kManifest && fs::is_regular_file(fs::symlink_status(fs::path(staging_) / n, ec))) staged.push_back(n);
  // The .xdmf last: it names the .h5, which is then already in place.
  std::stable_partition(staged.begin(), staged.end(), [](const std::string& n) { return fs::path(n).extension() != ".xdmf"; });
  Files mine;  // what this run wrote: size and hash of each staged file
  for (const auto& n : staged) {
    auto& e = mine[n];
    if (!hash_file(staging_ + "/" + n, e.first, e.second)) throw_write_error("reading back", staging_ + "/" + n, errno);
  }
  fs::create_directories(final_, ec);
  if (ec) throw_write_error("creating", final_, ec.value());
  const Manifest old = read_manifest(final_);
  for (const auto& n : staged)
    if (!old.files.count(n) && fs::exists(fs::symlink_status(fs::path(final_) / n, ec)) && !overwrite_)
      throw WriteError("results kept in " + staging_ + ": " + final_ + "/" + n + " appeared during the run and is not a "
                       "Stentor result; move it away and move the files from " + staging_ + " yourself");
  Files both = mine;
  for (const auto& [n, e] : old.files) both.emplace(n, std::make_pair(e.size, e.hash));
  write_manifest(both);  // an interrupted commit leaves every Stentor file listed
  for (const auto& [n, e] : old.files)  // only files still as the earlier run wrote them
    if (!mine.count(n) && matches(fs::path(final_) / n, e)) fs::remove(fs::path(final_) / n, ec);
  for (const auto& n : staged) {
    fs::rename(fs::path(staging_) / n, fs::path(final_) / n, ec);
    if (ec) throw_write_error("moving " + staging_ + "/" + n + " to", final_ + "/" + n, ec.value());
  }
  write_manifest(mine);
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
