// The rktsph command line as a user meets it: exit statuses, errors that name the file, line and
// key, a run's files (read back by an independent parser), and a diverging run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../support/shell.hpp"

namespace {

namespace fs = std::filesystem;

using Result = rktsph::test::ShellResult;

// The program with these arguments; output is stdout and stderr.
Result run(const std::string& arguments) {
  return rktsph::test::shell(std::string(RKTSPH_BINARY) + " " + arguments + " 2>&1");
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("rktsph_cli_" + std::to_string(getpid()));
  fs::create_directories(dir);
  return dir / name;
}

fs::path write_case(const std::string& name, const std::string& text) {
  const fs::path path = scratch(name);
  std::ofstream(path) << text;
  return path;
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
output: {interval: 0.01}
probes:
  - {name: free, group: xmin, fields: [velocity_x]}
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

TEST(CommandLine, VersionAndHelp) {
  const Result version = run("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_NE(version.output.find("rktsph "), std::string::npos);
  EXPECT_EQ(run("run --help").status, 0);
  EXPECT_EQ(run("no-such-command").status, 2);
}

TEST(CommandLine, CheckAcceptsAGoodCase) {
  const Result result = run("check " + write_case("good.yaml", kBar).string());
  EXPECT_EQ(result.status, 0) << result.output;
  EXPECT_NE(result.output.find("21 SPH nodes"), std::string::npos) << result.output;
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
  // Courant 1.5 is beyond the stability limit of 1 (docs/theory.md §2.4): the run must blow up.
  const fs::path out = scratch("diverge");
  const std::string text = replaced(replaced(kBar, "courant: 0.9", "courant: 1.5"),
                                    "time: {end: 0.05}", "time: {end: 20.0}");
  const Result result =
      run("run -q " + write_case("diverge.yaml", text).string() + " -o " + out.string());
  EXPECT_EQ(result.status, 3) << result.output;
  EXPECT_NE(result.output.find("diverged at step"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("SPH node"), std::string::npos) << result.output;
  std::ifstream summary(out / "summary.json");
  const std::string text_summary((std::istreambuf_iterator<char>(summary)),
                                 std::istreambuf_iterator<char>());
  EXPECT_NE(text_summary.find("\"diverged\""), std::string::npos) << text_summary;
  if (!fs::exists("/usr/bin/python3")) GTEST_SKIP() << "/usr/bin/python3 not installed";
  const std::string reader =
      std::string("/usr/bin/python3 ") + RKTSPH_TEST_DATA_DIR + "/../output/read_vtu.py ";
  for (const auto& entry : fs::directory_iterator(out / "fields"))
    EXPECT_EQ(std::system((reader + entry.path().string() + " > /dev/null").c_str()), 0)
        << entry.path();
}

TEST(CommandLine, ValidateRejectsUnknownCaseNames) {
  const Result result = run("validate no-such-case --json");
  EXPECT_EQ(result.status, 2);
  EXPECT_NE(result.output.find("no-such-case"), std::string::npos);
}

}  // namespace
