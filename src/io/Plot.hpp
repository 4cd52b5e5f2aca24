// PNG plots of CSV time series through gnuplot (optional at run time).
#pragma once
#include <chrono>
#include <string>
#include <vector>

namespace stentor {

// A table of named columns of equal length: the data of one or more plots.
struct PlotTable {
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
  // Index of column `name`, -1 when there is none.
  int find(const std::string& name) const;
  void add(std::string name, std::vector<double> values);
  std::size_t rows() const { return columns.empty() ? 0 : columns.front().size(); }
};

// Reads a CsvWriter file (header line, comma separated, RFC 4180 quoting) into `t`.
// False when it cannot be read or a row has the wrong number of fields.
bool read_csv_table(const std::string& csv, PlotTable& t);

// One curve: column `y` against column `x` (the plot's x when empty), with its legend.
struct PlotCurve {
  std::string y, legend, x;
};

// What one PNG shows: title, axis labels (with units: io/Units.hpp), curves.
struct PlotSpec {
  std::string title, xlabel, ylabel;
  std::string x;  // column of the x values
  std::vector<PlotCurve> curves;
  bool x_from_zero = false;  // the x axis starts at 0 (a time axis: the initial state)
};

// A vertical dashed line at x with its label (a stage boundary).
struct PlotMark {
  double x;
  std::string label;
};

// Plots `spec` from `table` into `png`, with lines. Writes the gnuplot script next to the
// png (<png without .png>.gp) with the plotted columns inline (a datablock), so
// `cd dir; gnuplot x.gp` redoes the plot wherever the directory went; the script is
// written even when gnuplot is not installed. Runs `gnuplot` from PATH in that directory
// (terminal pngcairo when available, else png); gnuplot's messages go to <script>.log
// (removed when empty). Every label and file name is written as a gnuplot single-quoted
// string, where gnuplot expands nothing (no `command` substitution, no escapes): text from
// the deck is never interpreted. Non-finite values are written as NaN (a gap in the curve).
// gnuplot gets 60 s per plot, then is killed with whatever it started (it runs in a
// process group of its own); after that the run's later plots are not tried (their
// scripts are written). A failed or stopped gnuplot leaves no PNG (not a truncated one),
// nor does one that exits 0 with a PNG cut short (its write failed: a full disk).
// Returns false when a column is missing, there is no curve or no row, gnuplot is not
// installed, or gnuplot fails, times out or produces no PNG; the run can go on without
// plots. Throws only WriteError, when the script itself cannot be written (a full disk:
// the run stops).
// `marks`: vertical dashed lines drawn over the plot.
bool plot_png(const PlotTable& table, const std::string& png, const PlotSpec& spec,
              const std::vector<PlotMark>& marks = {});

// plot_png of columns `ycols` of the CSV file `csv` against `xcol`, legends the column
// names, x label `xcol`.
bool plot_csv_png(const std::string& csv, const std::string& png, const std::string& xcol,
                  const std::vector<std::string>& ycols, const std::string& title,
                  const std::string& ylabel);

// True when a `gnuplot` executable is on PATH.
bool gnuplot_available();

// The time gnuplot gets per plot (60 s unless a test sets it); also forgets that gnuplot
// was stopped before, so that plots are tried again.
void set_plot_time_limit(std::chrono::milliseconds limit);

}  // namespace stentor
