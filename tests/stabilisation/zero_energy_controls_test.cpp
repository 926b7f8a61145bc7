// The zero-energy-mode controls (docs/theory.md §3.4): the cells' hourglass stiffness (eqs.
// 3.2-3.4) and the strain hourglass stiffness of nodal stress storage (eqs. 3.5-3.8).
// - each vanishes on the displacement fields it must leave alone (patch test);
// - each resists its mode with the stiffness the equations give;
// - with the mean-velocity stress update (eq. 2.5) and the cells' hourglass stiffness, a damped
//   lattice under a traction with a kink has a static state (a fixed point of the step with zero
//   velocity); without the stiffness it has none, and the kink drives a creep;
// - the step stays stable (spectral radius <= 1 + 1e-8) with every boundary type and the kink,
//   at h = 0.75 dx and 1.3 dx (to 1 + 1e-8: see kNeutral); the strain stiffness is stable below its
//   limit (1 - C^2)/C^2 (eq. 3.7) and the case file refuses it above.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "../support/elastic_block.hpp"
#include "../support/lattices.hpp"
#include "../support/step_matrix.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/core/error.hpp"
#include "rktsph/simulation/simulation.hpp"
#include "rktsph/sph/adjoint_operator.hpp"
#include "rktsph/stabilisation/hourglass_stiffness.hpp"
#include "rktsph/stabilisation/hourglass_stiffness_control.hpp"

namespace rktsph::zero_energy_controls_test {
namespace {

// The cells' Flanagan-Belytschko stiffness of the step; throws (failing the test) where none acts.
const HourglassStiffness& cell_stiffness_of(const Simulation& simulation) {
  const auto* control = simulation.step().control<HourglassStiffnessControl>();
  if (control == nullptr) throw std::runtime_error("the step has no cell hourglass stiffness");
  return control->stiffness();
}

// rho = 2000 kg/m3, E = 10 MPa, nu = 0.3 (test::ElasticBlock): M = lambda + 2G, G.
constexpr double kDensity = 2000.0;
const double kShear = 1.0e7 / 2.6;
const double kLambda = 1.0e7 * 0.3 / (1.3 * 0.4);
const double kConstrained = kLambda + 2.0 * kShear;

test::ElasticBlock block_with_controls(double epsilon, double epsilon_s, double courant = 0.5,
                                       const std::string& h = "0.75",
                                       const std::string& update = "mean_velocity") {
  test::ElasticBlock block;
  block.numerics = fmt::format(
      "{{courant: {}, h_over_dx: {}, stress_update: {}, hourglass: {{stiffness: {}, "
      "strain_stiffness: {}}}}}",
      courant, h, update, epsilon, epsilon_s);
  return block;
}

TEST(HourglassStiffness, CellVectorsAndStiffnessOnTheLattice) {
  Simulation simulation(block_with_controls(1.0, 0.0).description());
  const HourglassStiffness& control = cell_stiffness_of(simulation);
  ASSERT_TRUE(control.active());
  ASSERT_EQ(control.corners.size(), simulation.nodes().stress_points.size());
  for (std::size_t p = 0; p < control.corners.size(); ++p) {
    // On a square the Flanagan–Belytschko vector is h itself (eq. 3.2) ...
    const double h[4] = {1.0, -1.0, 1.0, -1.0};
    for (int a = 0; a < 4; ++a)
      EXPECT_NEAR(control.gamma[p][a], h[a], 1e-12);
    // ... and epsilon = 1 is the fully integrated bilinear element's hourglass energy,
    // k = (M + G)/12 (eq. 3.3).
    EXPECT_NEAR(control.stiffness[p], (kConstrained + kShear) / 12.0, 1e-6 * kConstrained);
  }
}

// The strength of each cell follows the flow around it (eq. 3.10): 1 away from flow, the
// near-flow ratio within kFlowNeighbourhood rings of a cell that flows or has flowed, psi times
// it in a flowing cell itself.
TEST(HourglassStiffness, StrengthFollowsTheFlowAroundTheCell) {
  Simulation simulation(block_with_controls(1.0, 0.0).description());
  HourglassStiffness control = cell_stiffness_of(simulation);
  ASSERT_TRUE(control.active());
  // An elastic material keeps its strength next to flow.
  for (double ratio : control.near_flow)
    EXPECT_EQ(ratio, 1.0);
  const double ratio = 0.05, psi = 0.4;
  std::fill(control.near_flow.begin(), control.near_flow.end(), ratio);
  const std::size_t cells = control.corners.size();
  // The lattice's cells by their lower-left corner's position.
  const auto& position = simulation.nodes().sph_nodes.position;
  const auto lower_left = [&](std::size_t p) {
    double x = 1e300, y = 1e300;
    for (std::int32_t node : control.corners[p]) {
      x = std::min(x, position[0][static_cast<std::size_t>(node)]);
      y = std::min(y, position[1][static_cast<std::size_t>(node)]);
    }
    return std::array<double, 2>{x, y};
  };
  std::size_t centre = cells;
  for (std::size_t p = 0; p < cells; ++p)
    if (lower_left(p) == std::array<double, 2>{6.0, 2.0}) centre = p;
  ASSERT_LT(centre, cells);
  std::vector<std::uint8_t> near_node(control.inverse_mass.size(), 0);
  std::vector<double> factor(cells, -1.0);
  for (const std::uint8_t state : {std::uint8_t{1}, std::uint8_t{2}}) {  // flows, has flowed
    std::vector<std::uint8_t> flowing(cells, 0);
    flowing[centre] = state;
    flow_strength_factors(simulation.nodes().cells, control.near_flow, flowing, psi, near_node,
                          factor);
    for (std::size_t p = 0; p < cells; ++p) {
      const auto corner = lower_left(p);
      const bool near = std::abs(corner[0] - 6.0) <= kFlowNeighbourhood &&
                        std::abs(corner[1] - 2.0) <= kFlowNeighbourhood;
      const double expected = p == centre && state == 1 ? psi * ratio : near ? ratio : 1.0;
      EXPECT_DOUBLE_EQ(factor[p], expected) << "cell at " << corner[0] << ", " << corner[1];
    }
  }
  // No flow: every cell at full strength.
  flow_strength_factors(simulation.nodes().cells, control.near_flow,
                        std::vector<std::uint8_t>(cells, 0), psi, near_node, factor);
  for (double value : factor)
    EXPECT_EQ(value, 1.0);
}

// The acceleration (eq. 3.4) of the hourglass forces k q of a displacement u (eq. 3.9 from rest).
void hourglass_acceleration(const HourglassStiffness& control, const FieldArray& displacement,
                            FieldArray& forces, FieldArray& rate) {
  const std::vector<double> elastic(forces.point_count(), 1.0);
  std::fill(forces.data().begin(), forces.data().end(), 0.0);
  advance_hourglass_force(control, displacement, {0, 1}, 1.0, elastic, forces, forces);
  add_hourglass_acceleration(control, forces, {0, 1}, rate);
}

TEST(HourglassStiffness, LeavesLinearFieldsAndRigidRotationAloneAndResistsTheCheckerboard) {
  const double epsilon = 0.4;
  Simulation simulation(block_with_controls(epsilon, 0.0).description());
  const HourglassStiffness& control = cell_stiffness_of(simulation);
  const NodeSets& nodes = simulation.nodes();
  const std::size_t n = nodes.sph_nodes.size();
  FieldArray displacement(2, n), forces(2, nodes.stress_points.size()), rate(2, n);
  // A linear field plus a small rigid rotation: no force anywhere.
  for (std::size_t i = 0; i < n; ++i) {
    const double x = nodes.sph_nodes.position[0][i], y = nodes.sph_nodes.position[1][i];
    displacement(0, i) = 1e-3 + 2e-4 * x - 3e-4 * y;
    displacement(1, i) = -2e-3 + 3e-4 * x + 5e-4 * y;
  }
  hourglass_acceleration(control, displacement, forces, rate);
  for (double a : rate.data())
    EXPECT_NEAR(a, 0.0, 1e-9);
  // The checkerboard u_x = U (-1)^(i+j): at an interior node -(16 k / (rho dx^2)) u_x (eq. 3.4).
  const double amplitude = 1e-3;
  for (std::size_t i = 0; i < n; ++i) {
    const auto index = test::lattice_index(nodes, i);
    displacement(0, i) = ((index[0] + index[1]) % 2 == 0 ? 1.0 : -1.0) * amplitude;
    displacement(1, i) = 0.0;
  }
  std::fill(rate.data().begin(), rate.data().end(), 0.0);
  hourglass_acceleration(control, displacement, forces, rate);
  const double k = epsilon * (kConstrained + kShear) / 12.0;
  int interior = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto index = test::lattice_index(nodes, i);
    if (index[0] == 0 || index[1] == 0 || index[0] == test::lattice_extent(nodes)[0] - 1 ||
        index[1] == test::lattice_extent(nodes)[1] - 1)
      continue;
    EXPECT_NEAR(rate(0, i), -16.0 * k / kDensity * displacement(0, i), 1e-9 * k);
    EXPECT_NEAR(rate(1, i), 0.0, 1e-12);
    ++interior;
  }
  EXPECT_GT(interior, 10);
}

// A block between two mirror planes y = 0 and y = H, free faces x = 0 and x = W: u_x = a x,
// u_y = b y with a = -(lambda/M) b, received by the nodal stress (e = (a, b, 0)), is a
// free-face-consistent linear field, so the strain control must add nothing; the strain mode
// u_x = U (-1)^i has A G u = 0 (the nodal stress receives nothing) and must meet the stiffness
// epsilon_s D G u in the interior.
TEST(StrainHourglassStiffness, NothingOnConsistentLinearFieldsAndFullStiffnessOnTheStrainMode) {
  const double epsilon_s = 0.2;
  test::ElasticBlock block;
  // The velocity filter would also damp the mode by 1 - kappa in the step: off here.
  block.numerics = fmt::format(
      "{{courant: 0.5, hourglass: {{enabled: false, strain_stiffness: {}}}}}", epsilon_s);
  block.conditions = {"{group: ymin, roller: y}", "{group: ymax, roller: y}"};
  Simulation simulation(block.description());
  const Simulation& view = simulation;
  const NodeSets& nodes = view.nodes();
  State& state = simulation.state();
  const double dt = simulation.time_step();
  const double b = 1e-4, a = -kLambda / kConstrained * b;
  // u at rest, and e the strain the nodal stress has received: (e_xx, e_yy) = (a, b) for the
  // linear field, zero for the strain mode (A G u = 0 there).
  auto stress_after_one_step = [&](auto displacement, double received_xx, double received_yy) {
    std::fill(state.fields.data().begin(), state.fields.data().end(), 0.0);
    std::fill(state.strain.data().begin(), state.strain.data().end(), 0.0);
    for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
      const auto [ux, uy] = displacement(i);
      state.displacement(0, i) = ux;
      state.displacement(1, i) = uy;
      state.strain(0, i) = received_xx;
      state.strain(1, i) = received_yy;
    }
    state.time = 0.0;
    simulation.step().advance(state, dt);
    return state.fields;
  };
  const FieldArray linear = stress_after_one_step(
      [&](std::size_t i) {
        return std::pair{a * nodes.sph_nodes.position[0][i], b * nodes.sph_nodes.position[1][i]};
      },
      a, b);
  for (double value : linear.data())
    EXPECT_NEAR(value, 0.0, 1e-9 * kConstrained * b);
  const double amplitude = 1e-4;
  const FieldArray mode = stress_after_one_step(
      [&](std::size_t i) {
        return std::pair{(test::lattice_index(nodes, i)[0] % 2 == 0 ? 1.0 : -1.0) * amplitude, 0.0};
      },
      0.0, 0.0);
  // Force on an interior node of the mode: 4 epsilon_s M (2U/dx) / dx ... as an acceleration,
  // dv = -dt 4 epsilon_s M u_x / (rho dx^2) (one-point stiffness of the alternating strain).
  int interior = 0;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    const auto index = test::lattice_index(nodes, i);
    if (index[0] < 2 || index[1] < 2 || index[0] > test::lattice_extent(nodes)[0] - 3 ||
        index[1] > test::lattice_extent(nodes)[1] - 3)
      continue;
    const double u = (index[0] % 2 == 0 ? 1.0 : -1.0) * amplitude;
    EXPECT_NEAR(mode(0, i), -dt * 4.0 * epsilon_s * kConstrained * u / kDensity,
                1e-6 * dt * kConstrained * amplitude / kDensity);
    ++interior;
  }
  EXPECT_GT(interior, 5);
}

// The mean-velocity stress update (docs/theory.md eq. 2.5) makes the nodal strain the lumped
// average of the stress points' strains of u, A G u, at every node a face condition does not
// project (here: the interior and the rough base), so that the stress and the displacement are one
// memory of the motion; the half-step update of the thesis (eq. 2.3) does not (O(dt^2) per step).
double largest_strain_mismatch(const std::string& update) {
  test::ElasticBlock block = block_with_controls(0.0, 0.0, 0.5, "0.75", update);
  block.conditions = {"{group: ymin, fixed: true}", "{group: load, traction: {y: -10000.0}}"};
  block.groups = "{load: {box: {min: [0, 5], max: [4, 5]}}}";
  Simulation simulation(block.description());
  for (int step = 0; step < 40; ++step)
    simulation.step().advance(simulation.state(), simulation.time_step());
  const NodeSets& nodes = simulation.nodes();
  const State& state = simulation.state();
  const std::size_t n = nodes.sph_nodes.size();
  const WeightTable& to_points = simulation.step().operators().nodes_to_points;
  FieldArray point_gradient(4, nodes.stress_points.size()), node_strain(4, n);
  const Parity parity[] = {kEven, kEven};  // no mirror planes here
  apply_operator(to_points, state.displacement, parity, nullptr, &point_gradient);
  std::vector<std::int32_t> every(n), none(n, -1);
  for (std::size_t i = 0; i < n; ++i)
    every[i] = static_cast<std::int32_t>(i);
  const AdjointOperator average =
      build_adjoint_operator(to_points, nodes.stress_points.volume, every, none);
  const Parity gradient_parity[] = {kEven, kEven, kEven, kEven};
  const std::uint8_t all[] = {1, 1, 1, 1};
  add_adjoint_interpolation(average, point_gradient, gradient_parity, all, node_strain);
  const int xx = simulation.model().stress_field(0, 0), yy = simulation.model().stress_field(1, 1);
  double largest = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto index = test::lattice_index(nodes, i);
    if (index[0] == 0 || index[0] == test::lattice_extent(nodes)[0] - 1 ||
        index[1] == test::lattice_extent(nodes)[1] - 1)
      continue;  // free sides and the loaded top: their normal stress is projected
    const double sxx = kConstrained * node_strain(0, i) + kLambda * node_strain(3, i);
    const double syy = kLambda * node_strain(0, i) + kConstrained * node_strain(3, i);
    largest = std::max(
        {largest, std::abs(state.fields(xx, i) - sxx), std::abs(state.fields(yy, i) - syy)});
    scale = std::max({scale, std::abs(sxx), std::abs(syy)});
  }
  return largest / scale;
}

TEST(MeanVelocityStressUpdate, NodalStressIsTheLumpedAverageOfTheStressPointsStrainOfU) {
  EXPECT_LT(largest_strain_mismatch("mean_velocity"), 1e-12);
  EXPECT_GT(largest_strain_mismatch("half_step"), 1e-4);
}

TEST(MeanVelocityStressUpdate, HourglassStiffnessWithTheHalfStepUpdateIsRefused) {
  test::ElasticBlock block = block_with_controls(0.5, 0.0, 0.5, "0.75", "half_step");
  try {
    Simulation simulation(block.description());
    ADD_FAILURE() << "stiffness 0.5 with stress_update: half_step was accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "numerics.hourglass.stiffness") << error.what();
    EXPECT_NE(std::string(error.what()).find("mean_velocity"), std::string::npos) << error.what();
  }
}

// Damped block on a rough base, free sides, a traction on part of the top: the kink at the load's
// edge (docs/theory.md §3.4).
// The load steps from q to 0 between the nodes x = 3 and x = 4: drawn over 0 <= x <= 4, which
// leaves the edge node x = 4 half of q, then unloaded over 4 <= x <= 5 (the later condition wins
// at x = 4). `drawn` keeps the load drawn over 0 <= x <= 3 alone, whose edge node carries q/2.
test::ElasticBlock kinked_load_block(double epsilon, double epsilon_s, const std::string& h,
                                     double damping, const std::string& update = "mean_velocity",
                                     bool drawn = false) {
  test::ElasticBlock block = block_with_controls(epsilon, epsilon_s, 0.5, h, update);
  block.shapes = test::ElasticBlock::rectangle(10.0, 5.0);
  block.conditions = {"{group: xmin, roller: x}", "{group: ymin, fixed: true}",
                      "{group: load, traction: {y: -10000.0}}"};
  if (drawn) {
    block.groups = "{load: {box: {min: [0, 5], max: [3, 5]}}}";
  } else {
    block.conditions.push_back("{group: unloaded, traction: {y: 0.0}}");
    block.groups =
        "{load: {box: {min: [0, 5], max: [4, 5]}}, unloaded: {box: {min: [4, 5], max: [5, 5]}}}";
  }
  if (damping > 0.0) block.loads = fmt::format("{{damping: {{coefficient: {}}}}}", damping);
  return block;
}

double fixed_point_residual(double epsilon, double epsilon_s, double* velocity,
                            const std::string& update = "mean_velocity",
                            const std::string& h = "0.75", bool drawn = false) {
  Simulation simulation(
      kinked_load_block(epsilon, epsilon_s, h, 20.0, update, drawn).description());
  const double impedance = kDensity * simulation.model().max_wave_speed();
  const test::AffineStep step = test::affine_step(simulation, impedance);
  const Eigen::MatrixXd system =
      Eigen::MatrixXd::Identity(step.matrix.rows(), step.matrix.cols()) - step.matrix;
  const Eigen::VectorXd x = system.completeOrthogonalDecomposition().solve(step.constant);
  *velocity = x.head(step.velocities).norm() / x.norm();
  return (system * x - step.constant).norm() / step.constant.norm();
}

// A load drawn over its width gives its edge node half the traction (docs/theory.md §5.1): the
// nodal load then does no work on the odd-even mode of the mean-velocity update, which has a
// static state at rest without any control; the half-step update still has none.
TEST(ZeroEnergyControlsSlow, ALoadDrawnOverItsWidthLeavesTheModeUnforced) {
  double velocity = 0.0;
  EXPECT_LT(fixed_point_residual(0.0, 0.0, &velocity, "mean_velocity", "0.75", true), 1e-10);
  EXPECT_LT(velocity, 1e-10);
  EXPECT_GT(fixed_point_residual(0.0, 0.0, &velocity, "half_step", "0.75", true), 1e-3);
}

TEST(ZeroEnergyControlsSlow, AKinkedTractionHasAStaticStateOnlyWithTheControls) {
  double velocity = 0.0;
  // Without the hourglass stiffness the kink does work on a mode nothing resists: no static
  // state, with either stress update.
  EXPECT_GT(fixed_point_residual(0.0, 0.0, &velocity), 1e-3);
  EXPECT_GT(fixed_point_residual(0.0, 0.0, &velocity, "half_step"), 1e-3);
  // With it (the default strength, half of it, and with the strain stiffness too) there is one,
  // at rest.
  for (const auto& [epsilon, epsilon_s] :
       {std::pair{1.0, 0.0}, std::pair{0.5, 0.0}, std::pair{1.0, 0.2}}) {
    EXPECT_LT(fixed_point_residual(epsilon, epsilon_s, &velocity), 1e-10) << epsilon << epsilon_s;
    EXPECT_LT(velocity, 1e-10) << epsilon << " " << epsilon_s;
  }
}

// With the controls the displacement and the received strain join the state, and the cluster of
// static states at |lambda| = 1 grows (five neutral unknowns per node instead of the stresses'
// few); its computed spread in long double reaches ~2e-9. 1e-8 per step would need 1e8 steps to
// grow e-fold, a hundred times the longest run.
constexpr double kNeutral = 1e-8;

double radius(Simulation& simulation) {
  return test::largest_eigenvalue_modulus(test::affine_step(simulation, 1.0).matrix);
}

TEST(ZeroEnergyControlsSlow, StepStaysStableWithTheKinkAtCompactAndWideStencils) {
  for (const char* h : {"0.75", "1.3"})
    for (double epsilon_s : {0.0, 0.2}) {
      test::ElasticBlock block = kinked_load_block(1.0, epsilon_s, h, 0.0);
      block.shapes = test::ElasticBlock::rectangle(6.0, 4.0);
      block.groups =
          "{load: {box: {min: [0, 4], max: [3, 4]}}, unloaded: {box: {min: [3, 4], "
          "max: [4, 4]}}}";
      Simulation simulation(block.description());
      const double r = radius(simulation);
      EXPECT_LE(r, 1.0 + kNeutral) << "h/dx " << h << " epsilon_s " << epsilon_s
                                   << fmt::format(" radius - 1 = {:.3e}", r - 1.0);
    }
}

TEST(ZeroEnergyControlsSlow, StrainStiffnessIsStableBelowItsLimitAndRejectedAbove) {
  // (1 - C^2)/C^2 = 0.235 at C = 0.9 (eq. 3.7).
  test::ElasticBlock block = kinked_load_block(0.0, 0.2, "0.75", 0.0);
  block.shapes = test::ElasticBlock::rectangle(6.0, 4.0);
  block.groups =
      "{load: {box: {min: [0, 4], max: [3, 4]}}, unloaded: {box: {min: [3, 4], max: [4, 4]}}}";
  block.numerics = "{courant: 0.9, hourglass: {strain_stiffness: 0.2}}";
  Simulation stable(block.description());
  EXPECT_LE(radius(stable), 1.0 + kNeutral);
  block.numerics = "{courant: 0.9, hourglass: {strain_stiffness: 0.3}}";
  try {
    Simulation rejected(block.description());
    ADD_FAILURE() << "strain_stiffness 0.3 at C = 0.9 was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("strain_stiffness"), std::string::npos)
        << error.what();
  }
}

// The step calls the controls the case asks for and no other
// (stabilisation/zero_energy_control.hpp), and the state carries what they carry from step to step.
TEST(ZeroEnergyControls, TheStepCallsExactlyTheControlsTheCaseAsksFor) {
  auto names = [](const Simulation& simulation) {
    std::vector<std::string> found;
    for (const auto& control : simulation.step().controls())
      found.emplace_back(control->name());
    return found;
  };
  const Simulation every(block_with_controls(1.0, 0.5).description());
  EXPECT_EQ(names(every), (std::vector<std::string>{"hourglass filter", "hourglass stiffness",
                                                    "strain hourglass stiffness"}));
  EXPECT_EQ(every.state().hourglass_force.point_count(), every.nodes().stress_points.size());
  EXPECT_EQ(every.state().strain.point_count(), every.nodes().sph_nodes.size());
  test::ElasticBlock bare = block_with_controls(0.0, 0.0);
  bare.numerics =
      "{courant: 0.5, stress_update: mean_velocity, hourglass: {enabled: false, "
      "stiffness: 0, strain_stiffness: 0}}";
  const Simulation none(bare.description());
  EXPECT_TRUE(none.step().controls().empty());
  EXPECT_EQ(none.step().control<HourglassStiffnessControl>(), nullptr);
  EXPECT_EQ(none.state().hourglass_force.point_count(), 0u);
  EXPECT_EQ(none.state().strain.point_count(), 0u);
}

}  // namespace
}  // namespace rktsph::zero_energy_controls_test
