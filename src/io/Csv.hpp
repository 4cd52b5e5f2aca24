// Time series as CSV: a header line, then one line per row, every value in the shortest
// form that reads back as the same double (format_double: 0.1, not %.17g's
// 0.10000000000000001). Each row is flushed as it is written:
// a long run that crashes keeps every row written so far.
#pragma once
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace stentor {

// The shortest of %.15g, %.16g, %.17g that reads back (strtod) as exactly v: the value
// to the last bit, without the noise digits of %.17g (0.1 -> "0.1", 0.1 + 0.2 ->
// "0.30000000000000004", which is not the double nearest 0.3).
std::string format_double(double v);

class CsvWriter {
 public:
  // Creates (truncates) `path` and writes the header. Column names containing ',', '"'
  // or line breaks are quoted (RFC 4180). Throws std::runtime_error naming the file.
  CsvWriter(const std::string& path, std::vector<std::string> columns);
  // Throws std::runtime_error if values.size() != number of columns, WriteError (naming
  // the file and the reason, e.g. "No space left on device") on a write error.
  void row(const std::vector<double>& values);

  const std::string& path() const { return path_; }
  const std::vector<std::string>& columns() const { return columns_; }

 private:
  struct Closer {
    void operator()(std::FILE* f) const { if (f) std::fclose(f); }
  };
  std::string path_;
  std::vector<std::string> columns_;
  std::unique_ptr<std::FILE, Closer> file_;
};

}  // namespace stentor
