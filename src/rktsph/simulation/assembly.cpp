#include "rktsph/simulation/assembly.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "rktsph/case/computed_defaults.hpp"
#include "rktsph/geometry/crowded_nodes.hpp"
#include "rktsph/geometry/formed_node_sets.hpp"
#include "rktsph/geometry/triangle_mesher.hpp"
#include "rktsph/geometry/triangle_node_sets.hpp"
#include "rktsph/materials/material_factory.hpp"
#include "rktsph/mesh/cell_geometry.hpp"
#include "rktsph/models/saturated_vpw.hpp"
#include "rktsph/sph/cell_stencils.hpp"

namespace rktsph {

namespace {

// epsilon_s of docs/theory.md eq. 3.5, checked against its stability limit (1 - C^2)/C^2 at the
// run's Courant number C (eq. 3.7; test
// ZeroEnergyControlsSlow.StrainStiffnessIsStableBelowItsLimitAndRejectedAbove).
double strain_hourglass_stiffness(const NumericsSpec& numerics, double courant) {
  const double limit = std::max((1.0 - courant * courant) / (courant * courant), 0.0);
  const double epsilon = numerics.strain_hourglass_stiffness;
  if (epsilon > limit)
    throw InputError(
        numerics.where, "numerics.hourglass.strain_stiffness", fmt::format("{}", epsilon),
        fmt::format("at Courant number {:.3g} the strain hourglass stiffness makes the "
                    "step unstable above (1 - C^2)/C^2 = {:.3g} (docs/theory.md eq. "
                    "3.7)",
                    courant, limit),
        fmt::format("a number in [0, {:.3g}], or a smaller courant", limit));
  return epsilon;
}

// beta of docs/theory.md eq. 3.12: by default on triangles only; one strain control at a time.
double patch_stiffness(const CaseDescription& description) {
  const NumericsSpec& numerics = description.numerics;
  const double beta = numerics.patch_stiffness.value_or(
      description.geometry.cells == CellLayout::Triangles && description.dimension == 2
          ? kDefaultTrianglePatchStiffness
          : 0.0);
  if (beta > 0.0 && numerics.strain_hourglass_stiffness > 0.0)
    throw InputError(numerics.where, "numerics.hourglass.strain_stiffness",
                     fmt::format("{}", numerics.strain_hourglass_stiffness),
                     fmt::format("the strain hourglass stiffness and the patch strain stiffness "
                                 "(patch_stiffness {}{}) are two forms of one control "
                                 "(docs/theory.md §3.4); a case takes one",
                                 beta, numerics.patch_stiffness ? "" : ", the triangles' default"),
                     "0, or numerics.hourglass.patch_stiffness: 0");
  return beta;
}

// epsilon of docs/theory.md eq. 3.3, by default on in 2D with the mean-velocity stress update (1,
// lowered to 0.05 around viscoplastic flow by eq. 3.10). With the half-step update the nodal stress
// and the hourglass forces keep two memories of the motion, and a loaded body creeps while they
// drift apart (theory §3.4), so that pair is refused.
HourglassStrength hourglass_stiffness(const NumericsSpec& numerics, StressUpdate update,
                                      int dimension) {
  if (dimension < 2) return {};
  if (!numerics.hourglass_stiffness)
    return update == StressUpdate::MeanVelocity
               ? HourglassStrength{kDefaultHourglassStiffness,
                                   kDefaultViscoplasticHourglassStiffness}
               : HourglassStrength{};
  const double epsilon = *numerics.hourglass_stiffness;
  if (epsilon > 0.0 && update != StressUpdate::MeanVelocity)
    throw InputError(numerics.where, "numerics.hourglass.stiffness", fmt::format("{}", epsilon),
                     "the hourglass stiffness needs the mean-velocity stress update: with "
                     "stress_update: half_step the nodal stress and the hourglass forces drift "
                     "apart and a loaded body creeps (docs/theory.md §3.4)",
                     "0 with numerics.stress_update: half_step, or stress_update: mean_velocity");
  return {epsilon, epsilon};
}

// The size of the lattice, estimated from the shapes in double before anything is allocated, so
// that a wrong spacing or coordinate is refused at once instead of exhausting memory.
NodeEstimate checked_node_estimate(const CaseDescription& description,
                                   const SimulationLimits& limits) {
  const GeometrySpec& geometry = description.geometry;
  const NodeEstimate estimate = estimate_node_sets(geometry, description.dimension);
  const double memory =
      estimated_run_memory(description.model, estimate.sph_nodes, estimate.lattice_points,
                           description.numerics.h_over_dx);
  // The node lookup spans the bounding box: far-apart shapes cost memory without nodes.
  const double lattice_limit = 16.0 * limits.max_nodes;
  if (estimate.sph_nodes <= limits.max_nodes && estimate.lattice_points <= lattice_limit)
    return estimate;
  if (!geometry.mesh.empty())
    throw InputError(geometry.mesh_where, "geometry.mesh", geometry.mesh,
                     fmt::format("the mesh has {:.0f} SPH nodes, about {:.3g} GB of memory, above "
                                 "the limit of {:.3g} nodes",
                                 estimate.sph_nodes, memory * 1e-9, limits.max_nodes),
                     "a coarser mesh; to run it anyway, raise the limit with --max-nodes N (run "
                     "and check)");
  const ShapeSpec& largest = geometry.shapes[estimate.largest_shape];
  const std::string problem =
      estimate.sph_nodes > limits.max_nodes
          ? fmt::format(
                "the shapes ask for about {:.3g} SPH nodes at this spacing (the shape at "
                "{} alone {:.3g}), about {:.3g} GB of memory, above the limit of {:.3g} "
                "nodes",
                estimate.sph_nodes, largest.where.to_string(), estimate.largest_shape_nodes,
                memory * 1e-9, limits.max_nodes)
          : fmt::format(
                "the shapes' bounding box spans about {:.3g} lattice points at this "
                "spacing, above the limit of {:.3g} (16 x --max-nodes)",
                estimate.lattice_points, lattice_limit);
  throw InputError(geometry.where, "geometry.spacing", fmt::format("{}", geometry.spacing), problem,
                   "a coarser spacing or smaller shapes; to run it anyway, raise the limit with "
                   "--max-nodes N (run and check)");
}

const Parameter* find_parameter(const ParameterBlock& block, const std::string& key) {
  const auto it = block.values.find(key);
  return it == block.values.end() ? nullptr : &it->second;
}

// c_p of every material finite and positive: the time step is C dx / c_p (a density of 1e-308
// made it 0).
void check_wave_speeds(const CaseDescription& description, const PhysicsModel& model,
                       const std::vector<std::string>& material_names) {
  for (std::size_t k = 0; k < material_names.size(); ++k) {
    const double speed = model.wave_speed(static_cast<std::int32_t>(k));
    if (std::isfinite(speed) && speed > 0.0) continue;
    const ParameterBlock& block = description.materials.at(material_names[k]);
    const Material& material = model.material(static_cast<std::int32_t>(k));
    const double young = material.elastic().young_modulus, density = material.density();
    // Blame the value farther (in decades) from a soil's (E ~ 1e8 Pa, rho ~ 2000 kg/m3).
    const bool density_at_fault =
        std::abs(std::log10(density / 2000.0)) > std::abs(std::log10(young / 1e8));
    const std::string key = density_at_fault ? "density" : "young_modulus";
    const Parameter* parameter = find_parameter(block, key);
    throw InputError(parameter ? parameter->where : block.where, block.path + "." + key,
                     fmt::format("{}", density_at_fault ? density : young),
                     fmt::format("the P-wave speed of material '{}' (young_modulus {}, density "
                                 "{}) is {}, so no time step can be derived from it",
                                 material_names[k], young, density, speed),
                     "young_modulus and density whose ratio gives a finite, non-zero wave speed");
  }
}

// The number of steps to time.end, computed in double and checked against time.max_steps before
// it is converted (1e14 s at dt = 1e-5 s overflowed a long to a negative count that passed).
long checked_step_count(const CaseDescription& description, double dt,
                        const std::string& dt_origin) {
  const TimeSpec& time = description.time;
  const double steps = std::ceil(time.end / dt - 1e-9);
  if (std::isfinite(dt) && dt > 0.0 && steps <= static_cast<double>(time.max_steps))
    return static_cast<long>(steps);
  throw InputError(time.where, "time.max_steps", fmt::format("{}", time.max_steps),
                   fmt::format("time.end = {:.6g} s needs {:.4g} steps of dt = {:.4g} s, where {}",
                               time.end, steps, dt, dt_origin),
                   fmt::format("at most max_steps steps: a shorter time.end, a larger dt, or "
                               "max_steps >= {:.4g}",
                               steps));
}

// The run's Courant number C = dt c_p / dx against the stable limit; the error names courant or,
// when dt is given, time_step with the Courant number it implies.
void check_courant(const CaseDescription& description, double courant, double wave_speed, double dx,
                   bool compact_stencils) {
  const NumericsSpec& numerics = description.numerics;
  const double limit = stable_courant_limit(numerics.artificial_viscosity, compact_stencils);
  if (courant <= limit * (1.0 + 1e-9)) return;
  std::string reason = "the two-step Lax-Wendroff limit";
  if (numerics.artificial_viscosity > 0.0)
    reason = fmt::format("with artificial_viscosity {}, sqrt(1 + a^2) - a",
                         numerics.artificial_viscosity);
  if (!compact_stencils && limit == 0.75)
    reason = fmt::format("with h_over_dx = {} (stencils wider than a cell)", numerics.h_over_dx);
  const std::string problem = fmt::format(
      "{}the step is unstable above Courant number {:.4g} ({}, measured: docs/theory.md §2.5)",
      numerics.time_step ? fmt::format("this time step is Courant number C = dt c_p / dx = {:.4g} "
                                       "(c_p = {:.4g} m/s, dx = {} m); ",
                                       courant, wave_speed, dx)
                         : "",
      limit, reason);
  if (numerics.time_step)
    throw InputError(numerics.where, "numerics.time_step", fmt::format("{}", *numerics.time_step),
                     problem,
                     fmt::format("a time step of at most {:.4g} s", limit * dx / wave_speed));
  throw InputError(numerics.where, "numerics.courant", fmt::format("{}", numerics.courant), problem,
                   fmt::format("a number in (0, {:.4g}]", limit));
}

// Row and column of a stress component as the case names it.
std::pair<int, int> stress_indices(const std::string& component) {
  const auto axis = [](char letter) { return letter == 'x' ? 0 : letter == 'y' ? 1 : 2; };
  return {axis(component[0]), axis(component[1])};
}

// The pore-pressure checkerboard term S (docs/theory.md eq. 6.5) is built on the lattice's
// squares: b_c is a square's twist, and lambda_cb the Morris Laplacian's eigenvalue on the
// lattice checkerboard. On triangles neither exists, and nothing calls for S: the cells' P1
// Laplacian (eq. 6.6) is zero only on constants and every triangle's gradient sees every nodal
// pattern but a constant, so no p_w mode escapes both the solve and the momentum balance (§6.3).
void refuse_checkerboard_on_triangles(const CaseDescription& description) {
  if (!description.pore_fluid || description.pore_fluid->checkerboard_stabilisation <= 0.0) return;
  throw InputError(description.pore_fluid->where, "pore_fluid.checkerboard_stabilisation",
                   fmt::format("{}", description.pore_fluid->checkerboard_stabilisation),
                   "the checkerboard stabilisation acts on the p_w checkerboard of a square "
                   "lattice; on triangles the cells' Laplacian has no such mode (docs/theory.md "
                   "§6.3, §6.6)",
                   "0 or no key with geometry.cells: triangles");
}

// Each node's spacing on the cells of the start, for the alpha criterion (eq. 3.15): dx on a
// lattice, on triangles its own length (its stencil's h over h_over_dx, §4.8).
std::vector<double> start_node_spacing(const NodeSets& nodes, double h_over_dx) {
  if (nodes.on_lattice()) return std::vector<double>(nodes.sph_nodes.size(), nodes.spacing);
  std::vector<double> node_h, point_h;
  cell_smoothing_lengths(nodes.cells, nodes.sph_nodes, nodes.stress_points, h_over_dx, node_h,
                         point_h);
  for (double& h : node_h)
    h /= h_over_dx;
  return node_h;
}

}  // namespace

double bending_mode_shape(double xi, double length) {
  // k L = 1.875104..., the first root of cos(kL) cosh(kL) = -1 (clamped-free beam).
  constexpr double kFirstRoot = 1.8751040687119611;
  const double k = kFirstRoot / length;
  const double kl = kFirstRoot;
  const double sigma = (std::cosh(kl) + std::cos(kl)) / (std::sinh(kl) + std::sin(kl));
  const auto shape = [k, sigma](double s) {
    return (std::cosh(k * s) - std::cos(k * s)) - sigma * (std::sinh(k * s) - std::sin(k * s));
  };
  return shape(std::clamp(xi, 0.0, length)) / shape(length);
}

void Assembly::add_initial_stress() {
  const std::size_t n = nodes_.sph_nodes.size();
  for (const auto& [component, parameter] : description_.initial.stress) {
    const auto [row, column] = stress_indices(component);
    const int field = model_->stress_field(row, column);
    if (field < 0) {
      // A zero is harmless; any other value would be dropped silently.
      if (parameter.value == 0.0) continue;
      const std::string carried =
          nodes_.dimension == 1
              ? "xx"
              : (model_->stress_field(2, 2) >= 0 ? "xx, yy, xy, zz" : "xx, yy, xy");
      throw InputError(
          parameter.where, "initial_conditions.stress." + component,
          fmt::format("{}", parameter.value),
          fmt::format("the {}D {} model does not carry the stress component {}", nodes_.dimension,
                      nodes_.dimension == 1                     ? "uniaxial"
                      : description_.plane == PlaneKind::Stress ? "plane-stress"
                                                                : "plane-strain",
                      component),
          fmt::format("components {} (or 0)", carried));
    }
    for (std::size_t i = 0; i < n; ++i)
      state_.fields(field, i) += parameter.value;
  }
}

void Assembly::add_initial_motion() {
  const InitialConditionsSpec& initial = description_.initial;
  if (!initial.angular_velocity && !initial.bending_mode) return;
  // The reader refuses both in 1D; checked again for descriptions built in code.
  if (nodes_.dimension != 2)
    throw InputError(
        initial.angular_velocity ? initial.angular_velocity->where : initial.bending_mode->where,
        initial.angular_velocity ? "initial_conditions.angular_velocity"
                                 : "initial_conditions.bending_mode",
        "", "only allowed in 2D cases", "remove it, or set dimension: 2");
  const auto& position = nodes_.sph_nodes.position;
  const int vx = model_->velocity_field(0), vy = model_->velocity_field(1);
  for (std::size_t i = 0; i < nodes_.sph_nodes.size(); ++i) {
    if (const auto& rotation = initial.angular_velocity) {
      // omega e_z x (X - c)
      state_.fields(vx, i) -= rotation->rate * (position[1][i] - rotation->centre[1]);
      state_.fields(vy, i) += rotation->rate * (position[0][i] - rotation->centre[0]);
    }
    if (const auto& mode = initial.bending_mode)
      state_.fields(vy, i) +=
          mode->tip_velocity * bending_mode_shape(position[0][i] - mode->root, mode->length);
  }
}

std::string Assembly::time_step_origin(const std::vector<std::string>& material_names) const {
  const NumericsSpec& numerics = description_.numerics;
  if (numerics.time_step) return fmt::format("dt is numerics.time_step = {}", *numerics.time_step);
  std::size_t stiffest = 0;
  for (std::size_t k = 1; k < material_names.size(); ++k)
    if (model_->wave_speed(static_cast<std::int32_t>(k)) >
        model_->wave_speed(static_cast<std::int32_t>(stiffest)))
      stiffest = k;
  const Material& material = model_->material(static_cast<std::int32_t>(stiffest));
  return fmt::format(
      "dt = numerics.courant {} x {} {} m / c_p {:.4g} m/s of material '{}' "
      "(young_modulus {}, density {})",
      numerics.courant,
      forms_cells()         ? "the narrowest formed cell's width"
      : nodes_.on_lattice() ? "geometry.spacing"
                            : "the smallest cell's width",
      courant_length_, model_->max_wave_speed(), material_names[stiffest],
      material.elastic().young_modulus, material.density());
}

double stable_courant_limit(double viscosity, bool compact_stencils) {
  const double lax_wendroff = std::sqrt(1.0 + viscosity * viscosity) - viscosity;
  return compact_stencils ? lax_wendroff : std::min(lax_wendroff, 0.75);
}

double estimated_run_memory(ModelKind model, double sph_nodes, double lattice_points,
                            double h_over_dx) {
  const double base = model == ModelKind::DryLargeDeformation ? 3.8e3
                      : model == ModelKind::SaturatedVpw      ? 2.7e3
                                                              : 1.3e3;
  const double bytes_per_node = base + 6.0e3 * std::max(h_over_dx - 0.75, 0.0);
  return sph_nodes * bytes_per_node + 4.0 * lattice_points;
}

double Assembly::estimated_memory() const {
  // The lattice builder's lookup spans the shapes' bounding box (none for triangles).
  return estimated_run_memory(description_.model, static_cast<double>(nodes_.sph_nodes.size()),
                              node_estimate_.lattice_points, description_.numerics.h_over_dx);
}

Assembly::Assembly(CaseDescription description, SimulationLimits limits)
    : description_(std::move(description)) {
  node_estimate_ = checked_node_estimate(description_, limits);
  std::vector<std::unique_ptr<Material>> materials = create_materials(description_.materials);
  std::vector<std::string> material_names;
  for (const auto& entry : description_.materials)
    material_names.push_back(entry.first);
  // The cells the case asks for (docs/theory.md §3.1, §3.6): both builders fill the same NodeSets.
  // A mesh file brings its own triangles and spacing (§3.8).
  if (!description_.geometry.mesh.empty()) {
    nodes_ = build_mesh_node_sets(description_.geometry, material_names);
    description_.geometry.spacing = nodes_.spacing;
  } else {
    nodes_ = description_.geometry.cells == CellLayout::Triangles
                 ? build_triangle_node_sets(description_.geometry, material_names)
                 : build_node_sets(description_.geometry, description_.dimension, material_names);
  }
  groups_ = select_groups(nodes_, description_.groups);

  const NumericsSpec& numerics = description_.numerics;
  registered_ = &rktsph::registered_model(description_.model);
  model_ = registered_->create(description_, std::move(materials));
  check_wave_speeds(description_, *model_, material_names);
  conditions_ = std::make_unique<BoundaryConditions>(description_.boundary_conditions, nodes_,
                                                     groups_, *model_);
  // On a lattice the cells' width is dx; elsewhere the smallest cell sets the step (§2.5).
  courant_length_ =
      nodes_.on_lattice() ? nodes_.spacing : smallest_cell_width(nodes_.cells, nodes_.sph_nodes);
  if (forms_cells()) {
    // Formed cells are triangles: the step is stable up to the Courant number of their narrowest
    // one (§2.5, §9.17; a lattice's Delaunay triangles are dx/sqrt 2 wide), so dt is set by the
    // cells formed at the start.
    node_spacing_ = start_node_spacing(nodes_, description_.numerics.h_over_dx);
    // As form_node_sets forms them: every node kept in a cell.
    const DelaunayCells start = delaunay_cells(nodes_.sph_nodes, node_spacing_,
                                               nodes_.node_material, numerics.reform_alpha, true);
    courant_length_ = std::min(courant_length_, smallest_cell_width(start.cells, nodes_.sph_nodes));
  }
  // dt = C dx / c_p (docs/theory.md §2.5), constant but for a shorter last step: the operators
  // are fixed. Both checked before the operators are built.
  time_step_ = numerics.time_step ? *numerics.time_step
                                  : numerics.courant * courant_length_ / model_->max_wave_speed();
  total_steps_ = checked_step_count(description_, time_step_, time_step_origin(material_names));

  StepOptions options;
  options.kernel = numerics.kernel;
  options.h_over_dx = numerics.h_over_dx;
  options.interpolation_order = numerics.interpolation_order;
  options.hourglass_filter = numerics.hourglass_filter;
  options.hourglass_kappa = numerics.hourglass_kappa;
  options.hourglass_h_over_dx = numerics.hourglass_h_over_dx;
  options.neighbour_search_distance = numerics.neighbour_search_distance;
  options.hourglass_fields = numerics.hourglass_fields;
  options.stress_update = numerics.stress_update.value_or(default_stress_update(nodes_.dimension));
  options.hourglass_stiffness =
      hourglass_stiffness(numerics, options.stress_update, nodes_.dimension);
  if (description_.geometry.cells == CellLayout::Triangles) {
    // The Flanagan-Belytschko stiffness acts on the quadrilaterals' hourglass modes, which
    // triangles do not have (docs/theory.md §3.4).
    if (numerics.hourglass_stiffness && *numerics.hourglass_stiffness > 0.0)
      throw InputError(numerics.where, "numerics.hourglass.stiffness",
                       fmt::format("{}", *numerics.hourglass_stiffness),
                       "the cells' hourglass stiffness acts on the hourglass modes of "
                       "quadrilaterals; triangles have none (docs/theory.md §3.4)",
                       "0 or no key with geometry.cells: triangles");
    options.hourglass_stiffness = {};
    refuse_checkerboard_on_triangles(description_);
  }
  options.hourglass_plastic_fraction = numerics.hourglass_plastic_fraction;
  options.strain_hourglass_stiffness =
      strain_hourglass_stiffness(numerics, time_step_ * model_->max_wave_speed() / courant_length_);
  const double patch = patch_stiffness(description_);
  if (patch > 0.0) {
    if (registered_->operator_policy != OperatorPolicy::ReferenceConfiguration && !forms_cells())
      throw InputError(numerics.where, "numerics.hourglass.patch_stiffness",
                       fmt::format("{}", patch),
                       "the patch strain stiffness fits the cells of the reference "
                       "configuration (docs/theory.md eq. 3.13); this model moves its points",
                       "0 with a moving configuration");
    options.strain_hourglass_stiffness = patch;
    options.strain_control = StrainControl::Patch;
  }
  options.artificial_viscosity = numerics.artificial_viscosity;
  state_.configuration = reference_configuration(nodes_, options.h_over_dx * nodes_.spacing);
  if (!nodes_.on_lattice())  // each point's h from its cells (docs/theory.md §4.8)
    cell_smoothing_lengths(nodes_.cells, state_.configuration.sph_nodes,
                           state_.configuration.stress_points, options.h_over_dx,
                           state_.configuration.node_smoothing_length,
                           state_.configuration.point_smoothing_length);
  StepOperatorBuilder builder(nodes_, options, conditions_->mirror_planes(),
                              conditions_->mirror_axes());
  step_options_ = options;
  step_ = std::make_unique<RkTaylorStep>(*model_, nodes_, options, std::move(builder),
                                         registered_->operator_policy, *conditions_,
                                         state_.configuration);
  if (registered_->operator_policy == OperatorPolicy::CurrentConfiguration)
    step_->set_moving_surface(conditions_.get());  // its faces turn with the body
  const bool compact_stencils = step_->operators().compact_stencils;
  if (numerics.hourglass_fields == HourglassFields::Velocity && !compact_stencils &&
      numerics.hourglass_filter && nodes_.dimension >= 2)
    throw InputError(numerics.where, "numerics.hourglass.fields", "velocity",
                     fmt::format("with h_over_dx = {} a stress point's stencil reaches beyond its "
                                 "cell's corners, and the velocity-only filter then leaves the "
                                 "step unstable (docs/theory.md §3.3)",
                                 numerics.h_over_dx),
                     "all, or h_over_dx below 0.79 (cubic spline; 0.52 for the quintic spline "
                     "and the Gaussian)");
  check_courant(description_, time_step_ * model_->max_wave_speed() / courant_length_,
                model_->max_wave_speed(), courant_length_,
                // Measured in 2D; a 1D bar is exact at C = 1 whatever its stencils.
                compact_stencils || nodes_.dimension < 2);
  if (registered_->create_projection) {
    projection_ = registered_->create_projection(*model_, nodes_, step_->operator_options(),
                                                 *conditions_, description_, time_step_);
    step_->set_projection(projection_.get());
  }
  initialise_state();
  if (forms_cells()) form_cells();
}

namespace {
// The heights of the soil each SPH node stands for: y -+ dx/2, cut at y on a side with no cell
// (a node of the top or bottom surface stands for soil on one side only).
std::vector<std::array<double, 2>> vertical_spans(const NodeSets& nodes) {
  const int d = nodes.dimension;
  const auto vertical = static_cast<std::size_t>(d - 1);
  const std::vector<double>& height = nodes.sph_nodes.position[vertical];
  std::vector<std::array<char, 2>> sides(nodes.sph_nodes.size(), {0, 0});  // below, above
  for (std::size_t p = 0; p < nodes.cells.cell_count(); ++p) {
    const auto corners = nodes.cells.corners(p);
    double centre = 0.0;
    for (const std::int32_t node : corners)
      centre += height[static_cast<std::size_t>(node)] / static_cast<double>(corners.size());
    for (const std::int32_t node : corners) {
      const double y = height[static_cast<std::size_t>(node)];
      if (centre < y - 1e-9 * nodes.spacing) sides[static_cast<std::size_t>(node)][0] = 1;
      if (centre > y + 1e-9 * nodes.spacing) sides[static_cast<std::size_t>(node)][1] = 1;
    }
  }
  std::vector<std::array<double, 2>> spans(sides.size());
  for (std::size_t i = 0; i < spans.size(); ++i)
    spans[i] = {height[i] - (sides[i][0] ? 0.5 * nodes.spacing : 0.0),
                height[i] + (sides[i][1] ? 0.5 * nodes.spacing : 0.0)};
  return spans;
}

// The mass per unit area above SPH node i of a column of its material from the ground surface
// down, each part at the density its body force carries (eq. 6.9): rho_above over the dry part
// above the water table, rho - alpha rho_w over the part below it. Times g_y it is sigma'_v.
double effective_overburden_mass(const SaturatedVpw& model, std::int32_t material,
                                 const PointCloud& sph_nodes, std::size_t i, double surface) {
  const int d = model.dimension();
  const double x = d == 2 ? sph_nodes.position[0][i] : 0.0;
  const double y = sph_nodes.position[static_cast<std::size_t>(d - 1)][i];
  const double table = model.water_table()->height(x);
  const double density = model.material(material).density();
  const double dry = std::max(0.0, surface - std::max(y, table));
  const double wet = std::max(0.0, std::min(surface, table) - y);
  const std::array<double, 2> above = model.body_force_weights(material, x, table + 1.0);
  const std::array<double, 2> below = model.body_force_weights(material, x, table - 1.0);
  return density * (above[0] * dry + below[0] * wet);
}
}  // namespace

void Assembly::initialise_state() {
  const std::size_t n = nodes_.sph_nodes.size();
  const int d = description_.dimension;
  state_.fields = FieldArray(model_->field_count(), n);
  state_.internal = FieldArray(model_->internal_count(), n);
  state_.displacement = FieldArray(d, n);
  if (step_->carries_received_strain()) state_.strain = FieldArray(3, n);
  if (step_->carries_cell_forces())
    state_.hourglass_force = FieldArray(2, nodes_.stress_points.size());
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < d; ++a)
      state_.fields(model_->velocity_field(a), i) = description_.initial.velocity[a];
    model_->initial_internal(nodes_.node_material[i], state_.internal, i);
  }
  auto* saturated = dynamic_cast<SaturatedVpw*>(model_.get());
  const bool water_table = saturated && saturated->has_water_table();
  if (water_table)
    saturated->place_water_table(nodes_.sph_nodes, nodes_.node_material, vertical_spans(nodes_),
                                 state_.internal);
  if (description_.initial.geostatic_surface) {
    // sigma_v = rho g_y (surface - y) (g_y < 0 gives compression), sigma_h = K0 sigma_v; with a
    // water table the effective overburden of eq. 6.9 instead.
    const double surface = *description_.initial.geostatic_surface;
    const double g_vertical =
        description_.gravity ? description_.gravity->acceleration[d - 1] : 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const Material& material = model_->material(nodes_.node_material[i]);
      const double nu = material.elastic().poisson_ratio;
      const double k0 = description_.initial.k0.value_or(nu / (1.0 - nu));
      const double depth = surface - nodes_.sph_nodes.position[d - 1][i];
      const double vertical =
          water_table ? g_vertical * effective_overburden_mass(*saturated, nodes_.node_material[i],
                                                               nodes_.sph_nodes, i, surface)
                      : material.density() * g_vertical * depth;
      state_.fields(model_->stress_field(d - 1, d - 1), i) = vertical;
      for (int a = 0; a < d - 1; ++a)
        state_.fields(model_->stress_field(a, a), i) = k0 * vertical;
      const int zz = model_->stress_field(2, 2);
      if (zz >= 0) state_.fields(zz, i) = k0 * vertical;
    }
  }
  add_initial_stress();
  add_initial_motion();
  conditions_->apply(0.0, state_.fields);
  step_->set_initial_state(state_);
}

namespace {
// A node in no cell has no stress point to take its gradients from: the run stops with where and
// why (docs/theory.md §9.17) rather than integrate it on nothing. form_node_sets keeps every node
// in a cell, so only nodes on a line, with no triangle at all, are left so.
void refuse_isolated_nodes(const FormedNodeSets& made, const State& state, double alpha) {
  if (made.count.isolated_nodes == 0) return;
  std::size_t first = 0;
  while (!made.nodes.cells.cells_of(first).empty())
    ++first;
  throw RunError(fmt::format(
      "forming the cells again at step {} (t = {:.6g} s) left {} node(s) in no cell, first the "
      "node at {}: no Delaunay triangle has it as a corner (the nodes lie on a line there, "
      "numerics.cells.alpha = {} aside), and a node in no cell has no stress point to take its "
      "gradients from (docs/theory.md §9.17). The body has collapsed to a line of nodes: stop "
      "the run before (time.end)",
      state.step, state.time, made.count.isolated_nodes,
      describe_point(made.nodes.sph_nodes, first), alpha));
}
}  // namespace

StepOptions Assembly::formed_cell_options() const {
  // Formed cells are triangles: no Flanagan-Belytschko stiffness (it needs quadrilaterals), and
  // the patch strain stiffness of triangles (eq. 3.12), fitted on the cells as they are formed,
  // unless the case takes the strain stiffness instead (§3.4, §9.17).
  const NumericsSpec& numerics = description_.numerics;
  StepOptions options = step_options_;
  options.hourglass_stiffness = {};
  const double beta = numerics.patch_stiffness.value_or(
      numerics.strain_hourglass_stiffness > 0.0 ? 0.0 : kDefaultTrianglePatchStiffness);
  if (beta > 0.0) {
    options.strain_hourglass_stiffness = beta;
    options.strain_control = StrainControl::Patch;
  }
  return options;
}

bool Assembly::forms_cells() const {
  return description_.numerics.cell_policy == CellPolicy::Reformed &&
         registered_->operator_policy == OperatorPolicy::CurrentConfiguration &&
         nodes_.dimension == 2;
}

int Assembly::step_parts() const {
  if (!forms_cells()) return 1;
  const ConfigurationMotion* motion = step_->motion();
  const double width = motion ? motion->quality().narrowest_width : 0.0;
  if (!(width > 0.0) || width >= courant_length_) return 1;
  // Bounded so that a cell crushed to nothing stops the run at its fold, not in a billion parts.
  return static_cast<int>(std::min(std::ceil(courant_length_ / width), 64.0));
}

bool Assembly::cells_need_forming() const {
  if (!forms_cells()) return false;
  const ConfigurationMotion* motion = step_->motion();
  // A corner squeezed below the ratio, or one stretched beyond its inverse, or a cell drawn out
  // that far (§9.17).
  const double ratio = description_.numerics.reform_corner_ratio;
  if (!motion) return false;
  const CellQuality& quality = motion->quality();
  return quality.smallest_corner_ratio < ratio || quality.largest_corner_ratio * ratio > 1.0 ||
         quality.largest_reach_ratio * ratio > 1.0;
}

void Assembly::form_cells() {
  spread_crowded_nodes_before_forming();
  form_cells_at(state_.configuration.sph_nodes, state_.fields);
}

std::vector<double> Assembly::node_spacing_at(const PointCloud& nodes) const {
  // Each node's spacing now: its spacing at the start stretched as its volume has (eq. 3.15), so
  // that a body that stretches keeps its cells and a node that leaves it does not.
  std::vector<double> spacing(node_spacing_.size());
  for (std::size_t i = 0; i < spacing.size(); ++i)
    spacing[i] = node_spacing_[i] * std::sqrt(nodes.volume[i] / nodes_.sph_nodes.volume[i]);
  return spacing;
}

std::vector<std::vector<Vec3>> Assembly::rigid_bodies_now() const {
  std::vector<std::vector<Vec3>> solids;
  for (const RigidBody& body : conditions_->rigid_bodies())
    solids.push_back(body.polygon_at(state_.time));
  return solids;
}

void Assembly::spread_crowded_nodes_before_forming() {
  // Eq. 9.16: a node crowded against a neighbour moves, its fields with it unchanged; its
  // displacement takes the move, so that x = X + u still holds.
  const double fraction = description_.numerics.spread_below;
  if (!(fraction > 0.0) || !formed_) return;
  PointCloud& positions = state_.configuration.sph_nodes;
  const std::size_t n = positions.size();
  const std::vector<double> spacing = node_spacing_at(positions);
  std::vector<std::uint8_t> held(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < nodes_.dimension; ++a)
      if (conditions_->velocity_imposed(static_cast<std::int32_t>(i), a))
        held[i] |= static_cast<std::uint8_t>(1u << a);
  }
  FieldArray shift(nodes_.dimension, n);
  forming_.nodes_spread +=
      static_cast<long>(spread_crowded_nodes(formed_->cells, formed_->outline, positions, spacing,
                                             fraction, held, rigid_bodies_now(), shift));
  for (int a = 0; a < nodes_.dimension; ++a) {
    const auto axis = static_cast<std::size_t>(a);
    for (std::size_t i = 0; i < n; ++i) {
      positions.position[axis][i] += shift(a, i);
      state_.displacement(a, i) += shift(a, i);
    }
  }
}

void Assembly::form_cells_at(const PointCloud& formation, const FieldArray& fields) {
  const auto start = std::chrono::steady_clock::now();
  Configuration& configuration = state_.configuration;
  const std::vector<double> spacing = node_spacing_at(formation);
  // No cell crosses a rigid body where it is now (§9.18).
  const std::vector<std::vector<Vec3>> solids = rigid_bodies_now();
  FormedNodeSets made =
      form_node_sets(nodes_, formation, spacing, description_.numerics.reform_alpha, solids);
  refuse_isolated_nodes(made, state_, description_.numerics.reform_alpha);
  ++forming_.formings;
  forming_.cells_formed += static_cast<long>(made.nodes.cells.cell_count());
  forming_.triangles_dropped += static_cast<long>(made.count.dropped);
  forming_.triangles_restored += static_cast<long>(made.count.restored);
  forming_.cells_now = made.nodes.cells.cell_count();
  forming_.isolated_nodes = made.count.isolated_nodes;
  forming_.narrowest_cell_ratio =
      std::min(forming_.narrowest_cell_ratio,
               smallest_cell_width(made.nodes.cells, made.nodes.sph_nodes) / courant_length_);
  auto formed = std::make_unique<NodeSets>(std::move(made.nodes));

  // The configuration on the new cells: the nodes where they were formed, with their volumes
  // (eq. 9.11); stress points at the centroids with the cells' areas; each point's h from its
  // cell (§4.8).
  // Held here for the new step's motion (CellFormation); the old step is not used again.
  formation_volume_ = formation.volume;
  if (&formation != &configuration.sph_nodes) configuration.sph_nodes = formation;
  configuration.stress_points = formed->stress_points;
  for (std::size_t p = 0; p < formed->cells.cell_count(); ++p)
    configuration.stress_points.volume[p] = formed->cells.reference_measure(p);
  cell_smoothing_lengths(formed->cells, configuration.sph_nodes, configuration.stress_points,
                         step_options_.h_over_dx, configuration.node_smoothing_length,
                         configuration.point_smoothing_length);
  const CellFormation cell_formation{&nodes_.sph_nodes, formation_volume_};

  auto conditions = std::make_unique<BoundaryConditions>(description_.boundary_conditions, *formed,
                                                         groups_, *model_, state_.time);
  const StepOptions options = formed_cell_options();
  StepOperatorBuilder builder(*formed, options, conditions->mirror_planes(),
                              conditions->mirror_axes());
  if (step_) {
    forming_.earlier_steps += step_->time_split();
    forming_.earlier_neighbour_searches += step_->neighbour_searches();
  }
  auto step = std::make_unique<RkTaylorStep>(*model_, *formed, options, std::move(builder),
                                             registered_->operator_policy, *conditions,
                                             configuration, &cell_formation);
  step->set_moving_surface(conditions.get());
  // The cells' generalised forces belong to the cells that are gone: the new ones start free.
  if (step->carries_cell_forces())
    state_.hourglass_force = FieldArray(2, formed->stress_points.size());
  // The controls start on the new cells from the fields of the forming (eq. 3.8), kept so that a
  // restart starts them alike.
  State at_forming;
  at_forming.fields = fields;
  at_forming.displacement = FieldArray(nodes_.dimension, nodes_.sph_nodes.size());
  for (int a = 0; a < nodes_.dimension; ++a) {
    const auto axis = static_cast<std::size_t>(a);
    for (std::size_t i = 0; i < nodes_.sph_nodes.size(); ++i)
      at_forming.displacement(a, i) =
          formation.position[axis][i] - nodes_.sph_nodes.position[axis][i];
  }
  step->set_initial_state(at_forming);
  formation_fields_ = std::move(at_forming.fields);
  conditions->carry_bodies(*conditions_, state_.time);
  step_ = std::move(step);  // before the conditions and cells it refers to are replaced
  conditions_ = std::move(conditions);
  formed_ = std::move(formed);
  // The configuration as a step leaves it (volumes, faces, contacts from the displacement), which
  // is also what a restart from a checkpoint written now places.
  step_->follow_state(state_);
  forming_.seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void Assembly::begin_body_step(double length) {
  const std::array<double, 3> gravity = model_->body_force(state_.time + 0.5 * length);
  conditions_->begin_body_step(state_.time, length, gravity);
}

void Assembly::save_cell_forming(CheckpointOut& out) const {
  out.put_u32(formed_ ? 1u : 0u);
  if (!formed_) return;
  // Where the cells were last formed: forming them again there gives the same cells (§9.17).
  for (int a = 0; a < nodes_.dimension; ++a)
    out.put_doubles(formed_->sph_nodes.position[static_cast<std::size_t>(a)]);
  out.put_doubles(formation_volume_);
  out.put_fields(formation_fields_);
  for (const long count : {forming_.formings, forming_.cells_formed, forming_.triangles_dropped,
                           forming_.triangles_restored, forming_.divided_steps,
                           static_cast<long>(forming_.most_parts), forming_.nodes_spread})
    out.put_i64(count);
  out.put_f64(forming_.narrowest_cell_ratio);
}

void Assembly::restore_cell_forming(CheckpointIn& in) {
  const bool formed = in.get_u32() == 1u;
  if (formed != (formed_ != nullptr))
    in.fail(formed ? "the checkpoint has cells formed again, this case does not form them"
                   : "this case forms its cells again, the checkpoint has none");
  if (!formed) return;
  PointCloud formation;
  formation.dimension = nodes_.dimension;
  formation.resize(nodes_.sph_nodes.size());
  for (int a = 0; a < nodes_.dimension; ++a)
    in.get_doubles_into(formation.position[static_cast<std::size_t>(a)].data(), formation.size());
  in.get_doubles_into(formation.volume.data(), formation.size());
  FieldArray fields(model_->field_count(), nodes_.sph_nodes.size());
  in.get_fields_into(fields);
  std::array<long, 7> counts{};
  for (long& count : counts)
    count = in.get_i64();
  const double narrowest = in.get_f64();
  form_cells_at(formation, fields);
  forming_.formings = counts[0];
  forming_.cells_formed = counts[1];
  forming_.triangles_dropped = counts[2];
  forming_.triangles_restored = counts[3];
  forming_.divided_steps = counts[4];
  forming_.most_parts = static_cast<int>(counts[5]);
  forming_.nodes_spread = counts[6];
  forming_.narrowest_cell_ratio = narrowest;
}

}  // namespace rktsph
