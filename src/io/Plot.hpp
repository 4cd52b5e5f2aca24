// PNG plots of CSV time series through gnuplot (optional at run time).
#pragma once
#include <string>
#include <vector>

namespace stentor {

// Plots columns `ycols` of `csv` (a CsvWriter file: header line, comma separated) against
// column `xcol` into `png`, with lines. Writes the gnuplot script next to the png
// (<png without .png>.gp, naming its files relative to its directory, so `cd dir; gnuplot
// x.gp` redoes the plot after the directory moved) and runs `gnuplot` from PATH in that
// directory (terminal pngcairo when available, else png); gnuplot's messages go to
// <script>.log (removed when empty). Every label and file name is written as a gnuplot
// single-quoted string, where gnuplot expands nothing (no `command` substitution, no
// escapes): text from the deck is never interpreted. gnuplot gets 60 s per plot, then is
// killed.
// Returns false when gnuplot is not installed, the CSV cannot be read, a column is missing,
// or gnuplot fails, times out or produces no PNG; the run can go on without plots. Throws
// only WriteError, when the script itself cannot be written (a full disk: the run stops).
bool plot_csv_png(const std::string& csv, const std::string& png, const std::string& xcol,
                  const std::vector<std::string>& ycols, const std::string& title,
                  const std::string& ylabel);

// True when a `gnuplot` executable is on PATH.
bool gnuplot_available();

}  // namespace stentor
