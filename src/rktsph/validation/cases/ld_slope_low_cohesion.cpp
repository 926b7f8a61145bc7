// Thesis §5.3.4 (docs/theory.md §9.14): a 10 m block of extremely low cohesion (N = 68) released
// against a smooth back wall on a rough base, followed into run-out with the large-deformation
// model. Checks, on the finest run and on whatever state it reached:
//   mass_conservation_error     |sum of rho_P V_P over the cells at the end - rho W0 H0| over
//                               rho W0 H0, with rho_P = rho_0 V_0/V the current density of a cell
//                               and V_P its current volume, against the block of the case file
//                               (<= 1e-12).
//   deposit_bound_exceedance    the largest height of a node above Nye's bound sqrt(2 c x'/gamma),
//                               x' behind the run's own front, over the bound's height at the
//                               back wall (<= 0.05, the thin-layer approximation's margin there).
//   runout_ratio                the front's distance from the back wall over Nye's minimum
//                               run-out L_min of a deposit at rest (>= 1).
//   final_kinetic_energy_ratio  kinetic energy at the end over its peak (<= 1e-3: it stops).
//   free_surface_error          nodes the detector of §9.4 misflags at the end (missed perimeter
//                               nodes plus interior nodes flagged) over perimeter nodes (<= 0.02).
//   volume_change               the cells' area at the end over W0 H0: the soil's change of volume
//                               and, with cells formed again (§9.17), what the alpha criterion
//                               leaves out or keeps (within 0.05).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "rktsph/simulation/energy_budget.hpp"
#include "rktsph/simulation/surface_watch.hpp"
#include "rktsph/validation/references/runout.hpp"
#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph::case_checks::ld_slope_low_cohesion {

namespace {

constexpr char kCase[] = "ld-slope-low-cohesion";
constexpr double kSampleInterval = 0.02;  // [s] of the kinetic-energy and front histories

// The block of the case file: the first shape, a rectangle from the back wall x = 0 on the base.
struct Block {
  double width = 0.0, height = 0.0;  // W0, H0 [m]
  double density = 0.0;              // rho [kg/m3]
  double gravity = 0.0;              // g [m/s2]
  double cohesion = 0.0;             // c = Y / sqrt(3) [Pa]
  double unit_weight() const { return density * gravity; }
  double runout_bound() const {
    return references::nye_minimum_runout(width * height, cohesion, unit_weight());
  }
};

Block read_block(const CaseDescription& description) {
  const Rectangle rectangle = rectangle_shape(description, 0);
  Block block;
  block.width = rectangle.width();
  block.height = rectangle.height();
  block.density = material_parameter(description, "soil", "density");
  block.gravity = downward_gravity(description);
  block.cohesion = material_parameter(description, "soil", "yield_stress") / std::sqrt(3.0);
  return block;
}

// One run and what it reached.
struct Collapse {
  double spacing = 0.0;
  ValidationRun run;
  double end_time = 0.0;
  std::vector<double> time, kinetic, front;  // sampled histories [s], [J/m], [m]
  std::vector<double> x, y;                  // node positions at the end [m]
  double runout = 0.0;                       // the front at the end: the largest x [m]
  double mass = 0.0;                         // sum of rho_P V_P at the end [kg/m]
  double area = 0.0;                         // sum of V_P at the end: the cells' area [m^2]
  std::size_t nodes = 0;
  SurfaceAgreement surface;
};

double largest_x(const PointCloud& nodes) {
  double front = -std::numeric_limits<double>::infinity();
  for (double x : nodes.position[0])
    front = std::max(front, x);
  return front;
}

Collapse run_collapse(const ValidationContext& context, double spacing, const std::string& label) {
  Collapse result;
  result.spacing = spacing;
  const CaseDescription description =
      load_bundled_case(context, kCase, {{"geometry.spacing", fmt::format("{:g}", spacing)}});
  SampledObserver sampler(kSampleInterval, [&result](const Simulation& simulation) {
    result.time.push_back(simulation.state().time);
    result.kinetic.push_back(measure_energy(simulation).kinetic);
    result.front.push_back(largest_x(simulation.state().configuration.sph_nodes));
  });
  const auto inspect = [&result](const Simulation& simulation) {
    const State& state = simulation.state();
    const PointCloud& current = state.configuration.sph_nodes;
    result.end_time = state.time;
    result.nodes = current.size();
    result.x = current.position[0];
    result.y = current.position[1];
    result.runout = largest_x(current);
    // The cells tile the body (§9.1): the material's mass is that of the stress points, each of
    // density rho_0 V_0 / V and volume V.
    // The cells the step integrates over at the end: the start's, or those formed last (§9.17).
    const PointCloud& points = state.configuration.stress_points;
    const NodeSets& cells = simulation.cells();
    const PointCloud& reference = cells.stress_points;
    for (std::size_t p = 0; p < points.size(); ++p) {
      const double density = simulation.model().density(cells.cells.material(p)) *
                             reference.volume[p] / points.volume[p];
      result.mass += density * points.volume[p];
      result.area += points.volume[p];
    }
    FreeSurface detected;
    detect_current_surface(simulation, detected);
    result.surface = compare_with_perimeter(simulation, detected);
  };
  result.run = run_allowing_failure(context, description, label, inspect, {&sampler});
  return result;
}

// Largest height of a node above the Nye bound behind the run's front, over the bound at x = 0.
double deposit_exceedance(const Collapse& collapse, const Block& block) {
  const double front = collapse.runout;
  const double wall_bound = references::nye_height(front, block.cohesion, block.unit_weight());
  double worst = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < collapse.x.size(); ++i) {
    const double bound = references::nye_height(std::max(0.0, front - collapse.x[i]),
                                                block.cohesion, block.unit_weight());
    worst = std::max(worst, collapse.y[i] - bound);
  }
  return worst / wall_bound;
}

std::string stop_text(const Collapse& collapse) {
  return collapse.run.completed
             ? fmt::format("ran to t = {:.3g} s", collapse.end_time)
             : fmt::format("stopped at t = {:.3g} s: {}", collapse.end_time, collapse.run.message);
}

void report(ValidationReport& report, const std::vector<Collapse>& runs, const Block& block) {
  const Collapse& finest = runs.front();
  std::string runs_text;
  for (const Collapse& run : runs)
    runs_text += fmt::format(" At dx = {:g} m the run {}; its front reached {:.2f} m.", run.spacing,
                             stop_text(run), run.runout);
  report.describe(fmt::format(
      "Thesis 5.3.4: a {:g} m x {:g} m block (N = gamma H / c = {:.0f}) collapses against a "
      "smooth back wall onto a rough base, with the large-deformation model. A deposit at rest "
      "must lie below Nye's profile sqrt(2 c x'/gamma) behind its front and run out at least "
      "{:.1f} m.{}",
      block.width, block.height, block.unit_weight() * block.height / block.cohesion,
      block.runout_bound(), runs_text));
  Figure deposit{
      "deposit", "Surface of the block at the end against Nye's bound", "x [m]", "y [m]", {}};
  for (const Collapse& run : runs)
    deposit.series.push_back(
        {fmt::format("SPH nodes, dx = {:g} m, t = {:.2f} s", run.spacing, run.end_time), run.x,
         run.y, "points"});
  const double front = finest.runout;
  deposit.series.push_back(
      sample_curve("Nye bound behind the SPH front", 0.0, front, 200, [&](double x) {
        return references::nye_height(std::max(0.0, front - x), block.cohesion,
                                      block.unit_weight());
      }));
  const double runout = block.runout_bound();
  deposit.series.push_back(
      sample_curve("steepest deposit at rest (minimum run-out)", 0.0, runout, 200, [&](double x) {
        return references::nye_height(std::max(0.0, runout - x), block.cohesion,
                                      block.unit_weight());
      }));
  report.add_figure(std::move(deposit));
  Figure energy{"kinetic_energy", "Kinetic energy", "time [s]", "kinetic energy [J/m]", {}};
  Figure fronts{"front", "Front of the collapsing block", "time [s]", "front x [m]", {}};
  for (const Collapse& run : runs) {
    energy.series.push_back(
        {fmt::format("SPH, dx = {:g} m", run.spacing), run.time, run.kinetic, "line"});
    fronts.series.push_back(
        {fmt::format("SPH, dx = {:g} m", run.spacing), run.time, run.front, "line"});
  }
  const double last = finest.time.back();
  fronts.series.push_back(
      sample_curve("Ritter dam break (upper bound)", 0.0, last, 50, [&](double t) {
        return references::ritter_front(t, block.width, block.height, block.gravity);
      }));
  fronts.series.push_back(
      sample_curve("minimum run-out at rest", 0.0, last, 2, [&](double) { return runout; }));
  report.add_figure(std::move(energy));
  report.add_figure(std::move(fronts));
  // The field output is on the current configuration: drawn at true scale, X + u (magnification 1).
  report.add_picture({"eps_vp", finest.run.directory.string(), "eps_vp", -1, -1.0, 1.0,
                      fmt::format("Equivalent viscoplastic strain on the deformed block, dx = "
                                  "{:g} m, at the last output of the run.",
                                  finest.spacing)});
}

}  // namespace

std::vector<CheckResult> validate_ld_slope_low_cohesion(const ValidationContext& context) {
  const Block block = read_block(load_bundled_case(context, kCase));
  // Full: dx = 0.5 m (20 cells over H, the case file) checked, and 1 m for the resolution
  // figure; quick: 1 m only.
  std::vector<Collapse> runs;
  runs.push_back(run_collapse(context, context.quick ? 1.0 : 0.5, "finest"));
  if (!context.quick) runs.push_back(run_collapse(context, 1.0, "coarse"));
  const Collapse& finest = runs.front();
  if (finest.nodes == 0 || finest.time.empty())
    throw RunError(
        fmt::format("{}: the run wrote no state to check ({})", kCase, finest.run.message));
  if (context.report) report(*context.report, runs, block);

  const double block_mass = block.density * block.width * block.height;
  const double peak_kinetic = *std::max_element(finest.kinetic.begin(), finest.kinetic.end());
  const double kinetic_ratio = peak_kinetic > 0.0 ? finest.kinetic.back() / peak_kinetic : 0.0;
  // mass 1e-12: the bound, a few hundred round-offs of the sum over the nodes.
  // deposit 0.05: the thin-layer balance behind the bound fails near the wall, where the deposit
  // is thickest; 5 % of the wall height is left for it. runout 1 and kinetic 1e-3: the issue's
  // floors. free surface 0.02: the issue's.
  return {check_at_most("mass_conservation_error", std::abs(finest.mass - block_mass) / block_mass,
                        0.0, 1e-12, "fraction"),
          check_at_most("deposit_bound_exceedance", deposit_exceedance(finest, block), 0.0, 0.05,
                        "fraction"),
          check_at_least("runout_ratio", finest.runout / block.runout_bound(), 1.0, 1.0, "1"),
          check_at_most("final_kinetic_energy_ratio", kinetic_ratio, 0.0, 1e-3, "fraction"),
          check_at_most("free_surface_error", finest.surface.misflagged_fraction(), 0.0, 0.02,
                        "fraction"),
          // 5 %: the bound.
          check_within("volume_change", finest.area / (block.width * block.height), 1.0, 0.05,
                       "ratio")};
}

}  // namespace rktsph::case_checks::ld_slope_low_cohesion
