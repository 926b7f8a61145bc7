#include "rktsph/validation/validation_support.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>

#include "rktsph/driver/run_case.hpp"
#include "rktsph/validation/references/elastic_moduli.hpp"
#include "rktsph/validation/references/terzaghi.hpp"

namespace rktsph {

ProbeTable ProbeTable::read(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw RunError("cannot read " + path.string());
  ProbeTable table;
  std::string line;
  std::getline(in, line);
  std::stringstream header(line);
  for (std::string name; std::getline(header, name, ',');)
    table.names_.push_back(name);
  table.columns_.resize(table.names_.size());
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::size_t c = 0;
    for (std::string cell; std::getline(row, cell, ',') && c < table.columns_.size(); ++c)
      table.columns_[c].push_back(std::strtod(cell.c_str(), nullptr));
  }
  return table;
}

const std::vector<double>& ProbeTable::column(const std::string& name) const {
  const auto it = std::find(names_.begin(), names_.end(), name);
  if (it == names_.end()) throw RunError("probes.csv has no column '" + name + "'");
  return columns_[static_cast<std::size_t>(it - names_.begin())];
}

double ProbeTable::mean(const std::string& name, double t0, double t1) const {
  const auto& t = time();
  const auto& v = column(name);
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= t0 && t[i] <= t1) {
      sum += v[i];
      ++count;
    }
  return count ? sum / count : std::numeric_limits<double>::quiet_NaN();
}

double ProbeTable::max(const std::string& name, double t0, double t1) const {
  const auto& t = time();
  const auto& v = column(name);
  double result = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= t0 && t[i] <= t1) result = std::max(result, v[i]);
  return result;
}

double ProbeTable::max_abs(const std::string& name, double t0, double t1) const {
  const auto& t = time();
  const auto& v = column(name);
  double result = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= t0 && t[i] <= t1) result = std::max(result, std::abs(v[i]));
  return result;
}

double ProbeTable::rms(const std::string& name, double t0, double t1) const {
  const auto& t = time();
  const auto& v = column(name);
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= t0 && t[i] < t1) {
      sum += v[i] * v[i];
      ++count;
    }
  return count ? std::sqrt(sum / count) : std::numeric_limits<double>::quiet_NaN();
}

double ProbeTable::first_crossing(const std::string& name, double level) const {
  const auto& t = time();
  const auto& v = column(name);
  for (std::size_t i = 1; i < t.size(); ++i)
    if ((v[i - 1] - level) * (v[i] - level) <= 0.0 && v[i] != v[i - 1])
      return t[i - 1] + (level - v[i - 1]) / (v[i] - v[i - 1]) * (t[i] - t[i - 1]);
  return std::numeric_limits<double>::quiet_NaN();
}

double ProbeTable::step_arrival(const std::string& name, double plateau, double t0,
                                double t1) const {
  const auto& t = time();
  const auto& v = column(name);
  double area = 0.0;  // trapezoidal integral of value/plateau over [t0, t1]
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double a = std::max(t[i - 1], t0), b = std::min(t[i], t1);
    if (b <= a) continue;
    auto at = [&](double s) {
      return v[i - 1] + (v[i] - v[i - 1]) * (s - t[i - 1]) / (t[i] - t[i - 1]);
    };
    area += 0.5 * (at(a) + at(b)) * (b - a) / plateau;
  }
  return t1 - area;
}

CaseDescription load_bundled_case(const ValidationContext& context, const std::string& folder,
                                  const std::vector<CaseOverride>& overrides) {
  std::vector<CaseOverride> all = context.overrides;
  all.insert(all.end(), overrides.begin(), overrides.end());
  return read_case_file((context.cases_directory / folder / "case.yaml").string(), all);
}

ValidationRun run_allowing_failure(const ValidationContext& context,
                                   const CaseDescription& description, const std::string& label,
                                   const std::function<void(const Simulation&)>& inspect,
                                   const std::vector<Observer*>& observers) {
  ValidationRun run;
  run.directory = context.output_directory / description.name / label;
  RunOptions options;
  options.quiet = true;
  options.observers = observers;
  // The validation owns its run folders: a new validation replaces the last one's runs.
  options.existing_results = ExistingResults::Overwrite;
  const RunOutcome outcome = run_case(description, run.directory, options, inspect);
  run.completed = outcome.status == RunStatus::Completed;
  run.message = outcome.message;
  return run;
}

std::filesystem::path run_for_validation(const ValidationContext& context,
                                         const CaseDescription& description,
                                         const std::string& label,
                                         const std::function<void(const Simulation&)>& inspect,
                                         const std::vector<Observer*>& observers) {
  const ValidationRun run = run_allowing_failure(context, description, label, inspect, observers);
  if (!run.completed)
    throw RunError(
        fmt::format("run '{}' of {} did not complete: {}", label, description.name, run.message));
  return run.directory;
}

SaturatedColumn read_saturated_column(const CaseDescription& description,
                                      const std::string& folder) {
  if (!description.pore_fluid) throw RunError("case " + folder + ": no pore_fluid");
  SaturatedColumn column;
  const ShapeSpec& rectangle = description.geometry.shapes.at(0);
  column.x_min = rectangle.vertices.at(0)[0];
  column.x_max = rectangle.vertices.at(1)[0];
  column.base = rectangle.vertices.at(0)[1];
  column.height = rectangle.vertices.at(1)[1] - column.base;
  column.spacing = description.geometry.spacing;
  column.oedometric_modulus =
      references::oedometric_modulus(material_parameter(description, "soil", "young_modulus"),
                                     material_parameter(description, "soil", "poisson_ratio"));
  const PoreFluidSpec& fluid = *description.pore_fluid;
  column.biot_modulus = references::biot_modulus(fluid.porosity, fluid.bulk_modulus);
  return column;
}

double material_parameter(const CaseDescription& description, const std::string& material,
                          const std::string& key) {
  const auto block = description.materials.find(material);
  if (block == description.materials.end())
    throw RunError("case " + description.name + ": no material '" + material + "'");
  const auto it = block->second.values.find(key);
  if (it == block->second.values.end())
    throw RunError("case " + description.name + ": material '" + material + "' has no '" + key +
                   "'");
  return it->second.value;
}

Rectangle rectangle_shape(const CaseDescription& description, std::size_t index) {
  const auto not_a_rectangle = [&] {
    return RunError(fmt::format("case {}: shape {} of the geometry is not a rectangle",
                                description.name, index));
  };
  if (index >= description.geometry.shapes.size()) throw not_a_rectangle();
  const ShapeSpec& shape = description.geometry.shapes[index];
  const std::vector<Vec3>& corners = shape.vertices;
  if (shape.kind == ShapeSpec::Kind::Rectangle)
    return {corners.at(0)[0], corners.at(0)[1], corners.at(1)[0], corners.at(1)[1]};
  if (shape.kind != ShapeSpec::Kind::Polygon) throw not_a_rectangle();
  // A rectangle drawn as a polygon, with more vertices on its sides (to put mesh nodes where a
  // triangle mesh needs them, e.g. at a load's edge): every vertex on the sides of the bounding
  // box and the polygon's area that of the box.
  Rectangle box{corners.at(0)[0], corners.at(0)[1], corners.at(0)[0], corners.at(0)[1]};
  for (const Vec3& v : corners) {
    box.x_min = std::min(box.x_min, v[0]);
    box.x_max = std::max(box.x_max, v[0]);
    box.y_min = std::min(box.y_min, v[1]);
    box.y_max = std::max(box.y_max, v[1]);
  }
  double twice_area = 0.0;
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const Vec3& a = corners[k];
    const Vec3& b = corners[(k + 1) % corners.size()];
    twice_area += a[0] * b[1] - b[0] * a[1];
    if (a[0] != box.x_min && a[0] != box.x_max && a[1] != box.y_min && a[1] != box.y_max)
      throw not_a_rectangle();
  }
  if (std::abs(0.5 * std::abs(twice_area) - box.width() * box.height()) >
      1e-12 * box.width() * box.height())
    throw not_a_rectangle();
  return box;
}

namespace {

const GroupSpec& find_group(const CaseDescription& description, const std::string& name,
                            GroupSpec::Kind kind, const char* kind_name) {
  for (const GroupSpec& group : description.groups)
    if (group.name == name) {
      if (group.kind != kind)
        throw RunError(
            fmt::format("case {}: group '{}' is not a {}", description.name, name, kind_name));
      return group;
    }
  throw RunError(fmt::format("case {}: no group '{}'", description.name, name));
}

}  // namespace

Rectangle group_box(const CaseDescription& description, const std::string& name) {
  const GroupSpec& group = find_group(description, name, GroupSpec::Kind::Box, "box");
  return {group.min[0], group.min[1], group.max[0], group.max[1]};
}

Vec3 group_point(const CaseDescription& description, const std::string& name) {
  return find_group(description, name, GroupSpec::Kind::Point, "point").point;
}

double downward_gravity(const CaseDescription& description) {
  if (!description.gravity) throw RunError("case " + description.name + ": no gravity");
  const Vec3& g = description.gravity->acceleration;
  if (g[0] != 0.0 || g[2] != 0.0 || !(g[1] < 0.0))
    throw RunError("case " + description.name + ": gravity must point down, (0, -g)");
  return -g[1];
}

const TimeFunction& imposed_on(const CaseDescription& description, const std::string& group,
                               int axis, bool traction) {
  const auto kind =
      traction ? BoundaryConditionSpec::Kind::Traction : BoundaryConditionSpec::Kind::Velocity;
  for (const BoundaryConditionSpec& condition : description.boundary_conditions) {
    const auto& component = traction ? condition.traction : condition.velocity;
    if (condition.group == group && condition.kind == kind && component.at(axis))
      return *component.at(axis);
  }
  throw RunError(fmt::format("case {}: no {} {} imposed on the group '{}'", description.name,
                             traction ? "traction" : "velocity", "xyz"[axis], group));
}

double final_value(const TimeFunction& function, const std::string& what) {
  switch (function.kind) {
    case TimeFunction::Kind::Constant:
    case TimeFunction::Kind::Step:
    case TimeFunction::Kind::LinearRamp:
      return function.value;
    case TimeFunction::Kind::Table:
      if (!function.table.empty()) return function.table.back().second;
      break;
    case TimeFunction::Kind::Harmonic:
      break;
  }
  throw RunError(what + ": a constant, step, ramp or table is needed, not a harmonic function");
}

FootingRow footing_row(const CaseDescription& description, FootingPlace place) {
  FootingRow row;
  row.body = rectangle_shape(description, 0);
  const Rectangle footing = group_box(description, "footing");
  row.left = footing.x_min;
  row.right = footing.x_max;
  row.surface = footing.y_max;
  if (footing.y_min != footing.y_max || footing.y_max != row.body.y_max ||
      footing.x_min < row.body.x_min || footing.x_max > row.body.x_max ||
      !(footing.x_min < footing.x_max))
    throw RunError("case " + description.name +
                   ": the group 'footing' must be a box of one row on the top of the first shape");
  if (place == FootingPlace::SymmetryPlane && (row.left != 0.0 || row.body.x_min != 0.0))
    throw RunError("case " + description.name +
                   ": the footing must start on the symmetry plane x = 0, the body's left side");
  if (place == FootingPlace::Crest && row.right != row.body.x_max)
    throw RunError("case " + description.name +
                   ": the footing must end at the crest, on the body's right side");
  return row;
}

HalfModelFooting half_model_footing(const ValidationContext& context, const std::string& folder,
                                    double quick_spacing) {
  std::vector<CaseOverride> overrides;
  if (context.quick) overrides.push_back({"geometry.spacing", fmt::format("{}", quick_spacing)});
  HalfModelFooting footing;
  footing.description = load_bundled_case(context, folder, overrides);
  footing.row = footing_row(footing.description, FootingPlace::SymmetryPlane);
  footing.width = 2.0 * footing.row.right;
  footing.nodes =
      static_cast<int>(std::lround(footing.row.right / footing.description.geometry.spacing)) + 1;
  return footing;
}

StripLoad read_strip_load(const CaseDescription& description) {
  StripLoad load;
  load.row = footing_row(description, FootingPlace::SymmetryPlane);
  // The traction acts on the facets within the group (docs/theory.md §5.1): the box is the strip.
  load.half_width = load.row.right;
  const TimeFunction& traction = imposed_on(description, "footing", 1, true);
  load.history = &traction;
  load.pressure = -final_value(traction, "the traction on 'footing'");
  if (!(load.pressure > 0.0))
    throw RunError("case " + description.name +
                   ": a compressive strip load -q on the row 'footing' from the symmetry plane "
                   "x = 0 to x = b is expected");
  return load;
}

WeakZone read_weak_zone(const CaseDescription& description) {
  const auto& shapes = description.geometry.shapes;
  if (shapes.size() != 2 || shapes[1].material == shapes[0].material)
    throw RunError("case " + description.name +
                   ": a weak zone, a second shape of its own material, is expected");
  return {rectangle_shape(description, 1)};
}

std::vector<double> add_row_probes(CaseDescription& description, const std::string& prefix,
                                   double x_min, double x_max, double y0, double spacing, int rows,
                                   const std::string& field) {
  std::vector<double> heights;
  for (int row = 0; row < rows; ++row) {
    const double y = y0 + row * spacing;
    GroupSpec group;
    group.name = fmt::format("{}{}", prefix, row);
    group.kind = GroupSpec::Kind::Box;
    group.min = {x_min, y - 0.25 * spacing, 0.0};
    group.max = {x_max, y + 0.25 * spacing, 0.0};
    description.groups.push_back(group);
    ProbeSpec probe;
    probe.name = group.name;
    probe.group = group.name;
    probe.fields = {field};
    description.probes.push_back(probe);
    heights.push_back(y);
  }
  return heights;
}

double relative_error(double value, double reference) {
  return std::abs(value / reference - 1.0);
}

std::span<const double> internal_variable(const Simulation& simulation, const std::string& name,
                                          const std::string& case_name) {
  const auto& names = simulation.model().internal_names();
  const auto found = std::find(names.begin(), names.end(), name);
  if (found == names.end()) throw RunError(case_name + ": the model has no " + name);
  return {simulation.state().internal.field(static_cast<int>(found - names.begin())),
          simulation.nodes().sph_nodes.size()};
}

Series band_centre_series(const std::vector<std::pair<double, double>>& centres) {
  Series measured{"SPH: band centre on each lattice row (eps_vp-weighted)", {}, {}, "points"};
  for (const auto& [x, y] : centres) {
    measured.x.push_back(x);
    measured.y.push_back(y);
  }
  return measured;
}

Series line_from_vertical(std::string label, double x0, double y0, double angle_deg, double y_low,
                          double y_high, std::string style) {
  const double dx_dy = std::tan(angle_deg * std::numbers::pi / 180.0);
  return Series{std::move(label),
                {x0 + (y_low - y0) * dx_dy, x0 + (y_high - y0) * dx_dy},
                {y_low, y_high},
                std::move(style)};
}

Series band_ridge_series(const BandLine& line, double y_low, double y_high) {
  // direction_deg is counter-clockwise from the vertical: the line leans left going up.
  return line_from_vertical(
      fmt::format("ridge fit of the check: {:.1f} degrees from the vertical", line.angle_deg),
      line.centre_x, line.centre_y, -line.direction_deg, y_low, y_high, "line");
}

BandMeasurement measure_band_in_region(const Simulation& simulation, const std::string& case_name,
                                       double x_min, double y_min) {
  const PointCloud& nodes = simulation.nodes().sph_nodes;
  const std::span<const double> strain = internal_variable(simulation, "eps_vp", case_name);
  std::vector<double> x, y, value;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double px = nodes.position[0][i], py = nodes.position[1][i];
    if (px < x_min || py < y_min) continue;
    x.push_back(px);
    y.push_back(py);
    value.push_back(strain[i]);
  }
  return measure_band(x, y, value, BandAngleOptions{});
}

FootingHistory read_footing_history(const std::filesystem::path& directory, int node_count,
                                    const std::string& stress, const std::string& end_a,
                                    const std::string& end_b) {
  const ProbeTable probes = ProbeTable::read(directory / "probes.csv");
  FootingHistory history;
  history.directory = directory;
  history.time = probes.time();
  const auto& mean = probes.column("footing." + stress);
  const auto& first = probes.column(end_a + "." + stress);
  const auto& last = probes.column(end_b + "." + stress);
  const auto& displacement = probes.column("footing.displacement_y");
  for (std::size_t row = 0; row < history.time.size(); ++row) {
    const double sum = mean[row] * node_count - 0.5 * (first[row] + last[row]);
    history.pressure.push_back(-sum / (node_count - 1));
    history.settlement.push_back(-displacement[row]);
  }
  return history;
}

FootingHistory run_coarse_footing(const ValidationContext& context, const std::string& folder,
                                  double spacing, double length, const std::string& stress,
                                  const std::string& end_a, const std::string& end_b) {
  const ValidationRun run = run_allowing_failure(
      context,
      load_bundled_case(
          context, folder,
          {{"geometry.spacing", fmt::format("{}", spacing)}, {"output.interval", "0"}}),
      "coarse");
  const int node_count = static_cast<int>(std::lround(length / spacing)) + 1;
  return read_footing_history(run.directory, node_count, stress, end_a, end_b);
}

Series footing_pressure_series(std::string label, const FootingHistory& history, double width) {
  Series series{std::move(label), {}, {}, "line"};
  for (std::size_t row = 0; row < history.time.size(); ++row) {
    series.x.push_back(history.settlement[row] / width);
    series.y.push_back(1e-3 * history.pressure[row]);
  }
  return series;
}

}  // namespace rktsph
