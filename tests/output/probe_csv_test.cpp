#include <gtest/gtest.h>

#include <unistd.h>

#include <bit>
#include <cfloat>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "rktsph/output/probe_csv.hpp"

namespace rktsph::probe_csv_test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream stream(text);
  while (std::getline(stream, part, separator))
    parts.push_back(part);
  return parts;
}

TEST(ProbeCsv, HeaderIsTheColumnNamesJoinedByCommas) {
  ProbeCsv csv({"time", "stress_xx@node26", "velocity_x@node26"});
  EXPECT_EQ(csv.to_string(), "time,stress_xx@node26,velocity_x@node26\n");
}

TEST(ProbeCsv, SimpleValuesAreWrittenPlainly) {
  ProbeCsv csv({"time", "a", "b"});
  const std::vector<double> first = {1.0, -2.5};
  const std::vector<double> second = {0.0, 1e-3};
  csv.add_row(0.0, first);
  csv.add_row(0.25, second);
  EXPECT_EQ(csv.row_count(), 2u);
  // %.17g of these values, worked out by hand: exact binary fractions print without noise.
  EXPECT_EQ(csv.to_string(), "time,a,b\n0,1,-2.5\n0.25,0,0.001\n");
}

TEST(ProbeCsv, FileValuesReadBackToTheSameDoubles) {
  const fs::path file =
      fs::temp_directory_path() / ("rktsph_probe_test_" + std::to_string(::getpid()) + ".csv");
  const std::vector<double> values = {0.1,     1.0 / 3.0, -3.5e-7, 12345.678, DBL_MAX,
                                      DBL_MIN, 4.9e-324,  -0.0,    1e300,     2.0 / 7.0e-9};
  ProbeCsv csv({"time", "v0", "v1", "v2", "v3", "v4", "v5", "v6", "v7", "v8", "v9"});
  csv.add_row(1.0 / 7.0, values);
  csv.flush(file);

  std::ifstream stream(file);
  std::string header, row, extra;
  ASSERT_TRUE(std::getline(stream, header));
  ASSERT_TRUE(std::getline(stream, row));
  EXPECT_FALSE(std::getline(stream, extra));
  EXPECT_EQ(header, "time,v0,v1,v2,v3,v4,v5,v6,v7,v8,v9");
  const std::vector<std::string> cells = split(row, ',');
  ASSERT_EQ(cells.size(), values.size() + 1);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(std::strtod(cells[0].c_str(), nullptr)),
            std::bit_cast<std::uint64_t>(1.0 / 7.0));
  for (std::size_t i = 0; i < values.size(); ++i) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(std::strtod(cells[i + 1].c_str(), nullptr)),
              std::bit_cast<std::uint64_t>(values[i]))
        << cells[i + 1];
  }
  fs::remove(file);
}

TEST(ProbeCsv, FlushRewritesTheWholeFile) {
  const fs::path file =
      fs::temp_directory_path() / ("rktsph_probe_rewrite_" + std::to_string(::getpid()) + ".csv");
  ProbeCsv csv({"time", "p"});
  const std::vector<double> value = {2.0};
  csv.add_row(0.5, value);
  csv.flush(file);
  csv.add_row(1.5, value);
  csv.flush(file);
  std::ifstream stream(file);
  std::ostringstream content;
  content << stream.rdbuf();
  EXPECT_EQ(content.str(), "time,p\n0.5,2\n1.5,2\n");
  fs::remove(file);
}

TEST(ProbeCsv, RejectsBadColumnsAndRows) {
  EXPECT_THROW(ProbeCsv({"t", "a"}), std::invalid_argument);
  EXPECT_THROW(ProbeCsv({}), std::invalid_argument);
  EXPECT_THROW(ProbeCsv({"time", "a,b"}), std::invalid_argument);
  ProbeCsv csv({"time", "a", "b"});
  const std::vector<double> too_short = {1.0};
  EXPECT_THROW(csv.add_row(0.0, too_short), std::invalid_argument);
  EXPECT_EQ(csv.row_count(), 0u);
}

}  // namespace
}  // namespace rktsph::probe_csv_test
