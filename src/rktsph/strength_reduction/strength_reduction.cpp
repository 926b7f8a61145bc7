// The factor of safety by strength reduction (docs/theory.md §10): the reduced case, the failure
// criterion (eq. 10.2) and the bisection on F.
#include "rktsph/strength_reduction/strength_reduction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "rktsph/core/error.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/materials/material.hpp"
#include "rktsph/output/json_writer.hpp"
#include "rktsph/simulation/quantities.hpp"

namespace rktsph {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

std::string model_of(const ParameterBlock& block) {
  const auto model = block.words.find("model");
  return model == block.words.end() ? std::string() : model->second.first;
}

bool is_frictional(const std::string& model) {
  return model == "perzyna_drucker_prager" || model == "perzyna_mohr_coulomb";
}

std::string allowed_models() {
  std::string allowed;
  for (const std::string& model : reducible_material_models())
    allowed += (allowed.empty() ? "" : ", ") + model;
  return allowed + " (linear_elastic materials are kept as they are)";
}

void divide(ParameterBlock& block, const std::string& key, double factor) {
  if (auto found = block.values.find(key); found != block.values.end())
    found->second.value /= factor;
}

// Angle [deg] whose tangent is tan(angle) / factor.
double reduced_angle(double degrees, double factor) {
  return std::atan(std::tan(degrees * kDegree) / factor) / kDegree;
}

/// The slowest consolidation of a saturated case: L^2 / c_v over the body's height L with the
/// least c_v = k_bar / (alpha^2 / M + n / K_w) of its materials (docs/theory.md eq. 10.3).
struct Drainage {
  double height = 0.0, coefficient = 0.0;
  double time() const { return height * height / coefficient; }
};

Drainage slowest_drainage(const CaseDescription& description) {
  const PoreFluidSpec& fluid = *description.pore_fluid;
  const double permeability = fluid.hydraulic_conductivity / (fluid.density * fluid.gravity);
  const double storage = fluid.porosity / fluid.bulk_modulus;
  const double alpha = fluid.biot_coefficient;
  Drainage drainage;
  drainage.coefficient = std::numeric_limits<double>::infinity();
  for (const auto& [name, block] : description.materials) {
    const auto young = block.values.find("young_modulus");
    const auto poisson = block.values.find("poisson_ratio");
    if (young == block.values.end() || poisson == block.values.end()) continue;
    const double oedometric =
        ElasticConstants{young->second.value, poisson->second.value}.constrained_modulus();
    drainage.coefficient =
        std::min(drainage.coefficient, permeability / (alpha * alpha / oedometric + storage));
  }
  // fos is 2D: the height is the body's extent along y.
  const Box box = bounding_box(description.geometry, 2);
  drainage.height = box.max[1] - box.min[1];
  return drainage;
}

/// Records the largest speed and displacement over the SPH nodes, about 400 samples a run, and
/// ends the run once the largest displacement exceeds `limit` (it fails whatever follows).
class MotionRecorder final : public Observer {
 public:
  MotionRecorder(ReductionRun& run, double limit) : run_(run), limit_(limit) {}
  std::string stop_reason() const override {
    return !run_.displacement.empty() && run_.displacement.back() > limit_
               ? fmt::format("the largest displacement exceeds {:.4g} m", limit_)
               : std::string();
  }
  void on_start(const Simulation& simulation) override {
    every_ = std::max(1L, simulation.total_steps() / 400);
    steps_ = 0;
    record(simulation);
  }
  void after_step(const Simulation& simulation) override {
    if (++steps_ % every_ == 0) record(simulation);
  }
  void on_finish(const Simulation& simulation, RunStatus status,
                 const std::string& message) override {
    (void)status;
    (void)message;
    const State& state =
        simulation.state_before_stop() ? *simulation.state_before_stop() : simulation.state();
    run_.end_time = state.time;
    run_.largest_displacement = largest_displacement(simulation, state);
    run_.came_to_rest = simulation.stopped_early() && run_.largest_displacement <= limit_;
  }

 private:
  static double largest_displacement(const Simulation& simulation, const State& state) {
    const int dimension = simulation.nodes().dimension;
    double largest = 0.0;
    for (std::size_t i = 0; i < simulation.nodes().sph_nodes.size(); ++i) {
      double squared = 0.0;
      for (int a = 0; a < dimension; ++a)
        squared += state.displacement(a, i) * state.displacement(a, i);
      largest = std::max(largest, squared);
    }
    return std::sqrt(largest);
  }
  void record(const Simulation& simulation) {
    run_.time.push_back(simulation.state().time);
    run_.speed.push_back(largest_speed(simulation));
    run_.displacement.push_back(largest_displacement(simulation, simulation.state()));
  }

  ReductionRun& run_;
  double limit_;
  long every_ = 1, steps_ = 0;
};

/// `limit`: the displacement beyond which the run is failing (infinite for the elastic one).
ReductionRun run_at(const CaseDescription& description, double factor,
                    const StrengthReductionOptions& options, const std::filesystem::path& folder,
                    double limit) {
  CaseDescription reduced =
      factor > 0.0 ? reduce_strength(description, factor) : elastic_reference(description);
  reduced.time.stop_when_at_rest = options.criterion.rest_fraction;
  ReductionRun run;
  run.factor = factor;
  run.directory = folder;
  MotionRecorder recorder(run, limit);
  RunOptions run_options;
  run_options.quiet = true;
  run_options.existing_results = options.existing_results;
  run_options.stop_check = options.stop_check;
  run_options.observers = {&recorder};
  const RunOutcome outcome = run_case(reduced, folder, run_options);
  if (outcome.status == RunStatus::Interrupted) throw RunError(outcome.message);
  run.diverged = outcome.status != RunStatus::Completed;
  if (run.diverged && factor == 0.0)
    throw RunError(fmt::format("the elastic reference run in {} did not complete: {}",
                               folder.string(), outcome.message));
  return run;
}

void classify(ReductionRun& run, double elastic_displacement, const FailureCriterion& criterion) {
  const double ratio = run.largest_displacement / elastic_displacement;
  run.failing = true;
  if (run.diverged) {
    run.reason = fmt::format("diverged at t = {:.3g} s", run.end_time);
  } else if (ratio > criterion.displacement_ratio) {
    run.reason =
        fmt::format("u_max = {:.3g} m = {:.3g} u_el > {:g} u_el at t = {:.3g} s",
                    run.largest_displacement, ratio, criterion.displacement_ratio, run.end_time);
  } else if (!run.came_to_rest) {
    run.reason = fmt::format(
        "still moving at t = {:.3g} s (largest speed {:.3g} m/s), u_max = {:.3g} m = {:.3g} u_el",
        run.end_time, run.speed.empty() ? 0.0 : run.speed.back(), run.largest_displacement, ratio);
  } else {
    run.failing = false;
    run.reason = fmt::format("at rest at t = {:.3g} s, u_max = {:.3g} m = {:.3g} u_el",
                             run.end_time, run.largest_displacement, ratio);
  }
}

}  // namespace

std::vector<std::string> reducible_material_models() {
  return {"perzyna_drucker_prager", "perzyna_mohr_coulomb", "perzyna_von_mises"};
}

void check_strength_reduction_case(const CaseDescription& description) {
  const SourceLocation file{description.file, 0, 0};
  if (description.model == ModelKind::SaturatedVpw) {
    // A drained factor (eq. 10.3): the excess pore pressures that a change of strength makes must
    // drain within the run, or the run mixes drained and undrained strengths.
    const Drainage drainage = slowest_drainage(description);
    if (!(description.time.end >= 2.0 * drainage.time()))
      throw InputError(
          description.pore_fluid->where, "pore_fluid.hydraulic_conductivity",
          fmt::format("{:g}", description.pore_fluid->hydraulic_conductivity),
          fmt::format("the factor of safety of a saturated case is a drained one, but its excess "
                      "pore pressures drain in about L^2/c_v = {:.3g} s (c_v = {:.3g} m2/s over "
                      "the body's height L = {:g} m), more than half of time.end = {:g} s",
                      drainage.time(), drainage.coefficient, drainage.height, description.time.end),
          std::isfinite(drainage.time())
              ? fmt::format("a conductivity of at least {:.3g} m/s (a drained factor does not "
                            "depend on it), or time.end >= {:.3g} s",
                            description.pore_fluid->hydraulic_conductivity * 2.0 * drainage.time() /
                                description.time.end,
                            2.0 * drainage.time())
              : std::string("a conductivity > 0 (a drained factor does not depend on it)"));
  }
  if (description.dimension != 2)
    throw InputError(file, "dimension", std::to_string(description.dimension),
                     "strength reduction needs a 2D body with a failure mechanism", "2");
  const std::vector<std::string> reducible = reducible_material_models();
  bool any_strength = false;
  for (const auto& [name, block] : description.materials) {
    const std::string model = model_of(block);
    if (std::find(reducible.begin(), reducible.end(), model) != reducible.end()) {
      any_strength = true;
      continue;
    }
    if (model == "linear_elastic") continue;
    const auto where = block.words.find("model");
    throw InputError(where != block.words.end() ? where->second.second : block.where,
                     block.path + ".model", model,
                     "strength reduction divides c' and tan phi' (or a yield stress); this "
                     "material's strength is not reduced so",
                     allowed_models());
  }
  if (!any_strength) {
    std::string models;
    for (const auto& [name, block] : description.materials)
      models += (models.empty() ? "" : ", ") + name + ": " + model_of(block);
    throw InputError(file, "materials", models,
                     "no material has a strength to reduce (every one is elastic)",
                     "at least one material of model " + allowed_models());
  }
}

CaseDescription reduce_strength(const CaseDescription& description, double factor) {
  check_strength_reduction_case(description);
  if (!(factor > 0.0) || !std::isfinite(factor))
    throw InputError({}, "factor", fmt::format("{}", factor), "not a usable strength factor",
                     "a finite number > 0");
  CaseDescription reduced = description;
  for (auto& [name, block] : reduced.materials) {
    const std::string model = model_of(block);
    if (is_frictional(model)) {
      for (const char* key :
           {"cohesion", "minimum_cohesion", "cohesion_hardening_modulus", "tension_cutoff"})
        divide(block, key, factor);
      double friction = 0.0;
      if (auto found = block.values.find("friction_angle"); found != block.values.end()) {
        found->second.value = reduced_angle(found->second.value, factor);
        friction = found->second.value;
      }
      if (auto found = block.values.find("minimum_friction_angle"); found != block.values.end())
        found->second.value = reduced_angle(found->second.value, factor);
      // Kept below the reduced friction angle (the material needs psi <= phi): as Plaxis does.
      if (auto found = block.values.find("dilatancy_angle"); found != block.values.end())
        found->second.value = std::min(found->second.value, friction);
    } else if (model == "perzyna_von_mises") {
      for (const char* key :
           {"yield_stress", "minimum_yield_stress", "hardening_modulus", "tension_cutoff"})
        divide(block, key, factor);
    }
  }
  return reduced;
}

CaseDescription elastic_reference(const CaseDescription& description) {
  check_strength_reduction_case(description);
  CaseDescription elastic = description;
  const std::vector<std::string> reducible = reducible_material_models();
  for (auto& [name, block] : elastic.materials) {
    if (std::find(reducible.begin(), reducible.end(), model_of(block)) == reducible.end()) continue;
    ParameterBlock replaced;
    replaced.path = block.path;
    replaced.where = block.where;
    replaced.words["model"] = {"linear_elastic", block.words.at("model").second};
    for (const char* key : {"density", "young_modulus", "poisson_ratio"})
      if (auto found = block.values.find(key); found != block.values.end())
        replaced.values[key] = found->second;
    block = std::move(replaced);
  }
  return elastic;
}

const ReductionRun* StrengthReductionResult::first_failing() const {
  const ReductionRun* first = nullptr;
  for (const ReductionRun& run : runs)
    if (run.failing && (!first || run.factor < first->factor)) first = &run;
  return first;
}

StrengthReductionResult find_factor_of_safety(const CaseDescription& description,
                                              const StrengthReductionOptions& options,
                                              const std::filesystem::path& directory) {
  check_strength_reduction_case(description);
  if (!(options.stable > 0.0) || !(options.failing > options.stable))
    throw InputError({}, "--bracket", fmt::format("{} {}", options.stable, options.failing),
                     "not a bracket of strength factors", "0 < LOW < HIGH");
  if (!(options.tolerance > 0.0))
    throw InputError({}, "--tolerance", fmt::format("{}", options.tolerance),
                     "not a usable tolerance", "a number > 0");
  const FailureCriterion& criterion = options.criterion;
  if (!(criterion.rest_fraction > 0.0 && criterion.rest_fraction < 1.0))
    throw InputError({}, "--rest-fraction", fmt::format("{}", criterion.rest_fraction),
                     "out of range", "(0, 1)");
  if (!(criterion.displacement_ratio > 1.0))
    throw InputError({}, "--displacement-ratio", fmt::format("{}", criterion.displacement_ratio),
                     "out of range", "a number > 1");
  StrengthReductionResult result;
  try {
    result.elastic = run_at(description, 0.0, options, directory / "elastic",
                            std::numeric_limits<double>::infinity());
    if (!result.elastic.came_to_rest)
      throw RunError(fmt::format(
          "the elastic reference ({}) did not come to rest (largest speed {} of its peak) by "
          "time.end = {} s: the case needs more time or more damping for strength reduction",
          (directory / "elastic").string(), criterion.rest_fraction, description.time.end));
    if (options.on_run) options.on_run(result.elastic);
    const double elastic_displacement = result.elastic.largest_displacement;
    const auto run_and_keep = [&](double factor) {
      ReductionRun run =
          run_at(description, factor, options, directory / fmt::format("F{:.4f}", factor),
                 criterion.displacement_ratio * elastic_displacement);
      classify(run, elastic_displacement, criterion);
      result.runs.push_back(std::move(run));
      if (options.on_run) options.on_run(result.runs.back());
      return result.runs.back().failing;
    };
    double stable = options.stable, failing = options.failing;
    if (run_and_keep(stable)) {
      result.message = fmt::format(
          "the case fails already at the bracket's low end F = {:g}; "
          "choose a lower one",
          stable);
      return result;
    }
    if (!run_and_keep(failing)) {
      result.message = fmt::format(
          "the case is still stable at the bracket's high end F = {:g}; "
          "choose a higher one",
          failing);
      return result;
    }
    result.bracket_holds = true;
    while (failing - stable > options.tolerance * (1.0 + 1e-9)) {
      const double middle = 0.5 * (stable + failing);
      (run_and_keep(middle) ? failing : stable) = middle;
    }
    result.stable = stable;
    result.failing = failing;
    result.factor = 0.5 * (stable + failing);
  } catch (const RunError& error) {
    if (options.stop_check && !options.stop_check().empty()) {
      result.interrupted = true;
      result.message = error.what();
      return result;
    }
    throw;
  }
  return result;
}

std::string strength_reduction_json(const CaseDescription& description,
                                    const StrengthReductionOptions& options,
                                    const StrengthReductionResult& result,
                                    const std::string& mechanism_picture) {
  const auto run_json = [&](const ReductionRun& run) {
    return fmt::format(
        "{{\"factor\": {}, \"outcome\": {}, \"at_rest\": {}, \"diverged\": {}, \"end_time\": {}, "
        "\"largest_displacement\": {}, \"displacement_over_elastic\": {}, \"reason\": {}, "
        "\"directory\": {}}}",
        json_number(run.factor), json_quote(run.failing ? "failing" : "stable"),
        run.came_to_rest ? "true" : "false", run.diverged ? "true" : "false",
        json_number(run.end_time), json_number(run.largest_displacement),
        json_number(run.largest_displacement / result.elastic.largest_displacement),
        json_quote(run.reason), json_quote(run.directory.string()));
  };
  std::string runs;
  for (const ReductionRun& run : result.runs)
    runs += (runs.empty() ? "\n    " : ",\n    ") + run_json(run);
  const bool found = std::isfinite(result.factor);
  return fmt::format(
      "{{\n  \"case\": {},\n  \"file\": {},\n  \"status\": {},\n  \"message\": {},\n"
      "  \"factor\": {},\n  \"bracket\": [{}, {}],\n  \"tolerance\": {},\n"
      "  \"initial_bracket\": [{}, {}],\n"
      "  \"criterion\": {{\"rest_fraction\": {}, \"displacement_ratio\": {}, \"time_end\": {}}},\n"
      "  \"elastic_displacement\": {},\n  \"mechanism_picture\": {},\n  \"runs\": [{}\n  ]\n}}\n",
      json_quote(description.name), json_quote(description.file),
      json_quote(found                ? "found"
                 : result.interrupted ? "interrupted"
                                      : "bracket_not_held"),
      json_quote(result.message), json_number(result.factor),
      json_number(found ? result.stable : std::nan("")),
      json_number(found ? result.failing : std::nan("")), json_number(options.tolerance),
      json_number(options.stable), json_number(options.failing),
      json_number(options.criterion.rest_fraction),
      json_number(options.criterion.displacement_ratio), json_number(description.time.end),
      json_number(result.elastic.largest_displacement),
      mechanism_picture.empty() ? "null" : json_quote(mechanism_picture), runs);
}

}  // namespace rktsph
