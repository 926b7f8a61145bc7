// `rktsph plot` and the report tools (tools/plot_field.py, make_report.py, check_report.sh) on a
// small 1D bar run. What is drawn is checked against what is known of the run without the
// drawing code: the lattice (0.5 m), the output times (every 0.01 s), the prescribed velocity
// of the right end (-0.1 m/s), and x0 + M u for the drawn positions. Skipped when
// python3-matplotlib (or, for the browser check, chromium) is not installed: they are only
// needed for reports (`make deps-report`).
#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "../support/shell.hpp"

namespace report_tools_test {
namespace {

namespace fs = std::filesystem;

using Result = rktsph::test::ShellResult;  // output: stdout only, unless stderr is redirected
using rktsph::test::shell;

const std::string kTools = std::string(RKTSPH_SOURCE_DIR) + "/tools";

bool has_matplotlib() {
  return shell("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1").status == 0;
}

/// Width and height from the PNG header, or {0, 0} if the file is not a PNG.
std::pair<unsigned, unsigned> png_size(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<unsigned char, 24> head{};
  in.read(reinterpret_cast<char*>(head.data()), head.size());
  const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!in || !std::equal(signature, signature + 8, head.begin())) return {0, 0};
  auto big_endian = [&](int at) {
    return (unsigned{head[at]} << 24) | (unsigned{head[at + 1]} << 16) |
           (unsigned{head[at + 2]} << 8) | unsigned{head[at + 3]};
  };
  return {big_endian(16), big_endian(20)};
}

constexpr double kEndVelocity = -0.1;  // m/s, prescribed at x = 10 m

class ReportTools : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    directory_ = fs::temp_directory_path() / ("rktsph_report_tools_" + std::to_string(getpid()));
    fs::remove_all(directory_);
    fs::create_directories(directory_);
    std::ofstream(directory_ / "bar.yaml") << R"(name: bar
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
)";
    run_status_ = shell(std::string(RKTSPH_BINARY) + " run -q " +
                        (directory_ / "bar.yaml").string() + " -o " + (directory_ / "run").string())
                      .status;
  }

  void SetUp() override {
    if (!has_matplotlib()) GTEST_SKIP() << "python3-matplotlib is not installed";
    ASSERT_EQ(run_status_, 0);
  }

  /// A report folder as `validate --report` leaves it, for a made-up case using the bar run.
  static fs::path write_report(const fs::path& root, const std::string& picture_field) {
    fs::remove_all(root);
    fs::create_directories(root / "made-up");
    fs::create_symlink(directory_ / "run", root / "made-up" / "run");
    std::ofstream(root / "made-up" / "report.json")
        << R"({"case":"made-up","passed":false,"wall_seconds":1.25,)"
        << R"("checks":[{"name":"plateau_error","value":0.0123,"reference":0.0,"tolerance":0.02,)"
        << R"("unit":"fraction","passed":true},{"name":"growth_ratio","value":1.5,"reference":1.0,)"
        << R"("tolerance":1.02,"unit":"ratio","passed":false}],"description":"A made-up case.",)"
        << R"("figures":[{"name":"curve","title":"A curve","x_label":"t [s]","y_label":"v [m/s]",)"
        << R"("series":[{"label":"measured","style":"line","x":[0.0,1.0,2.0],"y":[0.0,1.0,null]},)"
        << R"({"label":"exact","style":"dashed","x":[0.0,2.0],"y":[0.0,2.0]}]}],)"
        << R"("pictures":[{"name":"field","run_directory":"made-up/run","field":")" << picture_field
        << R"(","component":0,"time":-1.0,"magnification":5.0,"caption":"The bar."}]})";
    return root;
  }

  static fs::path directory_;
  static int run_status_;
};

fs::path ReportTools::directory_;
int ReportTools::run_status_ = -1;

TEST_F(ReportTools, PlotWritesAPngOfTheField) {
  const fs::path png = directory_ / "plot.png";
  const Result result =
      shell(std::string(RKTSPH_BINARY) + " plot " + (directory_ / "run").string() +
            " --field stress --component 0 --magnify 10 -o " + png.string() + " 2>&1");
  ASSERT_EQ(result.status, 0) << result.output;
  const auto [width, height] = png_size(png);
  EXPECT_GT(width, 100u);
  EXPECT_GT(height, 50u);
}

TEST_F(ReportTools, DrawsTheSnapshotNearestTheTimeOnMagnifiedPositions) {
  const std::string script =
      "/usr/bin/python3 " + kTools + "/plot_field.py " + (directory_ / "run").string();
  const Result velocity =
      shell(script + " --field velocity --component 0 --time 0.032 --magnify 10 --dump");
  const Result displacement =
      shell(script + " --field displacement --component 0 --time 0.032 --dump");
  ASSERT_EQ(velocity.status, 0);
  ASSERT_EQ(displacement.status, 0);
  const YAML::Node moved = YAML::Load(velocity.output);
  const YAML::Node still = YAML::Load(displacement.output);
  // Outputs every 0.01 s (each within one step, 1 ms here, after its time): 0.03 is nearest.
  EXPECT_NEAR(moved["time"].as<double>(), 0.03, 2e-3);
  EXPECT_EQ(moved["label"].as<std::string>(), "velocity_x");
  const auto x = moved["x"].as<std::vector<double>>();
  const auto values = moved["values"].as<std::vector<double>>();
  ASSERT_EQ(x.size(), 21u);
  // Nodes in order along the bar: the last is the driven end, at the prescribed velocity.
  EXPECT_NEAR(values.back(), kEndVelocity, 1e-12);
  // Drawn at x0 + 10 u_x, with x0 the lattice (0.5 m spacing) and u_x as the file holds it.
  const auto u = still["values"].as<std::vector<double>>();
  const auto x0 = still["x"].as<std::vector<double>>();
  ASSERT_EQ(u.size(), x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    EXPECT_NEAR(x0[i], 0.5 * static_cast<double>(i), 1e-12);
    EXPECT_NEAR(x[i], x0[i] + 10.0 * u[i], 1e-12) << i;
  }
  EXPECT_LT(u.back(), 0.0);  // moved, so the check above is not 0 = 0
}

TEST_F(ReportTools, TakesTheLastSnapshotWithoutTimeAndAMagnitudeWithoutComponent) {
  const std::string script =
      "/usr/bin/python3 " + kTools + "/plot_field.py " + (directory_ / "run").string();
  const Result magnitude = shell(script + " --field velocity --dump");
  const Result component = shell(script + " --field velocity --component 0 --dump");
  ASSERT_EQ(magnitude.status, 0);
  ASSERT_EQ(component.status, 0);
  const YAML::Node dump = YAML::Load(magnitude.output);
  EXPECT_NEAR(dump["time"].as<double>(), 0.05, 1e-3);  // the run's end
  EXPECT_EQ(dump["label"].as<std::string>(), "|velocity|");
  // In 1D the vector is (v_x, 0, 0): its magnitude is |v_x|.
  const auto values = dump["values"].as<std::vector<double>>();
  const auto x_components = YAML::Load(component.output)["values"].as<std::vector<double>>();
  ASSERT_EQ(values.size(), x_components.size());
  for (std::size_t i = 0; i < values.size(); ++i)
    EXPECT_NEAR(values[i], std::abs(x_components[i]), 1e-15) << i;
  EXPECT_NEAR(values.back(), std::abs(kEndVelocity), 1e-12);
  const auto x = dump["x"].as<std::vector<double>>();
  EXPECT_NEAR(x.back(), 10.0, 1e-12);  // undeformed: no --magnify
}

TEST_F(ReportTools, PlotRejectsAnUnknownFieldOrComponentOrRunAsBadInput) {
  const std::string plot = std::string(RKTSPH_BINARY) + " plot ";
  const std::string png = " -o " + (directory_ / "bad.png").string() + " 2>/dev/null";
  EXPECT_EQ(shell(plot + (directory_ / "run").string() + " --field nonsense" + png).status, 2);
  EXPECT_EQ(
      shell(plot + (directory_ / "run").string() + " --field velocity --component 5" + png).status,
      2);
  EXPECT_EQ(shell(plot + (directory_ / "missing").string() + " --field velocity" + png).status, 2);
  EXPECT_FALSE(fs::exists(directory_ / "bad.png"));
}

TEST_F(ReportTools, MakeReportDrawsEveryImageAndListsTheChecks) {
  const fs::path root = write_report(directory_ / "report", "displacement");
  ASSERT_EQ(shell("/usr/bin/python3 " + kTools + "/make_report.py " + root.string()).status, 0);
  EXPECT_GT(png_size(root / "made-up" / "curve.png").first, 0u);
  EXPECT_GT(png_size(root / "made-up" / "field.png").first, 0u);
  std::ifstream in(root / "index.html");
  const std::string page((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* expected :
       {"A made-up case.", "plateau_error", "0.0123", "growth_ratio", "FAILED",
        R"(src="made-up/curve.png")", R"(src="made-up/field.png")", "The bar."})
    EXPECT_NE(page.find(expected), std::string::npos) << expected;
  EXPECT_TRUE(fs::exists(root / "index.md"));
}

TEST_F(ReportTools, MakeReportSaysSoWhenAPictureCannotBeDrawn) {
  const fs::path root = write_report(directory_ / "broken", "no_such_field");
  EXPECT_EQ(
      shell("/usr/bin/python3 " + kTools + "/make_report.py " + root.string() + " 2>/dev/null")
          .status,
      1);
  std::ifstream in(root / "index.html");
  const std::string page((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(page.find("no field"), std::string::npos);                    // the reason, on the page
  EXPECT_EQ(page.find(R"(src="made-up/field.png")"), std::string::npos);  // no broken image
}

TEST_F(ReportTools, CheckReportPassesALoadedPageAndCatchesAMissingImage) {
  if (shell("command -v chromium >/dev/null 2>&1").status != 0)
    GTEST_SKIP() << "chromium is not installed";
  const fs::path root = write_report(directory_ / "browser", "displacement");
  ASSERT_EQ(shell("/usr/bin/python3 " + kTools + "/make_report.py " + root.string()).status, 0);
  const std::string check = kTools + "/check_report.sh " + root.string() + " >/dev/null 2>&1";
  EXPECT_EQ(shell(check).status, 0);
  EXPECT_GT(png_size(root / "page-screenshot.png").first, 0u);
  fs::remove(root / "made-up" / "curve.png");
  EXPECT_NE(shell(check).status, 0);
}

}  // namespace
}  // namespace report_tools_test
