#include "rktsph/output/run_observers.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "rktsph/case/key_spec.hpp"
#include "rktsph/case/yaml_reader.hpp"
#include "rktsph/core/build_info.hpp"
#include "rktsph/output/atomic_file.hpp"
#include "rktsph/output/json_writer.hpp"
#include "rktsph/output/vtu_writer.hpp"

namespace rktsph {

namespace {

// The fields of summary.json that say which program wrote it; shared by every kind of summary.
void set_program(JsonValue& summary) {
  summary.set("version", RKTSPH_VERSION);
  summary.set("commit", build_commit());
  summary.set("build_type", build_type());
}

const std::vector<std::string>& dry_output_fields() {
  static const std::vector<std::string> names = {
      "velocity", "displacement", "stress", "pressure", "deviatoric_stress", "eps_vp", "material"};
  return names;
}

// The large-deformation model adds what the free-surface detector finds (docs/theory.md §9.4).
const std::vector<std::string>& moving_output_fields() {
  static const std::vector<std::string> names = {"velocity", "displacement",      "stress",
                                                 "pressure", "deviatoric_stress", "eps_vp",
                                                 "material", "free_surface",      "surface_normal"};
  return names;
}

const std::vector<std::string>& saturated_output_fields() {
  static const std::vector<std::string> names = {"velocity",          "displacement",  "stress",
                                                 "total_stress",      "pore_pressure", "pressure",
                                                 "deviatoric_stress", "eps_vp",        "material"};
  return names;
}

// What a large-deformation run reports of its configuration (docs/theory.md §9.1, §9.4): the mass,
// which the motion conserves exactly; the cells' state; the re-seeds (none: stress points are
// their cells' centroids); and how the detected free surface agrees with the perimeter.
JsonValue moving_configuration_summary(const Simulation& simulation,
                                       const ConfigurationMotion& motion) {
  const State& state = simulation.state();
  const NodeSets& nodes = simulation.nodes();
  const PhysicsModel& model = simulation.model();
  double mass = 0.0, current_volume = 0.0, reference_volume = 0.0;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    mass += model.density(nodes.node_material[i]) * nodes.sph_nodes.volume[i];
    current_volume += state.configuration.sph_nodes.volume[i];
    reference_volume += nodes.sph_nodes.volume[i];
  }
  const CellQuality& quality = motion.quality();
  JsonValue cells = JsonValue::object();
  cells.set("smallest_volume_ratio", quality.smallest_volume_ratio);
  cells.set("distorted", quality.distorted_cells);
  cells.set("concave", quality.concave_cells);
  cells.set("folded", quality.inverted_cells);
  FreeSurface detected;
  detect_current_surface(simulation, detected);
  const SurfaceAgreement agreement = compare_with_perimeter(simulation, detected);
  JsonValue surface = JsonValue::object();
  surface.set("perimeter_nodes", agreement.perimeter_nodes);
  surface.set("missed", agreement.missed);
  surface.set("false_positive", agreement.false_positive);
  JsonValue summary = JsonValue::object();
  summary.set("mass", mass);
  summary.set("volume", current_volume);
  summary.set("reference_volume", reference_volume);
  summary.set("cells", std::move(cells));
  summary.set("reseeded_stress_points", 0);
  summary.set("fallback_gradient_rows", simulation.step().operators().fallback_rows);
  const CellForming& forming = simulation.assembly().cell_forming();
  summary.set("neighbour_searches",
              simulation.step().neighbour_searches() + forming.earlier_neighbour_searches);
  // Cells formed again from the moving nodes (docs/theory.md §9.17); zeros for the start's cells.
  JsonValue formed = JsonValue::object();
  formed.set("policy", simulation.assembly().forms_cells() ? "reformed" : "moving");
  formed.set("formings", forming.formings);
  formed.set("cells_formed", forming.cells_formed);
  formed.set("triangles_dropped", forming.triangles_dropped);
  formed.set("triangles_restored", forming.triangles_restored);
  formed.set("cells_now", forming.formings > 0 ? forming.cells_now : nodes.stress_points.size());
  formed.set("isolated_nodes", forming.isolated_nodes);
  formed.set("narrowest_cell_ratio", forming.narrowest_cell_ratio);
  formed.set("divided_steps", forming.divided_steps);
  formed.set("most_parts", forming.most_parts);
  formed.set("nodes_spread", forming.nodes_spread);
  formed.set("seconds", forming.seconds);
  summary.set("cell_forming", std::move(formed));
  summary.set("detected_free_surface", std::move(surface));
  JsonValue walls = JsonValue::object();
  walls.set("nodes_in_contact", simulation.boundary_conditions().nodes_in_contact());
  walls.set("deepest_penetration", simulation.boundary_conditions().deepest_penetration());
  summary.set("rigid_walls", std::move(walls));
  JsonValue bodies = JsonValue::array();
  for (const RigidBody& body : simulation.boundary_conditions().rigid_bodies()) {
    JsonValue entry = JsonValue::object();
    entry.set("name", body.name());
    entry.set("nodes_in_contact", body.nodes_in_contact());
    entry.set("deepest_penetration", body.deepest_penetration());
    entry.set("deepest_penetration_ratio", body.deepest_penetration() / simulation.nodes().spacing);
    bodies.push_back(std::move(entry));
  }
  summary.set("rigid_bodies", std::move(bodies));
  return summary;
}

// The "energy" block of summary.json (docs/input-reference.md, "Results").
JsonValue energy_summary(const EnergyTotals& totals, bool saturated) {
  JsonValue energy = JsonValue::object();
  energy.set("kinetic", totals.kinetic);
  energy.set("stored_elastic", totals.stored_elastic);
  energy.set("initial_kinetic", totals.initial_kinetic);
  energy.set("initial_stored_elastic", totals.initial_stored_elastic);
  energy.set("work_of_loads", totals.work_of_loads());
  energy.set("work_of_body_force", totals.work_of_body_force);
  energy.set("work_of_boundary", totals.work_of_boundary);
  energy.set("damping_dissipation", totals.damping_dissipation);
  energy.set("dissipated", totals.dissipated());
  energy.set("plastic_dissipation", totals.plastic_dissipation);
  energy.set("stress", saturated ? "effective" : "total");
  const EnergyClosure closure = energy_closure(totals);
  energy.set("scale", closure.scale);
  energy.set("residual_fraction", closure.residual);
  energy.set("closes", closure.closes);
  return energy;
}

// The output fields of the case, or every field of the model; InputError for one the model has not.
std::vector<std::string> output_field_selection(const Simulation& simulation) {
  const OutputSpec& output = simulation.description().output;
  const bool saturated = simulation.model().pore_pressure_field() >= 0;
  const bool moving = simulation.model().objective_stress_rate();
  const auto& available = saturated ? saturated_output_fields()
                          : moving  ? moving_output_fields()
                                    : dry_output_fields();
  for (const std::string& name : output.fields) {
    if (std::find(available.begin(), available.end(), name) == available.end()) {
      std::string allowed;
      for (const std::string& a : available)
        allowed += (allowed.empty() ? "" : ", ") + a;
      throw InputError(output.where, "output.fields", name,
                       saturated ? "field not available for the saturated model"
                       : moving  ? "field not available for the large-deformation model"
                                 : "field not available for the dry solid model",
                       allowed);
    }
  }
  if (output.fields.empty()) return available;
  // The points of a field file are X + u: with u beside them, X (and a drawing at X + M u) can
  // always be recovered.
  std::vector<std::string> selection = output.fields;
  if (std::find(selection.begin(), selection.end(), "displacement") == selection.end())
    selection.insert(selection.begin(), "displacement");
  return selection;
}

// The current positions X + u of the SPH nodes, one array per axis of the dimension. Every model
// writes these, so that a field file's points mean one thing: a small-deformation model keeps its
// configuration at X, a large-deformation one moves it to X + u (docs/theory.md §9.1).
std::vector<std::vector<double>> current_positions(const Simulation& simulation,
                                                   const State& state) {
  const PointCloud& reference = simulation.nodes().sph_nodes;
  const FieldArray& displacement = state.displacement;
  std::vector<std::vector<double>> positions(static_cast<std::size_t>(reference.dimension));
  for (int a = 0; a < reference.dimension; ++a) {
    const auto axis = static_cast<std::size_t>(a);
    const double* u = displacement.field(a);
    positions[axis].resize(reference.size());
    for (std::size_t i = 0; i < reference.size(); ++i)
      positions[axis][i] = reference.position[axis][i] + u[i];
  }
  return positions;
}

}  // namespace

void check_run_observers(const Simulation& simulation) {
  output_field_selection(simulation);
  // The recorder only resolves its probes when constructed; it writes at on_start and after.
  const ProbeRecorder probes(simulation, {});
}

FieldSeriesWriter::FieldSeriesWriter(const Simulation& simulation, std::filesystem::path directory)
    : directory_(std::move(directory)),
      collection_(directory_ / "series.pvd"),
      schedule_(simulation.description().output.interval) {
  selection_ = output_field_selection(simulation);
  std::error_code error;
  std::filesystem::create_directories(directory_ / "fields", error);
  if (error)
    throw RunError(fmt::format("cannot create the folder '{}': {}",
                               (directory_ / "fields").string(), error.message()));
}

void FieldSeriesWriter::write(const Simulation& simulation, const State& state) {
  const PhysicsModel& model = simulation.model();
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
      // With a water table p_w is the hydrostatic p_h plus the carried excess (eq. 6.7).
      const double alpha = model.biot_coefficient();
      const double* pore = model.has_water_table()
                               ? computed(find_quantity(simulation, "pore_pressure"))
                               : state.fields.field(model.pore_pressure_field());
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
    } else if (name == "free_surface" || name == "surface_normal") {
      if (detected_time_ != state.time || detected_.on_surface.size() != n) {
        field_free_surface(simulation, detected_);
        detected_time_ = state.time;
      }
      if (name == "free_surface") {
        derived.emplace_back(detected_.on_surface.begin(), detected_.on_surface.end());
        fields.push_back({name, 1, {derived.back().data()}});
      } else {
        fields.push_back(
            {name,
             3,
             {detected_.normal[0].data(), detected_.normal[1].data(), detected_.normal[2].data()}});
      }
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
  const std::vector<std::vector<double>> positions = current_positions(simulation, state);
  PointPositions points;
  points.dimension = static_cast<int>(positions.size());
  points.count = n;
  for (std::size_t a = 0; a < positions.size(); ++a)
    points.coordinates[a] = positions[a].data();
  write_vtu(directory_ / file, points, fields);
  collection_.add(state.time, file);
  last_written_time_ = state.time;
}

void FieldSeriesWriter::on_start(const Simulation& simulation) {
  write(simulation, simulation.state());
}

void FieldSeriesWriter::after_step(const Simulation& simulation) {
  if (schedule_.due(simulation.state().time, simulation.time_step()))
    write(simulation, simulation.state());
}

void FieldSeriesWriter::on_finish(const Simulation& simulation, RunStatus status,
                                  const std::string&) {
  // A run that diverged or failed inside a step ends with the state before that step, its last
  // good one, so that the last file shows where things stood, not an output of long before. An
  // interrupted run ends on a whole step, which is worth writing. Any other failure (a disk that
  // is full) keeps the files as they are.
  if (const State* before = simulation.state_before_stop()) {
    if (before->time != last_written_time_) write(simulation, *before);
    return;
  }
  if (status != RunStatus::Completed && status != RunStatus::Interrupted) return;
  if (simulation.state().time != last_written_time_) write(simulation, simulation.state());
}

void FieldSeriesWriter::on_resume(const Simulation&) {
  collection_.write();
  std::vector<std::string> listed;
  for (const PvdCollection::Entry& entry : collection_.entries())
    listed.push_back(std::filesystem::path(entry.file).filename().string());
  for (const auto& file : std::filesystem::directory_iterator(directory_ / "fields")) {
    const std::string name = file.path().filename().string();
    const bool series_file = name.rfind("fields_", 0) == 0 && file.path().extension() == ".vtu";
    if (series_file && std::find(listed.begin(), listed.end(), name) == listed.end())
      std::filesystem::remove(file.path());
  }
}

void FieldSeriesWriter::save_checkpoint(CheckpointOut& out) const {
  out.put_f64(schedule_.next_time());
  out.put_f64(last_written_time_);
  out.put_u64(collection_.entries().size());
  for (const PvdCollection::Entry& entry : collection_.entries()) {
    out.put_f64(entry.time);
    out.put_string(entry.file);
  }
}

void FieldSeriesWriter::restore_checkpoint(CheckpointIn& in) {
  schedule_.set_next_time(in.get_f64());
  last_written_time_ = in.get_f64();
  const std::uint64_t count = in.get_u64();
  std::vector<PvdCollection::Entry> entries;
  for (std::uint64_t e = 0; e < count; ++e) {
    const double time = in.get_f64();
    entries.push_back({time, in.get_string()});
  }
  collection_.set_entries(std::move(entries));
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
      every_step_(simulation.description().output.probe_interval <= 0.0),
      records_(simulation.description().output.probe_interval),
      field_outputs_(simulation.description().output.interval) {
  check_probes(simulation);  // every group and field below exists
  std::vector<std::string> names = {"time"};
  for (const ProbeSpec& probe : simulation.description().probes) {
    const auto& group = simulation.groups().at(probe.group);
    for (const std::string& field : probe.fields) {
      columns_.push_back({&group, find_quantity(simulation, field), probe.reduction});
      names.push_back(probe.name + "." + field);
    }
  }
  // Each rigid body's force from its contacts and its displacement (docs/theory.md §9.18).
  for (const RigidBody& body : simulation.boundary_conditions().rigid_bodies())
    for (const char* column : {".force_x", ".force_y", ".displacement_x", ".displacement_y"})
      names.push_back(body.name() + column);
  table_ = ProbeCsv(names);
  row_.resize(names.size() - 1);
  body_impulse_.assign(2 * simulation.boundary_conditions().rigid_bodies().size(), 0.0);
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
  // The bodies' mean force since the last row (the force of one step is the traction of the
  // nodes in contact then, which jumps as nodes join and leave the body), and their displacement.
  std::size_t c = columns_.size();
  const BoundaryConditions& conditions = simulation.boundary_conditions();
  const double interval = state.time - impulse_since_;
  for (std::size_t b = 0; b < conditions.rigid_bodies().size(); ++b) {
    const Vec3& now = conditions.rigid_body_force(b);
    const Vec3 displacement = conditions.rigid_bodies()[b].displacement(state.time);
    for (std::size_t a = 0; a < 2; ++a)
      row_[c++] = interval > 0.0 ? body_impulse_[2 * b + a] / interval : now[a];
    row_[c++] = displacement[0];
    row_[c++] = displacement[1];
  }
  std::fill(body_impulse_.begin(), body_impulse_.end(), 0.0);
  impulse_since_ = state.time;
  table_.add_row(state.time, row_);
}

void ProbeRecorder::on_start(const Simulation& simulation) {
  record(simulation);
  table_.flush(path_);
}

void ProbeRecorder::integrate_body_forces(const Simulation& simulation) {
  const double time = simulation.state().time;
  const BoundaryConditions& conditions = simulation.boundary_conditions();
  for (std::size_t b = 0; b < conditions.rigid_bodies().size(); ++b)
    for (std::size_t a = 0; a < 2; ++a)
      body_impulse_[2 * b + a] += conditions.rigid_body_force(b)[a] * (time - last_step_time_);
  last_step_time_ = time;
}

void ProbeRecorder::after_step(const Simulation& simulation) {
  integrate_body_forces(simulation);
  if (every_step_ || records_.due(simulation.state().time, simulation.time_step()))
    record(simulation);
  // With every field output, so the histories on disk always reach the last VTU (a killed run
  // loses no more than it loses of the fields), and every 2 s for runs with sparse field output.
  const bool field_output = field_outputs_.due(simulation.state().time, simulation.time_step());
  if (field_output || simulation.wall_seconds() - last_flush_wall_ > 2.0) {
    table_.flush(path_);
    last_flush_wall_ = simulation.wall_seconds();
  }
}

void ProbeRecorder::on_finish(const Simulation&, RunStatus, const std::string&) {
  table_.flush(path_);
}

void ProbeRecorder::on_resume(const Simulation&) {
  table_.flush(path_);
}

void ProbeRecorder::save_checkpoint(CheckpointOut& out) const {
  out.put_f64(records_.next_time());
  out.put_f64(field_outputs_.next_time());
  out.put_u32(static_cast<std::uint32_t>(table_.column_names().size()));
  out.put_doubles(table_.values());
  out.put_doubles(body_impulse_);
  out.put_f64(impulse_since_);
  out.put_f64(last_step_time_);
}

void ProbeRecorder::restore_checkpoint(CheckpointIn& in) {
  records_.set_next_time(in.get_f64());
  field_outputs_.set_next_time(in.get_f64());
  const std::uint32_t columns = in.get_u32();
  if (columns != table_.column_names().size())
    in.fail(fmt::format("{} probe columns stored where this case has {}", columns,
                        table_.column_names().size()));
  std::vector<double> values = in.get_doubles();
  if (values.size() % columns != 0) in.fail("probe values that are not whole rows");
  table_.set_values(std::move(values));
  std::vector<double> impulse = in.get_doubles();
  if (impulse.size() != body_impulse_.size())
    in.fail(fmt::format("{} rigid-body force sums stored where this case has {}", impulse.size(),
                        body_impulse_.size()));
  body_impulse_ = std::move(impulse);
  impulse_since_ = in.get_f64();
  last_step_time_ = in.get_f64();
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
  summary.set("stress_points", simulation.cells().stress_points.size());
  summary.set("boundary_nodes", simulation.step().operators().boundary_nodes.size());
  summary.set("threads", omp_get_max_threads());
  set_program(summary);
  JsonValue warnings = JsonValue::array();
  for (const std::string& warning : warnings_)
    warnings.push_back(warning);
  if (energy_)
    if (std::string energy = energy_closure_warning(energy_->totals()); !energy.empty())
      warnings.push_back(std::move(energy));
  summary.set("warnings", std::move(warnings));
  StepTimeSplit split = simulation.assembly().cell_forming().earlier_steps;
  split += simulation.step().time_split();
  JsonValue step_time = JsonValue::object();
  step_time.set("cell_lists_seconds", split.cell_lists);
  step_time.set("operator_tables_seconds", split.operator_tables);
  step_time.set("surface_seconds", split.surface);
  step_time.set("integration_seconds", split.integration);
  step_time.set("cell_forming_seconds", simulation.assembly().cell_forming().seconds);
  summary.set("step_time", std::move(step_time));
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
    solver.set("preconditioner", choice_word(preconditioner_words(),
                                             simulation.description().pore_fluid->preconditioner));
    // Shares of the time in steps (the projection is part of each step's integration).
    const double step_seconds =
        split.cell_lists + split.operator_tables + split.surface + split.integration;
    solver.set("solve_share", step_seconds > 0.0 ? stats.solve_seconds / step_seconds : 0.0);
    solver.set("projection_share",
               step_seconds > 0.0 ? stats.projection_seconds / step_seconds : 0.0);
    if (stats.multigrid_levels > 0) {
      solver.set("multigrid_levels", stats.multigrid_levels);
      solver.set("multigrid_operator_complexity", stats.multigrid_complexity);
    }
    summary.set("pressure_solver", std::move(solver));
  }
  if (const ConfigurationMotion* motion = simulation.step().motion())
    summary.set("moving_configuration", moving_configuration_summary(simulation, *motion));
  if (energy_)
    summary.set("energy",
                energy_summary(energy_->totals(), simulation.model().pore_pressure_field() >= 0));
  write_file_atomically(path_, summary.pretty() + "\n");
}

void write_setup_failure_summary(const std::filesystem::path& path,
                                 const CaseDescription& description, const std::string& message) {
  JsonValue summary = JsonValue::object();
  summary.set("case", description.name);
  summary.set("status", run_status_name(RunStatus::Failed));
  summary.set("message", message);
  summary.set("steps", 0);
  summary.set("simulated_time", 0.0);
  summary.set("end_time", description.time.end);
  summary.set("wall_seconds", 0.0);
  summary.set("threads", omp_get_max_threads());
  set_program(summary);
  write_file_atomically(path, summary.pretty() + "\n");
}

}  // namespace rktsph
