// A record of every end: however a run stops (interrupted between steps, an output it cannot
// write, a setup or input error once its folder exists), summary.json says how, with the error
// text, and the last line of run.log says the same; the probes on disk reach the last field file.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "../support/small_bar.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/core/error.hpp"
#include "rktsph/driver/run_case.hpp"

namespace rktsph::run_case_test {
namespace {

namespace fs = std::filesystem;

using rktsph::test::kBar;

std::string read_whole_file(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream content;
  content << stream.rdbuf();
  return content.str();
}

std::vector<std::string> lines_of(const fs::path& path) {
  std::ifstream stream(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(stream, line);)
    lines.push_back(line);
  return lines;
}

// The time of the last row of probes.csv.
double last_probe_time(const fs::path& path) {
  const std::vector<std::string> lines = lines_of(path);
  if (lines.size() < 2) return -1.0;
  return std::stod(lines.back().substr(0, lines.back().find(',')));
}

std::size_t files_in(const fs::path& directory) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(directory), {}));
}

class RunCaseTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("rktsph_run_case_test_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(directory_, ignored);
  }
  static CaseDescription bar() { return read_case_text(kBar, "bar.yaml"); }
  std::string summary() const { return read_whole_file(directory_ / "summary.json"); }
  std::string last_log_line() const {
    const std::vector<std::string> lines = lines_of(directory_ / "run.log");
    return lines.empty() ? std::string() : lines.back();
  }

  fs::path directory_;
};

TEST_F(RunCaseTest, AnInterruptedRunEndsOnAWholeStepAndRecordsIt) {
  RunOptions options;
  options.quiet = true;
  int checks = 0;
  options.stop_check = [&checks] { return ++checks > 7 ? std::string("test stop") : ""; };
  const RunOutcome outcome = run_case(bar(), directory_, options);
  EXPECT_EQ(outcome.status, RunStatus::Interrupted);
  EXPECT_EQ(outcome.steps, 7);
  EXPECT_NE(summary().find("\"status\": \"interrupted\""), std::string::npos) << summary();
  EXPECT_NE(summary().find("test stop"), std::string::npos) << summary();
  // A stop the user asked for is recorded, but it is not an error of the run.
  EXPECT_NE(last_log_line().find("INFO interrupted: interrupted at step 7"), std::string::npos)
      << last_log_line();
  EXPECT_EQ(read_whole_file(directory_ / "run.log").find("ERROR"), std::string::npos)
      << read_whole_file(directory_ / "run.log");
  // The probes and the last field file reach the step the run stopped at.
  const std::string pvd = read_whole_file(directory_ / "series.pvd");
  const double stopped_at = last_probe_time(directory_ / "probes.csv");
  EXPECT_GT(stopped_at, 0.0);
  EXPECT_NE(pvd.find(fmt::format("timestep=\"{}\"", stopped_at)), std::string::npos) << pvd;
}

// Checks, after the standard observers, that probes.csv on disk reaches every new field file.
class ProbesOnDiskObserver final : public Observer {
 public:
  explicit ProbesOnDiskObserver(fs::path directory) : directory_(std::move(directory)) {}
  void after_step(const Simulation& simulation) override {
    const std::size_t vtus = files_in(directory_ / "fields");
    if (vtus == vtus_) return;
    vtus_ = vtus;
    ++checked_;
    EXPECT_EQ(last_probe_time(directory_ / "probes.csv"), simulation.state().time)
        << "field file " << vtus;
  }
  int checked_ = 0;

 private:
  fs::path directory_;
  std::size_t vtus_ = 1;  // the one at t = 0
};

TEST_F(RunCaseTest, ProbesAreOnDiskWithEveryFieldOutput) {
  ProbesOnDiskObserver check(directory_);
  RunOptions options;
  options.quiet = true;
  options.observers = {&check};
  EXPECT_EQ(run_case(bar(), directory_, options).status, RunStatus::Completed);
  EXPECT_GE(check.checked_, 4);
}

// An output that cannot be written (here: a full disk, simulated) ends the run as failed.
class FailingOutput final : public Observer {
 public:
  void after_step(const Simulation& simulation) override {
    if (simulation.state().step == 5)
      throw RunError("cannot write 'out/fields_000002.vtu': No space left on device");
  }
};

TEST_F(RunCaseTest, AnOutputThatCannotBeWrittenEndsTheRunAsFailedWithItsReason) {
  FailingOutput failing;
  RunOptions options;
  options.quiet = true;
  options.observers = {&failing};
  const RunOutcome outcome = run_case(bar(), directory_, options);
  EXPECT_EQ(outcome.status, RunStatus::Failed);
  EXPECT_EQ(outcome.steps, 5);
  EXPECT_NE(summary().find("\"status\": \"failed\""), std::string::npos) << summary();
  EXPECT_NE(summary().find("No space left on device"), std::string::npos) << summary();
  EXPECT_NE(last_log_line().find("ERROR failed: failed at step 5"), std::string::npos)
      << last_log_line();
  EXPECT_NE(last_log_line().find("No space left on device"), std::string::npos);
}

TEST_F(RunCaseTest, AnInputErrorAtRunStartLeavesASummaryAndALogLine) {
  CaseDescription description = bar();
  description.probes.front().fields = {"velocity_q"};  // as if it had passed the reader
  RunOptions options;
  options.quiet = true;
  EXPECT_THROW(run_case(description, directory_, options), InputError);
  EXPECT_NE(summary().find("\"status\": \"failed\""), std::string::npos) << summary();
  EXPECT_NE(summary().find("velocity_q"), std::string::npos) << summary();
  EXPECT_NE(last_log_line().find("ERROR failed:"), std::string::npos) << last_log_line();
  EXPECT_NE(last_log_line().find("velocity_q"), std::string::npos) << last_log_line();
}

// The record of a case mistake must not stand in the way of the corrected case: the rerun into
// the same folder needs no --overwrite, since there are no results to protect.
TEST_F(RunCaseTest, TheRecordOfAnInputErrorDoesNotBlockTheCorrectedRun) {
  CaseDescription description = bar();
  description.probes.front().fields = {"velocity_q"};
  RunOptions options;
  options.quiet = true;
  EXPECT_THROW(run_case(description, directory_, options), InputError);
  ASSERT_TRUE(fs::exists(directory_ / "summary.json"));
  const RunOutcome outcome = run_case(bar(), directory_, options);
  EXPECT_EQ(outcome.status, RunStatus::Completed) << outcome.message;
  EXPECT_NE(summary().find("\"status\": \"completed\""), std::string::npos) << summary();
  // Results are still protected: a third run without --overwrite is refused.
  EXPECT_THROW(run_case(bar(), directory_, options), InputError);
}

TEST_F(RunCaseTest, ASetupErrorAfterTheFolderExistsLeavesASummaryNamingThePath) {
  fs::create_directories(directory_);
  std::ofstream(directory_ / "fields") << "a file where the field folder goes\n";
  RunOptions options;
  options.quiet = true;
  EXPECT_THROW(run_case(bar(), directory_, options), RunError);
  EXPECT_NE(summary().find("\"status\": \"failed\""), std::string::npos) << summary();
  EXPECT_NE(summary().find((directory_ / "fields").string()), std::string::npos) << summary();
  EXPECT_NE(last_log_line().find("ERROR failed:"), std::string::npos) << last_log_line();
}

TEST_F(RunCaseTest, TheSummaryAndTheLogNameTheCommitAndTheBuild) {
  RunOptions options;
  options.quiet = true;
  ASSERT_EQ(run_case(bar(), directory_, options).status, RunStatus::Completed);
  EXPECT_NE(summary().find("\"version\": \"" RKTSPH_VERSION "\""), std::string::npos);
  EXPECT_NE(summary().find("\"commit\": \""), std::string::npos) << summary();
  EXPECT_NE(summary().find("\"build_type\": \""), std::string::npos) << summary();
  EXPECT_NE(lines_of(directory_ / "run.log").front().find("(commit "), std::string::npos);
}

}  // namespace
}  // namespace rktsph::run_case_test
