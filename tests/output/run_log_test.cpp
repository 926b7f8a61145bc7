#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "rktsph/core/error.hpp"
#include "rktsph/output/run_log.hpp"

namespace rktsph::run_log_test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> read_lines(const fs::path& path) {
  std::ifstream stream(path);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(stream, line))
    lines.push_back(line);
  return lines;
}

class RunLogTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("rktsph_log_test_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(directory_, ignored);
  }
  fs::path directory_;
};

// "YYYY-MM-DDThh:mm:ss.mmmZ LEVEL text". Checked by hand rather than with std::regex, which
// trips a false -Wmaybe-uninitialized in GCC 12 under the sanitizers.
bool is_timestamped_line(const std::string& line) {
  const std::string_view pattern = "dddd-dd-ddTdd:dd:dd.dddZ ";
  if (line.size() < pattern.size()) return false;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    const bool matches =
        pattern[i] == 'd' ? (line[i] >= '0' && line[i] <= '9') : line[i] == pattern[i];
    if (!matches) return false;
  }
  const std::string rest = line.substr(pattern.size());
  return rest.starts_with("INFO ") || rest.starts_with("WARNING ") || rest.starts_with("ERROR ");
}

TEST_F(RunLogTest, LinesAreTimestampedFlushedAndEchoed) {
  std::ostringstream echo;
  RunLog log(directory_, /*quiet=*/false, echo);
  log.info("run started");
  // Read while the log is still open: each line must already be on disk.
  std::vector<std::string> lines = read_lines(directory_ / "run.log");
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_TRUE(is_timestamped_line(lines[0])) << lines[0];
  EXPECT_TRUE(lines[0].ends_with(" INFO run started")) << lines[0];

  log.warning("two\nlines");
  log.error("stopped");
  lines = read_lines(directory_ / "run.log");
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_TRUE(lines[1].ends_with(" WARNING two")) << lines[1];
  EXPECT_TRUE(lines[2].ends_with(" WARNING lines")) << lines[2];
  EXPECT_TRUE(lines[3].ends_with(" ERROR stopped")) << lines[3];
  for (const std::string& line : lines) {
    EXPECT_TRUE(is_timestamped_line(line)) << line;
  }
  EXPECT_EQ(echo.str(), "run started\nwarning: two\nlines\nerror: stopped\n");
}

TEST_F(RunLogTest, QuietEchoesNothing) {
  std::ostringstream echo;
  RunLog log(directory_, /*quiet=*/true, echo);
  log.info("hidden");
  log.error("also hidden");
  EXPECT_EQ(echo.str(), "");
  EXPECT_EQ(read_lines(directory_ / "run.log").size(), 2u);
}

TEST_F(RunLogTest, AReopenedLogIsAppendedTo) {
  std::ostringstream echo;
  {
    RunLog log(directory_, true, echo);
    log.info("first run");
  }
  {
    RunLog log(directory_, true, echo);
    log.info("restart");
  }
  const std::vector<std::string> lines = read_lines(directory_ / "run.log");
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_TRUE(lines[0].ends_with("first run"));
  EXPECT_TRUE(lines[1].ends_with("restart"));
}

TEST_F(RunLogTest, APlantedSymlinkIsNotWrittenThrough) {
  const fs::path victim = directory_ / "victim.txt";
  std::ofstream(victim) << "precious\n";
  fs::create_symlink(victim, directory_ / "run.log");
  std::ostringstream echo;
  EXPECT_THROW(RunLog(directory_, true, echo), RunError);
  EXPECT_EQ(read_lines(victim), std::vector<std::string>{"precious"});
}

TEST_F(RunLogTest, MissingDirectoryThrowsRunError) {
  std::ostringstream echo;
  EXPECT_THROW(RunLog(directory_ / "missing", false, echo), RunError);
}

}  // namespace
}  // namespace rktsph::run_log_test
