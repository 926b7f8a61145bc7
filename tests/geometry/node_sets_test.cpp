// Geometry to nodes (docs/theory.md §3.1): lattice filling of segments, rectangles and polygons,
// stress points at cell centres, materials by shape order, and node groups.
#include "rktsph/geometry/node_sets.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "../support/lattices.hpp"
#include "../support/shapes.hpp"

namespace rktsph::node_sets_test {
namespace {

using test::rectangle;

TEST(NodeSets, SegmentHasNodesAtBothEndsAndMidpointStressPoints) {
  GeometrySpec geometry;
  geometry.spacing = 0.5;
  geometry.shapes = {test::segment(2.0, 12.0, "soil")};
  const NodeSets nodes = build_node_sets(geometry, 1, {"soil"});
  ASSERT_EQ(nodes.sph_nodes.size(), 21u);
  ASSERT_EQ(nodes.stress_points.size(), 20u);
  EXPECT_DOUBLE_EQ(nodes.sph_nodes.position[0].front(), 2.0);
  EXPECT_DOUBLE_EQ(nodes.sph_nodes.position[0].back(), 12.0);
  EXPECT_DOUBLE_EQ(nodes.stress_points.position[0][3], 2.0 + 3.5 * 0.5);
  EXPECT_DOUBLE_EQ(nodes.sph_nodes.volume[0], 0.5);
}

TEST(NodeSets, RectangleCountsAndCellCentres) {
  GeometrySpec geometry;
  geometry.spacing = 0.04;
  geometry.shapes = {rectangle(0.0, 0.0, 1.0, 2.0, "soil")};
  const NodeSets nodes = build_node_sets(geometry, 2, {"soil"});
  EXPECT_EQ(nodes.sph_nodes.size(), 26u * 51u);
  EXPECT_EQ(nodes.stress_points.size(), 25u * 50u);
  // Every stress point is the centre of the four nodes around it.
  for (std::size_t p = 0; p < nodes.stress_points.size(); ++p) {
    // The lower-left corner's column and row, from the point's position (origin (0, 0)).
    const std::array<std::int32_t, 2> corner{
        static_cast<std::int32_t>(std::lround(nodes.stress_points.position[0][p] / 0.04 - 0.5)),
        static_cast<std::int32_t>(std::lround(nodes.stress_points.position[1][p] / 0.04 - 0.5))};
    double cx = 0.0, cy = 0.0;
    for (int dj = 0; dj <= 1; ++dj)
      for (int di = 0; di <= 1; ++di) {
        const std::int32_t node = test::lattice_node(nodes, corner[0] + di, corner[1] + dj);
        ASSERT_GE(node, 0);
        cx += 0.25 * nodes.sph_nodes.position[0][node];
        cy += 0.25 * nodes.sph_nodes.position[1][node];
      }
    EXPECT_NEAR(nodes.stress_points.position[0][p], cx, 1e-12);
    EXPECT_NEAR(nodes.stress_points.position[1][p], cy, 1e-12);
  }
  EXPECT_NEAR(nodes.sph_nodes.volume[0], 0.04 * 0.04, 1e-18);
}

TEST(NodeSets, ConcavePolygonAndMaterialOverride) {
  // An L-shaped block (a vertical cut) with a weak square overriding the corner material.
  GeometrySpec geometry;
  geometry.spacing = 1.0;
  ShapeSpec outline;
  outline.kind = ShapeSpec::Kind::Polygon;
  outline.vertices = {{0, 0, 0}, {20, 0, 0}, {20, 5, 0}, {10, 5, 0}, {10, 15, 0}, {0, 15, 0}};
  outline.material = "soil";
  geometry.shapes = {outline, rectangle(0.0, 0.0, 1.0, 1.0, "weak")};
  const NodeSets nodes = build_node_sets(geometry, 2, {"soil", "weak"});
  // Nodes: 21 x 6 (bottom band) + 11 x 10 (column above y = 5).
  EXPECT_EQ(nodes.sph_nodes.size(), 21u * 6u + 11u * 10u);
  // Cells: 20 x 5 + 10 x 10; none in the missing upper-right quadrant.
  EXPECT_EQ(nodes.stress_points.size(), 20u * 5u + 10u * 10u);
  for (std::size_t p = 0; p < nodes.stress_points.size(); ++p)
    EXPECT_FALSE(nodes.stress_points.position[0][p] > 10.0 &&
                 nodes.stress_points.position[1][p] > 5.0);
  int weak = 0;
  for (std::int32_t m : nodes.node_material)
    weak += m == 1;
  EXPECT_EQ(weak, 4);  // the four nodes of the unit square
  int weak_cells = 0;
  for (std::int32_t m : nodes.cells.materials())
    weak_cells += m == 1;
  EXPECT_EQ(weak_cells, 1);
}

TEST(NodeSets, VertexOffTheLatticeIsAnInputError) {
  GeometrySpec geometry;
  geometry.spacing = 0.3;
  geometry.shapes = {rectangle(0.0, 0.0, 1.0, 0.9, "soil")};
  geometry.shapes[0].where = {"case.yaml", 7, 5};
  try {
    build_node_sets(geometry, 2, {"soil"});
    FAIL() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.location().line, 7);
    EXPECT_NE(std::string(error.what()).find("not on the lattice"), std::string::npos);
  }
}

// Every vertex off the lattice is named in one report, not only the first one found.
TEST(NodeSets, EveryVertexOffTheLatticeIsReported) {
  GeometrySpec geometry;
  geometry.spacing = 0.3;
  geometry.shapes = {rectangle(0.0, 0.0, 1.0, 0.9, "soil"), rectangle(0.0, 0.0, 0.6, 1.1, "soil")};
  geometry.shapes[0].where = {"case.yaml", 7, 5};
  geometry.shapes[1].where = {"case.yaml", 9, 5};
  try {
    build_node_sets(geometry, 2, {"soil"});
    FAIL() << "expected an InputError";
  } catch (const InputError& error) {
    const std::vector<InputError> errors = error.errors();
    ASSERT_EQ(errors.size(), 2u) << error.what();
    EXPECT_EQ(errors[0].key(), "geometry.shapes.0");
    EXPECT_EQ(errors[0].value(), "1");
    EXPECT_NE(errors[0].problem().find("x of vertex 1"), std::string::npos) << error.what();
    EXPECT_EQ(errors[1].key(), "geometry.shapes.1");
    EXPECT_EQ(errors[1].value(), "1.1");
    EXPECT_NE(errors[1].problem().find("y of vertex 1"), std::string::npos) << error.what();
  }
}

TEST(NodeSets, ShapeThinnerThanOneSpacingIsAnInputError) {
  GeometrySpec geometry;
  geometry.spacing = 1.0;
  // 1e-308 rounds to the lattice line x = 0: on the lattice, but no cell wide.
  geometry.shapes = {rectangle(0.0, 0.0, 1e-308, 4.0, "soil")};
  geometry.shapes[0].where = {"case.yaml", 5, 5};
  try {
    build_node_sets(geometry, 2, {"soil"});
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.location().line, 5);
    EXPECT_NE(error.problem().find("less than one spacing"), std::string::npos) << error.what();
  }
}

TEST(NodeGroups, EdgesBoxesPolygonsAndPoints) {
  GeometrySpec geometry;
  geometry.spacing = 1.0;
  geometry.shapes = {rectangle(0.0, 0.0, 10.0, 4.0, "soil")};
  const NodeSets nodes = build_node_sets(geometry, 2, {"soil"});
  GroupSpec box;
  box.name = "footing";
  box.kind = GroupSpec::Kind::Box;
  box.min = {0.0, 4.0, 0.0};
  box.max = {3.0, 4.0, 0.0};
  GroupSpec triangle;
  triangle.name = "wedge";
  triangle.kind = GroupSpec::Kind::Polygon;
  triangle.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
  GroupSpec point;
  point.name = "probe";
  point.kind = GroupSpec::Kind::Point;
  point.point = {5.2, 1.9, 0.0};
  const auto groups = select_groups(nodes, {box, triangle, point});
  EXPECT_EQ(groups.at("all").size(), 55u);
  EXPECT_EQ(groups.at("xmin").size(), 5u);
  EXPECT_EQ(groups.at("ymax").size(), 11u);
  EXPECT_EQ(groups.at("footing").size(), 4u);
  EXPECT_EQ(groups.at("wedge").size(), 6u);  // (0,0) (1,0) (2,0) (0,1) (1,1) (0,2)
  ASSERT_EQ(groups.at("probe").size(), 1u);
  const auto probe = static_cast<std::size_t>(groups.at("probe")[0]);
  EXPECT_DOUBLE_EQ(nodes.sph_nodes.position[0][probe], 5.0);
  EXPECT_DOUBLE_EQ(nodes.sph_nodes.position[1][probe], 2.0);
}

TEST(NodeGroups, EmptySelectionIsAnInputErrorAtTheGroup) {
  GeometrySpec geometry;
  geometry.spacing = 1.0;
  geometry.shapes = {rectangle(0.0, 0.0, 10.0, 4.0, "soil")};
  const NodeSets nodes = build_node_sets(geometry, 2, {"soil"});
  GroupSpec outside;
  outside.name = "nowhere";
  outside.kind = GroupSpec::Kind::Box;
  outside.min = {20.0, 20.0, 0.0};
  outside.max = {30.0, 30.0, 0.0};
  outside.where = {"case.yaml", 12, 3};
  EXPECT_THROW(select_groups(nodes, {outside}), InputError);
}

TEST(NodeGroups, PointFartherThanHalfASpacingFromEveryNodeIsRefused) {
  GeometrySpec geometry;
  geometry.spacing = 1.0;
  geometry.shapes = {rectangle(0.0, 0.0, 10.0, 4.0, "soil")};
  const NodeSets nodes = build_node_sets(geometry, 2, {"soil"});
  GroupSpec point;
  point.name = "far";
  point.kind = GroupSpec::Kind::Point;
  point.where = {"case.yaml", 7, 3};
  // A cell centre is half a spacing from its corner nodes along each axis: still in the body.
  point.point = {5.5, 2.5, 0.0};
  EXPECT_EQ(select_groups(nodes, {point}).at("far").size(), 1u);
  // Beyond the right edge x = 10 by 5 spacings.
  point.point = {15.0, 2.0, 0.0};
  try {
    select_groups(nodes, {point});
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.location().line, 7);
    EXPECT_EQ(error.key(), "groups.far.point");
    EXPECT_EQ(error.value(), "[15, 2]");
    EXPECT_NE(error.problem().find("5 m from the nearest node (at [10, 2])"), std::string::npos)
        << error.what();
  }
  // Just over half a spacing along one axis.
  point.point = {10.6, 2.0, 0.0};
  EXPECT_THROW(select_groups(nodes, {point}), InputError);
}

}  // namespace
}  // namespace rktsph::node_sets_test
