#include "rktsph/validation/validation_case.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include <omp.h>

#include "rktsph/output/atomic_file.hpp"
#include "rktsph/output/json_writer.hpp"

namespace rktsph {

namespace {

// Names become file names in the report folder and ids in its HTML: keep them portable.
bool is_file_stem(const std::string& name) {
  if (name.empty() || name.front() == '.') return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-' || c == '.';
  });
}

JsonValue numbers(const std::vector<double>& values) {
  JsonValue array = JsonValue::array();
  for (double value : values)
    array.push_back(value);
  return array;
}

JsonValue checks_json(const std::vector<CheckResult>& checks) {
  JsonValue array = JsonValue::array();
  for (const CheckResult& check : checks) {
    JsonValue item = JsonValue::object();
    item.set("name", check.name);
    item.set("value", check.value);
    item.set("reference", check.reference);
    item.set("tolerance", check.tolerance);
    item.set("unit", check.unit);
    item.set("passed", check.passed);
    array.push_back(std::move(item));
  }
  return array;
}

JsonValue figure_json(const Figure& figure) {
  JsonValue series = JsonValue::array();
  for (const Series& curve : figure.series) {
    JsonValue item = JsonValue::object();
    item.set("label", curve.label);
    item.set("style", curve.style);
    item.set("x", numbers(curve.x));
    item.set("y", numbers(curve.y));
    series.push_back(std::move(item));
  }
  JsonValue item = JsonValue::object();
  item.set("name", figure.name);
  item.set("title", figure.title);
  item.set("x_label", figure.x_label);
  item.set("y_label", figure.y_label);
  item.set("x_scale", figure.x_scale);
  item.set("y_scale", figure.y_scale);
  item.set("series", std::move(series));
  return item;
}

std::string portable_run_directory(const std::string& run_directory,
                                   const std::filesystem::path& report_root) {
  const std::filesystem::path run = std::filesystem::absolute(run_directory).lexically_normal();
  const std::filesystem::path root = std::filesystem::absolute(report_root).lexically_normal();
  const std::filesystem::path relative = run.lexically_relative(root);
  const bool inside = !relative.empty() && *relative.begin() != "..";
  return (inside ? relative : run).generic_string();
}

JsonValue picture_json(const FieldPicture& picture, const std::filesystem::path& report_root) {
  JsonValue item = JsonValue::object();
  item.set("name", picture.name);
  item.set("run_directory", portable_run_directory(picture.run_directory, report_root));
  item.set("field", picture.field);
  item.set("component", picture.component);
  item.set("time", picture.time);
  item.set("magnification", picture.magnification);
  item.set("caption", picture.caption);
  return item;
}

}  // namespace

void ValidationReport::describe(std::string description) {
  description_ = std::move(description);
}

void ValidationReport::claim_name(const std::string& name) {
  if (!is_file_stem(name))
    throw std::invalid_argument("report item name '" + name +
                                "' is not a file stem (letters, digits, '_', '-', '.')");
  if (std::find(names_.begin(), names_.end(), name) != names_.end())
    throw std::invalid_argument("report item name '" + name + "' is used twice");
  names_.push_back(name);
}

void ValidationReport::add_figure(Figure figure) {
  for (const std::string* scale : {&figure.x_scale, &figure.y_scale})
    if (*scale != "linear" && *scale != "log")
      throw std::invalid_argument("figure '" + figure.name + "' has axis scale '" + *scale +
                                  "' (expected linear or log)");
  for (const Series& curve : figure.series) {
    if (curve.style != "line" && curve.style != "dashed" && curve.style != "points")
      throw std::invalid_argument("figure '" + figure.name + "': series '" + curve.label +
                                  "' has style '" + curve.style +
                                  "' (expected line, dashed or points)");
    if (curve.x.size() != curve.y.size())
      throw std::invalid_argument("figure '" + figure.name + "': series '" + curve.label +
                                  "' has x and y of different lengths");
  }
  claim_name(figure.name);
  figures_.push_back(std::move(figure));
}

void ValidationReport::add_picture(FieldPicture picture) {
  if (picture.field.empty() || picture.run_directory.empty())
    throw std::invalid_argument("picture '" + picture.name + "' needs a run directory and a field");
  if (picture.component < -1)
    throw std::invalid_argument("picture '" + picture.name + "' has a negative component");
  claim_name(picture.name);
  pictures_.push_back(std::move(picture));
}

Series sample_curve(std::string label, double x0, double x1, int count,
                    const std::function<double(double)>& function, std::string style) {
  if (count < 2) throw std::invalid_argument("sample_curve needs at least two points");
  Series curve{std::move(label), {}, {}, std::move(style)};
  curve.x.reserve(static_cast<std::size_t>(count));
  curve.y.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    // The last abscissa is x1 exactly, not x0 + (count - 1) * step with its round-off.
    const double x = i == count - 1 ? x1 : x0 + (x1 - x0) * i / (count - 1);
    curve.x.push_back(x);
    curve.y.push_back(function(x));
  }
  return curve;
}

CheckResult check_within(std::string name, double value, double reference, double tolerance,
                         std::string unit) {
  return {std::move(name), value,
          reference,       tolerance,
          std::move(unit), std::isfinite(value) && std::abs(value - reference) <= tolerance};
}

CheckResult check_at_most(std::string name, double value, double reference, double tolerance,
                          std::string unit) {
  return {std::move(name), value,           reference,
          tolerance,       std::move(unit), std::isfinite(value) && value <= tolerance,
          "at_most"};
}

CheckResult check_at_least(std::string name, double value, double reference, double minimum,
                           std::string unit) {
  return {std::move(name), value,           reference,
          minimum,         std::move(unit), std::isfinite(value) && value >= minimum,
          "at_least"};
}

ValidationResult run_validation(const ValidationCase& validation,
                                const ValidationContext& context) {
  ValidationResult result;
  result.case_name = validation.name;
  const auto start = std::chrono::steady_clock::now();
  ValidationReport report;
  ValidationContext case_context = context;
  case_context.report = context.write_report ? &report : nullptr;
  try {
    result.checks = validation.run(case_context);
    result.passed = !result.checks.empty();
    for (const CheckResult& check : result.checks)
      result.passed = result.passed && check.passed;
  } catch (const std::exception& error) {
    result.error = error.what();
    result.passed = false;
  }
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!context.write_report) return result;

  result.description = report.description().empty() ? validation.summary : report.description();
  result.figures = report.figures();
  result.pictures = report.pictures();
  const std::filesystem::path path = context.output_directory / validation.name / "report.json";
  try {
    std::filesystem::create_directories(path.parent_path());
    write_file_atomically(path, validation_report_json(result, context.output_directory) + "\n");
  } catch (const std::exception& error) {
    // A report that cannot be written would silently miss from the page: fail the case instead.
    result.error += (result.error.empty() ? "" : "; ") + std::string(error.what());
    result.passed = false;
  }
  return result;
}

void run_validations(const std::vector<const ValidationCase*>& cases,
                     const ValidationContext& context, int jobs, int threads,
                     const std::function<void(const ValidationResult&)>& done) {
  std::vector<std::optional<ValidationResult>> results(cases.size());
  std::mutex mutex;
  std::condition_variable finished;
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    omp_set_num_threads(std::max(threads, 1));  // this thread's OpenMP teams
    for (std::size_t i = next++; i < cases.size(); i = next++) {
      ValidationResult result = run_validation(*cases[i], context);
      const std::lock_guard<std::mutex> lock(mutex);
      results[i] = std::move(result);
      finished.notify_one();
    }
  };
  const std::size_t workers = std::min(cases.size(), static_cast<std::size_t>(std::max(jobs, 1)));
  std::vector<std::jthread> pool;
  for (std::size_t w = 0; w < workers; ++w)
    pool.emplace_back(work);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    std::unique_lock<std::mutex> lock(mutex);
    finished.wait(lock, [&] { return results[i].has_value(); });
    const ValidationResult result = *results[i];
    lock.unlock();
    done(result);
  }
}

std::string validation_json_line(const ValidationResult& result) {
  JsonValue line = JsonValue::object();
  line.set("case", result.case_name);
  line.set("passed", result.passed);
  line.set("wall_seconds", result.wall_seconds);
  line.set("checks", checks_json(result.checks));
  if (!result.error.empty()) line.set("error", result.error);
  return line.compact();
}

std::string validation_report_json(const ValidationResult& result,
                                   const std::filesystem::path& report_root) {
  JsonValue report = JsonValue::object();
  report.set("case", result.case_name);
  report.set("passed", result.passed);
  report.set("wall_seconds", result.wall_seconds);
  report.set("checks", checks_json(result.checks));
  if (!result.error.empty()) report.set("error", result.error);
  report.set("description", result.description);
  JsonValue figures = JsonValue::array();
  for (const Figure& figure : result.figures)
    figures.push_back(figure_json(figure));
  report.set("figures", std::move(figures));
  JsonValue pictures = JsonValue::array();
  for (const FieldPicture& picture : result.pictures)
    pictures.push_back(picture_json(picture, report_root));
  report.set("pictures", std::move(pictures));
  // One line: the curves hold thousands of numbers, which pretty() would put one per line.
  return report.compact();
}

}  // namespace rktsph
