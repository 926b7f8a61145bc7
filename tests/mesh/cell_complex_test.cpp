// The cell complex and its kinds (docs/theory.md §3.5): each kind's measure, centroid, corner
// Jacobians, faces and quality against hand computations; the cells around each node; a lattice
// body as a complex of quadrilaterals.
#include "rktsph/mesh/cell_complex.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/mesh/cell_geometry.hpp"

namespace rktsph::cell_complex_test {
namespace {

CellCorners corners_of(std::initializer_list<std::array<double, 2>> points) {
  CellCorners c;
  for (const auto& p : points) {
    c.x[static_cast<std::size_t>(c.count)] = p[0];
    c.y[static_cast<std::size_t>(c.count)] = p[1];
    ++c.count;
  }
  return c;
}

TEST(CellKinds, TriangleMeasureCentroidJacobiansQuality) {
  // Right triangle with legs 3 (x) and 2 (y): area 3, centroid (1, 2/3).
  const CellCorners c = corners_of({{1.0, 0.0}, {4.0, 0.0}, {1.0, 2.0}});
  EXPECT_DOUBLE_EQ(cell_measure(CellKind::Triangle, c), 3.0);
  const auto centre = cell_centroid(CellKind::Triangle, c);
  EXPECT_DOUBLE_EQ(centre[0], 2.0);
  EXPECT_DOUBLE_EQ(centre[1], 2.0 / 3.0);
  std::array<double, kMaxCellCorners> jacobian{};
  cell_corner_jacobians(CellKind::Triangle, c, jacobian);
  for (int k = 0; k < 3; ++k)
    EXPECT_DOUBLE_EQ(jacobian[static_cast<std::size_t>(k)], 6.0);  // twice the area at each corner
  // Smallest corner: the one at (4, 0), sin = 2 / sqrt(13).
  EXPECT_NEAR(cell_quality(CellKind::Triangle, c), 2.0 / std::sqrt(13.0), 1e-15);
  // Equilateral: sqrt(3)/2.
  const CellCorners equilateral = corners_of({{0.0, 0.0}, {1.0, 0.0}, {0.5, std::sqrt(0.75)}});
  EXPECT_NEAR(cell_quality(CellKind::Triangle, equilateral), std::sqrt(0.75), 1e-15);
  // Clockwise corners: inverted, negative area and quality.
  const CellCorners inverted = corners_of({{0.0, 0.0}, {0.0, 1.0}, {1.0, 0.0}});
  EXPECT_LT(cell_measure(CellKind::Triangle, inverted), 0.0);
  EXPECT_LT(cell_quality(CellKind::Triangle, inverted), 0.0);
  EXPECT_EQ(cell_faces(CellKind::Triangle).size(), 3u);
}

TEST(CellKinds, QuadrilateralMeasureAndFoldedCorner) {
  const CellCorners square = corners_of({{0.0, 0.0}, {2.0, 0.0}, {2.0, 2.0}, {0.0, 2.0}});
  EXPECT_DOUBLE_EQ(cell_measure(CellKind::Quadrilateral, square), 4.0);
  EXPECT_DOUBLE_EQ(cell_quality(CellKind::Quadrilateral, square), 1.0);
  const auto centre = cell_centroid(CellKind::Quadrilateral, square);
  EXPECT_DOUBLE_EQ(centre[0], 1.0);
  EXPECT_DOUBLE_EQ(centre[1], 1.0);
  // Arrowhead: corner 2 pushed inside past the diagonal from 1 to 3. Area by the shoelace formula:
  // (0,0) (2,0) (0.5,0.5) (0,2) -> 0.5 * |0 + 1 + 1 + 0| = 1; corner 2 is re-entrant.
  const CellCorners arrow = corners_of({{0.0, 0.0}, {2.0, 0.0}, {0.5, 0.5}, {0.0, 2.0}});
  EXPECT_DOUBLE_EQ(cell_measure(CellKind::Quadrilateral, arrow), 1.0);
  std::array<double, kMaxCellCorners> jacobian{};
  cell_corner_jacobians(CellKind::Quadrilateral, arrow, jacobian);
  EXPECT_LT(jacobian[2], 0.0);
  EXPECT_GT(jacobian[0], 0.0);
  EXPECT_LT(cell_quality(CellKind::Quadrilateral, arrow), 0.0);
}

TEST(CellKinds, SegmentIsItsLength) {
  const CellCorners c = corners_of({{1.5, 0.0}, {2.0, 0.0}});
  EXPECT_DOUBLE_EQ(cell_measure(CellKind::Segment, c), 0.5);
  EXPECT_DOUBLE_EQ(cell_centroid(CellKind::Segment, c)[0], 1.75);
  EXPECT_DOUBLE_EQ(cell_quality(CellKind::Segment, c), 1.0);
  EXPECT_EQ(cell_faces(CellKind::Segment).size(), 2u);
}

TEST(CellComplex, CellsAroundNodesAndReferenceMeasures) {
  // Two triangles sharing the diagonal of the unit square: 0-1-2 and 0-2-3.
  PointCloud nodes;
  nodes.dimension = 2;
  for (const auto& p : {std::array<double, 3>{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}})
    nodes.push_back(p, 0.25);
  CellComplex complex(2, nodes.size());
  complex.add_cell(CellKind::Triangle, std::array<std::int32_t, 3>{0, 1, 2}, 0);
  complex.add_cell(CellKind::Triangle, std::array<std::int32_t, 3>{0, 2, 3}, 1);
  complex.finish(nodes);
  EXPECT_EQ(complex.cell_count(), 2u);
  EXPECT_EQ(complex.cells_of(0).size(), 2u);
  EXPECT_EQ(complex.cells_of(1).size(), 1u);
  EXPECT_EQ(complex.cells_of(2).size(), 2u);
  EXPECT_EQ(complex.cells_of(3)[0], 1);
  EXPECT_DOUBLE_EQ(complex.reference_measure(0), 0.5);
  EXPECT_DOUBLE_EQ(complex.reference_measure(1), 0.5);
  EXPECT_EQ(complex.material(1), 1);
  // A corner that is no node, or a kind of another dimension, is a programming error.
  EXPECT_THROW(complex.add_cell(CellKind::Triangle, std::array<std::int32_t, 3>{0, 1, 7}, 0),
               std::logic_error);
  EXPECT_THROW(complex.add_cell(CellKind::Segment, std::array<std::int32_t, 2>{0, 1}, 0),
               std::logic_error);
  // Every complex gets a version of its own.
  CellComplex other(2, nodes.size());
  other.finish(nodes);
  EXPECT_NE(other.version(), complex.version());
}

TEST(CellComplex, LatticeBodyIsQuadrilateralsCounterClockwise) {
  // An L-shaped body: 4 x 2 cells with the upper right 2 x 1 removed.
  GeometrySpec geometry;
  geometry.spacing = 0.5;
  ShapeSpec shape;
  shape.kind = ShapeSpec::Kind::Polygon;
  shape.vertices = {{0, 0, 0}, {2, 0, 0}, {2, 0.5, 0}, {1, 0.5, 0}, {1, 1, 0}, {0, 1, 0}};
  shape.material = "soil";
  geometry.shapes = {shape};
  const NodeSets nodes = build_node_sets(geometry, 2, {"soil"});
  const CellComplex& cells = nodes.cells;
  ASSERT_EQ(cells.cell_count(), nodes.stress_points.size());
  EXPECT_EQ(cells.cell_count(), 6u);
  double area = 0.0;
  for (std::size_t p = 0; p < cells.cell_count(); ++p) {
    EXPECT_EQ(cells.kind(p), CellKind::Quadrilateral);
    const CellCorners c = cells.corner_positions(nodes.sph_nodes, p);
    EXPECT_DOUBLE_EQ(cell_measure(CellKind::Quadrilateral, c), 0.25);  // counter-clockwise
    const auto centre = cell_centroid(cells.kind(p), c);
    EXPECT_DOUBLE_EQ(centre[0], nodes.stress_points.position[0][p]);
    EXPECT_DOUBLE_EQ(centre[1], nodes.stress_points.position[1][p]);
    area += cells.reference_measure(p);
  }
  EXPECT_DOUBLE_EQ(area, 1.5);
  // Cells around each node: 4 inside, 3 at the re-entrant corner (1, 0.5), 1 at convex corners.
  std::size_t total = 0;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    const double x = nodes.sph_nodes.position[0][i], y = nodes.sph_nodes.position[1][i];
    const std::size_t around = cells.cells_of(i).size();
    total += around;
    std::size_t expected = 0;
    if (x == 1.0 && y == 0.5) expected = 3;
    if (x == 0.5 && y == 0.5) expected = 4;
    if ((x == 0.0 && y == 0.0) || (x == 2.0 && y == 0.5)) expected = 1;
    if (expected > 0) {
      EXPECT_EQ(around, expected) << x << ", " << y;
    }
  }
  EXPECT_EQ(total, 4u * cells.cell_count());
}

}  // namespace
}  // namespace rktsph::cell_complex_test
