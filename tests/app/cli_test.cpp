// The rktsph command line as a user meets it: exit statuses, errors that name the file, line and
// key, a run's files (read back by an independent parser), and a diverging run.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <yaml-cpp/yaml.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "../support/shell.hpp"
#include "../support/small_bar.hpp"

namespace cli_test {
namespace {

namespace fs = std::filesystem;

using Result = rktsph::test::ShellResult;

Result run(const std::string& arguments) {
  return rktsph::test::run_rktsph(arguments);
}

fs::path scratch(const std::string& name) {
  return rktsph::test::scratch_file("rktsph_cli", name);
}

fs::path write_case(const std::string& name, const std::string& text) {
  const fs::path path = scratch(name);
  std::ofstream(path) << text;
  return path;
}

using rktsph::test::kBar;

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

std::string read_whole_file(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream content;
  content << stream.rdbuf();
  return content.str();
}

std::size_t field_files(const fs::path& run_directory) {
  return static_cast<std::size_t>(
      std::distance(fs::directory_iterator(run_directory / "fields"), {}));
}

TEST(CommandLine, VersionAndHelp) {
  const Result version = run("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_NE(version.output.find("rktsph "), std::string::npos);
  EXPECT_EQ(run("run --help").status, 0);
  EXPECT_EQ(run("no-such-command").status, 2);
}

// `rktsph` alone is what a new user types first: it should say which commands there are and
// what each does, not only that one is required.
TEST(CommandLine, NoCommandListsTheCommands) {
  const Result result = run("");
  EXPECT_EQ(result.status, 2);
  for (const char* line : {"run ", "check ", "validate ", "plot "})
    EXPECT_NE(result.output.find(std::string("  ") + line), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("Validate a case file without running it"), std::string::npos)
      << result.output;
  EXPECT_EQ(result.output.find("A subcommand is required"), std::string::npos) << result.output;
}

// check builds the stencils as run does, so it takes the same --threads.
TEST(CommandLine, CheckTakesThreadsAsRunDoes) {
  const fs::path case_file = write_case("threads.yaml", kBar);
  const Result result = run("check " + case_file.string() + " --threads 1");
  EXPECT_EQ(result.status, 0) << result.output;
  EXPECT_EQ(run("check " + case_file.string() + " --threads 0").status, 2);
}

// The interpreter of `rktsph plot` is the python3 of PATH (a virtual environment's, with its
// matplotlib) when it has matplotlib, not always /usr/bin/python3. The stand-in python3 here says
// yes to everything and records what it was asked to run.
TEST(CommandLine, PlotRunsThePython3OfPath) {
  const fs::path bin = scratch("fake-python-bin");
  fs::create_directories(bin);
  const fs::path marker = scratch("fake-python-called");
  fs::remove(marker);
  std::ofstream(bin / "python3") << "#!/bin/sh\necho \"$@\" > " << marker.string() << "\nexit 0\n";
  fs::permissions(bin / "python3", fs::perms::owner_all);
  const Result result = rktsph::test::shell(
      "PATH=" + bin.string() + ":\"$PATH\" " + RKTSPH_BINARY + " plot " +
      scratch("no-run").string() + " --field velocity -o " + scratch("p.png").string() + " 2>&1");
  EXPECT_EQ(result.status, 0) << result.output;
  EXPECT_NE(read_whole_file(marker).find("plot_field.py"), std::string::npos);
}

// A user's own ./cases folder is theirs: validate still finds the bundled cases.
TEST(CommandLine, ValidateUsesTheBundledCasesBesideTheUsersOwn) {
  const fs::path work = scratch("own-cases");
  fs::create_directories(work / "cases" / "my-slope");
  std::ofstream(work / "cases" / "my-slope" / "case.yaml") << kBar;
  const Result result = rktsph::test::shell("cd " + work.string() + " && " + RKTSPH_BINARY +
                                            " validate bar1d-elastic --quick --threads 1 -o " +
                                            (work / "out").string() + " 2>&1");
  EXPECT_EQ(result.status, 0) << result.output;
}

// When the cases are not where validate looks, the error names that folder and how to change it.
TEST(CommandLine, ValidateNamesTheFolderItLookedIn) {
  const fs::path missing = scratch("no-such-cases-folder");
  const Result from_environment = rktsph::test::shell(
      "RKTSPH_CASES=" + missing.string() + " " + RKTSPH_BINARY + " validate bar1d-elastic 2>&1");
  EXPECT_EQ(from_environment.status, 2) << from_environment.output;
  EXPECT_NE(from_environment.output.find(missing.string()), std::string::npos)
      << from_environment.output;
  EXPECT_NE(from_environment.output.find("RKTSPH_CASES"), std::string::npos)
      << from_environment.output;

  const fs::path empty = scratch("empty-cases-folder");
  fs::create_directories(empty);
  const Result from_option = run("validate bar1d-elastic --quick --cases " + empty.string() +
                                 " -o " + scratch("empty-cases-out").string());
  EXPECT_EQ(from_option.status, 1) << from_option.output;
  EXPECT_NE(from_option.output.find("the cases were looked for in " + empty.string() + ": --cases"),
            std::string::npos)
      << from_option.output;
}

TEST(CommandLine, VersionNamesTheCommitAndTheBuildType) {
  const Result version = run("--version");
  EXPECT_NE(version.output.find("rktsph " RKTSPH_VERSION " (commit "), std::string::npos)
      << version.output;
  EXPECT_NE(version.output.find(" build)"), std::string::npos) << version.output;
}

TEST(CommandLine, AnUnknownCommandIsNamedWithTheCommandsThereAre) {
  const Result result = run("foo");
  EXPECT_EQ(result.status, 2);
  EXPECT_NE(result.output.find("unknown command 'foo'"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("run, check, validate, plot"), std::string::npos) << result.output;
}

TEST(CommandLine, ThreadsThatAreNotANumberAreCalledSo) {
  const fs::path path = write_case("threads.yaml", kBar);
  const Result text =
      run("run -q " + path.string() + " --threads abc -o " + scratch("threads").string());
  EXPECT_EQ(text.status, 2);
  EXPECT_NE(text.output.find("'abc' is not an integer"), std::string::npos) << text.output;
  const Result zero = run("run -q " + path.string() + " --threads 0");
  EXPECT_EQ(zero.status, 2);
  EXPECT_NE(zero.output.find("'0' is not in 1..1024"), std::string::npos) << zero.output;
}

TEST(CommandLine, AnOutputFolderThatCannotBeCreatedIsBadInputWithTheSystemReason) {
  const Result result =
      run("run -q " + write_case("unwritable.yaml", kBar).string() + " -o /dev/null/run");
  EXPECT_EQ(result.status, 2) << result.output;
  EXPECT_NE(result.output.find("'/dev/null/run'"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("Not a directory"), std::string::npos) << result.output;
}

TEST(CommandLine, ASecondRunIntoAFolderInUseFailsAtOnceNamingTheHolder) {
  const fs::path out = scratch("busy");
  fs::create_directories(out);
  // This test holds the folder's lock as a running rktsph would.
  const int lock = ::open((out / ".rktsph.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(lock, 0);
  ASSERT_EQ(::flock(lock, LOCK_EX), 0);
  const std::string pid = std::to_string(::getpid()) + "\n";
  ASSERT_EQ(::pwrite(lock, pid.data(), pid.size(), 0), static_cast<ssize_t>(pid.size()));
  const Result result =
      run("run -q " + write_case("busy.yaml", kBar).string() + " -o " + out.string());
  ::close(lock);
  EXPECT_EQ(result.status, 3) << result.output;
  EXPECT_NE(result.output.find("'" + out.string() + "' is in use by another rktsph run (pid " +
                               std::to_string(::getpid()) + ")"),
            std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(out / "summary.json"));  // the folder was not touched
}

TEST(CommandLine, AnEarlierRunsResultsAreRefusedUnlessOverwriteWhichRemovesThem) {
  const fs::path out = scratch("reused");
  fs::remove_all(out);
  const std::string many = replaced(kBar, "output: {interval: 0.01}", "output: {interval: 0.002}");
  ASSERT_EQ(run("run -q " + write_case("many.yaml", many).string() + " -o " + out.string()).status,
            0);
  const std::size_t before = field_files(out);
  ASSERT_GT(before, 10u);
  std::ofstream(out / "notes.txt") << "mine\n";
  const std::string few = write_case("few.yaml", kBar).string();
  const Result refused = run("run -q " + few + " -o " + out.string());
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_NE(refused.output.find("holds the results of an earlier run"), std::string::npos)
      << refused.output;
  EXPECT_NE(refused.output.find("--overwrite"), std::string::npos) << refused.output;
  EXPECT_EQ(field_files(out), before);

  const Result replaced_run = run("run -q --overwrite " + few + " -o " + out.string());
  ASSERT_EQ(replaced_run.status, 0) << replaced_run.output;
  EXPECT_EQ(field_files(out), 6u);  // t = 0, 0.01, ..., 0.05: none of the earlier run's
  EXPECT_EQ(read_whole_file(out / "notes.txt"), "mine\n");
}

TEST(CommandLine, TemporariesOfAKilledRunAreRemovedAndPlantedLinksNotFollowed) {
  const fs::path out = scratch("stale");
  fs::remove_all(out);
  fs::create_directories(out / "fields");
  std::ofstream(out / "fields" / "fields_000003.vtu.tmp-99999") << "partial";
  const fs::path victim = scratch("victim.txt");
  std::ofstream(victim) << "precious\n";
  fs::create_symlink(victim, out / "summary.json.tmp-99999");
  const Result result =
      run("run -q " + write_case("stale.yaml", kBar).string() + " -o " + out.string());
  ASSERT_EQ(result.status, 0) << result.output;
  for (const auto& entry : fs::recursive_directory_iterator(out))
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
  EXPECT_EQ(read_whole_file(victim), "precious\n");
  EXPECT_EQ(fs::symlink_status(out / "summary.json").type(), fs::file_type::regular);
  EXPECT_NE(read_whole_file(out / "run.log").find("removed 2 temporary files"), std::string::npos);
}

// A write the system refuses mid-run (a file-size limit stands in for a full disk: probes.csv
// outgrows it) ends the run as failed, names the file and the reason, and keeps the last
// complete files.
TEST(CommandLine, AnOutputTheSystemRefusesEndsTheRunAsFailedWithItsReason) {
  const fs::path out = scratch("refused");
  fs::remove_all(out);
  const std::string text = replaced(replaced(kBar, "time: {end: 0.05}", "time: {end: 2.0}"),
                                    "output: {interval: 0.01}", "output: {interval: 0.1}");
  // 32 blocks of 512 bytes: the field files (about 5 KB) and the summary fit, the probe history
  // (about 50 bytes a step, every step) does not.
  const Result result = rktsph::test::shell(
      "trap '' XFSZ; ulimit -f 32 && " + std::string(RKTSPH_BINARY) + " run -q " +
      write_case("refused.yaml", text).string() + " -o " + out.string() + " 2>&1");
  EXPECT_EQ(result.status, 3) << result.output;
  EXPECT_NE(result.output.find("probes.csv"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("File too large"), std::string::npos) << result.output;
  const std::string summary = read_whole_file(out / "summary.json");
  EXPECT_NE(summary.find("\"status\": \"failed\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("File too large"), std::string::npos) << summary;
  const std::string probes = read_whole_file(out / "probes.csv");
  ASSERT_FALSE(probes.empty());
  EXPECT_EQ(probes.back(), '\n');  // the last complete version
  EXPECT_EQ(probes.find(".tmp-"), std::string::npos);
  std::string last_line;
  for (std::istringstream lines(read_whole_file(out / "run.log")); std::getline(lines, last_line);)
    if (lines.peek() == EOF) break;
  EXPECT_NE(last_line.find("ERROR failed:"), std::string::npos) << last_line;
}

// Starts rktsph in the background (SIGINT not ignored, as under a terminal), waits until its
// loop runs, sends `signal_number` and returns the exit status.
int interrupted_run(const fs::path& out, int signal_number) {
  const std::string text =
      replaced(replaced(kBar, "time: {end: 0.05}", "time: {end: 1.0e5, max_steps: 100000000}"),
               "output: {interval: 0.01}", "output: {interval: 1000.0}");
  const std::string case_path = write_case("long.yaml", text).string();
  const std::string output = out.string();
  const pid_t child = ::fork();
  if (child == 0) {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    ::execl(RKTSPH_BINARY, RKTSPH_BINARY, "run", "-q", case_path.c_str(), "-o", output.c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // probes.csv is written once the loop is about to start; polling is only for the wait.
  while (!fs::exists(out / "probes.csv") && ::waitpid(child, nullptr, WNOHANG) == 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ::kill(child, signal_number);
  int status = 0;
  ::waitpid(child, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void expect_interrupted_record(const fs::path& out, const std::string& signal_name) {
  const std::string summary = read_whole_file(out / "summary.json");
  EXPECT_NE(summary.find("\"status\": \"interrupted\""), std::string::npos) << summary;
  EXPECT_NE(summary.find(signal_name + " received"), std::string::npos) << summary;
  EXPECT_NE(read_whole_file(out / "run.log").find("INFO interrupted: interrupted at step"),
            std::string::npos);
  // The probes on disk reach the step it stopped at (step 0 if the signal came that early).
  const std::size_t key = summary.find("\"simulated_time\": ");
  ASSERT_NE(key, std::string::npos) << summary;
  const double stopped_at = std::stod(summary.substr(key + 18));
  const std::string probes = read_whole_file(out / "probes.csv");
  const std::size_t last_row = probes.rfind('\n', probes.size() - 2) + 1;
  EXPECT_EQ(std::stod(probes.substr(last_row)), stopped_at) << probes.substr(last_row);
}

TEST(CommandLine, SigintFinishesTheStepWritesTheRecordAndExits130) {
  const fs::path out = scratch("sigint");
  fs::remove_all(out);
  EXPECT_EQ(interrupted_run(out, SIGINT), 130);
  expect_interrupted_record(out, "SIGINT");
}

TEST(CommandLine, SigtermFinishesTheStepWritesTheRecordAndExits143) {
  const fs::path out = scratch("sigterm");
  fs::remove_all(out);
  EXPECT_EQ(interrupted_run(out, SIGTERM), 143);
  expect_interrupted_record(out, "SIGTERM");
}

TEST(CommandLine, CheckAcceptsAGoodCase) {
  const Result result = run("check " + write_case("good.yaml", kBar).string());
  EXPECT_EQ(result.status, 0) << result.output;
  EXPECT_NE(result.output.find("21 SPH nodes"), std::string::npos) << result.output;
}

TEST(CommandLine, CheckBuildsATriangleMeshAndRefusesTheQuadrilateralsControlOnIt) {
  // A slope meshed with triangles (docs/theory.md §3.6): check builds and checks the mesh with the
  // defaults (triangles have no hourglass mode, so the default control is off there, §4.8).
  const std::string slope = std::string(RKTSPH_SOURCE_DIR) + "/cases/slope-elastic/case.yaml";
  const Result check = run("check " + slope + " --set geometry.cells=triangles");
  EXPECT_EQ(check.status, 0) << check.output;
  EXPECT_NE(check.output.find("OK ("), std::string::npos) << check.output;
  // The Flanagan-Belytschko stiffness asked for explicitly needs quadrilaterals: an input error at
  // the key, saying what to set, no crash.
  const Result stiffness = run(
      "check " + slope + " --set geometry.cells=triangles --set numerics.hourglass.stiffness=1");
  EXPECT_EQ(stiffness.status, 2) << stiffness.output;
  EXPECT_NE(stiffness.output.find("numerics.hourglass.stiffness"), std::string::npos)
      << stiffness.output;
  EXPECT_NE(stiffness.output.find("quadrilaterals"), std::string::npos) << stiffness.output;
}

TEST(CommandLine, CheckWritesTheCellsAsAGmshMeshAndRefusesItFor1D) {
  // The slope on triangles: the mesh file holds every node and cell check counts.
  const std::string slope = std::string(RKTSPH_SOURCE_DIR) + "/cases/slope-elastic/case.yaml";
  const fs::path mesh = scratch("slope.msh");
  fs::remove(mesh);
  const Result written =
      run("check " + slope + " --set geometry.cells=triangles --write-mesh " + mesh.string());
  ASSERT_EQ(written.status, 0) << written.output;
  EXPECT_NE(written.output.find("mesh written to " + mesh.string()), std::string::npos)
      << written.output;
  std::ifstream file(mesh);
  std::string first;
  std::getline(file, first);
  EXPECT_EQ(first, "$MeshFormat");
  // The bar is 1D: no mesh file, an input error naming the option, and nothing written.
  const fs::path bar_mesh = scratch("bar.msh");
  fs::remove(bar_mesh);
  const Result bar =
      run("check " + write_case("bar.yaml", kBar).string() + " --write-mesh " + bar_mesh.string());
  EXPECT_EQ(bar.status, 2) << bar.output;
  EXPECT_NE(bar.output.find("--write-mesh"), std::string::npos) << bar.output;
  EXPECT_FALSE(fs::exists(bar_mesh));
}

TEST(CommandLine, MisspelledKeyNamesFileLineAndKey) {
  const fs::path path = write_case("typo.yaml", replaced(kBar, "  spacing: 0.5", "  spacng: 0.5"));
  const Result result = run("check " + path.string());
  EXPECT_EQ(result.status, 2);
  EXPECT_NE(result.output.find(path.string() + ":4:"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("spacng"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("spacing"), std::string::npos) << result.output;  // suggestion
}

TEST(CommandLine, NegativeSpacingNamesTheLineAndTheRange) {
  const fs::path path =
      write_case("negative.yaml", replaced(kBar, "spacing: 0.5", "spacing: -0.5"));
  const Result result = run("check " + path.string());
  EXPECT_EQ(result.status, 2);
  EXPECT_NE(result.output.find(path.string() + ":4:"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("-0.5"), std::string::npos) << result.output;
}

TEST(CommandLine, YamlSyntaxErrorNamesTheLine) {
  const fs::path path =
      write_case("syntax.yaml", replaced(kBar, "time: {end: 0.05}", "time: {end: 0.05"));
  const Result result = run("check " + path.string());
  EXPECT_EQ(result.status, 2);
  EXPECT_NE(result.output.find(path.string() + ":"), std::string::npos) << result.output;
}

TEST(CommandLine, BadMaterialParameterNamesTheKey) {
  const fs::path path =
      write_case("nu.yaml", replaced(kBar, "poisson_ratio: 0.0", "poisson_ratio: 0.5"));
  const Result result = run("check " + path.string());
  EXPECT_EQ(result.status, 2);
  EXPECT_NE(result.output.find("materials.soil.poisson_ratio"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find(path.string() + ":9:"), std::string::npos) << result.output;
}

TEST(CommandLine, OverrideErrorsAreReported) {
  const fs::path path = write_case("ok.yaml", kBar);
  EXPECT_EQ(run("check " + path.string() + " --set time.end=-1").status, 2);
  EXPECT_EQ(run("check " + path.string() + " --set time.ende=1").status, 2);
  EXPECT_EQ(run("check " + path.string() + " --set time.end=0.02").status, 0);
}

TEST(CommandLine, MisspeltProbeFieldFromSetIsRefusedByCheckNamingTheArgument) {
  const fs::path path = write_case("probe.yaml", kBar);
  const Result result = run("check " + path.string() + " --set probes.0.fields.0=velocty_x");
  EXPECT_EQ(result.status, 2) << result.output;
  EXPECT_NE(result.output.find("<--set probes.0.fields.0=velocty_x>: error: key "
                               "'probes.0.fields.0': unknown probe field; did you mean "
                               "'velocity_x'?"),
            std::string::npos)
      << result.output;
  EXPECT_EQ(result.output.find(path.string()), std::string::npos) << result.output;
}

TEST(CommandLine, MisspeltProbeFieldInTheFileIsRefusedByCheckAtItsLine) {
  const fs::path path = write_case(
      "probe-line.yaml", replaced(kBar, "fields: [velocity_x]", "fields: [velocity_x, strss]"));
  const Result result = run("check " + path.string());
  EXPECT_EQ(result.status, 2) << result.output;
  EXPECT_NE(result.output.find(path.string() + ":16:"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("'probes.0.fields.1'"), std::string::npos) << result.output;
}

TEST(CommandLine, ADirectoryAsCaseFileIsNamedAsSuch) {
  const Result result = run("check " + scratch("").string());
  EXPECT_EQ(result.status, 2);
  EXPECT_NE(result.output.find("is a directory"), std::string::npos) << result.output;
}

TEST(CommandLine, ThreeMistakesAreReportedInOnePassInLineOrder) {
  std::string text = replaced(kBar, "poisson_ratio: 0.0", "poisson_ratio: zero");
  text = replaced(text, "spacing: 0.5", "spacing: -0.5");
  text = replaced(text, "courant: 0.9", "courant: 9");
  const fs::path path = write_case("three.yaml", text);
  const Result result = run("check " + path.string());
  EXPECT_EQ(result.status, 2);
  const std::size_t first = result.output.find(path.string() + ":4:");
  const std::size_t second = result.output.find(path.string() + ":9:");
  const std::size_t third = result.output.find(path.string() + ":12:");
  EXPECT_NE(third, std::string::npos) << result.output;
  EXPECT_LT(first, second) << result.output;
  EXPECT_LT(second, third) << result.output;
  EXPECT_NE(result.output.find("3 errors:"), std::string::npos) << result.output;
}

TEST(CommandLine, NestedAliasesAreRefusedQuickly) {
  std::string text = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int level = 1; level < 10; ++level) {
    const std::string name = std::to_string(level), previous = std::to_string(level - 1);
    text.append("a").append(name).append(": &a").append(name).append(" [");
    for (int i = 0; i < 10; ++i)
      text.append(i > 0 ? ", *a" : "*a").append(previous);
    text.append("]\n");
  }
  const fs::path path = write_case("bomb.yaml", text + "name: *a9\n");
  const Result result = run("check " + path.string());
  EXPECT_EQ(result.status, 2);
  EXPECT_NE(result.output.find(path.string() + ":5:"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("more than 100000 values"), std::string::npos) << result.output;
}

TEST(CommandLine, RunWritesAReadableSeriesProbesAndSummary) {
  const fs::path out = scratch("run");
  const Result result =
      run("run -q " + write_case("run.yaml", kBar).string() + " -o " + out.string());
  ASSERT_EQ(result.status, 0) << result.output;
  for (const char* file : {"series.pvd", "probes.csv", "summary.json", "case.yaml", "run.log"})
    EXPECT_TRUE(fs::exists(out / file)) << file;
  // Nothing half-written is left behind.
  for (const auto& entry : fs::recursive_directory_iterator(out))
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
  const std::string checker =
      std::string("/usr/bin/python3 ") + RKTSPH_TEST_DATA_DIR + "/../app/check_run_output.py ";
  if (!fs::exists("/usr/bin/python3")) GTEST_SKIP() << "/usr/bin/python3 not installed";
  EXPECT_EQ(std::system((checker + out.string() + " -0.1").c_str()), 0);
  // The resolved case re-reads as a valid case.
  EXPECT_EQ(run("check " + (out / "case.yaml").string()).status, 0);
}

TEST(CommandLine, DivergingRunStopsWithADiagnosisAndKeepsItsLastGoodOutput) {
  // h = 2.5 dx is unstable at every Courant number (docs/theory.md §2.5, §3.3): the run must blow
  // up (a Courant number beyond the limit is refused before the run).
  const fs::path out = scratch("diverge");
  // Field output every 0.25 s: about a dozen files before the blow-up near t = 3 s, each read
  // back below (at every 0.01 s it was 300 files and most of the test's half minute).
  const std::string text =
      replaced(replaced(replaced(kBar, "courant: 0.9", "courant: 0.9, h_over_dx: 2.5"),
                        "time: {end: 0.05}", "time: {end: 20.0}"),
               "output: {interval: 0.01}", "output: {interval: 0.25}");
  const Result result =
      run("run -q " + write_case("diverge.yaml", text).string() + " -o " + out.string());
  EXPECT_EQ(result.status, 3) << result.output;
  EXPECT_NE(result.output.find("diverged at step"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("SPH node"), std::string::npos) << result.output;
  // Issue 30: a stop says what to change (this case diverges from a Courant number too large for
  // its smoothing length) and where the last good state is.
  EXPECT_NE(result.output.find("lower numerics.courant"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("last field output"), std::string::npos) << result.output;
  std::ifstream summary(out / "summary.json");
  const std::string text_summary((std::istreambuf_iterator<char>(summary)),
                                 std::istreambuf_iterator<char>());
  EXPECT_NE(text_summary.find("\"diverged\""), std::string::npos) << text_summary;
  // The last field file is the state before the step that diverged (its last good state), not the
  // regular output of up to 0.25 s before: at t = (the time named) - dt.
  const std::size_t at = result.output.find("diverged at step");
  const std::size_t time_at = result.output.find("(t = ", at);
  ASSERT_NE(time_at, std::string::npos) << result.output;
  const double stopped = std::stod(result.output.substr(time_at + 5));
  const std::size_t step_at = text_summary.find("\"time_step\": ");
  ASSERT_NE(step_at, std::string::npos) << text_summary;
  const double dt = std::stod(text_summary.substr(step_at + 13));
  const std::string pvd = read_whole_file(out / "series.pvd");
  const std::size_t last = pvd.rfind("timestep=\"");
  ASSERT_NE(last, std::string::npos) << pvd;
  EXPECT_NEAR(std::stod(pvd.substr(last + 10)), stopped - dt, 1e-5 * stopped) << pvd;
  if (!fs::exists("/usr/bin/python3")) GTEST_SKIP() << "/usr/bin/python3 not installed";
  const std::string reader =
      std::string("/usr/bin/python3 ") + RKTSPH_TEST_DATA_DIR + "/../output/read_vtu.py ";
  for (const auto& entry : fs::directory_iterator(out / "fields"))
    EXPECT_EQ(std::system((reader + entry.path().string() + " > /dev/null").c_str()), 0)
        << entry.path();
}

// The points of a field file mean one thing for every model: the current positions X + u, with
// u written beside them (a small-deformation model used to write X, a large-deformation one X + u).
TEST(CommandLine, EveryModelWritesTheCurrentPositions) {
  if (!fs::exists("/usr/bin/python3")) GTEST_SKIP() << "/usr/bin/python3 not installed";
  const std::string checker =
      std::string("/usr/bin/python3 ") + RKTSPH_TEST_DATA_DIR + "/../output/check_positions.py ";
  // Without displacement among the fields asked for: it is written all the same.
  const fs::path bar = write_case(
      "positions.yaml",
      replaced(kBar, "output: {interval: 0.01}", "output: {interval: 0.01, fields: [stress]}"));
  const fs::path moving =
      write_case("positions-ld.yaml",
                 replaced(kBar, "name: bar\n", "name: bar\nmodel: dry_large_deformation\n"));
  const std::string consolidation =
      std::string(RKTSPH_SOURCE_DIR) + "/cases/vpw-consolidation/case.yaml";
  const std::vector<std::pair<std::string, std::string>> runs = {
      {"small-deformation", bar.string()},
      {"large-deformation", moving.string()},
      {"saturated", consolidation + " --set time.end=0.05 --set output.interval=0.01"}};
  for (const auto& [model, arguments] : runs) {
    const fs::path out = scratch("positions-" + model);
    const Result result = run("run -q --overwrite " + arguments + " -o " + out.string());
    ASSERT_EQ(result.status, 0) << model << ": " << result.output;
    const Result check = rktsph::test::shell(checker + out.string() + " 2>&1");
    EXPECT_EQ(check.status, 0) << model << ": " << check.output;
  }
}

// `plot --magnify M` draws X + M u for every model: on a large-deformation run, whose points
// were always X + u, M = 1 must be the current positions (not X + 2u) and M = 0 the reference.
TEST(CommandLine, PlotMagnifiesTheDisplacementFromTheReferenceForEveryModel) {
  if (!fs::exists("/usr/bin/python3")) GTEST_SKIP() << "/usr/bin/python3 not installed";
  const fs::path moving =
      write_case("magnify-ld.yaml",
                 replaced(kBar, "name: bar\n", "name: bar\nmodel: dry_large_deformation\n"));
  const fs::path out = scratch("magnify-ld");
  ASSERT_EQ(run("run -q --overwrite " + moving.string() + " -o " + out.string()).status, 0);
  const std::string plot = std::string("/usr/bin/python3 ") + RKTSPH_SOURCE_DIR +
                           "/tools/plot_field.py " + out.string() + " --dump ";
  const auto drawn_x = [&](const std::string& arguments) {
    const Result result = rktsph::test::shell(plot + arguments);
    EXPECT_EQ(result.status, 0) << result.output;
    return YAML::Load(result.output)["x"].as<std::vector<double>>();
  };
  const std::vector<double> reference = drawn_x("--field displacement --time 0 --magnify 1");
  const std::vector<double> u = YAML::Load(rktsph::test::shell(plot + "--field displacement "
                                                                      "--component 0")
                                               .output)["values"]
                                    .as<std::vector<double>>();
  const std::vector<double> undeformed = drawn_x("--field displacement --magnify 0");
  const std::vector<double> current = drawn_x("--field displacement --magnify 1");
  const std::vector<double> doubled = drawn_x("--field displacement --magnify 2");
  ASSERT_EQ(u.size(), reference.size());
  ASSERT_EQ(current.size(), reference.size());
  for (std::size_t i = 0; i < u.size(); ++i) {
    EXPECT_NEAR(undeformed[i], reference[i], 1e-12) << i;
    EXPECT_NEAR(current[i], reference[i] + u[i], 1e-12) << i;
    EXPECT_NEAR(doubled[i], reference[i] + 2.0 * u[i], 1e-12) << i;
  }
  EXPECT_LT(u.back(), 0.0);  // the driven end moved, so the checks above are not 0 = 0
}

// E = 10 Pa and rho = 2 kg/m^3 (meant as MPa and t/m^3) are legal but no soil: check and run say
// so, with the file and line, and run.log and summary.json keep the warnings; the run still
// goes (a warning is never fatal).
TEST(CommandLine, ImplausibleValuesAreWarnedOfByCheckAndRun) {
  const fs::path ordinary = write_case("plausible.yaml", kBar);
  const Result clean = run("check " + ordinary.string());
  EXPECT_EQ(clean.status, 0) << clean.output;
  EXPECT_EQ(clean.output.find("warning"), std::string::npos) << clean.output;

  std::string text = replaced(kBar, "young_modulus: 1.0e8", "young_modulus: 10");
  text = replaced(text, "density: 2000.0", "density: 2");
  const fs::path path = write_case("implausible.yaml", text);
  const Result checked = run("check " + path.string());
  EXPECT_EQ(checked.status, 0) << checked.output;
  EXPECT_NE(checked.output.find(path.string() + ":9:"), std::string::npos) << checked.output;
  EXPECT_NE(checked.output.find("warning: key 'materials.soil.young_modulus' = 10"),
            std::string::npos)
      << checked.output;
  EXPECT_NE(checked.output.find("warning: key 'materials.soil.density' = 2"), std::string::npos)
      << checked.output;

  const fs::path out = scratch("implausible-run");
  const Result ran = run("run -q --overwrite " + path.string() + " -o " + out.string());
  EXPECT_EQ(ran.status, 0) << ran.output;
  EXPECT_NE(ran.output.find("warning: key 'materials.soil.young_modulus'"), std::string::npos)
      << ran.output;
  const std::string log = read_whole_file(out / "run.log");
  EXPECT_NE(log.find("WARNING " + path.string() + ":9:"), std::string::npos) << log;
  const std::string summary = read_whole_file(out / "summary.json");
  const std::size_t warnings = summary.find("\"warnings\": [");
  ASSERT_NE(warnings, std::string::npos) << summary;
  EXPECT_NE(summary.find("materials.soil.young_modulus", warnings), std::string::npos) << summary;
}

// Issue 30: summary.json says whether the energy budget closes (docs/input-reference.md, "Energy
// budget"); a correct run does, without a warning (the flagged side is unit-tested in
// tests/simulation/energy_budget_test.cpp).
TEST(CommandLine, SummarySaysWhetherTheEnergyBudgetCloses) {
  const fs::path path = write_case("budget.yaml", kBar);
  const fs::path out = scratch("budget-run");
  const Result ran = run("run -q --overwrite " + path.string() + " -o " + out.string());
  EXPECT_EQ(ran.status, 0) << ran.output;
  EXPECT_EQ(ran.output.find("energy budget"), std::string::npos) << ran.output;
  const std::string summary = read_whole_file(out / "summary.json");
  EXPECT_NE(summary.find("\"residual_fraction\": "), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"closes\": true"), std::string::npos) << summary;
  EXPECT_EQ(summary.find("does not close"), std::string::npos) << summary;
}

// The bundled cases are what users copy: none of them may give a plausibility warning. The sizes
// L and XL of BAR-WAVE-2D (1.6e5 and 1e6 nodes, 0.2 and 1.2 GB to check) are left out: they are
// sizes S and M at finer spacings, with the same materials and loads, and a smaller time step.
TEST(CommandLine, EveryBundledCaseChecksWithoutAWarning) {
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(RKTSPH_SOURCE_DIR) / "cases")) {
    const std::string name = entry.path().filename().string();
    if (name == "bar-wave-2d-l" || name == "bar-wave-2d-xl") continue;
    if (!fs::exists(entry.path() / "case.yaml")) continue;
    const Result result = run("check --threads 1 " + (entry.path() / "case.yaml").string());
    EXPECT_EQ(result.status, 0) << name << ": " << result.output;
    EXPECT_EQ(result.output.find("warning"), std::string::npos) << name << ": " << result.output;
    ++checked;
  }
  EXPECT_GE(checked, 20);
}

// The examples (examples/*/case.yaml, e.g. a Gmsh mesh) read, build and pass every check of run.
TEST(CommandLine, EveryExampleChecksWithoutAWarning) {
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(RKTSPH_SOURCE_DIR) / "examples")) {
    if (!fs::exists(entry.path() / "case.yaml")) continue;
    const Result result = run("check --threads 1 " + (entry.path() / "case.yaml").string());
    EXPECT_EQ(result.status, 0) << entry.path() << ": " << result.output;
    EXPECT_EQ(result.output.find("warning"), std::string::npos) << result.output;
    ++checked;
  }
  EXPECT_GE(checked, 1);
}

// Cases run side by side (--jobs) give the same lines, in the order asked, as one after the
// other: they share no state. The lines' wall times differ and are left out of the comparison.
TEST(CommandLine, ValidateJobsKeepTheOrderAndTheResults) {
  const std::string cases =
      "validate --quick --json bar1d-viscoplastic ld-rotation-objectivity "
      "bar1d-elastic --threads 1 -o ";
  const Result serial = run(cases + scratch("jobs1").string() + " --jobs 1");
  const Result parallel = run(cases + scratch("jobs3").string() + " --jobs 3");
  ASSERT_EQ(serial.status, 0) << serial.output;
  ASSERT_EQ(parallel.status, 0) << parallel.output;
  const auto without_wall_times = [](const std::string& output) {
    std::string lines;
    std::istringstream stream(output);
    for (std::string line; std::getline(stream, line);) {
      const std::size_t at = line.find(",\"wall_seconds\":");
      if (at != std::string::npos) line.erase(at, line.find(',', at + 1) - at);
      lines += line + "\n";
    }
    return lines;
  };
  const std::string expected = without_wall_times(serial.output);
  EXPECT_EQ(without_wall_times(parallel.output), expected);
  EXPECT_LT(expected.find("bar1d-viscoplastic"), expected.find("ld-rotation-objectivity"));
  EXPECT_LT(expected.find("ld-rotation-objectivity"), expected.find("\"bar1d-elastic"));
  EXPECT_EQ(run("validate bar1d-elastic --jobs 0").status, 2);
}

// --set changes the case a validation runs, and its references follow it: slope-elastic at
// nu = 0.2 and rho = 2500 kg/m3 against K0 = 0.25 and its own overburden. A key the case cannot
// take fails the case, naming the key.
TEST(CommandLine, ValidateSetChecksAVariantAgainstItsOwnReferences) {
  const std::string variant = "validate slope-elastic --quick --json --threads 1 -o " +
                              scratch("set").string() +
                              " --set materials.soil.poisson_ratio=0.2"
                              " --set materials.soil.density=2500";
  const Result passed = run(variant);
  EXPECT_EQ(passed.status, 0) << passed.output;
  const Result unknown = run(variant + " --set materials.soil.no_such_key=1");
  EXPECT_EQ(unknown.status, 1) << unknown.output;
  EXPECT_NE(unknown.output.find("no_such_key"), std::string::npos) << unknown.output;
}

TEST(CommandLine, ValidateRejectsUnknownCaseNames) {
  const Result result = run("validate no-such-case --json");
  EXPECT_EQ(result.status, 2);
  EXPECT_NE(result.output.find("no-such-case"), std::string::npos);
}

}  // namespace
}  // namespace cli_test
