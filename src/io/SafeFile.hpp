// Files a run writes, opened without following symbolic links, and the FNV-1a hash that
// ties the manifest and checkpoints to the bytes a run wrote.
//
// A run writes only into folders it created (the staging folder, io/OutputDir.hpp), so a
// symbolic link there was planted by someone else: opening it would write through the
// link into a file outside the output folder. open_for_write() refuses it (ELOOP), and
// a name that is not a regular file (a FIFO, a device) is refused too.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>

namespace stentor {

// 64-bit FNV-1a: small, dependency-free, stable across platforms (not cryptographic: it
// detects a changed or exchanged file, not a forger).
struct Fnv1a {
  std::uint64_t h = 14695981039346656037ull;  // the FNV-1a 64-bit offset basis
  void add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  }
  void add(const std::string& s) {
    const std::uint64_t n = s.size();
    add(&n, sizeof n);
    add(s.data(), s.size());
  }
  // 16 lowercase hex digits.
  std::string hex() const;
};

// Size and FNV-1a of a regular file's bytes (with a `limit`: the FNV-1a of its first
// `limit` bytes at most, and its size as it stands), read through a descriptor opened
// without following a link. False (errno set) when it cannot
// be read or is not a regular file.
bool hash_file(const std::string& path, std::uint64_t& size, std::string& hash, std::uint64_t limit = ~std::uint64_t(0));

// Opens `path` for writing (created 0644, truncated; `append`: kept and appended to)
// without following a symbolic link in its last component. Returns the descriptor, or -1
// with errno (ELOOP for a link, EINVAL for a name that is not a regular file).
int open_for_write(const std::string& path, bool append = false);
// The same as a FILE* ("w" or "a"), nullptr with errno on failure.
std::FILE* fopen_for_write(const std::string& path, bool append = false);
// Whether `path` itself is a symbolic link (for files created by a library that cannot be
// given O_NOFOLLOW, HDF5: checked just before they are created).
bool is_link(const std::string& path);
// Writes `text` as the whole of `path` (open_for_write). False with errno on failure.
bool write_text_file(const std::string& path, const std::string& text);
// Why open_for_write failed, for a message: "is a symbolic link (a run never writes
// through one)" for ELOOP, else strerror(err).
std::string open_error(int err);

}  // namespace stentor
