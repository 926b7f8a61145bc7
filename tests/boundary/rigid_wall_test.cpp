// The `rigid_wall` boundary condition (docs/input-reference.md, "boundary_conditions";
// docs/theory.md §9.13): a node on the wall keeps only a velocity away from it, and on a rough wall
// does not slip; nodes off the wall are untouched; contacts follow the moving configuration; a zero
// normal is refused at its line.
#include <gtest/gtest.h>

#include <string>

#include "../support/case_text.hpp"
#include "../support/elastic_block.hpp"
#include "rktsph/boundary/boundary_conditions.hpp"
#include "rktsph/core/error.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::rigid_wall_test {
namespace {

std::string block(const std::string& wall) {
  test::ElasticBlock block;
  block.spacing = 0.5;
  block.shapes = test::ElasticBlock::rectangle(3.0, 2.0);
  block.conditions = {"{group: all, rigid_wall: " + wall + "}"};
  return block.text();
}

struct Velocity {
  double x = 0.0, y = 0.0;
};

/// Every node given velocity v, the conditions applied; the result at each node.
std::vector<Velocity> applied(const Simulation& simulation, Velocity v) {
  const int vx = simulation.model().velocity_field(0), vy = simulation.model().velocity_field(1);
  const std::size_t n = simulation.nodes().sph_nodes.size();
  FieldArray fields(simulation.model().field_count(), n);
  for (std::size_t i = 0; i < n; ++i) {
    fields(vx, i) = v.x;
    fields(vy, i) = v.y;
  }
  simulation.boundary_conditions().apply(0.0, fields);
  std::vector<Velocity> out(n);
  for (std::size_t i = 0; i < n; ++i)
    out[i] = {fields(vx, i), fields(vy, i)};
  return out;
}

TEST(RigidWall, RoughWallStopsApproachAndSlipButLetsANodeLeave) {
  Simulation simulation(
      read_case_text(block("{point: [0, 0], normal: [0, 2], surface: rough}"), "block.yaml"));
  const auto& y = simulation.nodes().sph_nodes.position[1];
  for (const Velocity v : {Velocity{0.3, -0.2}, Velocity{0.3, 0.2}}) {
    const auto result = applied(simulation, v);
    for (std::size_t i = 0; i < result.size(); ++i) {
      const bool on_wall = y[i] == 0.0;
      EXPECT_EQ(result[i].x, on_wall ? 0.0 : v.x) << i;
      EXPECT_EQ(result[i].y, on_wall ? std::max(v.y, 0.0) : v.y) << i;
    }
  }
  EXPECT_EQ(simulation.boundary_conditions().nodes_in_contact(), 7u);  // the 7 base nodes
}

TEST(RigidWall, SmoothWallOnlyRemovesTheApproachingNormalVelocity) {
  // An inclined wall through the corner (0, 0), normal (1, 1)/sqrt 2: only the corner touches it.
  Simulation simulation(
      read_case_text(block("{point: [0, 0], normal: [1, 1], surface: smooth}"), "block.yaml"));
  const auto& position = simulation.nodes().sph_nodes.position;
  const auto result = applied(simulation, {-0.5, 0.1});
  for (std::size_t i = 0; i < result.size(); ++i) {
    const bool corner = position[0][i] == 0.0 && position[1][i] == 0.0;
    // v.n = -0.4/sqrt 2 < 0 at the corner: v - (v.n) n = (-0.5, 0.1) + 0.2 (1, 1) = (-0.3, 0.3).
    EXPECT_NEAR(result[i].x, corner ? -0.3 : -0.5, 1e-15) << i;
    EXPECT_NEAR(result[i].y, corner ? 0.3 : 0.1, 1e-15) << i;
  }
}

TEST(RigidWall, ContactsFollowTheMovingNodes) {
  Simulation simulation(
      read_case_text(block("{point: [0, 0], normal: [0, 1], surface: rough}"), "block.yaml"));
  BoundaryConditions conditions = simulation.boundary_conditions();
  PointCloud moved = simulation.nodes().sph_nodes;
  // Lift the whole block 0.1 m, then push one node 0.02 m through the wall.
  for (std::size_t i = 0; i < moved.size(); ++i)
    moved.position[1][i] += 0.1;
  moved.position[1][3] = -0.02;
  conditions.follow_configuration(moved, 0.0);
  EXPECT_EQ(conditions.nodes_in_contact(), 1u);
  EXPECT_NEAR(conditions.deepest_penetration(), 0.02, 1e-15);
}

TEST(RigidWall, AZeroNormalIsRefusedAtItsLine) {
  try {
    read_case_text(block("{point: [0, 0], normal: [0, 0]}"), "block.yaml");
    FAIL() << "a zero normal was accepted";
  } catch (const InputError& error) {
    const std::string text = error.what();
    EXPECT_NE(text.find("normal"), std::string::npos) << text;
    EXPECT_NE(text.find("block.yaml:"), std::string::npos) << text;
  }
}

}  // namespace
}  // namespace rktsph::rigid_wall_test
