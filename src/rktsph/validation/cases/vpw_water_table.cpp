// Issue 30 (docs/theory.md §6.8, §8.12): a saturated elastic layer with a water table, settling
// under gravity ramped in from a stress-free start, comes to rest at the closed-form state of
// eqs. 6.6 and 6.9. Every number is read from the case file (densities, porosity, Biot
// coefficient, table level, geometry, gravity), so that a variant at other parameters is checked
// against its own closed form.
//
// - pore_pressure_error: max over every SPH node below the table of |p_w - rho_w g (y_w - y)|
//   over the largest hydrostatic pressure, rho_w g (y_w - y_base); p_w is the total pore pressure
//   of the output (the hydrostatic part plus the carried excess).
// - effective_stress_error: max over every SPH node of |sigma'_v - sigma'_v,ref| over the
//   reference at the base, sigma'_v,ref = -g [rho_above (dry part above the node) + (rho - alpha
//   rho_w) (wet part above it)] (eq. 6.9).
// - horizontal_stress_error: the same for sigma'_h against K0 sigma'_v,ref, K0 = nu/(1 - nu) (the
//   laterally confined layer, mirror sides).
// - residual_velocity_ratio: largest |v| at the end over its peak (rest_checks.hpp).
//
// And a slope with a water table (cases/vpw-water-table-slope, docs/theory.md §10.4): its drained
// factor of safety by strength reduction against Bishop's simplified method on the same pore
// pressures (references/slope_limit_equilibrium.hpp), and against the factor of the same slope
// dry (the model dry_solid, the weight above the table everywhere, no water):
// - slope_factor_of_safety: F with the table, within 5 % of Bishop's (as the dry slope's check);
// - slope_factor_ratio: F with the table over F dry, within 0.05 of Bishop's ratio (about 0.86:
//   the water lowers the factor by some 14 %).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "rktsph/core/error.hpp"
#include "rktsph/physics/water_table.hpp"
#include "rktsph/validation/fos_report.hpp"
#include "rktsph/validation/references/slope_limit_equilibrium.hpp"
#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph::case_checks::vpw_water_table {

namespace {

/// The density the case gives the soil above its water table (docs/theory.md §6.8).
double case_density_above(const PoreFluidSpec& fluid, double density) {
  return density_above_table(fluid.water_table ? fluid.water_table->density_above : std::nullopt,
                             density, fluid.porosity, fluid.density);
}

constexpr const char* kFolder = "vpw-water-table";

/// The layer of the case, read back from it.
struct Layer {
  double density = 0.0;        // rho, the saturated mixture
  double density_above = 0.0;  // rho_above, the drained soil above the table
  double water_density = 0.0;  // rho_w
  double biot = 1.0;           // alpha
  double poisson = 0.0, young = 0.0;
  double gravity = 0.0;  // g
  double table = 0.0;    // y_w
  double base = 0.0, top = 0.0, x_min = 0.0, x_max = 0.0, spacing = 0.0;

  /// p_h = rho_w g (y_w - y)^+ (eq. 6.6).
  double hydrostatic_pressure(double y) const {
    return water_density * gravity * std::max(0.0, table - y);
  }
  /// -sigma'_v, compression positive (eq. 6.9).
  double effective_overburden(double y) const {
    const double dry = std::max(0.0, top - std::max(y, table));
    const double wet = std::max(0.0, std::min(top, table) - y);
    return gravity * (density_above * dry + (density - biot * water_density) * wet);
  }
  double k0() const { return poisson / (1.0 - poisson); }
  double permeability = 0.0;  // k_bar = k / (rho_w g_k) [m3 s/kg]
  double storage = 0.0;       // 1/Q = n / K_w

  /// H_d^2 / c_v of the soil below the table, drained at the table (or the top) and impermeable
  /// at the base: c_v = k_bar / (alpha^2/M + 1/Q) (docs/theory.md §8.8).
  double drainage_time() const {
    const double oedometric = young * (1.0 - poisson) / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
    const double consolidation = permeability / (biot * biot / oedometric + storage);
    const double length = std::min(top, table) - base;
    return consolidation > 0.0 ? length * length / consolidation : 0.0;
  }
};

/// The time at which the gravity ramp reaches its full value (0 for a constant factor).
double full_gravity_time(const CaseDescription& description) {
  const TimeFunction& factor = description.gravity->factor;
  if (factor.kind == TimeFunction::Kind::LinearRamp) return factor.start + factor.duration;
  if (factor.kind == TimeFunction::Kind::Step) return factor.start;
  return 0.0;
}

Layer read_layer(const CaseDescription& description) {
  if (!description.pore_fluid || !description.pore_fluid->water_table ||
      !description.pore_fluid->water_table->level)
    throw RunError(std::string("case ") + kFolder +
                   ": expected pore_fluid.water_table with a level (the closed form is for a "
                   "horizontal table)");
  const PoreFluidSpec& fluid = *description.pore_fluid;
  Layer layer;
  layer.density = material_parameter(description, "soil", "density");
  layer.density_above = case_density_above(fluid, layer.density);
  layer.water_density = fluid.density;
  layer.biot = fluid.biot_coefficient;
  layer.poisson = material_parameter(description, "soil", "poisson_ratio");
  layer.young = material_parameter(description, "soil", "young_modulus");
  layer.gravity = downward_gravity(description);
  layer.table = *fluid.water_table->level;
  layer.permeability = fluid.hydraulic_conductivity / (fluid.density * fluid.gravity);
  layer.storage = fluid.porosity / fluid.bulk_modulus;
  const Rectangle body = rectangle_shape(description, 0);
  layer.base = body.y_min;
  layer.top = body.y_max;
  layer.x_min = body.x_min;
  layer.x_max = body.x_max;
  layer.spacing = description.geometry.spacing;
  if (layer.table <= layer.base)
    throw RunError(
        fmt::format("case {}: the water table y = {} m is not above the base y = {} m: "
                    "no node is below it to check",
                    kFolder, layer.table, layer.base));
  return layer;
}

struct RestErrors {
  double pore_pressure = 0.0, effective_stress = 0.0, horizontal_stress = 0.0;
};

/// The state at the end, and for the report the profiles along the column nearest the centre.
struct Profiles {
  std::vector<double> y, pore_pressure, vertical, horizontal;  // [m], [kPa] compression positive
};

RestErrors measure_rest(const Simulation& simulation, const Layer& layer, Profiles& profiles) {
  const NodeSets& nodes = simulation.nodes();
  const FieldArray& fields = simulation.state().fields;
  const int xx = simulation.model().stress_field(0, 0), yy = simulation.model().stress_field(1, 1);
  const NodeQuantity pore_pressure = find_quantity(simulation, "pore_pressure");
  const double pressure_scale = layer.hydrostatic_pressure(layer.base);
  const double stress_scale = layer.effective_overburden(layer.base);
  const double centre = 0.5 * (layer.x_min + layer.x_max);
  double nearest = 1e300;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i)
    nearest = std::min(nearest, std::abs(nodes.sph_nodes.position[0][i] - centre));
  RestErrors errors;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    const double x = nodes.sph_nodes.position[0][i], y = nodes.sph_nodes.position[1][i];
    const double p = pore_pressure(simulation.state(), i);
    if (y < layer.table)
      errors.pore_pressure = std::max(errors.pore_pressure,
                                      std::abs(p - layer.hydrostatic_pressure(y)) / pressure_scale);
    const double reference = layer.effective_overburden(y);
    errors.effective_stress =
        std::max(errors.effective_stress, std::abs(-fields(yy, i) - reference) / stress_scale);
    errors.horizontal_stress =
        std::max(errors.horizontal_stress,
                 std::abs(-fields(xx, i) - layer.k0() * reference) / (layer.k0() * stress_scale));
    if (std::abs(std::abs(x - centre) - nearest) < 1e-9 * layer.spacing && x <= centre) {
      profiles.y.push_back(y);
      profiles.pore_pressure.push_back(1e-3 * p);
      profiles.vertical.push_back(-1e-3 * fields(yy, i));
      profiles.horizontal.push_back(-1e-3 * fields(xx, i));
    }
  }
  return errors;
}

/// The layer's figures; returns its paragraph of the description.
std::string report_water_table(ValidationReport& report, const std::filesystem::path& directory,
                               const CaseDescription& description, const Layer& layer,
                               const Profiles& profiles, const SpeedHistory& speeds) {
  const std::string text = fmt::format(
      "Issue 30: a saturated linear elastic layer (E = {:g} MPa, nu = {:g}; rho = {:g} kg/m3 "
      "below the water table, rho_above = {:g} kg/m3 above it; rho_w = {:g} kg/m3, alpha = {:g}) "
      "{:g} m deep and {:g} m wide between mirror sides, on a fixed impermeable base, with the "
      "water table at y = {:g} m (dx = {:g} m). Gravity is ramped in over {:g} s from a "
      "stress-free start with mass damping {:g}/s; the excess pore pressure of the settlement "
      "drains through the table, where the soil above it is drained. At t = {:g} s every node "
      "must be at the closed-form rest state (docs/theory.md eqs. 6.6, 6.9): p_w = rho_w g "
      "(y_w - y) below the table, sigma'_v = rho_above g (y_top - y) above it and rho_above g "
      "H_dry + (rho - alpha rho_w) g (y_w - y) below it, sigma'_h = K0 sigma'_v; and at rest "
      "(largest velocity at the end below 1e-3 of its peak).",
      1e-6 * layer.young, layer.poisson, layer.density, layer.density_above, layer.water_density,
      layer.biot, layer.top - layer.base, layer.x_max - layer.x_min, layer.table, layer.spacing,
      description.gravity->factor.duration,
      description.damping ? description.damping->coefficient : 0.0, description.time.end);
  // A closed-form profile drawn as the SPH points are, the value against the height y.
  const auto profile = [&layer](std::string label, const std::function<double(double)>& value) {
    Series curve = sample_curve(std::move(label), layer.base, layer.top, 201, value);
    std::swap(curve.x, curve.y);
    return curve;
  };
  report.add_figure(
      {"rest_profiles",
       "Pore pressure and effective stresses at rest along the centre column",
       "pressure, compression positive [kPa]",
       fmt::format("height above the base y [m] (water table at y = {:g} m)", layer.table),
       {{"SPH p_w (hydrostatic + excess)", profiles.pore_pressure, profiles.y, "points"},
        {"SPH -sigma'_yy", profiles.vertical, profiles.y, "points"},
        {"SPH -sigma'_xx", profiles.horizontal, profiles.y, "points"},
        profile("p_w = rho_w g (y_w - y)",
                [&layer](double y) { return 1e-3 * layer.hydrostatic_pressure(y); }),
        profile("sigma'_v, eq. 6.9",
                [&layer](double y) { return 1e-3 * layer.effective_overburden(y); }),
        profile("K0 sigma'_v", [&layer](double y) {
          return 1e-3 * layer.k0() * layer.effective_overburden(y);
        })}});
  report.add_figure(speed_figure("max_velocity", speeds, 0.0, 1e-3));
  report.add_picture({"pore_pressure", directory.string(), "pore_pressure", -1, -1.0, 0.0,
                      "Total pore pressure at the end: hydrostatic below the water table, zero "
                      "in the drained soil above it, uniform across the width."});
  return text;
}

constexpr const char* kSlopeFolder = "vpw-water-table-slope";

/// The slope of the case as the limit-equilibrium reference sees it: the upper boundary of its
/// polygon (the vertices above its lowest point, by x) as the ground, its lowest point as the
/// rigid base, the weights of eq. 6.8 above and below the table, and u = alpha p_h (the model's
/// effective stress is sigma + alpha p_w I, eq. 6.7).
references::SlopeProfile slope_profile(const CaseDescription& description) {
  const ShapeSpec& shape = description.geometry.shapes.at(0);
  if (shape.kind != ShapeSpec::Kind::Polygon || !description.pore_fluid ||
      !description.pore_fluid->water_table)
    throw RunError(
        fmt::format("case {}: expected a polygon slope with a water table", kSlopeFolder));
  const PoreFluidSpec& fluid = *description.pore_fluid;
  const std::string& material = shape.material;
  const double gravity = downward_gravity(description);
  const double density = material_parameter(description, material, "density");
  references::SlopeProfile profile;
  profile.base = std::ranges::min(shape.vertices, {}, [](const Vec3& v) { return v[1]; })[1];
  for (const Vec3& vertex : shape.vertices)
    if (vertex[1] > profile.base) profile.ground.push_back({vertex[0], vertex[1]});
  std::sort(profile.ground.begin(), profile.ground.end());
  for (std::size_t i = 1; i < profile.ground.size(); ++i)
    if (profile.ground[i][0] == profile.ground[i - 1][0])
      throw RunError(
          fmt::format("case {}: the slope's ground is not a function of x (two vertices "
                      "at x = {} m)",
                      kSlopeFolder, profile.ground[i][0]));
  profile.unit_weight_above = case_density_above(fluid, density) * gravity;
  profile.unit_weight_below = density * gravity;
  profile.cohesion = material_parameter(description, material, "cohesion");
  profile.friction_angle = material_parameter(description, material, "friction_angle");
  const WaterTableSpec& table = *fluid.water_table;
  if (table.level)
    profile.water_table = {{0.0, *table.level}};
  else
    profile.water_table = table.polyline;
  profile.water_unit_weight = fluid.biot_coefficient * fluid.density * gravity;
  return profile;
}

/// The same slope dry: the dry model, every material weighing what it weighs above the table,
/// no pore fluid (and no pore-pressure condition or probe).
CaseDescription dry_slope(const CaseDescription& wet) {
  CaseDescription dry = wet;
  dry.model = ModelKind::DrySolid;
  for (auto& [name, block] : dry.materials) {
    Parameter& density = block.values.at("density");
    density.value = case_density_above(*wet.pore_fluid, density.value);
  }
  dry.pore_fluid.reset();
  std::erase_if(dry.boundary_conditions, [](const BoundaryConditionSpec& condition) {
    return condition.kind == BoundaryConditionSpec::Kind::PorePressure;
  });
  for (ProbeSpec& probe : dry.probes)
    std::erase(probe.fields, std::string("pore_pressure"));
  std::erase_if(dry.probes, [](const ProbeSpec& probe) { return probe.fields.empty(); });
  return dry;
}

struct SlopeFactors {
  references::SlipCircle bishop_wet, bishop_dry;
  StrengthReductionResult wet, dry;
  double ratio() const { return factor_or_nan(wet) / factor_or_nan(dry); }
  double bishop_ratio() const { return bishop_wet.factor / bishop_dry.factor; }
};

/// Both strength reductions, each bracketed about its Bishop factor: full, [0.85, 1.15] F_B
/// halved to 1 % of F_B; quick (dx = 1 m), [0.9, 1.1] F_B halved to 2.5 % (three bisections). The
/// result is the middle of a final bracket, so it lies on a grid of the reference: these grids
/// keep it off the check's 5 % bounds (quick: F_B (0.9125 + 0.025 k)).
SlopeFactors measure_slope_factors(const ValidationContext& context) {
  std::vector<CaseOverride> overrides = {{"output.interval", "0"}};
  if (context.quick) overrides.push_back({"geometry.spacing", "1"});
  // The overrides of a variant (`--set`) apply to the slope too, except where the water table
  // lies: the layer's level means nothing on the slope, whose phreatic line is drawn with its
  // ground (a level there would also clash with its polyline).
  ValidationContext slope_context = context;
  std::erase_if(slope_context.overrides, [](const CaseOverride& override) {
    return override.key.starts_with("pore_fluid.water_table.level") ||
           override.key.starts_with("pore_fluid.water_table.polyline");
  });
  const CaseDescription wet = load_bundled_case(slope_context, kSlopeFolder, overrides);
  SlopeFactors factors;
  references::SlopeProfile profile = slope_profile(wet);
  factors.bishop_wet = references::critical_bishop_circle(profile);
  profile.water_table.clear();
  factors.bishop_dry = references::critical_bishop_circle(profile);
  const auto bisect = [&](const CaseDescription& description, double reference,
                          const std::string& label) {
    StrengthReductionOptions options;
    options.stable = (context.quick ? 0.9 : 0.85) * reference;
    options.failing = (context.quick ? 1.1 : 1.15) * reference;
    options.tolerance = (context.quick ? 0.025 : 0.01) * reference;
    return run_strength_reduction(context, description, options, label);
  };
  factors.wet = bisect(wet, factors.bishop_wet.factor, "wet");
  factors.dry = bisect(dry_slope(wet), factors.bishop_dry.factor, "dry");
  return factors;
}

/// The slope's figures; returns its paragraph of the description.
std::string report_slope(ValidationReport& report, const SlopeFactors& factors) {
  const std::string text = fmt::format(
      " The slope of {} (Verruijt's slope of slope-fos-homogeneous with a phreatic line to the "
      "toe), drained strength reduction (docs/theory.md §10.4): with the water table F = {:.3f} "
      "in [{:.3f}, {:.3f}] ({}) against Bishop's simplified {:.3f} on the same pore pressures "
      "(critical circle centre ({:.2f}, {:.2f}) m, R = {:.2f} m); dry F = {:.3f} in [{:.3f}, "
      "{:.3f}] ({}) against Bishop's {:.3f}. Ratio wet/dry {:.3f} against Bishop's {:.3f}.",
      kSlopeFolder, factors.wet.factor, factors.wet.stable, factors.wet.failing,
      strength_reduction_runs_text(factors.wet), factors.bishop_wet.factor,
      factors.bishop_wet.centre_x, factors.bishop_wet.centre_y, factors.bishop_wet.radius,
      factors.dry.factor, factors.dry.stable, factors.dry.failing,
      strength_reduction_runs_text(factors.dry), factors.bishop_dry.factor, factors.ratio(),
      factors.bishop_ratio());
  add_bisection_figure(report, "slope_bisection_wet",
                       "Slope with a water table: outcome of each run", factors.wet,
                       {{"Bishop, same pore pressures", factors.bishop_wet.factor}});
  add_bisection_figure(report, "slope_bisection_dry", "The same slope dry: outcome of each run",
                       factors.dry, {{"Bishop, dry", factors.bishop_dry.factor}});
  add_mechanism_picture(report, "slope_mechanism_wet", factors.wet);
  return text;
}

}  // namespace

std::vector<CheckResult> validate_vpw_water_table(const ValidationContext& context) {
  // Quick: dx = 0.5 m (20 cells over the depth) instead of 0.25 m.
  std::vector<CaseOverride> overrides;
  if (context.quick) overrides.push_back({"geometry.spacing", "0.5"});
  CaseDescription description = load_bundled_case(context, kFolder, overrides);
  const Layer layer = read_layer(description);
  // Long enough to drain: 4 H_d^2/c_v after gravity is in full leaves exp(-pi^2) of the excess's
  // rate of decay (a variant with a deeper table or a lower k gets a longer run).
  description.time.end =
      std::max(description.time.end, full_gravity_time(description) + 4.0 * layer.drainage_time());
  RestErrors errors;
  Profiles profiles;
  SpeedRecorder speeds(description.output.probe_interval);
  const auto directory = run_for_validation(
      context, description, context.quick ? "dx05" : "dx025",
      [&](const Simulation& simulation) { errors = measure_rest(simulation, layer, profiles); },
      {&speeds.observer()});
  const double residual = residual_velocity_ratio(speeds.history());
  std::string description_text;
  if (context.report)
    description_text = report_water_table(*context.report, directory, description, layer, profiles,
                                          speeds.history());
  // Tolerances: the 2 % on p_w and sigma'_v; sigma'_h alike; rest as the other held
  // loads (1e-3 of the peak velocity).
  std::vector<CheckResult> checks = {
      check_at_most("pore_pressure_error", errors.pore_pressure, 0.0, 0.02, "fraction"),
      check_at_most("effective_stress_error", errors.effective_stress, 0.0, 0.02, "fraction"),
      check_at_most("horizontal_stress_error", errors.horizontal_stress, 0.0, 0.02, "fraction"),
      check_at_most("residual_velocity_ratio", residual, 0.0, 1e-3, "fraction"),
  };
  // The slope: 5 % on F as the dry slope's check against Bishop (slope_fos.cpp); the ratio within
  // 0.05, of which the bisections' final brackets (2.5 % of F quick, 1 % full) take up to 0.025.
  const SlopeFactors slope = measure_slope_factors(context);
  checks.push_back(check_within("slope_factor_of_safety", factor_or_nan(slope.wet),
                                slope.bishop_wet.factor, 0.05 * slope.bishop_wet.factor, "1"));
  checks.push_back(
      check_within("slope_factor_ratio", slope.ratio(), slope.bishop_ratio(), 0.05, "1"));
  if (context.report)
    context.report->describe(description_text + report_slope(*context.report, slope));
  return checks;
}

}  // namespace rktsph::case_checks::vpw_water_table
