#include "rktsph/validation/validation_case.hpp"

#include <chrono>
#include <cmath>
#include <exception>

#include "rktsph/output/json_writer.hpp"

namespace rktsph {

CheckResult check_within(std::string name, double value, double reference, double tolerance,
                         std::string unit) {
  return {std::move(name), value,
          reference,       tolerance,
          std::move(unit), std::isfinite(value) && std::abs(value - reference) <= tolerance};
}

CheckResult check_at_most(std::string name, double value, double reference, double tolerance,
                          std::string unit) {
  return {std::move(name), value,           reference,
          tolerance,       std::move(unit), std::isfinite(value) && value <= tolerance};
}

ValidationResult run_validation(const ValidationCase& validation,
                                const ValidationContext& context) {
  ValidationResult result;
  result.case_name = validation.name;
  const auto start = std::chrono::steady_clock::now();
  try {
    result.checks = validation.run(context);
    result.passed = !result.checks.empty();
    for (const CheckResult& check : result.checks)
      result.passed = result.passed && check.passed;
  } catch (const std::exception& error) {
    result.error = error.what();
    result.passed = false;
  }
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::string validation_json_line(const ValidationResult& result) {
  JsonValue line = JsonValue::object();
  line.set("case", result.case_name);
  line.set("passed", result.passed);
  line.set("wall_seconds", result.wall_seconds);
  JsonValue checks = JsonValue::array();
  for (const CheckResult& check : result.checks) {
    JsonValue item = JsonValue::object();
    item.set("name", check.name);
    item.set("value", check.value);
    item.set("reference", check.reference);
    item.set("tolerance", check.tolerance);
    item.set("unit", check.unit);
    item.set("passed", check.passed);
    checks.push_back(std::move(item));
  }
  line.set("checks", std::move(checks));
  if (!result.error.empty()) line.set("error", result.error);
  return line.compact();
}

}  // namespace rktsph
