#include "rktsph/output/run_observers.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "rktsph/case/yaml_reader.hpp"
#include "rktsph/output/atomic_file.hpp"
#include "rktsph/output/json_writer.hpp"
#include "rktsph/output/vtu_writer.hpp"

namespace rktsph {

namespace {

// A time counts as reached when within a millionth of a step of it (round-off of t += dt).
bool reached(double time, double target, double dt) {
  return time >= target - 1e-6 * dt;
}

const std::vector<std::string>& dry_output_fields() {
  static const std::vector<std::string> names = {
      "velocity", "displacement", "stress", "pressure", "deviatoric_stress", "eps_vp", "material"};
  return names;
}

const std::vector<std::string>& saturated_output_fields() {
  static const std::vector<std::string> names = {"velocity",          "displacement",  "stress",
                                                 "total_stress",      "pore_pressure", "pressure",
                                                 "deviatoric_stress", "eps_vp",        "material"};
  return names;
}

}  // namespace

FieldSeriesWriter::FieldSeriesWriter(const Simulation& simulation, std::filesystem::path directory)
    : directory_(std::move(directory)),
      collection_(directory_ / "series.pvd"),
      interval_(simulation.description().output.interval) {
  const OutputSpec& output = simulation.description().output;
  const bool saturated = simulation.model().pore_pressure_field() >= 0;
  const auto& available = saturated ? saturated_output_fields() : dry_output_fields();
  selection_ = output.fields.empty() ? available : output.fields;
  for (const std::string& name : selection_) {
    if (std::find(available.begin(), available.end(), name) == available.end()) {
      std::string allowed;
      for (const std::string& a : available)
        allowed += (allowed.empty() ? "" : ", ") + a;
      throw InputError(output.where, "output.fields", name,
                       saturated ? "field not available for the saturated model"
                                 : "field not available for the dry solid model",
                       allowed);
    }
  }
  std::filesystem::create_directories(directory_ / "fields");
}

void FieldSeriesWriter::write(const Simulation& simulation) {
  const State& state = simulation.state();
  const DrySolid& model = simulation.model();
  const std::size_t n = simulation.nodes().sph_nodes.size();
  const int d = model.dimension();
  const std::vector<double> zeros(n, 0.0);
  std::vector<PointField> fields;
  std::vector<std::vector<double>> derived;  // storage for computed arrays
  derived.reserve(32);                       // pointers into it are kept: no reallocation
  auto computed = [&](const NodeQuantity& quantity) {
    derived.emplace_back(n);
    for (std::size_t i = 0; i < n; ++i)
      derived.back()[i] = quantity(state, i);
    return derived.back().data();
  };

  for (const std::string& name : selection_) {
    if (name == "velocity" || name == "displacement") {
      PointField field{name, 3, {}};
      for (int a = 0; a < 3; ++a)
        field.component_data.push_back(a >= d ? zeros.data()
                                              : (name == "velocity"
                                                     ? state.fields.field(model.velocity_field(a))
                                                     : state.displacement.field(a)));
      fields.push_back(field);
    } else if (name == "stress") {
      // 9 components in row order xx xy xz yx yy yz zx zy zz, as ParaView reads tensors.
      PointField field{name, 9, {}};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const int f = model.stress_field(i, j);
          field.component_data.push_back(f >= 0 ? state.fields.field(f) : zeros.data());
        }
      fields.push_back(field);
    } else if (name == "total_stress") {
      // sigma = sigma' - alpha p_w I (docs/theory.md §1.1).
      const double alpha = model.biot_coefficient();
      const double* pore = state.fields.field(model.pore_pressure_field());
      PointField field{name, 9, {}};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const int f = model.stress_field(i, j);
          derived.emplace_back(n, 0.0);
          for (std::size_t k = 0; k < n; ++k)
            derived.back()[k] =
                (f >= 0 ? state.fields(f, k) : 0.0) - (i == j ? alpha * pore[k] : 0.0);
          field.component_data.push_back(derived.back().data());
        }
      fields.push_back(field);
    } else if (name == "pressure" || name == "deviatoric_stress") {
      fields.push_back({name, 1, {computed(find_quantity(simulation, name))}});
    } else if (name == "material") {
      derived.emplace_back(simulation.nodes().node_material.begin(),
                           simulation.nodes().node_material.end());
      fields.push_back({name, 1, {derived.back().data()}});
    } else {
      const NodeQuantity quantity = find_quantity(simulation, name);
      if (quantity) fields.push_back({name, 1, {computed(quantity)}});
    }
  }
  const std::string file = fmt::format("fields/fields_{:06d}.vtu", collection_.entries().size());
  write_vtu(directory_ / file, simulation.nodes().sph_nodes, fields);
  collection_.add(state.time, file);
  last_written_time_ = state.time;
}

void FieldSeriesWriter::on_start(const Simulation& simulation) {
  write(simulation);
  next_time_ = interval_ > 0.0 ? interval_ : std::numeric_limits<double>::infinity();
}

void FieldSeriesWriter::after_step(const Simulation& simulation) {
  if (!reached(simulation.state().time, next_time_, simulation.time_step())) return;
  write(simulation);
  while (reached(simulation.state().time, next_time_, simulation.time_step()))
    next_time_ += interval_;
}

void FieldSeriesWriter::on_finish(const Simulation& simulation, RunStatus status,
                                  const std::string&) {
  if (status == RunStatus::Diverged) return;  // keep the last good files
  if (simulation.state().time != last_written_time_) write(simulation);
}

namespace {
std::string join_names(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names)
    text += (text.empty() ? "" : ", ") + name;
  return text;
}
}  // namespace

void check_probes(const Simulation& simulation) {
  for (const ProbeSpec& probe : simulation.description().probes) {
    if (simulation.groups().count(probe.group) == 0)
      throw InputError(probe.where, probe.path.empty() ? "probes.group" : probe.path + ".group",
                       probe.group, "unknown group",
                       "a group defined under 'groups' or a built-in group");
    for (std::size_t f = 0; f < probe.fields.size(); ++f) {
      if (find_quantity(simulation, probe.fields[f])) continue;
      // Probes built in code (validation cases) carry no per-field locations.
      const bool located = f < probe.field_where.size();
      const std::vector<std::string> names = quantity_names(simulation);
      const std::string suggestion = closest_match(probe.fields[f], names);
      throw InputError(
          located ? probe.field_where[f] : probe.where,
          located ? fmt::format("{}.fields.{}", probe.path, f) : "probes.fields", probe.fields[f],
          suggestion.empty() ? "unknown probe field"
                             : fmt::format("unknown probe field; did you mean '{}'?", suggestion),
          join_names(names));
    }
  }
}

ProbeRecorder::ProbeRecorder(const Simulation& simulation, std::filesystem::path path)
    : path_(std::move(path)),
      table_({"time"}),
      interval_(simulation.description().output.probe_interval) {
  check_probes(simulation);
  std::vector<std::string> names = {"time"};
  for (const ProbeSpec& probe : simulation.description().probes) {
    const auto group = simulation.groups().find(probe.group);
    if (group == simulation.groups().end())
      throw InputError(probe.where, "probes.group", probe.group, "unknown group",
                       "a group defined under 'groups' or a built-in group");
    for (const std::string& field : probe.fields) {
      NodeQuantity quantity = find_quantity(simulation, field);
      if (!quantity) {
        std::string allowed;
        for (const std::string& name : quantity_names(simulation))
          allowed += (allowed.empty() ? "" : ", ") + name;
        throw InputError(probe.where, "probes.fields", field, "unknown probe field", allowed);
      }
      columns_.push_back({&group->second, std::move(quantity), probe.reduction});
      names.push_back(probe.name + "." + field);
    }
  }
  table_ = ProbeCsv(names);
  row_.resize(columns_.size());
}

void ProbeRecorder::record(const Simulation& simulation) {
  const State& state = simulation.state();
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    const Column& column = columns_[c];
    double sum = 0.0, low = std::numeric_limits<double>::max(),
           high = std::numeric_limits<double>::lowest(), largest = 0.0;
    for (std::int32_t node : *column.nodes) {
      const double value = column.quantity(state, static_cast<std::size_t>(node));
      sum += value;
      low = std::min(low, value);
      high = std::max(high, value);
      largest = std::max(largest, std::abs(value));
    }
    switch (column.reduction) {
      case ProbeSpec::Reduction::Mean:
        row_[c] = sum / static_cast<double>(column.nodes->size());
        break;
      case ProbeSpec::Reduction::Min:
        row_[c] = low;
        break;
      case ProbeSpec::Reduction::Max:
        row_[c] = high;
        break;
      case ProbeSpec::Reduction::MaxAbs:
        row_[c] = largest;
        break;
    }
  }
  table_.add_row(state.time, row_);
}

void ProbeRecorder::on_start(const Simulation& simulation) {
  record(simulation);
  next_time_ = interval_;
  table_.flush(path_);
}

void ProbeRecorder::after_step(const Simulation& simulation) {
  if (interval_ <= 0.0 || reached(simulation.state().time, next_time_, simulation.time_step())) {
    record(simulation);
    while (interval_ > 0.0 && reached(simulation.state().time, next_time_, simulation.time_step()))
      next_time_ += interval_;
  }
  if (simulation.wall_seconds() - last_flush_wall_ > 2.0) {
    table_.flush(path_);
    last_flush_wall_ = simulation.wall_seconds();
  }
}

void ProbeRecorder::on_finish(const Simulation&, RunStatus, const std::string&) {
  table_.flush(path_);
}

void SummaryWriter::on_finish(const Simulation& simulation, RunStatus status,
                              const std::string& message) {
  const State& state = simulation.state();
  const double nodes = static_cast<double>(simulation.nodes().sph_nodes.size());
  const double wall = simulation.wall_seconds();
  JsonValue summary = JsonValue::object();
  summary.set("case", simulation.description().name);
  summary.set("status", run_status_name(status));
  summary.set("message", message);
  summary.set("steps", state.step);
  summary.set("simulated_time", state.time);
  summary.set("end_time", simulation.description().time.end);
  summary.set("time_step", simulation.time_step());
  summary.set("wall_seconds", wall);
  summary.set("particle_steps_per_second",
              wall > 0.0 ? nodes * static_cast<double>(state.step) / wall : 0.0);
  summary.set("sph_nodes", simulation.nodes().sph_nodes.size());
  summary.set("stress_points", simulation.nodes().stress_points.size());
  summary.set("boundary_nodes", simulation.step().operators().boundary_nodes.size());
  summary.set("threads", omp_get_max_threads());
  summary.set("version", RKTSPH_VERSION);
  if (const PressureProjection* projection = simulation.pressure_projection()) {
    const SolverStatistics& stats = projection->statistics();
    JsonValue solver = JsonValue::object();
    solver.set("solves", stats.solves);
    solver.set("mean_iterations", stats.solves ? static_cast<double>(stats.total_iterations) /
                                                     static_cast<double>(stats.solves)
                                               : 0.0);
    solver.set("max_iterations", stats.max_iterations);
    solver.set("last_relative_residual", stats.last_residual);
    solver.set("assembly_seconds", stats.assembly_seconds);
    solver.set("solve_seconds", stats.solve_seconds);
    solver.set("projection_seconds", stats.projection_seconds);
    solver.set("laplacian_scale", stats.laplacian_scale);
    summary.set("pressure_solver", std::move(solver));
  }
  write_file_atomically(path_, summary.pretty() + "\n");
}

}  // namespace rktsph
