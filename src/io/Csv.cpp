#include "io/Csv.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "io/SafeFile.hpp"
#include "io/WriteError.hpp"

namespace stentor {

namespace {

std::string csv_quote(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string r = "\"";
  for (char c : s) {
    if (c == '"') r += '"';
    r += c;
  }
  return r + '"';
}

}  // namespace

CsvWriter::CsvWriter(const std::string& path, std::vector<std::string> columns)
    : path_(path), columns_(std::move(columns)) {
  if (columns_.empty()) throw std::runtime_error("CsvWriter: no columns for " + path_);
  file_.reset(fopen_for_write(path_));
  if (!file_) throw std::runtime_error("CsvWriter: cannot open " + path_ + " for writing: " + open_error(errno));
  std::string header;
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    if (i) header += ',';
    header += csv_quote(columns_[i]);
  }
  header += '\n';
  check_write(std::fputs(header.c_str(), file_.get()) >= 0 && std::fflush(file_.get()) == 0,
              "CsvWriter: writing the header of", path_);
}

std::string format_double(double v) {
  char buf[40];
  for (int prec = 15; prec < 17; ++prec) {
    std::snprintf(buf, sizeof buf, "%.*g", prec, v);
    if (std::strtod(buf, nullptr) == v) return buf;  // NaN never compares equal: %.17g
  }
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

void CsvWriter::row(const std::vector<double>& values) {
  if (values.size() != columns_.size())
    throw std::runtime_error("CsvWriter: row of " + std::to_string(values.size()) +
                             " values for " + std::to_string(columns_.size()) + " columns in " +
                             path_);
  std::string line;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) line += ',';
    line += format_double(values[i]);
  }
  line += '\n';
  check_write(std::fputs(line.c_str(), file_.get()) >= 0 && std::fflush(file_.get()) == 0,
              "CsvWriter: writing a row to", path_);
}

}  // namespace stentor
