// Checkpoint and restart as a user meets them: a run killed with SIGKILL after a checkpoint and
// continued with `rktsph run CASE --restart RUN_DIR` ends with the same bytes as a run that was
// never interrupted (every VTU, series.pvd, probes.csv), also on another thread count; and a
// checkpoint that cannot be continued is refused with exit status 2 before anything is written.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../support/shell.hpp"
#include "rktsph/core/checkpoint.hpp"

namespace restart_test {
namespace {

namespace fs = std::filesystem;

using Result = rktsph::test::ShellResult;

Result run(const std::string& arguments) {
  return rktsph::test::run_rktsph(arguments);
}

fs::path scratch(const std::string& name) {
  return rktsph::test::scratch_file("rktsph_restart", name);
}

std::string read_bytes(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream content;
  content << stream.rdbuf();
  return content.str();
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

std::string bundled_case(const std::string& name) {
  return std::string(RKTSPH_TEST_DATA_DIR) + "/../../cases/" + name + "/case.yaml";
}

// Starts the program in the background (output discarded) and returns its process id.
pid_t start(const std::vector<std::string>& arguments) {
  std::vector<char*> argv;
  std::string binary = RKTSPH_BINARY;
  argv.push_back(binary.data());
  std::vector<std::string> copies = arguments;
  for (std::string& argument : copies)
    argv.push_back(argument.data());
  argv.push_back(nullptr);
  const pid_t child = fork();
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    ::execv(argv[0], argv.data());
    _exit(127);
  }
  return child;
}

// Polls until `file` exists or the child has exited; false after a minute (a hang guard, not a
// timing assertion: the runs here take about a second).
bool wait_for_file_or_exit(const fs::path& file, pid_t child) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  while (std::chrono::steady_clock::now() < give_up) {
    if (fs::exists(file)) return true;
    siginfo_t info{};
    if (::waitid(P_PID, static_cast<id_t>(child), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
        info.si_pid == child)
      return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return false;
}

std::string join(const std::vector<std::string>& words) {
  std::string text;
  for (const std::string& word : words)
    text += " " + word;
  return text;
}

// The "energy" object of a run folder's summary.json, as text (it holds no nested object).
std::string energy_block(const fs::path& folder) {
  const std::string summary = read_bytes(folder / "summary.json");
  const std::size_t begin = summary.find("\"energy\": {");
  if (begin == std::string::npos) return "no energy block in " + summary;
  return summary.substr(begin, summary.find('}', begin) - begin);
}

// Every file of the uninterrupted run's series and probes has the same bytes in the restarted
// run's folder, the restarted folder has no other VTU, and the summaries' energy budgets are
// the same.
void expect_same_results(const fs::path& uninterrupted, const fs::path& restarted) {
  for (const char* name : {"probes.csv", "series.pvd"})
    EXPECT_TRUE(read_bytes(uninterrupted / name) == read_bytes(restarted / name)) << name;
  EXPECT_EQ(energy_block(uninterrupted), energy_block(restarted));
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(uninterrupted / "fields")) {
    const fs::path other = restarted / "fields" / entry.path().filename();
    ASSERT_TRUE(fs::exists(other)) << other;
    EXPECT_TRUE(read_bytes(entry.path()) == read_bytes(other)) << other;
    ++files;
  }
  EXPECT_EQ(static_cast<std::size_t>(std::distance(fs::directory_iterator(restarted / "fields"),
                                                   fs::directory_iterator{})),
            files);
  EXPECT_GE(files, 3u);
}

// Runs `case_file` with `sets` once uninterrupted (2 threads, no checkpoints), once with
// checkpoints every `interval` killed by SIGKILL as soon as `kill_after` (relative to the run
// folder) exists past the first checkpoint, then continues that run on 1 thread.
void expect_restart_bit_identical(const std::string& name, const std::string& case_file,
                                  const std::vector<std::string>& sets, double interval,
                                  const std::string& kill_after) {
  const fs::path uninterrupted = scratch(name + "-uninterrupted");
  const fs::path killed = scratch(name + "-killed");
  fs::remove_all(uninterrupted);
  fs::remove_all(killed);
  const Result whole =
      run("run " + case_file + " -q --threads 2 -o " + uninterrupted.string() + join(sets));
  ASSERT_EQ(whole.status, 0) << whole.output;

  std::vector<std::string> checkpointed = sets;
  for (const std::string& set :
       {std::string("--set"), "output.checkpoint_interval=" + std::to_string(interval)})
    checkpointed.push_back(set);
  std::vector<std::string> arguments = {"run", case_file, "-q",           "--threads",
                                        "2",   "-o",      killed.string()};
  arguments.insert(arguments.end(), checkpointed.begin(), checkpointed.end());
  const pid_t child = start(arguments);
  ASSERT_GT(child, 0);
  const bool reached = wait_for_file_or_exit(killed / "checkpoint.bin", child) &&
                       wait_for_file_or_exit(killed / kill_after, child);
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(reached) << "no checkpoint within a minute";
  // Whether the kill came before the run ended depends on the machine's load; either way the
  // restart continues from the checkpoint and must end with the same bytes.
  ::testing::Test::RecordProperty("killed_before_the_end", WIFSIGNALED(status) ? 1 : 0);
  ASSERT_TRUE(fs::exists(killed / "checkpoint.bin"));

  const Result restarted =
      run("run " + case_file + " -q --threads 1 --restart " + killed.string() + join(checkpointed));
  ASSERT_EQ(restarted.status, 0) << restarted.output;
  EXPECT_NE(read_bytes(killed / "run.log").find("continuing from"), std::string::npos);
  expect_same_results(uninterrupted, killed);
}

TEST(Restart, KilledDryRunWithInternalVariablesAndStrainStiffnessContinuesBitIdentical) {
  // Perzyna softening (internal variables), both hourglass stiffnesses on (State::strain).
  expect_restart_bit_identical(
      "dry", bundled_case("sample2d-localization"),
      {"--set", "geometry.spacing=0.05", "--set", "time.end=0.06", "--set",
       "numerics.hourglass.strain_stiffness=0.2", "--set", "numerics.hourglass.stiffness=0.5"},
      0.025, "fields/fields_000003.vtu");
}

TEST(Restart, KilledSaturatedRunContinuesBitIdentical) {
  // The pressure solve's warm start (the previous step's p_w) is part of the checkpoint.
  expect_restart_bit_identical("saturated", bundled_case("vpw-consolidation"),
                               {"--set", "time.end=1.0", "--set", "output.interval=0.25"}, 0.4,
                               "fields/fields_000002.vtu");
}

const char* kBar = R"(name: bar
dimension: 1
geometry:
  spacing: 0.5
  shapes:
    - segment: [0.0, 10.0]
      material: soil
materials:
  soil: {model: linear_elastic, density: 2000.0, young_modulus: 1.0e8, poisson_ratio: 0.0}
boundary_conditions:
  - {group: xmax, velocity: {x: -0.1}}
numerics: {courant: 0.9}
time: {end: 0.05}
output: {interval: 0.01, checkpoint_interval: 0.02}
probes:
  - {name: free, group: xmin, fields: [velocity_x]}
)";

class RestartRefusal : public ::testing::Test {
 protected:
  void SetUp() override {
    case_file_ = scratch("bar.yaml");
    std::ofstream(case_file_) << kBar;
    folder_ = scratch("bar-run");
    fs::remove_all(folder_);
    const Result first = run("run " + case_file_.string() + " -q -o " + folder_.string());
    ASSERT_EQ(first.status, 0) << first.output;
    ASSERT_TRUE(fs::exists(checkpoint()));
    probes_ = read_bytes(folder_ / "probes.csv");
  }
  fs::path checkpoint() const { return folder_ / "checkpoint.bin"; }
  // Restarts with extra arguments; the refusal must leave the results as they were.
  Result restart(const std::string& extra = "") const {
    const Result result =
        run("run " + case_file_.string() + " -q --restart " + folder_.string() + extra);
    EXPECT_EQ(read_bytes(folder_ / "probes.csv"), probes_);
    return result;
  }
  void expect_refused(const Result& result, const std::string& text) const {
    EXPECT_EQ(result.status, 2) << result.output;
    EXPECT_NE(result.output.find(text), std::string::npos) << result.output;
  }

  fs::path case_file_, folder_;
  std::string probes_;
};

TEST_F(RestartRefusal, ContinuesItsOwnCheckpoint) {
  const Result result = restart();
  EXPECT_EQ(result.status, 0) << result.output;
}

TEST(Restart, ResolvedCaseOfTheRunFolderNeedsNoOverrides) {
  // case.yaml in the run folder reads back to the same case, --set overrides included.
  const fs::path case_file = scratch("bar-overridden.yaml");
  std::ofstream(case_file) << kBar;
  const fs::path folder = scratch("bar-overridden-run");
  fs::remove_all(folder);
  const Result first =
      run("run " + case_file.string() + " -q --set time.end=0.045 -o " + folder.string());
  ASSERT_EQ(first.status, 0) << first.output;
  const Result again =
      run("run " + (folder / "case.yaml").string() + " -q --restart " + folder.string());
  EXPECT_EQ(again.status, 0) << again.output;
}

TEST(Restart, NegativeCheckpointIntervalIsRefused) {
  const fs::path case_file = scratch("bar-negative.yaml");
  std::ofstream(case_file) << kBar;
  const Result result = run("check " + case_file.string() + " --set output.checkpoint_interval=-1");
  EXPECT_EQ(result.status, 2) << result.output;
  EXPECT_NE(result.output.find("output.checkpoint_interval"), std::string::npos) << result.output;
}

TEST_F(RestartRefusal, OtherCaseIsRefusedNamingBothHashes) {
  const Result result = restart(" --set time.end=0.06");
  expect_refused(result,
                 "checkpoint.bin: error: key '--restart': the checkpoint was written for "
                 "a different case: case hash ");
  EXPECT_NE(result.output.find("for this case file with these --set overrides"), std::string::npos);
}

TEST_F(RestartRefusal, OtherFormatVersionIsRefused) {
  std::string bytes = read_bytes(checkpoint());
  bytes[8] = 99;  // the u32 after the 8-byte magic
  write_bytes(checkpoint(), bytes);
  expect_refused(restart(),
                 "checkpoint format version 99, but this build of rktsph reads only "
                 "version " +
                     std::to_string(rktsph::kCheckpointFormatVersion));
}

TEST_F(RestartRefusal, TruncatedCheckpointIsRefused) {
  const std::string bytes = read_bytes(checkpoint());
  write_bytes(checkpoint(), bytes.substr(0, bytes.size() / 2));
  expect_refused(restart(), "the checkpoint is truncated or damaged");
}

TEST_F(RestartRefusal, DamagedCheckpointIsRefused) {
  std::string bytes = read_bytes(checkpoint());
  bytes[bytes.size() / 2] ^= 0x10;
  write_bytes(checkpoint(), bytes);
  expect_refused(restart(), "the checkpoint is truncated or damaged (checksum mismatch");
}

TEST_F(RestartRefusal, OtherFileIsRefused) {
  write_bytes(checkpoint(), "name: not a checkpoint\n");
  expect_refused(restart(), "not an rktsph checkpoint");
}

TEST_F(RestartRefusal, MissingCheckpointIsRefused) {
  fs::remove(checkpoint());
  expect_refused(restart(), "no checkpoint in the run folder");
}

TEST_F(RestartRefusal, MissingFolderIsRefused) {
  const Result result =
      run("run " + case_file_.string() + " -q --restart " + scratch("no-such-run").string());
  expect_refused(result, "no such run folder");
}

TEST_F(RestartRefusal, OtherOutputFolderIsRefused) {
  expect_refused(restart(" -o " + scratch("elsewhere").string()),
                 "a restarted run continues in its own folder");
}

TEST_F(RestartRefusal, NewRunRemovesTheCheckpointOfTheOldOne) {
  // A checkpoint left by an earlier run would restore results that are no longer beside it: it
  // counts among the earlier run's results, which a new run refuses, and --overwrite removes it.
  const Result refused = run("run " + case_file_.string() + " -q -o " + folder_.string() +
                             " --set output.checkpoint_interval=0");
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_NE(refused.output.find("checkpoint.bin"), std::string::npos) << refused.output;
  const Result again = run("run " + case_file_.string() + " -q --overwrite -o " + folder_.string() +
                           " --set output.checkpoint_interval=0");
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_FALSE(fs::exists(checkpoint()));
}

}  // namespace
}  // namespace restart_test
