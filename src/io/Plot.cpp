#include "io/Plot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cerrno>
#include <chrono>
#include <thread>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

extern char** environ;

#include "io/SafeFile.hpp"
#include "io/WriteError.hpp"

namespace stentor {

namespace {

namespace fs = std::filesystem;

// gnuplot gets this long per plot; a plot is an extra, never a reason to hang or fail a run.
std::chrono::milliseconds g_plot_time_limit{std::chrono::seconds(60)};
// Set when gnuplot ran past the limit once: the later plots of the run are not tried (their
// scripts are still written), so a gnuplot that hangs costs one limit, not one per plot.
bool g_gnuplot_stopped = false;

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

// Waits for `pid` (the leader of its own process group) at most `limit`: 1 when it
// exited (status set), 0 when it ran past the limit (then its whole group is killed and
// it is reaped), -1 when waitpid failed. Whatever it left running is killed either way.
int wait_limited(pid_t pid, std::chrono::milliseconds limit, int& status) {
  struct KillGroup {
    pid_t pid;
    ~KillGroup() { ::kill(-pid, SIGKILL); }
  } kill_group{pid};
  const auto deadline = std::chrono::steady_clock::now() + limit;
  for (;;) {
    const pid_t w = ::waitpid(pid, &status, WNOHANG);
    if (w == pid) return 1;
    if (w < 0 && errno != EINTR) return -1;
    if (std::chrono::steady_clock::now() >= deadline) {
      ::kill(-pid, SIGKILL);
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

void set_plot_time_limit(std::chrono::milliseconds limit) {
  g_plot_time_limit = limit;
  g_gnuplot_stopped = false;
}

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

int PlotTable::find(const std::string& name) const {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  return -1;
}

void PlotTable::add(std::string name, std::vector<double> values) {
  names.push_back(std::move(name));
  columns.push_back(std::move(values));
}

bool read_csv_table(const std::string& csv, PlotTable& t) {
  std::ifstream in(csv);
  std::string line;
  if (!in || !std::getline(in, line)) return false;
  t = PlotTable{};
  t.names = split_csv_line(line);
  t.columns.assign(t.names.size(), {});
  while (std::getline(in, line)) {
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> f = split_csv_line(line);
    if (f.size() != t.names.size()) return false;
    for (std::size_t k = 0; k < f.size(); ++k) {
      char* end = nullptr;
      const double v = std::strtod(f[k].c_str(), &end);
      t.columns[k].push_back(end == f[k].c_str() ? std::nan("") : v);
    }
  }
  return true;
}

namespace {

// Runs gnuplot on `script` in its directory: true when it wrote a non-empty `png`.
bool run_gnuplot(const fs::path& script, const fs::path& png) {
  const std::string log = script.string() + ".log";
  std::error_code ec;
  posix_spawn_file_actions_t fa;
  if (posix_spawn_file_actions_init(&fa) != 0) return warn("posix_spawn_file_actions_init");
  posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 29))
  posix_spawn_file_actions_addchdir_np(&fa, script.parent_path().c_str());
#endif
  std::string arg0 = "gnuplot", arg1 = script.string();
  char* argv[] = {arg0.data(), arg1.data(), nullptr};
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setpgroup(&attr, 0);  // its own process group: stopped with its helpers
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, "gnuplot", &fa, &attr, argv, environ);
  posix_spawn_file_actions_destroy(&fa);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) return warn("cannot run gnuplot");
  int status = 0;
  const int w = wait_limited(pid, g_plot_time_limit, status);
  // A failed gnuplot may leave a truncated PNG behind (a full disk): no PNG then.
  auto no_png = [&](const std::string& why) {
    fs::remove(png, ec);
    return warn(why);
  };
  if (w == 0) {
    g_gnuplot_stopped = true;
    std::ostringstream limit;
    limit << std::chrono::duration<double>(g_plot_time_limit).count();
    return no_png("gnuplot took longer than " + limit.str() + " s on " + script.filename().string() +
                  " and was stopped; the later plots of this run are not tried");
  }
  if (w < 0) return no_png("waitpid on gnuplot failed");
  const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (fs::exists(log, ec) && fs::file_size(log, ec) == 0) fs::remove(log, ec);
  // Named without their folder: the run moves its staging folder into the results.
  if (!ok)
    return no_png("gnuplot failed on " + script.filename().string() + ", see " + fs::path(log).filename().string() +
                  " beside it");
  if (!fs::exists(png, ec) || fs::file_size(png, ec) == 0) return no_png("gnuplot wrote no " + png.string());
  // A whole PNG ends with its IEND chunk: gnuplot exits 0 even when its write failed
  // (a full disk, a file size limit) and leaves a truncated file.
  static const unsigned char kEnd[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
  unsigned char tail[12] = {};
  std::ifstream in(png, std::ios::binary);
  in.seekg(-12, std::ios::end);
  in.read(reinterpret_cast<char*>(tail), 12);
  if (!in || !std::equal(tail, tail + 12, kEnd))
    return no_png("gnuplot wrote an incomplete " + png.filename().string() + " (a full disk?)");
  return true;
}

// The gnuplot script of `spec`: the plotted columns inline as the datablock $data (x
// columns first, then the curves' y columns), then the plot command.
std::string plot_script(const PlotTable& t, const std::string& png_ref, const std::string& script_name,
                        const PlotSpec& spec, const std::vector<int>& xi, const std::vector<int>& yi,
                        const std::vector<PlotMark>& marks) {
  std::vector<int> cols;  // table columns in datablock order
  auto slot = [&](int c) {
    for (std::size_t k = 0; k < cols.size(); ++k)
      if (cols[k] == c) return static_cast<int>(k) + 1;
    cols.push_back(c);
    return static_cast<int>(cols.size());
  };
  std::vector<std::pair<int, int>> uses;
  for (std::size_t k = 0; k < spec.curves.size(); ++k) {
    const int x = slot(xi[k]);  // x columns before y columns (argument order is unspecified)
    uses.emplace_back(x, slot(yi[k]));
  }
  std::ostringstream gp;
  gp << "# Generated by Stentor. Run from this directory: gnuplot " << script_name << "\n"
     << "# Columns of $data:";
  for (int c : cols) gp << ' ' << gp_string(t.names[static_cast<std::size_t>(c)]);
  gp << "\n$data << EOD\n";
  char buf[32];
  for (std::size_t r = 0; r < t.rows(); ++r) {
    for (std::size_t k = 0; k < cols.size(); ++k) {
      const double v = t.columns[static_cast<std::size_t>(cols[k])][r];
      if (std::isfinite(v))
        std::snprintf(buf, sizeof buf, "%.10g", v);
      else
        std::snprintf(buf, sizeof buf, "NaN");
      gp << (k ? " " : "") << buf;
    }
    gp << "\n";
  }
  gp << "EOD\n"
     << "if (strstrt(GPVAL_TERMINALS, \"pngcairo\") > 0) {\n"
     << "  set terminal pngcairo noenhanced size 1200,800 font \",12\"\n"
     << "} else {\n"
     << "  set terminal png noenhanced size 1200,800\n"
     << "}\n"
     << "set output " << gp_string(png_ref) << "\n"
     << "set title " << gp_string(spec.title) << "\n"
     << "set xlabel " << gp_string(spec.xlabel) << "\n"
     << "set ylabel " << gp_string(spec.ylabel) << "\n"
     << "set grid\n";
  // The key below the x label, in two columns when the legends are short, with room for
  // its rows (gnuplot would draw a long key over the label).
  std::size_t longest = 0;
  for (const PlotCurve& c : spec.curves) longest = std::max(longest, c.legend.size());
  const std::size_t key_cols = longest <= 35 ? 2 : 1, key_rows = (spec.curves.size() + key_cols - 1) / key_cols;
  gp << "set key outside below center maxcols " << key_cols << "\n"
     << "set bmargin " << 4 + key_rows << "\n";
  if (spec.x_from_zero) gp << "set xrange [0:*]\n";
  for (std::size_t k = 0; k < marks.size(); ++k) {
    char at[32];
    std::snprintf(at, sizeof at, "%.10g", marks[k].x);
    gp << "set arrow from " << at << ", graph 0 to " << at << ", graph 1 nohead dashtype 2 lc rgb 'gray40'\n"
       << "set label " << k + 1 << " " << gp_string(marks[k].label) << " at " << at
       << ", graph 0.98 right rotate by 90 offset -0.5, 0 textcolor rgb 'gray40'\n";
  }
  gp << "plot ";
  for (std::size_t k = 0; k < spec.curves.size(); ++k) {
    if (k) gp << ", \\\n     ";
    // Ten distinguishable colours, then dashed lines: no two curves look alike.
    static const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                                     "#8c564b", "#e377c2", "#17becf", "#7f7f7f", "#bcbd22"};
    gp << "$data using " << uses[k].first << ':' << uses[k].second << " with lines lw 2 lc rgb '" << kColours[k % 10]
       << "' dt " << 1 + (k / 10) % 5 << " title "
       << gp_string(spec.curves[k].legend);
  }
  gp << "\nset output\n";
  return gp.str();
}

}  // namespace

bool plot_png(const PlotTable& table, const std::string& png, const PlotSpec& spec, const std::vector<PlotMark>& marks) {
  try {
    if (spec.curves.empty()) return warn("no curves to plot for " + png);
    if (table.rows() == 0) return warn("no data to plot for " + png);
    std::vector<int> xi, yi;
    for (const PlotCurve& c : spec.curves) {
      const std::string& x = c.x.empty() ? spec.x : c.x;
      xi.push_back(table.find(x));
      yi.push_back(table.find(c.y));
      if (xi.back() < 0) return warn("column '" + x + "' not in the data of " + png);
      if (yi.back() < 0) return warn("column '" + c.y + "' not in the data of " + png);
    }
    const fs::path png_abs = fs::absolute(png).lexically_normal();
    fs::path script = png_abs;
    if (script.extension() == ".png")
      script.replace_extension(".gp");
    else
      script += ".gp";
    // The script names the png relative to its own directory and gnuplot runs there, so
    // it stays valid when the directory is moved (OutputDir::commit): cd dir; gnuplot x.gp
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 29))
    const std::string png_ref = png_abs.filename().string();
#else
    const std::string png_ref = png_abs.string();
#endif
    {
      const bool ok = write_text_file(script.string(), plot_script(table, png_ref, script.filename().string(), spec, xi, yi, marks));
      check_write(ok, "writing the plot script", script.string());
    }
    std::error_code ec;
    fs::remove(png_abs, ec);  // a stale plot must not pass for a new one
    if (!gnuplot_available()) return false;
    if (g_gnuplot_stopped) return false;  // it hung before: said once, in run_gnuplot
    return run_gnuplot(script, png_abs);
  } catch (const WriteError&) {
    throw;  // the disk is full (or the like): the run stops
  } catch (const std::exception& e) {
    return warn(e.what());
  } catch (...) {
    return false;
  }
}

bool plot_csv_png(const std::string& csv, const std::string& png, const std::string& xcol,
                  const std::vector<std::string>& ycols, const std::string& title,
                  const std::string& ylabel) {
  PlotTable t;
  if (!read_csv_table(csv, t)) return warn("cannot read " + csv);
  PlotSpec spec{title, xcol, ylabel, xcol, {}, false};
  for (const auto& y : ycols) spec.curves.push_back({y, y, ""});
  return plot_png(t, png, spec);
}

}  // namespace stentor
