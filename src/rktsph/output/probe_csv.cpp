#include "rktsph/output/probe_csv.hpp"

#include <iterator>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "rktsph/output/atomic_file.hpp"

namespace rktsph {

namespace {

void check_column_names(const std::vector<std::string>& column_names) {
  if (column_names.empty() || column_names.front() != "time") {
    throw std::invalid_argument("ProbeCsv: the first column must be named 'time'");
  }
  for (const std::string& name : column_names) {
    if (name.empty() || name.find_first_of(",\"\r\n") != std::string::npos) {
      throw std::invalid_argument(
          fmt::format("ProbeCsv: column name '{}' is empty or needs CSV quoting", name));
    }
  }
}

}  // namespace

ProbeCsv::ProbeCsv(std::vector<std::string> column_names) : column_names_(std::move(column_names)) {
  check_column_names(column_names_);
}

void ProbeCsv::add_row(double time, std::span<const double> values) {
  if (values.size() + 1 != column_names_.size()) {
    throw std::invalid_argument(fmt::format("ProbeCsv: row has {} values, expected {}",
                                            values.size(), column_names_.size() - 1));
  }
  values_.push_back(time);
  values_.insert(values_.end(), values.begin(), values.end());
}

void ProbeCsv::set_values(std::vector<double> values) {
  if (values.size() % column_names_.size() != 0) {
    throw std::invalid_argument(fmt::format("ProbeCsv: {} values are not rows of {} columns",
                                            values.size(), column_names_.size()));
  }
  values_ = std::move(values);
}

std::string ProbeCsv::to_string() const {
  fmt::memory_buffer buffer;
  fmt::format_to(std::back_inserter(buffer), "{}\n", fmt::join(column_names_, ","));
  const std::size_t columns = column_names_.size();
  for (std::size_t row_start = 0; row_start < values_.size(); row_start += columns) {
    for (std::size_t column = 0; column < columns; ++column) {
      fmt::format_to(std::back_inserter(buffer), "{}{:.17g}", column == 0 ? "" : ",",
                     values_[row_start + column]);
    }
    buffer.push_back('\n');
  }
  return fmt::to_string(buffer);
}

void ProbeCsv::flush(const std::filesystem::path& path) const {
  write_file_atomically(path, to_string());
}

}  // namespace rktsph
