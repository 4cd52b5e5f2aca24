#include "io/LogCopy.hpp"

#include <cerrno>
#include <cstdio>
#include <iostream>
#include <memory>
#include <streambuf>

#include "io/SafeFile.hpp"
#include "io/WriteError.hpp"

namespace stentor::log_copy {

namespace {

constexpr std::size_t kHeldMax = 1 << 20;

// The copy shared by both streams: in memory until a file is attached.
struct Sink {
  std::string held;
  std::FILE* file = nullptr;
  std::string path;
  int error = 0;  // errno of the first failed write (0: none)
  void put(const char* s, std::size_t n) {
    if (error) return;
    if (!file) {
      if (held.size() + n <= kHeldMax) held.append(s, n);
      return;
    }
    if (write_fails_for_test(path))
      error = ENOSPC;
    else if (std::fwrite(s, 1, n, file) != n || std::fflush(file) != 0)
      error = errno ? errno : EIO;
  }
};

// Writes through to the stream's own buffer and to the sink (unbuffered itself).
class TeeBuf : public std::streambuf {
 public:
  TeeBuf(std::streambuf* own, Sink& sink) : own_(own), sink_(sink) {}
  std::streambuf* own() const { return own_; }

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    const char ch = traits_type::to_char_type(c);
    sink_.put(&ch, 1);
    return own_->sputc(ch);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    sink_.put(s, static_cast<std::size_t>(n));
    return own_->sputn(s, n);
  }
  int sync() override { return own_->pubsync(); }

 private:
  std::streambuf* own_;
  Sink& sink_;
};

Sink* g_sink = nullptr;
TeeBuf* g_out = nullptr;
TeeBuf* g_err = nullptr;

}  // namespace

void start() {
  if (g_sink) return;
  g_sink = new Sink;
  g_out = new TeeBuf(std::cout.rdbuf(), *g_sink);
  g_err = new TeeBuf(std::cerr.rdbuf(), *g_sink);
  std::cout.rdbuf(g_out);
  std::cerr.rdbuf(g_err);
}

void attach(const std::string& path) {
  if (!g_sink) return;
  std::cout.flush();
  if (g_sink->file) std::fclose(g_sink->file);
  g_sink->path = path;
  g_sink->error = 0;
  g_sink->file = fopen_for_write(path);
  check_write(g_sink->file != nullptr, "creating", path);
  const std::string held = std::move(g_sink->held);
  g_sink->held.clear();
  g_sink->put(held.data(), held.size());
  check();
}

void check() {
  if (g_sink && g_sink->file && g_sink->error) throw_write_error("writing the log copy", g_sink->path, g_sink->error);
}

void stop() {
  if (!g_sink) return;
  std::cout.flush();
  std::cout.rdbuf(g_out->own());
  std::cerr.rdbuf(g_err->own());
  if (g_sink->file) std::fclose(g_sink->file);
  delete g_out;
  delete g_err;
  delete g_sink;
  g_sink = nullptr;
  g_out = g_err = nullptr;
}

}  // namespace stentor::log_copy
