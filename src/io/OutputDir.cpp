#include "io/OutputDir.hpp"

#include <filesystem>
#include <stdexcept>
#include <system_error>

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

}  // namespace

OutputDir::OutputDir(const std::string& final_dir)
    : final_(normalized(final_dir)), staging_(final_ + ".partial") {
  std::error_code ec;
  fs::remove_all(staging_, ec);
  if (ec) fail("cannot remove the leftover " + staging_, ec);
  fs::create_directories(staging_, ec);
  if (ec) fail("cannot create " + staging_, ec);
}

void OutputDir::commit() {
  if (committed_) throw std::runtime_error("OutputDir: " + final_ + " already committed");
  std::error_code ec;
  if (!fs::is_directory(staging_, ec))
    throw std::runtime_error("OutputDir: staging directory " + staging_ + " vanished");
  const std::string old = final_ + ".old";
  bool had_final = fs::exists(fs::symlink_status(final_, ec));
  if (had_final) {
    fs::remove_all(old, ec);
    if (ec) fail("cannot remove the leftover " + old, ec);
    fs::rename(final_, old, ec);
    if (ec) fail("cannot move " + final_ + " to " + old, ec);
  }
  fs::rename(staging_, final_, ec);
  if (ec) {
    std::error_code ec2;
    if (had_final) fs::rename(old, final_, ec2);  // put the earlier results back
    fail("cannot move " + staging_ + " to " + final_, ec);
  }
  committed_ = true;
  if (had_final) {
    fs::remove_all(old, ec);
    if (ec) fail("results committed to " + final_ + " but cannot remove " + old, ec);
  }
}

}  // namespace stentor
