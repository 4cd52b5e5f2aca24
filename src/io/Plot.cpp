#include "io/Plot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cerrno>
#include <chrono>
#include <thread>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

extern char** environ;

#include "io/WriteError.hpp"

namespace stentor {

namespace {

namespace fs = std::filesystem;

// gnuplot gets this long per plot; a plot is an extra, never a reason to hang or fail a run.
constexpr std::chrono::seconds kPlotTimeLimit{60};

// Splits one CSV line (RFC 4180 quoting) into fields.
std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        cur += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        cur += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.push_back(cur);
      cur.clear();
    } else if (c != '\r') {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

// A gnuplot single-quoted string literal. gnuplot expands backquotes (`cmd` runs cmd)
// and backslash escapes inside double quotes, but nothing inside single quotes, where the
// only special character is the quote itself, written twice. Deck text (load names, the
// basename) must never be interpreted, so every label and file name goes through here.
std::string gp_string(const std::string& s) {
  std::string r = "'";
  for (char c : s) {
    if (c == '\'') r += '\'';
    if (c == '\n' || c == '\r' || c == '\0') c = ' ';
    r += c;
  }
  return r + "'";
}

// Waits for `pid` at most `limit`: 1 when it exited (status set), 0 when it ran past the
// limit (then it is killed and reaped), -1 when waitpid failed.
int wait_limited(pid_t pid, std::chrono::seconds limit, int& status) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  for (;;) {
    const pid_t w = ::waitpid(pid, &status, WNOHANG);
    if (w == pid) return 1;
    if (w < 0 && errno != EINTR) return -1;
    if (std::chrono::steady_clock::now() >= deadline) {
      ::kill(pid, SIGKILL);
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      return 0;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

bool warn(const std::string& msg) {
  std::cerr << "plot_csv_png: " << msg << " (no plot)\n";
  return false;
}

}  // namespace

bool gnuplot_available() {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::stringstream ss(path);
  std::string dir;
  while (std::getline(ss, dir, ':')) {
    if (dir.empty()) dir = ".";
    const std::string exe = dir + "/gnuplot";
    struct stat st;
    if (::stat(exe.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(exe.c_str(), X_OK) == 0)
      return true;
  }
  return false;
}

bool plot_csv_png(const std::string& csv, const std::string& png, const std::string& xcol,
                  const std::vector<std::string>& ycols, const std::string& title,
                  const std::string& ylabel) {
  try {
    if (!gnuplot_available()) return false;
    if (ycols.empty()) return warn("no columns to plot for " + png);

    std::string header;
    {
      std::ifstream in(csv);
      if (!in || !std::getline(in, header)) return warn("cannot read the header of " + csv);
    }
    const std::vector<std::string> cols = split_csv_line(header);
    auto index_of = [&](const std::string& name) -> int {
      for (std::size_t i = 0; i < cols.size(); ++i)
        if (cols[i] == name) return static_cast<int>(i) + 1;  // gnuplot columns are 1-based
      return 0;
    };
    const int xi = index_of(xcol);
    if (!xi) return warn("column '" + xcol + "' not in " + csv);
    std::vector<int> yi;
    for (const auto& y : ycols) {
      yi.push_back(index_of(y));
      if (!yi.back()) return warn("column '" + y + "' not in " + csv);
    }

    const fs::path png_abs = fs::absolute(png).lexically_normal();
    fs::path script = png_abs;
    if (script.extension() == ".png")
      script.replace_extension(".gp");
    else
      script += ".gp";
    const std::string log = script.string() + ".log";
    // The script names its files relative to its own directory and gnuplot runs there, so
    // it stays valid when the directory is moved (OutputDir::commit): cd dir; gnuplot x.gp
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 29))
    constexpr bool relative_paths = true;
#else
    constexpr bool relative_paths = false;
#endif
    const fs::path run_dir = script.parent_path();
    const fs::path csv_abs = fs::absolute(csv).lexically_normal();
    std::string csv_ref = csv_abs.string(), png_ref = png_abs.string();
    if (relative_paths) {
      const fs::path rel = csv_abs.lexically_relative(run_dir);
      if (!rel.empty()) csv_ref = rel.string();
      png_ref = png_abs.filename().string();
    }

    std::ostringstream gp;
    gp << "# Generated by Stentor. Run from this directory: gnuplot " << script.filename().string()
       << "\n"
       << "set datafile separator \",\"\n"
       << "if (strstrt(GPVAL_TERMINALS, \"pngcairo\") > 0) {\n"
       << "  set terminal pngcairo noenhanced size 1200,800 font \",12\"\n"
       << "} else {\n"
       << "  set terminal png noenhanced size 1200,800\n"
       << "}\n"
       << "set output " << gp_string(png_ref) << "\n"
       << "set title " << gp_string(title) << "\n"
       << "set xlabel " << gp_string(xcol) << "\n"
       << "set ylabel " << gp_string(ylabel) << "\n"
       << "set grid\n"
       << "set key autotitle columnhead\n"
       << "plot ";
    for (std::size_t k = 0; k < ycols.size(); ++k) {
      if (k) gp << ", \\\n     ";
      gp << gp_string(csv_ref) << " using " << xi << ':' << yi[k] << " with lines lw 2 title "
         << gp_string(ycols[k]);
    }
    gp << "\nset output\n";
    {
      std::ofstream out(script);
      out << gp.str();
      out.flush();
      check_write(static_cast<bool>(out), "writing the plot script", script.string());
    }

    std::error_code ec;
    fs::remove(png_abs, ec);  // a stale plot must not pass for a new one

    posix_spawn_file_actions_t fa;
    if (posix_spawn_file_actions_init(&fa) != 0) return warn("posix_spawn_file_actions_init");
    posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, log.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 29))
    posix_spawn_file_actions_addchdir_np(&fa, run_dir.c_str());
#endif
    std::string arg0 = "gnuplot", arg1 = script.string();
    char* argv[] = {arg0.data(), arg1.data(), nullptr};
    pid_t pid = -1;
    const int rc = posix_spawnp(&pid, "gnuplot", &fa, nullptr, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) return warn("cannot run gnuplot");
    int status = 0;
    const int w = wait_limited(pid, kPlotTimeLimit, status);
    if (w == 0) return warn("gnuplot took longer than " + std::to_string(kPlotTimeLimit.count()) + " s on " +
                            script.string() + " and was stopped");
    if (w < 0) return warn("waitpid on gnuplot failed");
    const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (fs::exists(log, ec) && fs::file_size(log, ec) == 0) fs::remove(log, ec);
    if (!ok) return warn("gnuplot failed on " + script.string() + ", see " + log);
    if (!fs::exists(png_abs, ec) || fs::file_size(png_abs, ec) == 0)
      return warn("gnuplot wrote no " + png);
    return true;
  } catch (const WriteError&) {
    throw;  // the disk is full (or the like): the run stops
  } catch (const std::exception& e) {
    return warn(e.what());
  } catch (...) {
    return false;
  }
}

}  // namespace stentor
