#include "rktsph/validation/rest_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/format.h>

#include "rktsph/core/error.hpp"
#include "rktsph/simulation/quantities.hpp"

namespace rktsph {

double oddeven_residual(std::span<const double> values, bool mirror_first) {
  const std::size_t n = values.size();
  double largest = 0.0;
  if (mirror_first && n >= 2)  // s_{-1} = s_1
    largest = std::abs(2.0 * values[0] - 2.0 * values[1]) / 4.0;
  for (std::size_t i = 1; i + 1 < n; ++i)
    largest = std::max(largest, std::abs(-values[i - 1] + 2.0 * values[i] - values[i + 1]) / 4.0);
  return largest;
}

double oddeven_residual_along(const NodeLine& line, bool mirror_first) {
  const std::size_t n = line.x.size();
  bool even = true;
  for (std::size_t i = 1; i + 1 < n && even; ++i)
    even = std::abs((line.x[i + 1] - line.x[i]) - (line.x[1] - line.x[0])) <=
           1e-9 * std::abs(line.x[1] - line.x[0]);
  if (n < 3 || even) return oddeven_residual(line.value, mirror_first);
  double largest = 0.0;
  if (mirror_first)  // the image of node 1 lies as far beyond node 0: L_0 = s_1
    largest = std::abs(line.value[0] - line.value[1]) / 2.0;
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double before = line.x[i] - line.x[i - 1], after = line.x[i + 1] - line.x[i];
    const double straight =
        (line.value[i - 1] * after + line.value[i + 1] * before) / (before + after);
    largest = std::max(largest, std::abs(line.value[i] - straight) / 2.0);
  }
  return largest;
}

NodeLine node_row(const Simulation& simulation, double y, double x_min, double x_max,
                  const std::function<double(std::size_t node)>& value) {
  const PointCloud& nodes = simulation.nodes().sph_nodes;
  const double tolerance = 0.25 * simulation.nodes().spacing;
  std::vector<std::pair<double, std::size_t>> row;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const double x = nodes.position[0][k];
    if (std::abs(nodes.position[1][k] - y) < tolerance && x >= x_min - tolerance &&
        x <= x_max + tolerance)
      row.emplace_back(x, k);
  }
  std::sort(row.begin(), row.end());
  NodeLine line;
  for (const auto& [x, k] : row) {
    line.x.push_back(x);
    line.value.push_back(value(k));
  }
  return line;
}

NodeLine surface_settlement(const Simulation& simulation, double surface, double x_min,
                            double x_max) {
  const State& state = simulation.state();
  return node_row(simulation, surface, x_min, x_max,
                  [&state](std::size_t k) { return -state.displacement(1, k); });
}

NodeLine contact_pressure(const Simulation& simulation, double surface, double x_min,
                          double x_max) {
  const bool saturated = simulation.model().pore_pressure_field() >= 0;
  const NodeQuantity stress =
      find_quantity(simulation, saturated ? "total_stress_yy" : "stress_yy");
  if (!stress) throw RunError("contact_pressure: the model has no vertical stress");
  const State& state = simulation.state();
  return node_row(simulation, surface, x_min, x_max,
                  [&](std::size_t k) { return -stress(state, k); });
}

double settlement_oddeven_ratio(const NodeLine& settlement, double half_width) {
  // The loaded surface and two loaded widths B = 2b beyond it: 0 <= x <= b + 2B.
  const double x_end = 5.0 * half_width;
  const double tolerance = 1e-6 * half_width;
  NodeLine checked;
  bool starts_on_symmetry_plane = false;
  double largest = 0.0;
  for (std::size_t k = 0; k < settlement.x.size(); ++k) {
    if (settlement.x[k] < -tolerance || settlement.x[k] > x_end + tolerance) continue;
    if (checked.x.empty()) starts_on_symmetry_plane = std::abs(settlement.x[k]) < tolerance;
    checked.x.push_back(settlement.x[k]);
    checked.value.push_back(settlement.value[k]);
    largest = std::max(largest, std::abs(settlement.value[k]));
  }
  if (checked.x.size() < 3 || largest == 0.0) return std::numeric_limits<double>::quiet_NaN();
  return oddeven_residual_along(checked, starts_on_symmetry_plane) / largest;
}

double FootingContactSampler::sample(const Simulation& simulation) {
  const NodeLine settlement = surface_settlement(simulation, surface, x_min, x_max);
  if (settlement.value.empty()) return 0.0;
  const double s = settlement.value.front() / width;
  if (s < from || s > to) return s;
  last = contact_pressure(simulation, surface, x_min, x_max);
  const double ratio = contact_pressure_oddeven_ratio(last);
  if (std::isnan(largest_ratio) || ratio > largest_ratio) largest_ratio = ratio;
  return s;
}

double contact_pressure_oddeven_ratio(const NodeLine& pressure) {
  const std::size_t n = pressure.value.size();
  if (n < 3) return std::numeric_limits<double>::quiet_NaN();
  const double mean = std::accumulate(pressure.value.begin() + 1, pressure.value.end() - 1, 0.0) /
                      static_cast<double>(n - 2);
  return oddeven_residual(pressure.value) / std::abs(mean);
}

LatticeView lattice_view(const NodeSets& nodes) {
  if (!nodes.on_lattice())
    throw RunError("this check reads the nodes on a lattice, and the body is meshed otherwise");
  const PointCloud& points = nodes.sph_nodes;
  LatticeView view;
  view.spacing = nodes.spacing;
  const auto [x_min, x_max] =
      std::minmax_element(points.position[0].begin(), points.position[0].end());
  const auto [y_min, y_max] =
      std::minmax_element(points.position[1].begin(), points.position[1].end());
  view.origin_x = *x_min;
  view.origin_y = nodes.dimension >= 2 ? *y_min : 0.0;
  auto cell = [&](double x, double origin) {
    return static_cast<int>(std::lround((x - origin) / nodes.spacing));
  };
  view.columns = cell(*x_max, view.origin_x) + 1;
  view.rows = nodes.dimension >= 2 ? cell(*y_max, view.origin_y) + 1 : 1;
  view.index.resize(points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
    view.index[k] = {cell(points.position[0][k], view.origin_x),
                     nodes.dimension >= 2 ? cell(points.position[1][k], view.origin_y) : 0};
  return view;
}

LatticeField lattice_field(const Simulation& simulation,
                           const std::function<double(std::size_t node)>& value) {
  const NodeSets& nodes = simulation.nodes();
  const LatticeView view = lattice_view(nodes);
  LatticeField field;
  field.columns = view.columns;
  field.rows = view.rows;
  field.spacing = view.spacing;
  field.origin_x = view.origin_x;
  field.origin_y = view.origin_y;
  field.value.assign(static_cast<std::size_t>(field.columns) * field.rows, std::nan(""));
  for (std::size_t k = 0; k < nodes.sph_nodes.size(); ++k) {
    const auto& [i, j] = view.index[k];
    field.value[static_cast<std::size_t>(j) * field.columns + i] = value(k);
  }
  return field;
}

LatticeField lattice_field(const Simulation& simulation, int field) {
  const FieldArray& fields = simulation.state().fields;
  return lattice_field(simulation, [&](std::size_t k) { return fields(field, k); });
}

double checkerboard_amplitude(const LatticeField& field,
                              const std::function<bool(double x, double y)>& skip) {
  const double weights[3] = {1.0, 2.0, 1.0};
  double largest = 0.0;
  for (int j = 1; j + 1 < field.rows; ++j)
    for (int i = 1; i + 1 < field.columns; ++i) {
      if (skip && skip(field.x(i), field.y(j))) continue;
      double alternating = 0.0;
      bool complete = true;
      for (int b = -1; b <= 1; ++b)
        for (int a = -1; a <= 1; ++a) {
          const double value = field.at(i + a, j + b);
          if (std::isnan(value)) complete = false;
          const double sign = ((a + b) % 2 == 0) ? 1.0 : -1.0;
          alternating += sign * weights[a + 1] * weights[b + 1] * value;
        }
      if (complete) largest = std::max(largest, std::abs(alternating) / 16.0);
    }
  return largest;
}

double max_abs(const LatticeField& field) {
  double largest = 0.0;
  for (double value : field.value)
    if (!std::isnan(value)) largest = std::max(largest, std::abs(value));
  return largest;
}

namespace {
// As the output observers: a time counts as reached within a millionth of a step of it.
bool reached(double time, double target, double dt) {
  return time >= target - 1e-6 * dt;
}
}  // namespace

void SampledObserver::take(const Simulation& simulation) {
  sample_(simulation);
  last_time_ = simulation.state().time;
}

void SampledObserver::on_start(const Simulation& simulation) {
  take(simulation);
  next_time_ = simulation.state().time + interval_;
}

void SampledObserver::after_step(const Simulation& simulation) {
  const double time = simulation.state().time, dt = simulation.time_step();
  if (interval_ > 0.0 && !reached(time, next_time_, dt)) return;
  take(simulation);
  while (interval_ > 0.0 && reached(time, next_time_, dt))
    next_time_ += interval_;
}

void SampledObserver::on_finish(const Simulation& simulation, RunStatus status,
                                const std::string&) {
  if (status == RunStatus::Completed && simulation.state().time != last_time_) take(simulation);
}

SpeedRecorder::SpeedRecorder(double interval)
    : observer_(interval, [this](const Simulation& simulation) {
        history_.time.push_back(simulation.state().time);
        history_.speed.push_back(largest_speed(simulation));
      }) {}

double residual_velocity_ratio(const SpeedHistory& history, double from) {
  if (history.speed.empty()) return std::numeric_limits<double>::quiet_NaN();
  double peak = 0.0;
  for (std::size_t k = 0; k < history.time.size(); ++k)
    if (history.time[k] >= from) peak = std::max(peak, history.speed[k]);
  return history.speed.back() / peak;
}

std::vector<double> positive_or_nan(const std::vector<double>& values) {
  std::vector<double> result;
  result.reserve(values.size());
  for (double value : values)
    result.push_back(value > 0.0 ? value : std::numeric_limits<double>::quiet_NaN());
  return result;
}

Figure speed_figure(const std::string& name, const SpeedHistory& history, double from,
                    double limit) {
  double peak = 0.0;
  for (std::size_t k = 0; k < history.time.size(); ++k)
    if (history.time[k] >= from) peak = std::max(peak, history.speed[k]);
  const double end = history.time.empty() ? from : history.time.back();
  Figure figure{
      name,
      "Largest velocity magnitude over all nodes",
      "time [s]",
      "max |v| over all nodes [m/s]",
      {{"SPH", history.time, positive_or_nan(history.speed), "line"},
       sample_curve(
           fmt::format("{:g} of the peak after t = {:g} s (limit at the end)", limit, from), from,
           end > from ? end : from + 1.0, 2, [&](double) { return limit * peak; })}};
  figure.y_scale = "log";
  return figure;
}

Figure settlement_figure(const std::string& name, const NodeLine& settlement, double half_width,
                         const std::string& title) {
  Series measured{"SPH surface nodes", settlement.x, {}, "line"};
  for (double s : settlement.value)
    measured.y.push_back(1e3 * s);
  return {name,
          title,
          fmt::format("x [m] (symmetry plane x = 0, load on 0 <= x <= b = {:g} m)", half_width),
          "settlement -u_y [mm]",
          {std::move(measured)}};
}

}  // namespace rktsph
