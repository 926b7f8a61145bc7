// The report side of `rktsph validate`: the sink a case fills (ValidationReport), the curves of
// analytical references (sample_curve), and report.json as run_validation writes it, read back
// with yaml-cpp (JSON is YAML) rather than with the writer's own code.
#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "rktsph/validation/validation_case.hpp"

namespace rktsph::validation_report_test {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path directory =
      fs::temp_directory_path() / ("rktsph_report_" + std::to_string(getpid())) / name;
  fs::remove_all(directory);
  fs::create_directories(directory);
  return directory;
}

Figure one_curve_figure(std::string name) {
  return {std::move(name), "title", "x", "y", {{"curve", {0.0, 1.0}, {2.0, 3.0}, "line"}}};
}

FieldPicture picture_named(std::string name) {
  return {std::move(name), "/some/run", "stress", 0, -1.0, 0.0, "caption"};
}

// ---------------------------------------------------------------------------------------------
// The sink

TEST(ValidationReport, KeepsWhatTheCaseAddsInOrder) {
  ValidationReport report;
  report.describe("what it is");
  report.add_figure(one_curve_figure("first"));
  report.add_figure(one_curve_figure("second"));
  report.add_picture(picture_named("third"));
  EXPECT_EQ(report.description(), "what it is");
  ASSERT_EQ(report.figures().size(), 2u);
  EXPECT_EQ(report.figures()[0].name, "first");
  EXPECT_EQ(report.figures()[1].name, "second");
  ASSERT_EQ(report.pictures().size(), 1u);
  EXPECT_EQ(report.pictures()[0].field, "stress");
}

TEST(ValidationReport, RejectsNamesThatAreNotPortableFileStems) {
  ValidationReport report;
  for (const char* bad : {"", "a/b", "a b", "../x", ".hidden", "x\\y", "é"})
    EXPECT_THROW(report.add_figure(one_curve_figure(bad)), std::invalid_argument) << bad;
  EXPECT_NO_THROW(report.add_figure(one_curve_figure("Mid_bar-stress.c06")));
}

TEST(ValidationReport, RejectsANameUsedTwiceAcrossFiguresAndPictures) {
  // Both become <name>.png in the same folder.
  ValidationReport report;
  report.add_figure(one_curve_figure("same"));
  EXPECT_THROW(report.add_figure(one_curve_figure("same")), std::invalid_argument);
  EXPECT_THROW(report.add_picture(picture_named("same")), std::invalid_argument);
  EXPECT_EQ(report.figures().size(), 1u);
  EXPECT_TRUE(report.pictures().empty());
}

TEST(ValidationReport, RejectsUnknownStylesAndRaggedSeries) {
  ValidationReport report;
  Figure styled = one_curve_figure("styled");
  styled.series[0].style = "dotted";
  EXPECT_THROW(report.add_figure(styled), std::invalid_argument);
  Figure ragged = one_curve_figure("ragged");
  ragged.series[0].y.push_back(4.0);
  EXPECT_THROW(report.add_figure(ragged), std::invalid_argument);
  for (const char* style : {"line", "dashed", "points"}) {
    Figure good = one_curve_figure(std::string("good_") + style);
    good.series[0].style = style;
    EXPECT_NO_THROW(report.add_figure(good)) << style;
  }
}

TEST(ValidationReport, AcceptsLinearAndLogAxesOnly) {
  ValidationReport report;
  Figure logarithmic = one_curve_figure("loglog");
  logarithmic.x_scale = "log";
  logarithmic.y_scale = "log";
  EXPECT_NO_THROW(report.add_figure(logarithmic));
  for (const char* scale : {"", "symlog", "Log"}) {
    Figure bad_x = one_curve_figure(std::string("bad_x_") + (*scale ? scale : "empty"));
    bad_x.x_scale = scale;
    EXPECT_THROW(report.add_figure(bad_x), std::invalid_argument) << scale;
    Figure bad_y = one_curve_figure(std::string("bad_y_") + (*scale ? scale : "empty"));
    bad_y.y_scale = scale;
    EXPECT_THROW(report.add_figure(bad_y), std::invalid_argument) << scale;
  }
}

TEST(ValidationReport, RejectsPicturesWithoutRunFieldOrWithABadComponent) {
  ValidationReport report;
  FieldPicture no_field = picture_named("a");
  no_field.field.clear();
  EXPECT_THROW(report.add_picture(no_field), std::invalid_argument);
  FieldPicture no_run = picture_named("b");
  no_run.run_directory.clear();
  EXPECT_THROW(report.add_picture(no_run), std::invalid_argument);
  FieldPicture bad_component = picture_named("c");
  bad_component.component = -2;
  EXPECT_THROW(report.add_picture(bad_component), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// sample_curve

TEST(SampleCurve, SamplesEvenlyIncludingBothEnds) {
  // x_i = x0 + i (x1 - x0) / (n - 1): for [-1, 2] and n = 7, steps of 0.5.
  const Series curve = sample_curve("parabola", -1.0, 2.0, 7, [](double x) { return x * x; });
  ASSERT_EQ(curve.x.size(), 7u);
  ASSERT_EQ(curve.y.size(), 7u);
  for (int i = 0; i < 7; ++i) {
    EXPECT_DOUBLE_EQ(curve.x[i], -1.0 + 0.5 * i);
    EXPECT_DOUBLE_EQ(curve.y[i], curve.x[i] * curve.x[i]);
  }
  EXPECT_EQ(curve.x.back(), 2.0);  // exactly the end, not up to round-off
  EXPECT_EQ(curve.label, "parabola");
  EXPECT_EQ(curve.style, "dashed");  // references are dashed by default
}

TEST(SampleCurve, EndsExactlyAtAnEndThatEvenSpacingRoundsOff) {
  // 0.1 * 3 != 0.3 in binary; the last sample must still be the given end.
  const Series curve = sample_curve(
      "", 0.0, 0.3, 4, [](double) { return 0.0; }, "line");
  EXPECT_EQ(curve.x.back(), 0.3);
  EXPECT_EQ(curve.style, "line");
}

TEST(SampleCurve, NeedsTwoPoints) {
  EXPECT_THROW(sample_curve("", 0.0, 1.0, 1, [](double) { return 0.0; }), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// run_validation and report.json

/// A case that records whether it saw a sink and, if so, fills it.
struct RecordingCase {
  bool saw_report = false;
  bool throw_after_figure = false;
  fs::path run_directory;

  std::vector<CheckResult> operator()(const ValidationContext& context) {
    saw_report = context.report != nullptr;
    if (context.report) {
      context.report->describe("A case made up for the test.");
      context.report->add_figure({"curve",
                                  "Made-up curve",
                                  "time [s]",
                                  "value [1]",
                                  {{"measured", {0.0, 0.5, 1.0}, {1.0, 0.25, -2.5}, "points"},
                                   {"exact", {0.0, 1.0}, {1.0, -2.5}, "dashed"}}});
      context.report->add_picture(
          {"field", run_directory.string(), "velocity", 1, 0.25, 20.0, "a caption"});
      context.report->add_picture(
          {"elsewhere", "/outside/run", "stress", -1, -1.0, 0.0, "another caption"});
    }
    if (throw_after_figure) throw std::runtime_error("the run diverged");
    return {check_at_most("error", 0.004, 0.0, 0.01, "fraction")};
  }
};

ValidationCase case_from(RecordingCase& recorder) {
  return {"made-up", "one-line summary",
          [&recorder](const ValidationContext& context) { return recorder(context); }};
}

TEST(RunValidation, GivesNoSinkAndWritesNoReportUnlessAsked) {
  const fs::path output = scratch("no_report");
  RecordingCase recorder;
  ValidationContext context;
  context.output_directory = output;
  const ValidationResult result = run_validation(case_from(recorder), context);
  EXPECT_FALSE(recorder.saw_report);
  EXPECT_TRUE(result.passed);
  EXPECT_TRUE(result.figures.empty());
  EXPECT_FALSE(fs::exists(output / "made-up" / "report.json"));
}

TEST(RunValidation, WritesReportJsonWithChecksFiguresAndPictures) {
  const fs::path output = scratch("report");
  RecordingCase recorder;
  recorder.run_directory = output / "made-up-case" / "run-1";
  ValidationContext context;
  context.output_directory = output;
  context.write_report = true;
  const ValidationResult result = run_validation(case_from(recorder), context);
  EXPECT_TRUE(recorder.saw_report);
  ASSERT_TRUE(result.passed) << result.error;
  EXPECT_EQ(result.description, "A case made up for the test.");
  ASSERT_EQ(result.figures.size(), 1u);
  ASSERT_EQ(result.pictures.size(), 2u);

  const YAML::Node report = YAML::LoadFile((output / "made-up" / "report.json").string());
  EXPECT_EQ(report["case"].as<std::string>(), "made-up");
  EXPECT_TRUE(report["passed"].as<bool>());
  EXPECT_EQ(report["description"].as<std::string>(), "A case made up for the test.");
  ASSERT_EQ(report["checks"].size(), 1u);
  EXPECT_EQ(report["checks"][0]["name"].as<std::string>(), "error");
  EXPECT_EQ(report["checks"][0]["value"].as<double>(), 0.004);
  EXPECT_EQ(report["checks"][0]["tolerance"].as<double>(), 0.01);
  EXPECT_EQ(report["checks"][0]["unit"].as<std::string>(), "fraction");

  ASSERT_EQ(report["figures"].size(), 1u);
  const YAML::Node figure = report["figures"][0];
  EXPECT_EQ(figure["name"].as<std::string>(), "curve");
  EXPECT_EQ(figure["title"].as<std::string>(), "Made-up curve");
  EXPECT_EQ(figure["x_label"].as<std::string>(), "time [s]");
  EXPECT_EQ(figure["y_label"].as<std::string>(), "value [1]");
  EXPECT_EQ(figure["x_scale"].as<std::string>(), "linear");
  EXPECT_EQ(figure["y_scale"].as<std::string>(), "linear");
  ASSERT_EQ(figure["series"].size(), 2u);
  EXPECT_EQ(figure["series"][0]["label"].as<std::string>(), "measured");
  EXPECT_EQ(figure["series"][0]["style"].as<std::string>(), "points");
  EXPECT_EQ(figure["series"][0]["x"].as<std::vector<double>>(), (std::vector{0.0, 0.5, 1.0}));
  EXPECT_EQ(figure["series"][0]["y"].as<std::vector<double>>(), (std::vector{1.0, 0.25, -2.5}));
  EXPECT_EQ(figure["series"][1]["style"].as<std::string>(), "dashed");

  ASSERT_EQ(report["pictures"].size(), 2u);
  const YAML::Node inside = report["pictures"][0];
  // Inside the report folder: relative to it, so that the folder can be moved or served.
  EXPECT_EQ(inside["run_directory"].as<std::string>(), "made-up-case/run-1");
  EXPECT_EQ(inside["field"].as<std::string>(), "velocity");
  EXPECT_EQ(inside["component"].as<int>(), 1);
  EXPECT_EQ(inside["time"].as<double>(), 0.25);
  EXPECT_EQ(inside["magnification"].as<double>(), 20.0);
  EXPECT_EQ(inside["caption"].as<std::string>(), "a caption");
  const YAML::Node outside = report["pictures"][1];
  EXPECT_EQ(outside["run_directory"].as<std::string>(), "/outside/run");
  EXPECT_EQ(outside["component"].as<int>(), -1);
  EXPECT_EQ(outside["time"].as<double>(), -1.0);
}

TEST(RunValidation, FallsBackOnTheSummaryWhenTheCaseDescribesNothing) {
  const fs::path output = scratch("summary");
  ValidationCase silent{"silent", "one-line summary", [](const ValidationContext&) {
                          return std::vector{check_at_most("x", 0.0, 0.0, 1.0, "1")};
                        }};
  ValidationContext context;
  context.output_directory = output;
  context.write_report = true;
  const ValidationResult result = run_validation(silent, context);
  EXPECT_EQ(result.description, "one-line summary");
  const YAML::Node report = YAML::LoadFile((output / "silent" / "report.json").string());
  EXPECT_EQ(report["description"].as<std::string>(), "one-line summary");
  EXPECT_EQ(report["figures"].size(), 0u);
  EXPECT_EQ(report["pictures"].size(), 0u);
}

TEST(RunValidation, ReportsACaseThatThrewWithWhatItHadAdded) {
  const fs::path output = scratch("threw");
  RecordingCase recorder;
  recorder.run_directory = output / "run";
  recorder.throw_after_figure = true;
  ValidationContext context;
  context.output_directory = output;
  context.write_report = true;
  const ValidationResult result = run_validation(case_from(recorder), context);
  EXPECT_FALSE(result.passed);
  EXPECT_EQ(result.error, "the run diverged");
  const YAML::Node report = YAML::LoadFile((output / "made-up" / "report.json").string());
  EXPECT_FALSE(report["passed"].as<bool>());
  EXPECT_EQ(report["error"].as<std::string>(), "the run diverged");
  EXPECT_EQ(report["figures"].size(), 1u);
  EXPECT_EQ(report["checks"].size(), 0u);
}

TEST(RunValidation, FailsTheCaseWhenTheReportCannotBeWritten) {
  const fs::path output = scratch("blocked");
  std::ofstream(output / "made-up") << "a file where the case folder should go";
  RecordingCase recorder;
  recorder.run_directory = output / "run";
  ValidationContext context;
  context.output_directory = output;
  context.write_report = true;
  const ValidationResult result = run_validation(case_from(recorder), context);
  EXPECT_FALSE(result.passed);
  EXPECT_FALSE(result.error.empty());
}

TEST(ValidationReportJson, WritesNonFiniteCurveValuesAsNull) {
  // JSON has no NaN; a gap in a curve must still parse.
  ValidationResult result;
  result.case_name = "gaps";
  result.figures.push_back(
      {"gap",
       "",
       "",
       "",
       {{"c", {0.0, 1.0}, {std::numeric_limits<double>::quiet_NaN(), 1.0}, "line"}}});
  const YAML::Node report = YAML::Load(validation_report_json(result, "/tmp"));
  EXPECT_TRUE(report["figures"][0]["series"][0]["y"][0].IsNull());
  EXPECT_EQ(report["figures"][0]["series"][0]["y"][1].as<double>(), 1.0);
}

TEST(ValidationJsonLine, KeepsTheContractFieldsOnly) {
  // The --json line is read by other tools: the report's additions must not appear in it.
  ValidationResult result;
  result.case_name = "c";
  result.passed = true;
  result.wall_seconds = 1.5;
  result.checks = {check_at_most("e", 0.25, 0.0, 0.5, "fraction")};
  result.description = "not in the line";
  result.figures.push_back(one_curve_figure("f"));
  result.pictures.push_back(picture_named("p"));
  EXPECT_EQ(validation_json_line(result),
            R"({"case":"c","passed":true,"wall_seconds":1.5,"checks":[{"name":"e","value":0.25,)"
            R"("reference":0.0,"tolerance":0.5,"unit":"fraction","passed":true}]})");
}

}  // namespace
}  // namespace rktsph::validation_report_test
