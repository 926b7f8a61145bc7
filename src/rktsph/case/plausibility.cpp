#include "rktsph/case/plausibility.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

namespace rktsph {

namespace {

// The range of a material parameter across real soils and rocks (docs/input-reference.md,
// "Plausibility warnings", has the sources), and what a value far below it usually means.
struct PlausibleRange {
  const char* key;
  const char* unit;
  double low;
  double high;
  const char* what;  ///< "moduli of soils and rocks"
  /// Below this the value is most likely in a larger unit: the hint names it.
  double wrong_unit_below;
  const char* wrong_unit_hint;
};

const std::vector<PlausibleRange>& material_ranges() {
  static const std::vector<PlausibleRange> ranges = {
      {"density", "kg/m^3", 900.0, 3500.0, "densities of soils and rocks", 10.0,
       "given in t/m^3 or g/cm^3? the unit is kg/m^3 (2 t/m^3 = 2000 kg/m^3)"},
      {"young_modulus", "Pa", 1e5, 1.5e11, "Young's moduli of soils and rocks", 1e5,
       "given in MPa or kPa? the unit is Pa (10 MPa = 1.0e7 Pa)"},
      // G = E / (2(1 + nu)) of the same soils and rocks (perzyna_modified_cam_clay's
      // pressure-dependent elasticity with a constant G).
      {"shear_modulus", "Pa", 3e4, 7.5e10, "shear moduli of soils and rocks", 3e4,
       "given in MPa or kPa? the unit is Pa (4 MPa = 4.0e6 Pa)"},
      {"yield_stress", "Pa", 1e3, 1e9, "strengths of soils and rocks", 1e3,
       "given in kPa? the unit is Pa (50 kPa = 5.0e4 Pa)"},
      {"minimum_yield_stress", "Pa", 1e2, 1e9, "strengths of soils and rocks", 1e2,
       "given in kPa? the unit is Pa (10 kPa = 1.0e4 Pa)"},
      {"preconsolidation_pressure", "Pa", 1e3, 1e8,
       "preconsolidation pressures of soils (1 kPa to 100 MPa)", 1e3,
       "given in kPa? the unit is Pa (100 kPa = 1.0e5 Pa)"},
      {"friction_angle", "deg", 5.0, 60.0, "friction angles of soils and rock joints",
       std::numbers::pi / 2.0, "given in radians? the unit is degrees (0.44 rad = 25.2 deg)"},
  };
  return ranges;
}

std::string number_text(double value) {
  return fmt::format("{:.6g}", value);
}

std::optional<CaseWarning> out_of_range(const PlausibleRange& range, const std::string& path,
                                        const Parameter& parameter) {
  const double value = parameter.value;
  if (value >= range.low && value <= range.high) return std::nullopt;
  CaseWarning warning{parameter.where, path, number_text(value), ""};
  const std::string span =
      fmt::format("{} to {} {}", number_text(range.low), number_text(range.high), range.unit);
  if (value < range.wrong_unit_below)
    warning.text =
        fmt::format("far below the {} ({}): {}", range.what, span, range.wrong_unit_hint);
  else
    warning.text = fmt::format("outside the {} ({})", range.what, span);
  return warning;
}

void check_materials(const CaseDescription& description, std::vector<CaseWarning>& warnings) {
  for (const auto& [name, block] : description.materials)
    for (const PlausibleRange& range : material_ranges()) {
      const auto found = block.values.find(range.key);
      if (found == block.values.end()) continue;
      if (auto warning = out_of_range(range, block.path + "." + range.key, found->second))
        warnings.push_back(std::move(*warning));
    }
}

void check_pore_fluid(const CaseDescription& description, std::vector<CaseWarning>& warnings) {
  if (!description.pore_fluid) return;
  const PoreFluidSpec& fluid = *description.pore_fluid;
  // Hydraulic conductivity spans 1e-13 m/s (unfractured rock) to 1 m/s (clean gravel).
  const PlausibleRange conductivity = {"hydraulic_conductivity",
                                       "m/s",
                                       1e-13,
                                       1.0,
                                       "hydraulic conductivities of soils and rocks",
                                       0.0,
                                       ""};
  const bool undrained = fluid.hydraulic_conductivity == 0.0;  // a deliberate choice
  if (!undrained)
    if (auto warning = out_of_range(conductivity, "pore_fluid.hydraulic_conductivity",
                                    Parameter{fluid.hydraulic_conductivity, fluid.where}))
      warnings.push_back(std::move(*warning));
  const PlausibleRange water = {"density",
                                "kg/m^3",
                                900.0,
                                1300.0,
                                "densities of pore water and brines",
                                10.0,
                                "given in t/m^3 or g/cm^3? the unit is kg/m^3 (water: 1000)"};
  if (auto warning =
          out_of_range(water, "pore_fluid.density", Parameter{fluid.density, fluid.where}))
    warnings.push_back(std::move(*warning));
}

// The water table (docs/theory.md §6.8) against the body's vertical extent: a table above the
// body is allowed (a submerged body, every node saturated) and gets no warning; one below the
// body leaves it dry, drained throughout, which is most likely a table given in the wrong frame.
void check_water_table(const CaseDescription& description, std::vector<CaseWarning>& warnings) {
  if (!description.pore_fluid || !description.pore_fluid->water_table) return;
  const WaterTableSpec& table = *description.pore_fluid->water_table;
  const PoreFluidSpec& fluid = *description.pore_fluid;
  const auto vertical = static_cast<std::size_t>(description.dimension - 1);
  double lowest = std::numeric_limits<double>::infinity();
  for (const ShapeSpec& shape : description.geometry.shapes)
    for (const Vec3& vertex : shape.vertices)
      lowest = std::min(lowest, vertex[vertical]);
  double highest_table = table.level.value_or(-std::numeric_limits<double>::infinity());
  for (const auto& vertex : table.polyline)
    highest_table = std::max(highest_table, vertex[1]);
  if (std::isfinite(lowest) && highest_table <= lowest)
    warnings.push_back({table.where, "pore_fluid.water_table", number_text(highest_table),
                        fmt::format("at or below the lowest point of the body ({} m): the body "
                                    "is dry, drained throughout, and carries no pore pressure",
                                    number_text(lowest))});
  if (table.density_above) {
    const PlausibleRange above = {"density_above",
                                  "kg/m^3",
                                  900.0,
                                  3500.0,
                                  "densities of soils and rocks",
                                  10.0,
                                  "given in t/m^3 or g/cm^3? the unit is kg/m^3 (2 t/m^3 = 2000 "
                                  "kg/m^3)"};
    if (auto warning = out_of_range(above, "pore_fluid.water_table.density_above",
                                    Parameter{*table.density_above, table.where}))
      warnings.push_back(std::move(*warning));
  } else {
    // The default rho - n rho_w must stay a density: a porosity and mixture density that leave
    // the drained soil lighter than water are most likely a mistake in one of them.
    for (const auto& [name, block] : description.materials) {
      const auto found = block.values.find("density");
      if (found == block.values.end()) continue;
      const double drained = found->second.value - fluid.porosity * fluid.density;
      if (drained < 900.0)
        warnings.push_back({table.where, "pore_fluid.water_table", "density_above unset",
                            fmt::format("the drained density of material '{}' above the table, "
                                        "rho - n rho_w = {} kg/m^3, is below those of soils",
                                        name, number_text(drained))});
    }
  }
}

/// The time at which `function` first takes its full value, if it is a ramp or a step.
std::optional<double> full_value_time(const TimeFunction& function) {
  if (function.kind == TimeFunction::Kind::LinearRamp) return function.start + function.duration;
  if (function.kind == TimeFunction::Kind::Step) return function.start;
  return std::nullopt;
}

void check_ramp(const TimeFunction& function, const SourceLocation& where, const std::string& key,
                double end, double time_step, std::vector<CaseWarning>& warnings) {
  const std::optional<double> full = full_value_time(function);
  if (full && *full > end)
    warnings.push_back({where, key, number_text(function.value),
                        fmt::format("reaches its full value at t = {} s, after time.end = {} s: "
                                    "the run ends before it is applied in full",
                                    number_text(*full), number_text(end))});
  // The step takes an imposed value at the middle of each step (docs/theory.md eq. 2.2), so a
  // ramp shorter than a step is seen as a jump: its timing is lost by up to half its duration.
  // A run of one step has its own warning (check_time_step).
  if (function.kind == TimeFunction::Kind::LinearRamp && function.duration < time_step &&
      time_step < end)
    warnings.push_back(
        {where, key, number_text(function.value),
         fmt::format("ramps over {} s, less than the time step dt = {} s: the step takes the "
                     "imposed value at the middle of each step, so it sees a jump, and the ramp's "
                     "timing is lost by up to half its duration. Ramp over two steps or more, or "
                     "write function: step if a jump is meant",
                     number_text(function.duration), number_text(time_step))});
}

void check_loads_within_run(const CaseDescription& description, double time_step,
                            std::vector<CaseWarning>& warnings) {
  const double end = description.time.end;
  const char* axes = "xyz";
  for (std::size_t b = 0; b < description.boundary_conditions.size(); ++b) {
    const BoundaryConditionSpec& condition = description.boundary_conditions[b];
    const std::string path = fmt::format("boundary_conditions.{}", b);
    for (int a = 0; a < 3; ++a) {
      if (condition.velocity[a])
        check_ramp(*condition.velocity[a], condition.where,
                   fmt::format("{}.velocity.{}", path, axes[a]), end, time_step, warnings);
      if (condition.traction[a])
        check_ramp(*condition.traction[a], condition.where,
                   fmt::format("{}.traction.{}", path, axes[a]), end, time_step, warnings);
    }
    if (condition.pore_pressure)
      check_ramp(*condition.pore_pressure, condition.where, path + ".pore_pressure", end, time_step,
                 warnings);
  }
  if (description.gravity)
    check_ramp(description.gravity->factor, description.gravity->where, "gravity.factor", end,
               time_step, warnings);
}

void check_time_step(const CaseDescription& description, double time_step,
                     std::vector<CaseWarning>& warnings) {
  const double end = description.time.end;
  if (time_step >= end)
    warnings.push_back({description.time.where, "time.end", number_text(end),
                        fmt::format("not longer than the time step dt = {} s: the run is a "
                                    "single step",
                                    number_text(time_step))});
  const double interval = description.output.interval;
  if (interval > 0.0 && interval < time_step)
    warnings.push_back({description.output.where, "output.interval", number_text(interval),
                        fmt::format("shorter than the time step dt = {} s: field files come "
                                    "once per step, not every {} s",
                                    number_text(time_step), number_text(interval))});
  if (interval > end)
    warnings.push_back({description.output.where, "output.interval", number_text(interval),
                        fmt::format("longer than the run (time.end = {} s): only the first and "
                                    "the last state are written",
                                    number_text(end))});
}

bool earlier(const CaseWarning& a, const CaseWarning& b) {
  if (a.where.line != b.where.line) return a.where.line < b.where.line;
  return a.where.column < b.where.column;
}

}  // namespace

std::string CaseWarning::to_string() const {
  std::string text = where.to_string();
  if (!text.empty()) text += ": ";
  text += "warning: ";
  if (!key.empty()) text += fmt::format("key '{}' = {}: ", key, value);
  return text + this->text;
}

std::vector<CaseWarning> plausibility_warnings(const CaseDescription& description,
                                               double time_step) {
  std::vector<CaseWarning> warnings;
  check_materials(description, warnings);
  check_pore_fluid(description, warnings);
  check_water_table(description, warnings);
  check_loads_within_run(description, time_step, warnings);
  check_time_step(description, time_step, warnings);
  std::stable_sort(warnings.begin(), warnings.end(), earlier);
  return warnings;
}

std::vector<std::string> warning_lines(const std::vector<CaseWarning>& warnings) {
  std::vector<std::string> lines;
  for (const CaseWarning& warning : warnings)
    lines.push_back(warning.to_string());
  return lines;
}

}  // namespace rktsph
