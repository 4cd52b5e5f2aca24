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
  return v && *v && std::filesystem::path(path).filename() == v;
}

void check_write(bool ok, const std::string& what, const std::string& path) {
  const int err = errno;
  if (write_fails_for_test(path)) throw_write_error(what, path, ENOSPC);
  if (!ok) throw_write_error(what, path, err);
}

}  // namespace stentor
