#include "io/SafeFile.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

namespace stentor {

std::string Fnv1a::hex() const {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

bool hash_file(const std::string& path, std::uint64_t& size, std::string& hash, std::uint64_t limit) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return false;
  struct stat st;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    errno = EINVAL;
    return false;
  }
  Fnv1a f;
  std::vector<char> buf(1 << 16);
  std::uint64_t n = 0;
  while (n < limit) {
    const ssize_t got = ::read(fd, buf.data(), static_cast<std::size_t>(std::min<std::uint64_t>(buf.size(), limit - n)));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      const int err = errno;
      ::close(fd);
      errno = err;
      return false;
    }
    if (got == 0) break;
    f.add(buf.data(), static_cast<std::size_t>(got));
    n += static_cast<std::uint64_t>(got);
  }
  ::close(fd);
  size = limit == ~std::uint64_t(0) ? n : static_cast<std::uint64_t>(st.st_size);
  hash = f.hex();
  return true;
}

int open_for_write(const std::string& path, bool append) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK | (append ? O_APPEND : 0), 0644);
  if (fd < 0) return -1;
  struct stat st;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    errno = EINVAL;
    return -1;
  }
  // Truncated only now that it is known to be a regular file of ours to write.
  if ((!append && ::ftruncate(fd, 0) != 0) || ::fcntl(fd, F_SETFL, append ? O_APPEND : 0) != 0) {
    const int err = errno;
    ::close(fd);
    errno = err;
    return -1;
  }
  return fd;
}

std::FILE* fopen_for_write(const std::string& path, bool append) {
  const int fd = open_for_write(path, append);
  if (fd < 0) return nullptr;
  std::FILE* f = ::fdopen(fd, append ? "a" : "w");
  if (!f) {
    const int err = errno;
    ::close(fd);
    errno = err;
  }
  return f;
}

bool is_link(const std::string& path) {
  struct stat st;
  return ::lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode);
}

bool write_text_file(const std::string& path, const std::string& text) {
  const int fd = open_for_write(path);
  if (fd < 0) return false;
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t w = ::write(fd, text.data() + done, text.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) break;
    done += static_cast<std::size_t>(w);
  }
  const int err = errno;
  const bool ok = ::close(fd) == 0 && done == text.size();
  if (!ok && done != text.size()) errno = err ? err : EIO;
  return ok;
}

std::string open_error(int err) {
  if (err == ELOOP) return "it is a symbolic link (a run never writes through one)";
  if (err == EINVAL) return "it is not a regular file";
  return std::strerror(err);
}

}  // namespace stentor
