// Time histories at probes, kept in memory and written as one CSV file.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace rktsph {

class ProbeCsv {
 public:
  /// `column_names` must start with "time" and must not contain ',', '"', or line breaks (so the
  /// header needs no quoting); otherwise std::invalid_argument.
  explicit ProbeCsv(std::vector<std::string> column_names);

  /// Stores one row; `values` holds every column after "time", in order. A wrong count is a
  /// programming error (std::invalid_argument).
  void add_row(double time, std::span<const double> values);

  /// Rewrites the whole file atomically with all rows so far; throws RunError on I/O failure.
  /// Values are written with 17 significant digits, so they read back to the same doubles.
  void flush(const std::filesystem::path& path) const;

  /// The file content: header line, then one line per row, each ending in '\n'.
  std::string to_string() const;

  const std::vector<std::string>& column_names() const { return column_names_; }
  std::size_t row_count() const { return values_.size() / column_names_.size(); }
  /// Every row so far, row-major, time first (what a checkpoint keeps).
  const std::vector<double>& values() const { return values_; }
  /// Replaces the rows (a restarted run's, from its checkpoint); a count that is not a whole
  /// number of rows is std::invalid_argument.
  void set_values(std::vector<double> values);

 private:
  std::vector<std::string> column_names_;
  /// Row-major, column_names_.size() values per row, time first.
  std::vector<double> values_;
};

}  // namespace rktsph
