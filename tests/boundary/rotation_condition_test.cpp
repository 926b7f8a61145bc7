// The `rotation` boundary condition (docs/input-reference.md, "boundary_conditions"): the imposed
// velocity of every node of the group is that of the rigid rotation about the centre, it imposes
// both components like `fixed` (faces and conflicts), and a zero rate is refused.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "../support/case_text.hpp"
#include "../support/elastic_block.hpp"
#include "../support/lattices.hpp"
#include "rktsph/boundary/boundary_conditions.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::rotation_condition_test {
namespace {

/// A 3 m x 2 m block whose left part, a box reaching into the body (so that the rigid-body check
/// has nodes off one line), turns about (0.5, 1.25) at `omega`; `extra`: one more condition.
std::string block(const std::string& omega, const std::string& extra = "") {
  test::ElasticBlock block;
  block.spacing = 0.5;
  block.shapes = test::ElasticBlock::rectangle(3.0, 2.0);
  block.groups = "{plate: {box: {min: [0, 0], max: [1, 2]}}}";
  block.conditions = {"{group: plate, rotation: {angular_velocity: " + omega +
                      ", centre: [0.5, 1.25]}}"};
  if (!extra.empty()) block.conditions.push_back(extra);
  return block.text();
}

struct Velocity {
  double x = 0.0, y = 0.0;
};

/// v(t) = omega e_z x R(omega t)(X - c), written out.
Velocity rigid_rotation(double omega, double cx, double cy, double x, double y, double t) {
  const double rx = x - cx, ry = y - cy;
  const double s = std::sin(omega * t), c = std::cos(omega * t);
  return {-omega * (s * rx + c * ry), omega * (c * rx - s * ry)};
}

class RotationCondition : public testing::TestWithParam<double> {};

TEST_P(RotationCondition, ImposesTheRigidRotationVelocity) {
  const double omega = GetParam();
  Simulation simulation(read_case_text(block(fmt::format("{}", omega)), "block.yaml"));
  const auto& group = simulation.assembly().groups().at("plate");
  const auto& position = simulation.nodes().sph_nodes.position;
  const int vx = simulation.model().velocity_field(0), vy = simulation.model().velocity_field(1);
  ASSERT_GE(group.size(), 9u);
  for (const double t : {0.0, 0.013, 0.5, 2.0, 7.25}) {
    FieldArray fields(simulation.model().field_count(), simulation.nodes().sph_nodes.size());
    simulation.boundary_conditions().apply(t, fields);
    std::vector<double> x, y, u, v;
    for (const std::int32_t node : group) {
      const auto i = static_cast<std::size_t>(node);
      const Velocity expected = rigid_rotation(omega, 0.5, 1.25, position[0][i], position[1][i], t);
      const double radius = std::hypot(position[0][i] - 0.5, position[1][i] - 1.25);
      const double scale = std::abs(omega) * std::max(radius, 1e-300);
      EXPECT_NEAR(fields(vx, i), expected.x, 1e-12 * scale) << "t = " << t << ", node " << node;
      EXPECT_NEAR(fields(vy, i), expected.y, 1e-12 * scale) << "t = " << t << ", node " << node;
      // The node's place at t, from its reference position.
      const double rx = position[0][i] - 0.5, ry = position[1][i] - 1.25;
      x.push_back(0.5 + std::cos(omega * t) * rx - std::sin(omega * t) * ry);
      y.push_back(1.25 + std::sin(omega * t) * rx + std::cos(omega * t) * ry);
      u.push_back(fields(vx, i));
      v.push_back(fields(vy, i));
    }
    // A rigid motion: every relative velocity is perpendicular to the relative position, so the
    // symmetric velocity gradient vanishes.
    for (std::size_t a = 0; a < x.size(); ++a)
      for (std::size_t b = a + 1; b < x.size(); ++b) {
        const double dx = x[b] - x[a], dy = y[b] - y[a];
        const double du = u[b] - u[a], dv = v[b] - v[a];
        EXPECT_NEAR(du * dx + dv * dy, 0.0, 1e-12 * std::abs(omega) * (dx * dx + dy * dy))
            << "t = " << t << ", nodes " << a << ", " << b;
      }
  }
}

INSTANTIATE_TEST_SUITE_P(CounterClockwiseAndClockwise, RotationCondition,
                         testing::Values(0.8, -3.0));

TEST(RotationCondition, ImposesBothComponentsLikeFixed) {
  Simulation simulation(read_case_text(block("1.0"), "block.yaml"));
  const BoundaryConditions& conditions = simulation.boundary_conditions();
  const auto& group = simulation.assembly().groups().at("plate");
  for (const std::int32_t node : group) {
    EXPECT_TRUE(conditions.velocity_imposed(node, 0));
    EXPECT_TRUE(conditions.velocity_imposed(node, 1));
  }
  // The plate's left face (x = 0): both traction components are reactions, none projected.
  const SurfaceSet& surface = conditions.surface();
  const std::int32_t left = test::lattice_node(simulation.nodes(), 0, 2);
  const auto k = std::find(surface.node.begin(), surface.node.end(), left);
  ASSERT_NE(k, surface.node.end());
  const auto index = static_cast<std::size_t>(k - surface.node.begin());
  EXPECT_EQ(surface.projected_normals(index).count, 0);
  for (std::int32_t f = surface.facets_begin(index); f < surface.facets_end(index); ++f)
    EXPECT_EQ(surface.reactions[static_cast<std::size_t>(f)], 3u);
}

TEST(RotationCondition, ConflictsWithOtherVelocitiesButNotWithItself) {
  try {
    Simulation(read_case_text(block("1.0", "{group: xmin, fixed: true}"), "block.yaml"));
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& error) {
    const std::string text = block("1.0", "{group: xmin, fixed: true}");
    EXPECT_EQ(error.location().line, test::line_of(text, "fixed: true"));
    EXPECT_NE(error.problem().find("'rotation' condition on group 'plate' at block.yaml:" +
                                   std::to_string(test::line_of(text, "rotation:"))),
              std::string::npos)
        << error.what();
  }
  // A different rotation of the same nodes conflicts; the same one written twice does not.
  const auto turning = [](const std::string& omega) {
    return "{group: xmin, rotation: {angular_velocity: " + omega + ", centre: [0.5, 1.25]}}";
  };
  EXPECT_THROW(Simulation(read_case_text(block("1.0", turning("2.0")), "block.yaml")), InputError);
  EXPECT_NO_THROW(Simulation(read_case_text(block("1.0", turning("1.0")), "block.yaml")));
}

TEST(RotationCondition, ZeroRateBuiltInCodeIsRefused) {
  CaseDescription description = read_case_text(block("1.0"), "block.yaml");
  description.boundary_conditions[0].angular_velocity = 0.0;
  try {
    Simulation simulation(description);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "boundary_conditions.rotation.angular_velocity");
    EXPECT_EQ(error.value(), "0");
    EXPECT_NE(error.problem().find("angular_velocity must be non-zero"), std::string::npos);
  }
}

}  // namespace
}  // namespace rktsph::rotation_condition_test
