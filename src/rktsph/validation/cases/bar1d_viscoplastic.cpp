// Thesis §4.3, validation.md §4.3, algorithm.md §7 case 4.3: the 1D Perzyna Von Mises bar.
//
// Two measurements, both against references::viscoplastic_bar.hpp:
// - front_decay_error: a sudden velocity with Z|V| = 2 Y0 sends a front of amplitude sigma0 = 2 Y0
//   into the bar at rest. Its overstress must decay as |sigma_f| - Y0 = (sigma0 - Y0)
//   exp(-E gamma t / (2 Y0)) (N = 1). Compared at t = d/c for d = 0.5, 1 and 2 decay lengths
//   2cY0/(E gamma) from the loaded end (how the front stress is read: see front_decay_error). The
//   error is that of the overstress, the quantity the law is about (the total stress would hide
//   it behind Y0).
// - history_l1_error: the case as written (ramp in 2 ms to Z|V0| = 0.6 Y0, fixed left end): the
//   stress history at the fixed end against the method of characteristics on a fine grid,
//   relative L1 over the run. history_l1_error_stiff repeats it with gamma = 50 1/s, whose
//   relaxation time Y0/(E gamma) = 20 us is 1/45 of the SPH step, so the source is integrated by
//   RK sub-steps.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "rktsph/core/error.hpp"
#include "rktsph/validation/references/viscoplastic_bar.hpp"
#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph {

namespace {

constexpr const char* kFolder = "bar1d-viscoplastic";

/// The material and load of the case file, read back so that the references use exactly them.
struct BarSetup {
  double length = 0.0;
  double young_modulus = 0.0;
  double density = 0.0;
  double yield_stress = 0.0;
  double fluidity = 0.0;
  double exponent = 0.0;
  double hardening_modulus = 0.0;
  TimeFunction right_velocity;

  double wave_speed() const { return std::sqrt(young_modulus / density); }
  double impedance() const { return density * wave_speed(); }
  double decay_length() const {
    return references::viscoplastic_decay_length(young_modulus, density, yield_stress, fluidity);
  }
};

double material_value(const CaseDescription& description, const std::string& key) {
  return material_parameter(description, "soil", key);
}

/// The condition of the loaded end (group xmax) of the case file.
BoundaryConditionSpec& loaded_end(CaseDescription& description) {
  for (BoundaryConditionSpec& condition : description.boundary_conditions)
    if (condition.group == "xmax" && condition.velocity[0]) return condition;
  throw RunError("case " + description.name + ": no velocity condition on xmax");
}

BarSetup read_setup(CaseDescription& description) {
  BarSetup setup;
  const ShapeSpec& segment = description.geometry.shapes.at(0);
  setup.length = segment.vertices.at(1)[0] - segment.vertices.at(0)[0];
  setup.young_modulus = material_value(description, "young_modulus");
  setup.density = material_value(description, "density");
  setup.yield_stress = material_value(description, "yield_stress");
  setup.fluidity = material_value(description, "fluidity");
  setup.exponent = material_value(description, "exponent");
  setup.hardening_modulus = material_value(description, "hardening_modulus");
  setup.right_velocity = *loaded_end(description).velocity[0];
  return setup;
}

references::ViscoplasticBarParameters reference_parameters(const BarSetup& setup, int cells) {
  references::ViscoplasticBarParameters parameters;
  parameters.length = setup.length;
  parameters.young_modulus = setup.young_modulus;
  parameters.density = setup.density;
  parameters.initial_yield_stress = setup.yield_stress;
  parameters.fluidity = setup.fluidity;
  parameters.exponent = setup.exponent;
  parameters.hardening_modulus = setup.hardening_modulus;
  parameters.left_end = references::ViscoplasticBarParameters::LeftEnd::Fixed;
  const TimeFunction velocity = setup.right_velocity;
  parameters.right_velocity = [velocity](double time) { return velocity(time); };
  parameters.cells = cells;
  return parameters;
}

void add_point_probe(CaseDescription& description, const std::string& name, double x) {
  GroupSpec group;
  group.name = name;
  group.kind = GroupSpec::Kind::Point;
  group.point = {x, 0.0, 0.0};
  description.groups.push_back(group);
  ProbeSpec probe;
  probe.name = name;
  probe.group = name;
  probe.fields = {"stress_xx"};
  description.probes.push_back(probe);
}

/// Value at t0 of the least-squares line through the samples of `column` in [t0 + a, t0 + b].
double extrapolate_to(const ProbeTable& probes, const std::string& column, double t0, double a,
                      double b) {
  const std::vector<double>& time = probes.time();
  const std::vector<double>& value = probes.column(column);
  double count = 0.0, sum_t = 0.0, sum_v = 0.0, sum_tt = 0.0, sum_tv = 0.0;
  for (std::size_t i = 0; i < time.size(); ++i) {
    const double t = time[i] - t0;
    if (t < a || t > b) continue;
    count += 1.0;
    sum_t += t;
    sum_v += value[i];
    sum_tt += t * t;
    sum_tv += t * value[i];
  }
  if (count < 3.0) throw RunError("front_decay_error: too few samples behind the front");
  const double slope = (count * sum_tv - sum_t * sum_v) / (count * sum_tt - sum_t * sum_t);
  return (sum_v - slope * sum_t) / count;
}

/// Largest relative error of the front overstress at 0.5, 1 and 2 decay lengths.
double front_decay_error(const ValidationContext& context) {
  CaseDescription description = load_bundled_case(context, kFolder);
  const BarSetup setup = read_setup(description);
  if (setup.exponent != 1.0) throw RunError("front_decay_error: the decay law needs N = 1");
  const double decay_length = setup.decay_length(), c = setup.wave_speed();
  // How the front stress is read. At Courant 1 the SPH front is one node wide, but it leaves a
  // node-to-node ripple behind it whose amplitude scales with the jump (~Y0, not with the
  // overstress) and dies out over ~10 nodes. So the history at a probe a distance d from the
  // loaded end is fitted by a straight line over 8 to 30 dx/c after the nominal arrival d/c (which
  // also averages the ripple out) and extrapolated back to d/c. The line's error is second order
  // in the window, ~(30 dx / decay length)^2: measured 1.0 % of the overstress at
  // dx = decay length / 100 (full variant), 3.7 % at 1/50 (quick variant), 0.2 % at 1/200.
  const double points_per_decay_length = context.quick ? 50.0 : 100.0;
  const double spacing = decay_length / points_per_decay_length;
  const std::vector<double> distance_ratios = {0.5, 1.0, 2.0};
  const double window_start = 8.0, window_end = 30.0;  // in dx / c
  // A bar of 4 decay lengths: the reflection from its fixed end is back at the farthest probe
  // (2 decay lengths) only after 6 decay lengths / c, later than the end of the last window.
  const double length = std::round(4.0 * points_per_decay_length) * spacing;
  description.geometry.shapes.at(0).vertices.at(0)[0] = 0.0;
  description.geometry.shapes.at(0).vertices.at(1)[0] = length;
  description.geometry.spacing = spacing;
  const double front_stress = -2.0 * setup.yield_stress;
  TimeFunction sudden;
  sudden.kind = TimeFunction::Kind::Step;
  sudden.value = front_stress / setup.impedance();
  loaded_end(description).velocity[0] = sudden;
  std::vector<double> distances;
  description.probes.clear();
  for (std::size_t k = 0; k < distance_ratios.size(); ++k) {
    // On a node, so that the distance used for the law is the node's.
    const double distance = std::round(distance_ratios[k] * points_per_decay_length) * spacing;
    distances.push_back(distance);
    add_point_probe(description, "front" + std::to_string(k), length - distance);
  }
  description.time.end = (distances.back() + (window_end + 2.0) * spacing) / c;
  description.output.interval = 0.0;
  description.output.probe_interval = 0.0;
  const ProbeTable probes =
      ProbeTable::read(run_for_validation(context, description, "front-decay") / "probes.csv");
  double worst = 0.0;
  for (std::size_t k = 0; k < distances.size(); ++k) {
    const double arrival = distances[k] / c;
    const double front =
        std::abs(extrapolate_to(probes, "front" + std::to_string(k) + ".stress_xx", arrival,
                                window_start * spacing / c, window_end * spacing / c));
    const double law = std::abs(references::viscoplastic_front_stress(
        front_stress, setup.yield_stress, setup.young_modulus, setup.fluidity, arrival));
    worst =
        std::max(worst, std::abs((front - setup.yield_stress) / (law - setup.yield_stress) - 1.0));
  }
  return worst;
}

/// Linear interpolation of the reference history at `time` (its samples are equally spaced).
double interpolate(const std::vector<references::ViscoplasticBarSample>& history, double time) {
  if (time <= history.front().time) return history.front().values.stress;
  const auto after = std::lower_bound(
      history.begin(), history.end(), time,
      [](const references::ViscoplasticBarSample& sample, double t) { return sample.time < t; });
  if (after == history.end()) return history.back().values.stress;
  const auto before = after - 1;
  const double weight = (time - before->time) / (after->time - before->time);
  return before->values.stress + weight * (after->values.stress - before->values.stress);
}

/// Relative L1 error of the fixed-end stress history: integral |sigma - sigma_ref| dt over
/// integral |sigma_ref| dt (trapezoidal on the SPH samples; the reference is on a finer grid).
/// A positive `fluidity` replaces the case's.
double history_l1_error(const ValidationContext& context, double fluidity,
                        const std::string& label) {
  CaseDescription description = load_bundled_case(context, kFolder, {{"output.interval", "0"}});
  if (fluidity > 0.0) description.materials.at("soil").values.at("fluidity").value = fluidity;
  const BarSetup setup = read_setup(description);
  const double end = description.time.end;
  const ProbeTable probes =
      ProbeTable::read(run_for_validation(context, description, label) / "probes.csv");
  // 400 cells (dx = decay length / 18 at gamma = 1): against 6400 cells this history differs by
  // 8e-6 (gamma = 1) and 2e-5 (gamma = 50) in the same relative L1 norm, far below the tolerance.
  const auto reference =
      references::viscoplastic_bar_history(reference_parameters(setup, 400), 0.0, end);
  const std::vector<double>& time = probes.time();
  const std::vector<double>& stress = probes.column("fixed_end.stress_xx");
  double error = 0.0, norm = 0.0;
  for (std::size_t i = 1; i < time.size(); ++i) {
    const double step = time[i] - time[i - 1];
    const double before = interpolate(reference, time[i - 1]);
    const double after = interpolate(reference, time[i]);
    error += 0.5 * step * (std::abs(stress[i - 1] - before) + std::abs(stress[i] - after));
    norm += 0.5 * step * (std::abs(before) + std::abs(after));
  }
  return error / norm;
}

}  // namespace

std::vector<CheckResult> validate_bar1d_viscoplastic(const ValidationContext& context) {
  const double front = front_decay_error(context);
  const double history = history_l1_error(context, 0.0, "history");
  const double stiff = history_l1_error(context, 50.0, "history-stiff");
  return {
      check_at_most("front_decay_error", front, 0.0, 0.05, "fraction"),
      check_at_most("history_l1_error", history, 0.0, 0.05, "fraction"),
      check_at_most("history_l1_error_stiff", stiff, 0.0, 0.05, "fraction"),
  };
}

}  // namespace rktsph
