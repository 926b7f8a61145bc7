// Two rigid-motion tests of the large-deformation model (docs/theory.md §9.2, §9.8):
//
// ld-rotation-objectivity: a block pre-stressed uniformly (sigma_0), every node driven through a
// rigid quarter turn about its centre. The exact stress is R(wt) sigma_0 R(wt)^T at every node.
//   stress_rotation_error  the largest |sigma - R sigma_0 R^T| (Frobenius) over every node and
//                          every sampled time, over |sigma_0|.
//
// ld-spinning-square: a free elastic square set spinning (the SPHinXsys updated-Lagrangian test,
// L = 1 m, rho = 1100 kg/m3, E = 17 MPa, nu = 0.45, w = 50 rad/s).
//   angular_momentum_error  the largest |L_z(t) - L_z(0)| / |L_z(0)|, L_z = sum m (x - x_c) x v
//                           about the centre of mass, over every sampled time.
//   min_spacing_ratio       the smallest distance between two SPH nodes at any sampled time, over
//                           dx: clumping (tensile instability) would pull pairs together.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph::case_checks::ld_rigid_motion {

namespace {

struct RotationStress {
  double xx, yy, xy;
};

// R(theta) sigma R(theta)^T for a counter-clockwise rotation R = [[c, -s], [s, c]].
RotationStress rotated(const RotationStress& sigma, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return {c * c * sigma.xx - 2.0 * c * s * sigma.xy + s * s * sigma.yy,
          s * s * sigma.xx + 2.0 * c * s * sigma.xy + c * c * sigma.yy,
          c * s * (sigma.xx - sigma.yy) + (c * c - s * s) * sigma.xy};
}

double frobenius(const RotationStress& s) {
  return std::sqrt(s.xx * s.xx + s.yy * s.yy + 2.0 * s.xy * s.xy);
}

double initial_stress(const CaseDescription& description, const std::string& component) {
  const auto it = description.initial.stress.find(component);
  return it == description.initial.stress.end() ? 0.0 : it->second.value;
}

}  // namespace

std::vector<CheckResult> validate_ld_rotation_objectivity(const ValidationContext& context) {
  std::vector<CaseOverride> overrides;
  if (context.quick) overrides.push_back({"geometry.spacing", "0.2"});
  const CaseDescription description =
      load_bundled_case(context, "ld-rotation-objectivity", overrides);
  const auto& rotation = description.boundary_conditions.front();
  const double rate = rotation.angular_velocity;
  const RotationStress start{initial_stress(description, "xx"), initial_stress(description, "yy"),
                             initial_stress(description, "xy")};
  const double scale = frobenius(start);
  double largest = 0.0;
  std::vector<double> times, errors;
  SampledObserver sampler(0.0, [&](const Simulation& simulation) {
    const State& state = simulation.state();
    const PhysicsModel& model = simulation.model();
    const RotationStress exact = rotated(start, rate * state.time);
    double worst = 0.0;
    for (std::size_t i = 0; i < state.fields.point_count(); ++i) {
      const RotationStress error{state.fields(model.stress_field(0, 0), i) - exact.xx,
                                 state.fields(model.stress_field(1, 1), i) - exact.yy,
                                 state.fields(model.stress_field(0, 1), i) - exact.xy};
      worst = std::max(worst, frobenius(error) / scale);
    }
    largest = std::max(largest, worst);
    times.push_back(state.time);
    errors.push_back(worst);
  });
  const auto run =
      run_for_validation(context, description, context.quick ? "quick" : "full", {}, {&sampler});
  if (context.report) {
    context.report->describe(
        "A 1 m square block, pre-stressed uniformly (sigma_xx = -100 kPa, sigma_yy = -40 kPa, "
        "sigma_xy = 20 kPa), every node driven through a rigid quarter turn at 2 rad/s with the "
        "large-deformation model. The stress must turn with the block: sigma(t) = R sigma_0 R^T, "
        "with no strain. The Jaumann rate integrated as a Hughes-Winget rotation, with the "
        "velocity gradient taken on the mid-step configuration, turns it exactly.");
    context.report->add_figure({"stress_rotation_error",
                                "Largest error of the rotated stress over the nodes",
                                "time [s]",
                                "|sigma - R sigma_0 R^T| / |sigma_0|",
                                {{"large deformation", times, errors, "line"}}});
    context.report->add_picture({"stress_xx_end", run.string(), "stress", 0, -1.0, 1.0,
                                 "sigma_xx after the quarter turn: sigma_yy of the start"});
  }
  return {check_at_most("stress_rotation_error", largest, 0.0, 0.01, "fraction")};
}

std::vector<CheckResult> validate_ld_spinning_square(const ValidationContext& context) {
  std::vector<CaseOverride> overrides;
  if (context.quick) {
    overrides.push_back({"geometry.spacing", "0.1"});
    overrides.push_back({"time.end", "0.15"});
  }
  const CaseDescription description = load_bundled_case(context, "ld-spinning-square", overrides);
  const double dx = description.geometry.spacing;
  double initial_momentum = std::numeric_limits<double>::quiet_NaN();
  double momentum_error = 0.0, smallest_spacing = std::numeric_limits<double>::infinity();
  std::vector<double> times, momentum, kinetic;
  SampledObserver sampler(0.0, [&](const Simulation& simulation) {
    const State& state = simulation.state();
    const PhysicsModel& model = simulation.model();
    const NodeSets& nodes = simulation.nodes();
    const PointCloud& x = state.configuration.sph_nodes;
    const std::size_t n = x.size();
    double mass = 0.0, cx = 0.0, cy = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double m = model.density(nodes.node_material[i]) * nodes.sph_nodes.volume[i];
      mass += m;
      cx += m * x.position[0][i];
      cy += m * x.position[1][i];
    }
    cx /= mass;
    cy /= mass;
    double lz = 0.0, energy = 0.0;
    const double* vx = state.fields.field(model.velocity_field(0));
    const double* vy = state.fields.field(model.velocity_field(1));
    for (std::size_t i = 0; i < n; ++i) {
      const double m = model.density(nodes.node_material[i]) * nodes.sph_nodes.volume[i];
      lz += m * ((x.position[0][i] - cx) * vy[i] - (x.position[1][i] - cy) * vx[i]);
      energy += 0.5 * m * (vx[i] * vx[i] + vy[i] * vy[i]);
    }
    if (std::isnan(initial_momentum)) initial_momentum = lz;
    momentum_error = std::max(momentum_error, std::abs(lz - initial_momentum) / initial_momentum);
    double closest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        closest = std::min(closest, std::hypot(x.position[0][i] - x.position[0][j],
                                               x.position[1][i] - x.position[1][j]));
    smallest_spacing = std::min(smallest_spacing, closest / dx);
    times.push_back(state.time);
    momentum.push_back(lz / initial_momentum);
    kinetic.push_back(energy);
  });
  const auto run =
      run_for_validation(context, description, context.quick ? "quick" : "full", {}, {&sampler});
  if (context.report) {
    context.report->describe(fmt::format(
        "A free elastic square (L = 1 m, rho = 1100 kg/m3, E = 17 MPa, nu = 0.45, plane strain) "
        "set spinning at 50 rad/s about its centre, run with the large-deformation model for "
        "{:g} s (about {:.1f} turns). The corners move at 35 m/s, half the shear-wave speed: the "
        "square stretches and oscillates as it turns. Angular momentum must be conserved and "
        "the particles must not clump (tensile instability).",
        description.time.end, description.time.end * 50.0 / (2.0 * std::acos(-1.0))));
    context.report->add_figure({"angular_momentum",
                                "Angular momentum about the centre of mass",
                                "time [s]",
                                "L_z / L_z(0)",
                                {{"SPH", times, momentum, "line"}}});
    context.report->add_figure({"kinetic_energy",
                                "Kinetic energy",
                                "time [s]",
                                "[J/m]",
                                {{"SPH", times, kinetic, "line"}}});
    context.report->add_picture({"stress_end", run.string(), "stress", -1, -1.0, 1.0,
                                 "|sigma| on the spinning square at the end"});
  }
  return {check_at_most("angular_momentum_error", momentum_error, 0.0, 0.01, "fraction"),
          check_at_least("min_spacing_ratio", smallest_spacing, 1.0, 0.5, "ratio")};
}

}  // namespace rktsph::case_checks::ld_rigid_motion
