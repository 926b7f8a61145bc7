// Triangle meshes of the shapes (docs/theory.md §3.6): areas, orientation, angles and edge lengths,
// node volumes, material boundaries, exact straight edges, holes, determinism, the outline and the
// filled fraction, groups on triangle nodes, and the refusal of bad cells.
#include "rktsph/geometry/triangle_mesher.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "../support/shapes.hpp"
#include "rktsph/mesh/cell_geometry.hpp"
#include "rktsph/mesh/cell_kinds/triangle.hpp"
#include "rktsph/mesh/node_classification.hpp"

namespace rktsph::triangle_mesher_test {
namespace {

using test::polygon;
using test::rectangle;

GeometrySpec triangles(double spacing, std::vector<ShapeSpec> shapes) {
  GeometrySpec geometry;
  geometry.spacing = spacing;
  geometry.cells = CellLayout::Triangles;
  geometry.shapes = std::move(shapes);
  return geometry;
}

// A 2:1 slope whose vertices lie on no lattice of the spacing used.
std::vector<Vec3> slope() {
  return {{0.0, 0.0, 0.0}, {13.1, 0.0, 0.0}, {13.1, 2.3, 0.0},
          {9.7, 2.3, 0.0}, {3.7, 5.3, 0.0},  {0.0, 5.3, 0.0}};
}

std::vector<Vec3> circle(double cx, double cy, double radius, int sides) {
  std::vector<Vec3> vertices;
  for (int k = 0; k < sides; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / sides;
    vertices.push_back({cx + radius * std::cos(angle), cy + radius * std::sin(angle), 0.0});
  }
  return vertices;
}

std::vector<Vec3> l_shape() {
  return {{0.0, 0.0, 0.0}, {6.0, 0.0, 0.0}, {6.0, 2.0, 0.0},
          {2.0, 2.0, 0.0}, {2.0, 5.0, 0.0}, {0.0, 5.0, 0.0}};
}

double sum(const std::vector<double>& values) {
  double total = 0.0;
  for (const double value : values)
    total += value;
  return total;
}

double distance_to_segment(double x, double y, const Vec3& a, const Vec3& b) {
  const double ex = b[0] - a[0], ey = b[1] - a[1];
  const double s = std::clamp(((x - a[0]) * ex + (y - a[1]) * ey) / (ex * ex + ey * ey), 0.0, 1.0);
  return std::hypot(x - a[0] - s * ex, y - a[1] - s * ey);
}

double distance_to_outline(const std::vector<Vec3>& v, double x, double y) {
  double distance = std::numeric_limits<double>::max();
  for (std::size_t k = 0; k < v.size(); ++k)
    distance = std::min(distance, distance_to_segment(x, y, v[k], v[(k + 1) % v.size()]));
  return distance;
}

// The squared sine of a triangle's smallest angle, as CGAL's shape criterion measures it.
double squared_smallest_sine(const CellCorners& c) {
  std::array<double, 3> squared_edges{};
  for (int k = 0; k < 3; ++k)
    squared_edges[k] =
        std::pow(c.x[(k + 1) % 3] - c.x[k], 2) + std::pow(c.y[(k + 1) % 3] - c.y[k], 2);
  std::sort(squared_edges.begin(), squared_edges.end());
  const double twice_area = 2.0 * triangle::measure(c);
  return twice_area * twice_area / (squared_edges[2] * squared_edges[1]);
}

TEST(TriangleMesher, TrianglesFillThePolygonCounterClockwiseWithBoundedAnglesAndEdges) {
  struct Case {
    const char* name;
    std::vector<Vec3> outline;
    double spacing, area, perimeter;
  };
  // Areas and perimeters by hand: the slope is 13.1 x 2.3 below, 3.7 x 3 and a 6 x 3 triangle
  // above; the 48-gon of radius r has 48 triangles of apex 2 pi / 48.
  const double r = 3.3, apex = 2.0 * std::numbers::pi / 48.0;
  const std::vector<Case> cases = {
      {"2:1 slope", slope(), 0.37, 13.1 * 2.3 + 3.7 * 3.0 + 9.0, 27.8 + std::sqrt(45.0)},
      {"circle", circle(1.1, 2.2, r, 48), 0.3, 24.0 * r * r * std::sin(apex),
       96.0 * r * std::sin(0.5 * apex)},
      {"L", l_shape(), 0.25, 18.0, 22.0}};
  for (const Case& test : cases) {
    SCOPED_TRACE(test.name);
    const NodeSets nodes = build_triangle_node_sets(
        triangles(test.spacing, {polygon(test.outline, "soil")}), {"soil"});
    const double area = test.area, perimeter = test.perimeter;
    ASSERT_GT(nodes.cells.cell_count(), 50u);
    EXPECT_EQ(nodes.stress_points.size(), nodes.cells.cell_count());
    EXPECT_NEAR(sum(nodes.stress_points.volume), area, 1e-10 * area);
    EXPECT_NEAR(sum(nodes.sph_nodes.volume), area, 1e-10 * area);
    double smallest = 1.0, longest = 0.0;
    for (std::size_t p = 0; p < nodes.cells.cell_count(); ++p) {
      ASSERT_EQ(nodes.cells.kind(p), CellKind::Triangle);
      const CellCorners c = nodes.cells.corner_positions(nodes.sph_nodes, p);
      ASSERT_GT(triangle::measure(c), 0.0) << "cell " << p << " is not counter-clockwise";
      EXPECT_DOUBLE_EQ(nodes.stress_points.volume[p], triangle::measure(c));
      const auto centroid = triangle::centroid(c);
      EXPECT_DOUBLE_EQ(nodes.stress_points.position[0][p], centroid[0]);
      EXPECT_DOUBLE_EQ(nodes.stress_points.position[1][p], centroid[1]);
      smallest = std::min(smallest, squared_smallest_sine(c));
      for (int k = 0; k < 3; ++k)
        longest =
            std::max(longest, std::hypot(c.x[(k + 1) % 3] - c.x[k], c.y[(k + 1) % 3] - c.y[k]));
    }
    // Every input angle here is at least 90°, so the bound holds everywhere.
    EXPECT_GE(smallest, kTriangleShapeBound * (1.0 - 1e-9));
    EXPECT_LE(longest, test.spacing * (1.0 + 1e-9));
    // The outline of the complex is the polygon's boundary.
    double outline_length = 0.0;
    for (std::size_t f = 0; f < nodes.outline.facet_count(); ++f)
      outline_length += nodes.outline.measure(f);
    EXPECT_NEAR(outline_length, perimeter, 1e-10 * perimeter);
    for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i)
      if (!nodes.outline.facets_at(i).empty()) {
        EXPECT_LT(distance_to_outline(test.outline, nodes.sph_nodes.position[0][i],
                                      nodes.sph_nodes.position[1][i]),
                  1e-9);
      }
    // None of the lattice's own fields.
    EXPECT_FALSE(nodes.on_lattice());
  }
}

TEST(TriangleMesher, EstimateIsWithinAFactorOfTheMesh) {
  for (const double spacing : {0.2, 0.5}) {
    const GeometrySpec geometry = triangles(spacing, {polygon(slope(), "soil")});
    const NodeSets nodes = build_triangle_node_sets(geometry, {"soil"});
    const NodeEstimate estimate = estimate_node_sets(geometry, 2);
    const double nodes_ratio = estimate.sph_nodes / static_cast<double>(nodes.sph_nodes.size());
    const double cells_ratio =
        estimate.stress_points / static_cast<double>(nodes.cells.cell_count());
    EXPECT_GT(nodes_ratio, 0.8) << spacing;
    EXPECT_LT(nodes_ratio, 1.25) << spacing;
    EXPECT_GT(cells_ratio, 0.8) << spacing;
    EXPECT_LT(cells_ratio, 1.25) << spacing;
    EXPECT_EQ(estimate.lattice_points, 0.0);
  }
}

TEST(TriangleMesher, NodesOnAStraightEdgeLieExactlyOnIt) {
  // Mirror planes (x = 0 here) need their nodes exactly on the plane.
  const NodeSets nodes =
      build_triangle_node_sets(triangles(0.3, {rectangle(0.0, -2.9, 4.1, 0.0, "soil")}), {"soil"});
  std::size_t on_axis = 0, on_top = 0;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    const double x = nodes.sph_nodes.position[0][i], y = nodes.sph_nodes.position[1][i];
    if (std::abs(x) < 1e-6) {
      EXPECT_EQ(x, 0.0);
      ++on_axis;
    }
    if (std::abs(y) < 1e-6) {
      EXPECT_EQ(y, 0.0);
      ++on_top;
    }
  }
  EXPECT_GE(on_axis, static_cast<std::size_t>(std::ceil(2.9 / 0.3)) + 1);
  EXPECT_GE(on_top, static_cast<std::size_t>(std::ceil(4.1 / 0.3)) + 1);
}

// The boundary layer (docs/theory.md §3.6): each straight edge along an axis (a slanted edge is
// left to refinement: with the layer CGAL's refinement did not end on some) is split into equal
// segments of
// at most kBoundaryLayerSpacing h, and the triangles along it, away from the shape's corners, are
// equilateral (the first row sits at s sqrt(3)/2, staggered by s/2), so that a node on the edge
// sees its cells symmetrically. Their width s sqrt(3)/2 is far above the thin edge triangles of
// refinement alone, so the narrowest cell, which sets the step (§4.8), lies inside the body.
TEST(TriangleMesher, StraightEdgesCarryALayerOfEquilateralTriangles) {
  struct Case {
    const char* name;
    std::vector<Vec3> outline;
    double spacing;
  };
  const std::vector<Case> cases = {
      {"rectangle", {{0.0, -2.9, 0.0}, {4.1, -2.9, 0.0}, {4.1, 0.0, 0.0}, {0.0, 0.0, 0.0}}, 0.3},
      {"2:1 slope", slope(), 0.37},
      {"L", l_shape(), 0.25}};
  for (const Case& test : cases) {
    SCOPED_TRACE(test.name);
    const double h = test.spacing;
    const NodeSets nodes =
        build_triangle_node_sets(triangles(h, {polygon(test.outline, "soil")}), {"soil"});
    const auto& x = nodes.sph_nodes.position[0];
    const auto& y = nodes.sph_nodes.position[1];
    const auto near_a_vertex = [&](double px, double py) {
      for (const Vec3& v : test.outline)
        if (std::hypot(px - v[0], py - v[1]) < 2.0 * h) return true;
      return false;
    };
    // The nodes on each edge: equal gaps of at most 0.7 h.
    const std::vector<Vec3>& v = test.outline;
    for (std::size_t k = 0; k < v.size(); ++k) {
      const Vec3& a = v[k];
      const Vec3& b = v[(k + 1) % v.size()];
      if (a[0] != b[0] && a[1] != b[1]) continue;  // slanted: no layer
      const double length = std::hypot(b[0] - a[0], b[1] - a[1]);
      std::vector<double> along;
      for (std::size_t i = 0; i < x.size(); ++i)
        if (distance_to_segment(x[i], y[i], a, b) < 1e-9 * length)
          along.push_back(std::hypot(x[i] - a[0], y[i] - a[1]));
      std::sort(along.begin(), along.end());
      ASSERT_GE(along.size(), 2u);
      const double gap = length / static_cast<double>(along.size() - 1);
      EXPECT_LE(gap, kBoundaryLayerSpacing * h * (1.0 + 1e-9));
      for (std::size_t i = 1; i < along.size(); ++i)
        EXPECT_NEAR(along[i] - along[i - 1], gap, 1e-9 * length) << "edge " << k;
    }
    // The triangles with an edge on the outline, away from the corners: equilateral.
    std::size_t layer = 0;
    for (std::size_t p = 0; p < nodes.cells.cell_count(); ++p) {
      const CellCorners c = nodes.cells.corner_positions(nodes.sph_nodes, p);
      const double cx = (c.x[0] + c.x[1] + c.x[2]) / 3.0, cy = (c.y[0] + c.y[1] + c.y[2]) / 3.0;
      if (near_a_vertex(cx, cy)) continue;
      int on_outline = 0;
      for (int k = 0; k < 3; ++k)
        for (std::size_t e = 0; e < v.size(); ++e) {
          const Vec3& a = v[e];
          const Vec3& b = v[(e + 1) % v.size()];
          if ((a[0] == b[0] || a[1] == b[1]) &&
              distance_to_segment(c.x[k], c.y[k], a, b) < 1e-9 * h) {
            ++on_outline;
            break;
          }
        }
      if (on_outline < 2) continue;
      ++layer;
      EXPECT_NEAR(squared_smallest_sine(c), 0.75, 1e-9) << "cell " << p;
    }
    EXPECT_GT(layer, 20u);
    // The narrowest cell: 0.33-0.35 h measured on these shapes and the bar of
    // triangles-bar-wave-2d (refinement's triangles inside the body), against 0.22-0.25 h from
    // the thin triangles refinement alone leaves along straight edges.
    EXPECT_GE(smallest_cell_width(nodes.cells, nodes.sph_nodes), 0.3 * h);
  }
}

TEST(TriangleMesher, NoTriangleStraddlesAMaterialBoundary) {
  // A weak zone listed after the soil it lies in, off any lattice.
  const std::vector<Vec3> weak = {{2.03, 1.07, 0.0}, {5.31, 1.19, 0.0}, {3.13, 3.71, 0.0}};
  const NodeSets nodes = build_triangle_node_sets(
      triangles(0.35, {rectangle(0.0, 0.0, 8.0, 4.5, "soil"), polygon(weak, "weak")}),
      {"soil", "weak"});
  const auto strictly_inside = [&](double x, double y) {
    return polygon_contains(weak, x, y, 0.0) && distance_to_outline(weak, x, y) > 1e-9;
  };
  std::array<std::size_t, 2> count{};
  double weak_area = 0.0;
  for (std::size_t p = 0; p < nodes.cells.cell_count(); ++p) {
    const std::int32_t material = nodes.cells.material(p);
    ASSERT_TRUE(material == 0 || material == 1);
    ++count[static_cast<std::size_t>(material)];
    const bool centroid_weak =
        strictly_inside(nodes.stress_points.position[0][p], nodes.stress_points.position[1][p]);
    EXPECT_EQ(material, centroid_weak ? 1 : 0) << "cell " << p;
    if (material == 1) weak_area += nodes.stress_points.volume[p];
    for (const std::int32_t node : nodes.cells.corners(p)) {
      const double x = nodes.sph_nodes.position[0][node], y = nodes.sph_nodes.position[1][node];
      if (material == 1)
        EXPECT_TRUE(polygon_contains(weak, x, y, 1e-9)) << "weak cell " << p << " leaves the zone";
      else
        EXPECT_FALSE(strictly_inside(x, y)) << "soil cell " << p << " enters the zone";
    }
  }
  EXPECT_GT(count[0], 0u);
  EXPECT_GT(count[1], 0u);
  const double weak_twice_area = (weak[1][0] - weak[0][0]) * (weak[2][1] - weak[0][1]) -
                                 (weak[2][0] - weak[0][0]) * (weak[1][1] - weak[0][1]);
  EXPECT_NEAR(weak_area, 0.5 * weak_twice_area, 1e-10);
  // A node inside the zone is weak, one outside it soil; those on its edge are the later shape's.
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i)
    EXPECT_EQ(nodes.node_material[i], polygon_contains(weak, nodes.sph_nodes.position[0][i],
                                                       nodes.sph_nodes.position[1][i], 1e-9)
                                          ? 1
                                          : 0);
}

TEST(TriangleMesher, OverlappingShapesWhoseEdgesCrossMeetAtTheCrossings) {
  // The later rectangle wins where they overlap; its edges cross the earlier one's at (4, 1.1)
  // and (2.5, 3).
  const NodeSets nodes = build_triangle_node_sets(
      triangles(0.3,
                {rectangle(0.0, 0.0, 4.0, 3.0, "soil"), rectangle(2.5, 1.1, 6.3, 4.2, "weak")}),
      {"soil", "weak"});
  std::array<double, 2> area{};
  for (std::size_t p = 0; p < nodes.cells.cell_count(); ++p)
    area[static_cast<std::size_t>(nodes.cells.material(p))] += nodes.stress_points.volume[p];
  const double weak = 3.8 * 3.1, overlap = 1.5 * 1.9;
  EXPECT_NEAR(area[1], weak, 1e-9);
  EXPECT_NEAR(area[0], 12.0 - overlap, 1e-9);
  const auto is_node = [&](double x, double y) {
    for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i)
      if (std::abs(nodes.sph_nodes.position[0][i] - x) < 1e-12 &&
          std::abs(nodes.sph_nodes.position[1][i] - y) < 1e-12)
        return true;
    return false;
  };
  EXPECT_TRUE(is_node(4.0, 1.1));
  EXPECT_TRUE(is_node(2.5, 3.0));
}

TEST(TriangleMesher, TheSpaceBetweenShapesStaysEmpty) {
  // A frame of four rectangles around a 4 x 4 hole, and a disjoint square beside it.
  const GeometrySpec geometry =
      triangles(0.5, {rectangle(0, 0, 6, 1, "soil"), rectangle(0, 5, 6, 6, "soil"),
                      rectangle(0, 1, 1, 5, "soil"), rectangle(5, 1, 6, 5, "soil"),
                      rectangle(7.5, 0, 9.5, 2, "soil")});
  const NodeSets nodes = build_triangle_node_sets(geometry, {"soil"});
  EXPECT_NEAR(sum(nodes.stress_points.volume), 36.0 - 16.0 + 4.0, 1e-9);
  for (std::size_t p = 0; p < nodes.stress_points.size(); ++p) {
    const double x = nodes.stress_points.position[0][p], y = nodes.stress_points.position[1][p];
    EXPECT_FALSE(x > 1.0 && x < 5.0 && y > 1.0 && y < 5.0) << "a triangle in the hole";
    EXPECT_FALSE(x > 6.0 && x < 7.5) << "a triangle between the shapes";
  }
  // Outline: the frame's outer and inner boundaries and the square's.
  double outline_length = 0.0;
  for (std::size_t f = 0; f < nodes.outline.facet_count(); ++f)
    outline_length += nodes.outline.measure(f);
  EXPECT_NEAR(outline_length, 24.0 + 16.0 + 8.0, 1e-9);
}

TEST(TriangleMesher, BuildsAreIdentical) {
  const GeometrySpec geometry =
      triangles(0.4, {polygon(slope(), "soil"), polygon(circle(5.0, 2.0, 1.3, 17), "weak")});
  const NodeSets a = build_triangle_node_sets(geometry, {"soil", "weak"});
  const NodeSets b = build_triangle_node_sets(geometry, {"soil", "weak"});
  ASSERT_EQ(a.sph_nodes.size(), b.sph_nodes.size());
  ASSERT_EQ(a.cells.cell_count(), b.cells.cell_count());
  for (int axis = 0; axis < 2; ++axis) {
    EXPECT_EQ(a.sph_nodes.position[axis], b.sph_nodes.position[axis]);
    EXPECT_EQ(a.stress_points.position[axis], b.stress_points.position[axis]);
  }
  EXPECT_EQ(a.sph_nodes.volume, b.sph_nodes.volume);
  EXPECT_EQ(a.node_material, b.node_material);
  for (std::size_t p = 0; p < a.cells.cell_count(); ++p) {
    const auto ca = a.cells.corners(p), cb = b.cells.corners(p);
    EXPECT_TRUE(std::equal(ca.begin(), ca.end(), cb.begin(), cb.end()));
    EXPECT_EQ(a.cells.material(p), b.cells.material(p));
  }
  // Numbered by (y, x).
  for (std::size_t i = 1; i < a.sph_nodes.size(); ++i) {
    const double y0 = a.sph_nodes.position[1][i - 1], y1 = a.sph_nodes.position[1][i];
    EXPECT_TRUE(y0 < y1 ||
                (y0 == y1 && a.sph_nodes.position[0][i - 1] < a.sph_nodes.position[0][i]));
  }
}

TEST(TriangleMesher, FilledFractionIsOneInsideAndAHalfOnStraightEdges) {
  const std::vector<Vec3> outline = l_shape();
  const NodeSets nodes =
      build_triangle_node_sets(triangles(0.3, {polygon(outline, "soil")}), {"soil"});
  std::size_t interior = 0, on_edges = 0;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    const double x = nodes.sph_nodes.position[0][i], y = nodes.sph_nodes.position[1][i];
    const double fraction = filled_fraction(nodes.cells, nodes.sph_nodes, i);
    const bool at_vertex = std::any_of(outline.begin(), outline.end(), [&](const Vec3& v) {
      return std::hypot(v[0] - x, v[1] - y) < 1e-9;
    });
    if (distance_to_outline(outline, x, y) > 1e-9) {
      EXPECT_NEAR(fraction, 1.0, 1e-12) << "interior node " << i;
      EXPECT_EQ(node_place(fraction, 2), NodePlace::Interior);
      ++interior;
    } else if (!at_vertex) {
      EXPECT_NEAR(fraction, 0.5, 1e-9) << "edge node " << i;
      EXPECT_EQ(node_place(fraction, 2), NodePlace::Boundary);
      ++on_edges;
    } else {
      // Convex corners fill a quarter, the re-entrant one (2, 2) three quarters.
      EXPECT_NEAR(fraction, x == 2.0 && y == 2.0 ? 0.75 : 0.25, 1e-9) << "corner node " << i;
    }
  }
  EXPECT_GT(interior, 100u);
  EXPECT_GT(on_edges, 50u);
}

TEST(TriangleMesher, GroupsSelectTriangleNodes) {
  const NodeSets nodes =
      build_triangle_node_sets(triangles(0.37, {polygon(slope(), "soil")}), {"soil"});
  std::vector<GroupSpec> groups(4);
  groups[0].name = "base";
  groups[0].kind = GroupSpec::Kind::Edge;
  groups[0].edge = "ymin";
  groups[1].name = "window";
  groups[1].kind = GroupSpec::Kind::Box;
  groups[1].min = {1.0, 1.0, 0.0};
  groups[1].max = {2.0, 2.0, 0.0};
  groups[2].name = "crest";
  groups[2].kind = GroupSpec::Kind::Point;
  groups[2].point = {1.234, 5.3, 0.0};
  // Inside the body but farther than half a spacing, along an axis, from every node would be
  // refused on a lattice test; on triangles the test is the distance to the cells.
  groups[3].name = "inside";
  groups[3].kind = GroupSpec::Kind::Point;
  groups[3].point = {6.54321, 1.23456, 0.0};
  const auto selected = select_groups(nodes, groups);
  for (const std::int32_t node : selected.at("base"))
    EXPECT_EQ(nodes.sph_nodes.position[1][node], 0.0);
  EXPECT_GE(selected.at("base").size(), static_cast<std::size_t>(13.1 / 0.37));
  EXPECT_FALSE(selected.at("window").empty());
  ASSERT_EQ(selected.at("crest").size(), 1u);
  EXPECT_EQ(nodes.sph_nodes.position[1][selected.at("crest")[0]], 5.3);

  // On the slope's face but 0.2 m (more than half a spacing) outside the body: refused.
  GroupSpec outside;
  outside.name = "air";
  outside.kind = GroupSpec::Kind::Point;
  outside.point = {11.0, 2.3 + 0.2, 0.0};
  outside.where = SourceLocation{"case.yaml", 7, 3};
  try {
    select_groups(nodes, {outside});
    FAIL() << "a point off the body was accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "groups.air.point");
    EXPECT_EQ(error.location().line, 7);
    EXPECT_NE(error.problem().find("from every cell"), std::string::npos) << error.what();
  }
  // Within half a spacing of the surface: the nearest node.
  outside.point = {11.0, 2.3 + 0.1, 0.0};
  EXPECT_EQ(select_groups(nodes, {outside}).at("air").size(), 1u);
}

TEST(TriangleMesher, SharpInputAnglesAreMeshedNotRefused) {
  // A 10° wedge: the triangles at its tip keep that angle, the rest the bound.
  const double tip = 10.0 * std::numbers::pi / 180.0;
  const NodeSets nodes = build_triangle_node_sets(
      triangles(0.5, {polygon({{0, 0, 0}, {6, 0, 0}, {6 * std::cos(tip), 6 * std::sin(tip), 0}},
                              "soil")}),
      {"soil"});
  double smallest = 1.0;
  for (std::size_t p = 0; p < nodes.cells.cell_count(); ++p)
    smallest = std::min(smallest, cell_quality(CellKind::Triangle,
                                               nodes.cells.corner_positions(nodes.sph_nodes, p)));
  EXPECT_GE(smallest, kMinimumCellQuality);
  EXPECT_NEAR(sum(nodes.stress_points.volume), 0.5 * 36.0 * std::sin(tip), 1e-10);
}

// Quadrilaterals with one slanted side, on which the mesher with a boundary layer on that side did
// not end (§3.6): they are meshed, and their area is the polygon's. A hang here is a timeout.
TEST(TriangleMesher, PolygonsWithSlantedSidesAreMeshed) {
  const std::vector<std::array<double, 8>> quadrilaterals = {
      {0, 0, 4.1, 0, 2.3, 2.7, 0, 2.2}, {0, 0, 4.1, 0, 3.3, 2.7, 0, 2.2}, {0, 0, 4, 0, 2, 3, 0, 2}};
  for (const auto& q : quadrilaterals) {
    const NodeSets nodes = build_triangle_node_sets(
        triangles(0.5,
                  {polygon({{q[0], q[1], 0}, {q[2], q[3], 0}, {q[4], q[5], 0}, {q[6], q[7], 0}},
                           "soil")}),
        {"soil"});
    const double area = 0.5 * std::abs((q[0] * q[3] - q[2] * q[1]) + (q[2] * q[5] - q[4] * q[3]) +
                                       (q[4] * q[7] - q[6] * q[5]) + (q[6] * q[1] - q[0] * q[7]));
    EXPECT_NEAR(sum(nodes.stress_points.volume), area, 1e-10 * area) << q[4] << " " << q[5];
  }
}

// A hand-made complex of two triangles over the square [0, 1]^2 of the shape at line 4.
NodeSets two_triangles(const std::array<Vec3, 4>& corners) {
  NodeSets nodes;
  nodes.dimension = 2;
  nodes.spacing = 1.0;
  nodes.sph_nodes.dimension = 2;
  nodes.stress_points.dimension = 2;
  for (const Vec3& x : corners)
    nodes.sph_nodes.push_back(x, 0.25);
  nodes.node_material = {0, 0, 0, 0};
  nodes.cells = CellComplex(2, 4);
  const std::array<std::int32_t, 3> lower{0, 1, 2}, upper{0, 2, 3};
  nodes.cells.add_cell(CellKind::Triangle, lower, 0);
  nodes.cells.add_cell(CellKind::Triangle, upper, 0);
  nodes.cells.finish(nodes.sph_nodes);
  return nodes;
}

TEST(TriangleMesher, DegenerateInvertedOrSliverCellsAreRefusedAtTheirShape) {
  GeometrySpec geometry = triangles(1.0, {rectangle(0, 0, 1, 1, "soil")});
  geometry.shapes[0].where = SourceLocation{"case.yaml", 4, 7};
  geometry.where = SourceLocation{"case.yaml", 2, 1};
  EXPECT_NO_THROW(
      check_cells(two_triangles({{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}}), geometry));
  struct Bad {
    const char* name;
    std::array<Vec3, 4> corners;
    const char* says;
  };
  const std::vector<Bad> bad = {
      // Corner 1 pulled across the diagonal: the lower triangle turns clockwise.
      {"inverted", {{{0, 0, 0}, {0.2, 0.8, 0}, {1, 1, 0}, {0, 1, 0}}}, "inverted"},
      // Corner 1 on the line from 0 to 2: zero area.
      {"degenerate", {{{0, 0, 0}, {0.5, 0.5, 0}, {1, 1, 0}, {0, 1, 0}}}, "degenerate"},
      // Corner 1 a hair off that line: positive area, a corner far below a degree.
      {"sliver", {{{0, 0, 0}, {0.5, 0.499, 0}, {1, 1, 0}, {0, 1, 0}}}, "sliver"},
  };
  for (const Bad& test : bad) {
    SCOPED_TRACE(test.name);
    try {
      check_cells(two_triangles(test.corners), geometry);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& error) {
      EXPECT_EQ(error.location().line, 4) << error.what();
      EXPECT_EQ(error.location().column, 7) << error.what();
      EXPECT_EQ(error.key(), "geometry.shapes") << error.what();
      EXPECT_NE(error.problem().find(test.says), std::string::npos) << error.what();
      EXPECT_NE(error.problem().find("triangle 0"), std::string::npos) << error.what();
    }
  }
}

}  // namespace
}  // namespace rktsph::triangle_mesher_test
