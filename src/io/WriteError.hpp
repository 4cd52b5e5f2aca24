// A result file that could not be written (disk full, quota, file size limit, I/O error).
// The run stops at once with exit status 3 and a message naming the file; the results
// written so far stay in the staging folder, earlier results are not touched.
#pragma once
#include <stdexcept>
#include <string>

namespace stentor {

struct WriteError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws WriteError "<what> <path> failed: <strerror(err)>".
[[noreturn]] void throw_write_error(const std::string& what, const std::string& path, int err);

// Test hook (documented in tests/cli/CMakeLists.txt): with STENTOR_TEST_FAIL_WRITE=NAME[:N]
// the N-th (default 1st) and every later write check of a file named NAME (the name
// without its folder) in this process report a failure with errno ENOSPC, as on a disk
// that fills up. Returns whether this check of `path` is such a failure.
bool write_fails_for_test(const std::string& path);

// Throws WriteError (as above) when `ok` is false (errno then says why) or the test hook
// names `path`.
void check_write(bool ok, const std::string& what, const std::string& path);

}  // namespace stentor
