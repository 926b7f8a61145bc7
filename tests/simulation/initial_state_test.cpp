// The state at t = 0 built from initial_conditions (docs/input-reference.md,
// "initial_conditions"): a uniform stress on top of the geostatic one, refused where the model
// does not carry the component; a rigid rotation and the first cantilever bending mode on top of
// the uniform velocity.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "../support/case_text.hpp"
#include "../support/elastic_block.hpp"
#include "../support/lattices.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::initial_state_test {
namespace {

/// A free 4 m x 2 m block (no boundary conditions, so that nothing overwrites the initial
/// velocity) with `extra` appended.
std::string block(const std::string& plane, const std::string& extra) {
  test::ElasticBlock block;
  block.spacing = 0.5;
  block.shapes = test::ElasticBlock::rectangle(4.0, 2.0);
  block.plane = plane;
  return block.text() + extra;
}

double field_at(const Simulation& simulation, int field, double x, double y) {
  const double dx = simulation.nodes().spacing;
  const std::int32_t node =
      test::lattice_node(simulation.nodes(), static_cast<std::int32_t>(std::lround(x / dx)),
                         static_cast<std::int32_t>(std::lround(y / dx)));
  EXPECT_GE(node, 0) << x << ", " << y;
  return simulation.state().fields(field, static_cast<std::size_t>(node));
}

TEST(InitialState, UniformStressAddsToTheGeostaticStress) {
  const std::string text = block("strain",
                                 "loads: {gravity: {acceleration: [0, -10.0]}}\n"
                                 "initial_conditions:\n"
                                 "  geostatic: {surface: 2.0}\n"
                                 "  stress: {xx: -1000.0, yy: 300.0, xy: 250.0, zz: -50.0}\n");
  const Simulation simulation(read_case_text(text, "block.yaml"));
  const PhysicsModel& model = simulation.model();
  const double k0 = 0.3 / 0.7;
  // Interior nodes only: the traction-free faces overwrite the surface nodes' stress.
  for (const auto& [x, y] : {std::pair{1.0, 0.5}, std::pair{2.5, 1.0}, std::pair{3.0, 1.5}}) {
    const double vertical = 2000.0 * -10.0 * (2.0 - y);
    EXPECT_NEAR(field_at(simulation, model.stress_field(0, 0), x, y), k0 * vertical - 1000.0,
                1e-9 * std::abs(vertical));
    EXPECT_NEAR(field_at(simulation, model.stress_field(1, 1), x, y), vertical + 300.0,
                1e-9 * std::abs(vertical));
    EXPECT_NEAR(field_at(simulation, model.stress_field(2, 2), x, y), k0 * vertical - 50.0,
                1e-9 * std::abs(vertical));
    EXPECT_DOUBLE_EQ(field_at(simulation, model.stress_field(0, 1), x, y), 250.0);
  }
}

TEST(InitialState, StressWithoutGeostaticIsUniform) {
  const Simulation simulation(read_case_text(
      block("stress", "initial_conditions: {stress: {xy: -20.0, zz: 0}}\n"), "block.yaml"));
  EXPECT_DOUBLE_EQ(field_at(simulation, simulation.model().stress_field(0, 1), 2.0, 1.0), -20.0);
  EXPECT_DOUBLE_EQ(field_at(simulation, simulation.model().stress_field(0, 0), 2.0, 1.0), 0.0);
}

TEST(InitialState, StressComponentTheModelDoesNotCarryIsRefusedAtItsKey) {
  const std::string text = block("stress", "initial_conditions:\n  stress: {xx: 1.0, zz: -50.0}\n");
  try {
    Simulation simulation(read_case_text(text, "block.yaml"));
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.location().file, "block.yaml");
    EXPECT_EQ(error.location().line, test::line_of(text, "zz: -50.0"));
    EXPECT_EQ(error.key(), "initial_conditions.stress.zz");
    EXPECT_EQ(error.value(), "-50");
    EXPECT_NE(error.problem().find("plane-stress"), std::string::npos) << error.what();
    EXPECT_NE(error.allowed().find("xx, yy, xy"), std::string::npos) << error.what();
  }
}

TEST(InitialState, OneDimensionalBarTakesOnlyXx) {
  const std::string bar = test::free_bar();
  const Simulation simulation(
      read_case_text(bar + "initial_conditions: {stress: {xx: -7.0}}\n", "bar.yaml"));
  const std::int32_t middle = test::lattice_node(simulation.nodes(), 10, 0);
  EXPECT_DOUBLE_EQ(simulation.state().fields(simulation.model().stress_field(0, 0),
                                             static_cast<std::size_t>(middle)),
                   -7.0);
  const std::string text = bar + "initial_conditions:\n  stress: {yy: 5.0}\n";
  try {
    Simulation refused(read_case_text(text, "bar.yaml"));
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.location().line, test::line_of(text, "yy: 5.0"));
    EXPECT_EQ(error.key(), "initial_conditions.stress.yy");
  }
}

TEST(InitialState, RotationAndBendingModeAddToTheUniformVelocity) {
  const std::string text = block("strain",
                                 "initial_conditions:\n"
                                 "  velocity: [0.1, -0.2]\n"
                                 "  angular_velocity: {rate: 0.5, centre: [1.0, 1.0]}\n"
                                 "  bending_mode: {root: 1.0, length: 2.5, tip_velocity: 0.03}\n");
  const Simulation simulation(read_case_text(text, "block.yaml"));
  const int vx = simulation.model().velocity_field(0), vy = simulation.model().velocity_field(1);
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, std::pair{0.5, 2.0}, std::pair{2.0, 1.5},
                             std::pair{3.5, 0.5}, std::pair{4.0, 2.0}}) {
    const double mode = 0.03 * bending_mode_shape(x - 1.0, 2.5);
    EXPECT_NEAR(field_at(simulation, vx, x, y), 0.1 - 0.5 * (y - 1.0), 1e-14) << x << ", " << y;
    EXPECT_NEAR(field_at(simulation, vy, x, y), -0.2 + 0.5 * (x - 1.0) + mode, 1e-14)
        << x << ", " << y;
  }
  // Behind the root the mode is still; at the tip and beyond it is the tip velocity.
  EXPECT_NEAR(field_at(simulation, vy, 0.5, 1.0), -0.2 + 0.5 * -0.5, 1e-14);
  EXPECT_NEAR(field_at(simulation, vy, 3.5, 1.0), -0.2 + 0.5 * 2.5 + 0.03, 1e-14);
  EXPECT_NEAR(field_at(simulation, vy, 4.0, 1.0), -0.2 + 0.5 * 3.0 + 0.03, 1e-14);
}

TEST(InitialState, BendingModeShapeIsClampedAtTheRootAndOneAtTheTip) {
  const double length = 0.2;
  EXPECT_EQ(bending_mode_shape(0.0, length), 0.0);
  EXPECT_DOUBLE_EQ(bending_mode_shape(length, length), 1.0);
  EXPECT_EQ(bending_mode_shape(-0.1, length), 0.0);
  EXPECT_DOUBLE_EQ(bending_mode_shape(2.0 * length, length), 1.0);
  // f'(0) = 0: the one-sided difference quotient vanishes like f ~ xi^2 at the clamped root.
  const double h = 1e-5 * length;
  EXPECT_LT(std::abs(bending_mode_shape(h, length) / h), 1e-3);
  EXPECT_GT(bending_mode_shape(h, length), 0.0);
  // The mode shape is an eigenfunction of the beam equation: f'''' = k^4 f, checked by finite
  // differences in the middle of the beam; and it rises monotonically from root to tip.
  const double k = 1.8751040687119611 / length, xi = 0.5 * length, d = 1e-3 * length;
  const double fourth =
      (bending_mode_shape(xi - 2 * d, length) - 4 * bending_mode_shape(xi - d, length) +
       6 * bending_mode_shape(xi, length) - 4 * bending_mode_shape(xi + d, length) +
       bending_mode_shape(xi + 2 * d, length)) /
      (d * d * d * d);
  EXPECT_NEAR(fourth / (std::pow(k, 4) * bending_mode_shape(xi, length)), 1.0, 1e-3);
  // Free tip: f''(L) = 0 (no moment), as a centred second difference just inside the tip.
  const double f2 = (bending_mode_shape(length - 2 * d, length) -
                     2 * bending_mode_shape(length - d, length) + 1.0) /
                    (d * d);
  EXPECT_LT(std::abs(f2) / (k * k), 1e-2);
  for (int i = 1; i <= 10; ++i)
    EXPECT_GT(bending_mode_shape(0.1 * i * length, length),
              bending_mode_shape(0.1 * (i - 1) * length, length));
}

TEST(InitialState, InitialMotionBuiltInCodeForABarIsRefused) {
  const std::string bar = test::free_bar();
  CaseDescription description = read_case_text(bar, "bar.yaml");
  description.initial.bending_mode = BendingModeSpec{0.0, 5.0, 0.1, {}};
  try {
    Simulation simulation(description);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "initial_conditions.bending_mode");
    EXPECT_NE(error.problem().find("2D"), std::string::npos);
  }
}

}  // namespace
}  // namespace rktsph::initial_state_test
