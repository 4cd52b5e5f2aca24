#include "mesh/Confine.hpp"

#include <fcntl.h>
#include <linux/landlock.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace stentor {
namespace {

// Access rights of later ABIs than the system header may know (linux/landlock.h).
constexpr std::uint64_t kTruncate = 1ull << 14;  // ABI 3
constexpr std::uint64_t kIoctlDev = 1ull << 15;  // ABI 5
constexpr std::uint64_t kNetBindTcp = 1ull << 0, kNetConnectTcp = 1ull << 1;  // ABI 4
constexpr std::uint64_t kScopeAbstractUnix = 1ull << 0, kScopeSignal = 1ull << 1;  // ABI 6

// struct landlock_ruleset_attr as of ABI 6; the kernel reads the first `size` bytes.
struct RulesetAttr {
  std::uint64_t handled_access_fs = 0, handled_access_net = 0, scoped = 0;
};

constexpr std::uint64_t kFileRights = LANDLOCK_ACCESS_FS_EXECUTE | LANDLOCK_ACCESS_FS_WRITE_FILE |
                                      LANDLOCK_ACCESS_FS_READ_FILE | kTruncate | kIoctlDev;

// Every file-system right the kernel of ABI `abi` handles.
std::uint64_t fs_rights(int abi) {
  std::uint64_t r = (LANDLOCK_ACCESS_FS_MAKE_SYM << 1) - 1;  // ABI 1: bits 0-12
  if (abi >= 2) r |= LANDLOCK_ACCESS_FS_REFER;
  if (abi >= 3) r |= kTruncate;
  if (abi >= 5) r |= kIoctlDev;
  return r;
}

std::string sys_error(const std::string& what) { return what + ": " + std::strerror(errno); }

// Allows `rights` beneath `path` (a folder) or on it (a file: file rights only). A path
// that does not exist is skipped.
std::string allow(int ruleset, const std::string& path, std::uint64_t rights, std::uint64_t handled) {
  const int fd = ::open(path.c_str(), O_PATH | O_CLOEXEC);
  if (fd < 0) return errno == ENOENT || errno == ENOTDIR ? "" : sys_error("open " + path);
  struct stat st;
  if (::fstat(fd, &st) == 0 && !S_ISDIR(st.st_mode)) rights &= kFileRights;
  struct landlock_path_beneath_attr rule = {};
  rule.allowed_access = rights & handled;
  rule.parent_fd = fd;
  const long rc = ::syscall(SYS_landlock_add_rule, ruleset, LANDLOCK_RULE_PATH_BENEATH, &rule, 0);
  ::close(fd);
  return rc == 0 ? "" : sys_error("landlock_add_rule " + path);
}

}  // namespace

int landlock_abi() {
  const long v = ::syscall(SYS_landlock_create_ruleset, nullptr, 0, LANDLOCK_CREATE_RULESET_VERSION);
  return v < 0 ? 0 : static_cast<int>(v);
}

std::string confine_process(const std::string& write_dir, const std::vector<std::string>& read_files) {
  const char* off = std::getenv("STENTOR_TEST_NO_LANDLOCK");
  if (off && std::strcmp(off, "1") == 0) return "turned off by STENTOR_TEST_NO_LANDLOCK=1";
  const int abi = landlock_abi();
  if (abi < 1) return "this kernel has no Landlock (Linux 5.13 or later with landlock in its LSM list)";
  RulesetAttr attr;
  attr.handled_access_fs = fs_rights(abi);
  std::size_t size = sizeof(std::uint64_t);
  if (abi >= 4) attr.handled_access_net = kNetBindTcp | kNetConnectTcp, size = 2 * sizeof(std::uint64_t);
  if (abi >= 6) attr.scoped = kScopeAbstractUnix | kScopeSignal, size = sizeof attr;
  const int ruleset = static_cast<int>(::syscall(SYS_landlock_create_ruleset, &attr, size, 0));
  if (ruleset < 0) return sys_error("landlock_create_ruleset");
  const std::uint64_t all = attr.handled_access_fs;
  const std::uint64_t read = LANDLOCK_ACCESS_FS_READ_FILE | LANDLOCK_ACCESS_FS_READ_DIR;
  std::string err = allow(ruleset, write_dir, all, all);
  for (const char* lib : {"/usr", "/lib", "/lib64", "/lib32", "/libx32", "/etc/ld.so.cache"})
    if (err.empty()) err = allow(ruleset, lib, read | LANDLOCK_ACCESS_FS_EXECUTE, all);
  if (err.empty()) err = allow(ruleset, "/dev/null", LANDLOCK_ACCESS_FS_READ_FILE | LANDLOCK_ACCESS_FS_WRITE_FILE, all);
  for (const std::string& f : read_files)
    if (err.empty()) err = allow(ruleset, f, LANDLOCK_ACCESS_FS_READ_FILE, all);
  if (err.empty() && ::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) err = sys_error("prctl(PR_SET_NO_NEW_PRIVS)");
  if (err.empty() && ::syscall(SYS_landlock_restrict_self, ruleset, 0) != 0) err = sys_error("landlock_restrict_self");
  ::close(ruleset);
  return err;
}

}  // namespace stentor
