// Boundary conditions compiled from a case: which faces are free, where the stress increments are
// projected (docs/theory.md eq. 5.1), mirror planes, traction faces, and the errors for impossible
// input.
#include "rktsph/boundary/boundary_conditions.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "../support/lattices.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::boundary_conditions_test {
namespace {

const char* kBlock = R"(
name: block
dimension: 2
geometry:
  spacing: 1.0
  shapes: [{rectangle: {min: [0, 0], max: [6, 4]}, material: soil}]
materials:
  soil: {model: linear_elastic, density: 2000.0, young_modulus: 1.0e7, poisson_ratio: 0.3}
groups:
  footing: {box: {min: [0, 4], max: [2, 4]}}
boundary_conditions:
  - {group: xmin, fixed: true}
  - {group: ymin, roller: y}
  - {group: footing, traction: {y: -1000.0}}
time: {end: 0.01}
)";

std::int32_t node_at(const Simulation& simulation, double x, double y) {
  return test::lattice_node(simulation.nodes(), static_cast<std::int32_t>(x),
                            static_cast<std::int32_t>(y));
}

/// The normals along which the node's stress increment is projected (none off the surface).
SurfaceNormals projected_normals(const BoundaryConditions& conditions, std::int32_t node) {
  const SurfaceSet& surface = conditions.surface();
  const auto k = std::find(surface.node.begin(), surface.node.end(), node);
  if (k == surface.node.end()) return {};
  return surface.projected_normals(static_cast<std::size_t>(k - surface.node.begin()));
}

TEST(BoundaryConditions, FacesMirrorsAndProjections) {
  Simulation simulation(read_case_text(kBlock, "block.yaml"));
  const BoundaryConditions& conditions = simulation.boundary_conditions();
  ASSERT_EQ(conditions.mirror_planes().size(), 1u);
  EXPECT_EQ(conditions.mirror_planes()[0].axis, 1);
  // The bottom is a mirror plane, not a face.
  const auto& surface_nodes = conditions.surface().node;
  EXPECT_EQ(std::count(surface_nodes.begin(), surface_nodes.end(), node_at(simulation, 3, 0)), 0);
  // The free right face is projected along x; the fixed left face is not (its stress is a
  // reaction); the fixed-free corner at the top left is projected along y (its top face is free).
  const Vec3 x{1.0, 0.0, 0.0}, y{0.0, 1.0, 0.0};
  const SurfaceNormals right = projected_normals(conditions, node_at(simulation, 6, 2));
  ASSERT_EQ(right.count, 1);
  EXPECT_EQ(right.normal[0], x);
  EXPECT_EQ(projected_normals(conditions, node_at(simulation, 0, 2)).count, 0);
  const SurfaceNormals top_left = projected_normals(conditions, node_at(simulation, 0, 4));
  ASSERT_EQ(top_left.count, 1);
  EXPECT_EQ(top_left.normal[0], y);
  const SurfaceNormals corner = projected_normals(conditions, node_at(simulation, 6, 4));
  ASSERT_EQ(corner.count, 2);  // free-free corner
  EXPECT_EQ(corner.normal[0], x);
  EXPECT_EQ(corner.normal[1], y);
}

TEST(BoundaryConditions, TractionIsImposedAsSigmaDotN) {
  Simulation simulation(read_case_text(kBlock, "block.yaml"));
  FieldArray fields(simulation.model().field_count(), simulation.nodes().sph_nodes.size());
  std::fill(fields.data().begin(), fields.data().end(), 123.0);
  simulation.boundary_conditions().apply(0.0, fields);
  const int syy = simulation.model().stress_field(1, 1),
            sxy = simulation.model().stress_field(0, 1);
  // Top face, outward normal +y: sigma_yy = t_y = -1000 under the footing, 0 beyond it.
  EXPECT_DOUBLE_EQ(fields(syy, static_cast<std::size_t>(node_at(simulation, 1, 4))), -1000.0);
  EXPECT_DOUBLE_EQ(fields(sxy, static_cast<std::size_t>(node_at(simulation, 1, 4))), 0.0);
  EXPECT_DOUBLE_EQ(fields(syy, static_cast<std::size_t>(node_at(simulation, 4, 4))), 0.0);
  // Interior untouched; fixed face velocities zero.
  EXPECT_DOUBLE_EQ(fields(syy, static_cast<std::size_t>(node_at(simulation, 3, 2))), 123.0);
  EXPECT_DOUBLE_EQ(fields(0, static_cast<std::size_t>(node_at(simulation, 0, 2))), 0.0);
  EXPECT_DOUBLE_EQ(fields(1, static_cast<std::size_t>(node_at(simulation, 0, 2))), 0.0);
  // The roller: v_y = 0 and sigma_xy = 0 on the mirror plane.
  EXPECT_DOUBLE_EQ(fields(1, static_cast<std::size_t>(node_at(simulation, 3, 0))), 0.0);
  EXPECT_DOUBLE_EQ(fields(sxy, static_cast<std::size_t>(node_at(simulation, 3, 0))), 0.0);
}

TEST(BoundaryConditions, TractionActsOnTheFacetsWithinItsGroup) {
  // The footing group spans 0 <= x <= 2 at dx = 1: the facets [0, 1] and [1, 2] are loaded, so the
  // corner node x = 0 (its top face is that one facet) and x = 1 carry t, the edge node x = 2 half
  // of it (one of its two facets), and the nodal tractions integrate to t times the width.
  Simulation simulation(read_case_text(kBlock, "block.yaml"));
  FieldArray fields(simulation.model().field_count(), simulation.nodes().sph_nodes.size());
  std::fill(fields.data().begin(), fields.data().end(), 0.0);
  simulation.boundary_conditions().apply(0.0, fields);
  const int syy = simulation.model().stress_field(1, 1);
  auto top = [&](double x) {
    return fields(syy, static_cast<std::size_t>(node_at(simulation, x, 4)));
  };
  EXPECT_DOUBLE_EQ(top(0), -1000.0);
  EXPECT_DOUBLE_EQ(top(1), -1000.0);
  EXPECT_DOUBLE_EQ(top(2), -500.0);
  EXPECT_DOUBLE_EQ(top(3), 0.0);
  // Trapezoidal rule over the top face: 1 * (t0/2 + t1 + t2 + t3 + ... ) = t * 2.
  double load = 0.5 * top(0) + 0.5 * top(6);
  for (int x = 1; x < 6; ++x)
    load += top(x);
  EXPECT_DOUBLE_EQ(load, -1000.0 * 2.0);
}

TEST(BoundaryConditions, TractionOnOneNodeIsAnError) {
  // A single node holds no facet: the load would have no width.
  std::string text = kBlock;
  text.replace(text.find("box: {min: [0, 4], max: [2, 4]}"), 31, "point: [3, 4]");
  try {
    Simulation simulation(read_case_text(text, "block.yaml"));
    FAIL() << "a traction on one node was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("no whole facet"), std::string::npos) << error.what();
  }
}

TEST(BoundaryConditions, TractionOnAGroupWithNoCommonFaceIsAnError) {
  std::string text = kBlock;
  text.replace(text.find("box: {min: [0, 4], max: [2, 4]}"), 31, "box: {min: [0, 3], max: [2, 4]}");
  EXPECT_THROW(Simulation(read_case_text(text, "block.yaml")), InputError);
}

TEST(BoundaryConditions, RollerOffAPlaneIsAnError) {
  std::string text = kBlock;
  text.replace(text.find("{group: ymin, roller: y}"), 24, "{group: footing, roller: x}");
  EXPECT_THROW(Simulation(read_case_text(text, "block.yaml")), InputError);
}

/// kBlock with one more boundary condition at the end of the list (line 15).
std::string block_with(const std::string& condition) {
  std::string text = kBlock;
  const std::string last = "  - {group: footing, traction: {y: -1000.0}}\n";
  text.replace(text.find(last), last.size(), last + "  - " + condition + "\n");
  return text;
}

TEST(BoundaryConditions, TwoDifferentVelocitiesOnOneNodeAndComponentAreRefused) {
  // xmin is fixed (line 12); a velocity along x on it contradicts that.
  try {
    Simulation(read_case_text(block_with("{group: xmin, velocity: {x: 0.1}}"), "block.yaml"));
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.location().line, 15);
    EXPECT_NE(error.problem().find("'fixed' condition on group 'xmin' at block.yaml:12"),
              std::string::npos)
        << error.what();
    EXPECT_NE(error.problem().find("different velocities along x"), std::string::npos);
  }
}

TEST(BoundaryConditions, TractionAndVelocityOnTheSameFaceAndComponentAreRefused) {
  try {
    // The footing moved off the fixed left face, so that only the traction is in the way.
    std::string text = block_with("{group: footing, velocity: {y: -0.01}}");
    const std::string footing = "box: {min: [0, 4], max: [2, 4]}";
    text.replace(text.find(footing), footing.size(), "box: {min: [1, 4], max: [2, 4]}");
    Simulation(read_case_text(text, "block.yaml"));
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.location().line, 14);  // the traction, which would be dropped
    EXPECT_NE(error.problem().find("'velocity' condition on group 'footing' at block.yaml:15"),
              std::string::npos)
        << error.what();
  }
}

TEST(BoundaryConditions, EqualImposedVelocitiesMayOverlap) {
  // The fixed left face and the bottom roller share the corner (0, 0): both impose zero there.
  EXPECT_NO_THROW(Simulation(read_case_text(kBlock, "block.yaml")));
  EXPECT_NO_THROW(
      Simulation(read_case_text(block_with("{group: xmin, velocity: {x: 0}}"), "block.yaml")));
}

}  // namespace
}  // namespace rktsph::boundary_conditions_test
