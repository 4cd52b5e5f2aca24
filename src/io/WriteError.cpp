#include "io/WriteError.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace stentor {

void throw_write_error(const std::string& what, const std::string& path, int err) {
  throw WriteError(what + " " + path + " failed: " + (err ? std::strerror(err) : "unknown error"));
}

bool write_fails_for_test(const std::string& path) {
  const char* v = std::getenv("STENTOR_TEST_FAIL_WRITE");
  if (!v || !*v) return false;
  const std::string spec = v;
  const std::size_t colon = spec.rfind(':');
  const std::string name = spec.substr(0, colon);
  const long from = colon == std::string::npos ? 1 : std::atol(spec.c_str() + colon + 1);
  if (std::filesystem::path(path).filename() != name) return false;
  static long checks = 0;  // of that one file (the hook names one)
  return ++checks >= from;
}

void check_write(bool ok, const std::string& what, const std::string& path) {
  const int err = errno;
  if (write_fails_for_test(path)) throw_write_error(what, path, ENOSPC);
  if (!ok) throw_write_error(what, path, err);
}

}  // namespace stentor
