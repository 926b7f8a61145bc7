// Cells formed from a node cloud (docs/theory.md §3.9, eq. 3.15): the Delaunay triangles of the
// nodes trimmed by the alpha criterion, against areas and shapes known by hand.
#include "rktsph/mesh/delaunay_cells.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

#include "rktsph/mesh/cell_geometry.hpp"
#include "rktsph/mesh/outline.hpp"

namespace rktsph::delaunay_cells_test {
namespace {

// The nodes (i dx, j dx), 0 <= i < nx, 0 <= j < ny, that `keep` accepts.
PointCloud lattice_cloud(
    int nx, int ny, double dx,
    const std::function<bool(int, int)>& keep = [](int, int) { return true; }) {
  PointCloud cloud;
  cloud.dimension = 2;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (keep(i, j)) {
        cloud.resize(cloud.size() + 1);
        cloud.position[0].back() = i * dx;
        cloud.position[1].back() = j * dx;
      }
  return cloud;
}

DelaunayCells form(const PointCloud& cloud, double spacing, double alpha,
                   std::vector<std::int32_t> material = {}) {
  if (material.empty()) material.assign(cloud.size(), 0);
  const std::vector<double> spacings(cloud.size(), spacing);
  return delaunay_cells(cloud, spacings, material, alpha);
}

double total_area(const DelaunayCells& formed) {
  double area = 0.0;
  for (std::size_t p = 0; p < formed.cells.cell_count(); ++p)
    area += formed.cells.reference_measure(p);
  return area;
}

// Twice the signed area of cell p: positive when its corners run counter-clockwise.
double signed_double_area(const PointCloud& cloud, const DelaunayCells& formed, std::size_t p) {
  const CellCorners c = formed.cells.corner_positions(cloud, p);
  return (c.x[1] - c.x[0]) * (c.y[2] - c.y[0]) - (c.x[2] - c.x[0]) * (c.y[1] - c.y[0]);
}

TEST(DelaunayCells, KeepsALatticeWholeWithItsArea) {
  const double dx = 0.5;
  const PointCloud cloud = lattice_cloud(11, 6, dx);
  const DelaunayCells formed = form(cloud, dx, 0.75);
  EXPECT_EQ(formed.cells.cell_count(), 2u * 10u * 5u);
  EXPECT_EQ(formed.count.triangles, 100u);
  EXPECT_EQ(formed.count.dropped, 0u);
  EXPECT_EQ(formed.count.isolated_nodes, 0u);
  EXPECT_NEAR(total_area(formed), 5.0 * 2.5, 1e-12);
  for (std::size_t p = 0; p < formed.cells.cell_count(); ++p) {
    EXPECT_EQ(formed.cells.kind(p), CellKind::Triangle);
    EXPECT_NEAR(signed_double_area(cloud, formed, p), dx * dx, 1e-12);  // counter-clockwise
  }
}

TEST(DelaunayCells, AlphaBelowHalfTheDiagonalKeepsNoLatticeCell) {
  // Every triangle of a square lattice has R = dx / sqrt(2).
  const DelaunayCells formed = form(lattice_cloud(5, 5, 1.0), 1.0, 0.7);
  EXPECT_EQ(formed.cells.cell_count(), 0u);
  EXPECT_EQ(formed.count.dropped, 32u);
  EXPECT_EQ(formed.count.isolated_nodes, 25u);
}

TEST(DelaunayCells, KeepsTheNotchOfAnLShapeOpen) {
  // 0 <= x, y <= 10 without the quarter x > 5, y > 5: the hull spans the notch, the cells do not,
  // but for the half cell (5, 5), (6, 5), (5, 6) at its corner, whose R = 1/sqrt(2) is a lattice
  // cell's. The next triangle into the notch, (5, 7), (5, 6), (6, 5), has R = sqrt(2.5).
  const PointCloud cloud =
      lattice_cloud(11, 11, 1.0, [](int i, int j) { return i <= 5 || j <= 5; });
  const DelaunayCells formed = form(cloud, 1.0, 1.5);
  EXPECT_NEAR(total_area(formed), 100.0 - 25.0 + 0.5, 1e-9);
  EXPECT_GT(formed.count.dropped, 0u);
  EXPECT_EQ(formed.count.isolated_nodes, 0u);
  EXPECT_GT(total_area(form(cloud, 1.0, 1.6)), 75.5 + 1.0);
}

TEST(DelaunayCells, AOneNodeHoleStaysOpenBelowAlphaOneAndClosesAbove) {
  // The hole's four edge neighbours lie on a circle of radius dx about the missing node.
  const double dx = 0.2;
  const PointCloud cloud =
      lattice_cloud(7, 7, dx, [](int i, int j) { return !(i == 3 && j == 3); });
  EXPECT_NEAR(total_area(form(cloud, dx, 0.9)), 36.0 * dx * dx - 2.0 * dx * dx, 1e-12);
  EXPECT_NEAR(total_area(form(cloud, dx, 1.1)), 36.0 * dx * dx, 1e-12);
}

TEST(DelaunayCells, TwoBodiesApartFormNoCellBetweenThem) {
  // Two 5 x 5 blocks of unit spacing with a gap of three spacings between x = 4 and x = 7.
  const PointCloud cloud = lattice_cloud(12, 5, 1.0, [](int i, int) { return i <= 4 || i >= 7; });
  const DelaunayCells formed = form(cloud, 1.0, 1.5);
  EXPECT_NEAR(total_area(formed), 2.0 * 16.0, 1e-12);
  for (std::size_t p = 0; p < formed.cells.cell_count(); ++p) {
    const CellCorners c = formed.cells.corner_positions(cloud, p);
    const bool left = c.x[0] <= 4.0 && c.x[1] <= 4.0 && c.x[2] <= 4.0;
    const bool right = c.x[0] >= 7.0 && c.x[1] >= 7.0 && c.x[2] >= 7.0;
    EXPECT_TRUE(left || right) << "cell " << p << " spans the gap";
  }
}

TEST(DelaunayCells, ACellTakesTheMaterialOfMostOfItsCorners) {
  // Material 1 on the nodes x >= 2 of a 5 x 3 lattice: a cell with two corners there is of 1.
  const PointCloud cloud = lattice_cloud(5, 3, 1.0);
  std::vector<std::int32_t> material(cloud.size(), 0);
  for (std::size_t n = 0; n < cloud.size(); ++n)
    if (cloud.position[0][n] >= 2.0) material[n] = 1;
  const DelaunayCells formed = form(cloud, 1.0, 1.0, material);
  for (std::size_t p = 0; p < formed.cells.cell_count(); ++p) {
    int on_one = 0;
    for (const std::int32_t n : formed.cells.corners(p))
      on_one += material[static_cast<std::size_t>(n)];
    EXPECT_EQ(formed.cells.material(p), on_one >= 2 ? 1 : 0) << "cell " << p;
  }
}

TEST(DelaunayCells, ACloudWithNoAreaFormsNoCell) {
  const PointCloud line = lattice_cloud(6, 1, 1.0);
  const DelaunayCells formed = form(line, 1.0, 10.0);
  EXPECT_EQ(formed.cells.cell_count(), 0u);
  EXPECT_EQ(formed.count.isolated_nodes, 6u);
  EXPECT_EQ(form(lattice_cloud(2, 1, 1.0), 1.0, 10.0).cells.cell_count(), 0u);
  EXPECT_EQ(form(lattice_cloud(0, 0, 1.0), 1.0, 10.0).cells.cell_count(), 0u);
}

TEST(DelaunayCells, RefusesInputItCannotFormCellsFrom) {
  const PointCloud cloud = lattice_cloud(3, 3, 1.0);
  const std::vector<double> spacing(cloud.size(), 1.0);
  const std::vector<std::int32_t> material(cloud.size(), 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(delaunay_cells(cloud, spacing, material, 0.0), std::invalid_argument);
  EXPECT_THROW(delaunay_cells(cloud, spacing, material, nan), std::invalid_argument);
  EXPECT_THROW(delaunay_cells(cloud, std::vector<double>(2, 1.0), material, 1.0),
               std::invalid_argument);
  std::vector<double> negative = spacing;
  negative[4] = -1.0;
  EXPECT_THROW(delaunay_cells(cloud, negative, material, 1.0), std::invalid_argument);
  PointCloud flat = cloud;
  flat.dimension = 1;
  EXPECT_THROW(delaunay_cells(flat, spacing, material, 1.0), std::invalid_argument);
  PointCloud twice = cloud;
  twice.position[0][1] = twice.position[0][0];
  twice.position[1][1] = twice.position[1][0];
  EXPECT_THROW(delaunay_cells(twice, spacing, material, 1.0), std::invalid_argument);
}

TEST(DelaunayCells, NoCellCrossesASolidInANotchItFills) {
  // A 6 m x 4 m lattice (dx = 1) with a notch 2 m wide from y = 2 up (the nodes x = 3, y >= 2
  // left out) and a rigid body filling it: with alpha = 3 the notch would be bridged (area 24);
  // with the body, no triangle crosses it and the cells cover the rectangle less the notch.
  const PointCloud cloud = lattice_cloud(7, 5, 1.0, [](int i, int j) { return i != 3 || j < 2; });
  const std::vector<double> spacing(cloud.size(), 1.0);
  const std::vector<std::int32_t> material(cloud.size(), 0);
  EXPECT_NEAR(total_area(delaunay_cells(cloud, spacing, material, 3.0, true)), 24.0, 1e-12);
  const std::vector<std::vector<Vec3>> body = {{{2, 2, 0}, {4, 2, 0}, {4, 5, 0}, {2, 5, 0}}};
  const DelaunayCells formed = delaunay_cells(cloud, spacing, material, 3.0, true, body);
  EXPECT_NEAR(total_area(formed), 20.0, 1e-12);
  EXPECT_EQ(formed.count.isolated_nodes, 0u);
}

}  // namespace
TEST(DelaunayCells, TwoTrianglesTouchingAtANodeAreJoinedIntoOneFan) {
  // Two triangles meet at the origin only (a bow tie): triangle (-2,-1), (-2,1), (0,0) has
  // R = abc/(4A) = 2 sqrt5 sqrt5 / (4 * 2) = 1.25, the Delaunay triangles above and below the
  // origin ((-2,1), (0,0), (2,1) and its mirror) R = 4 sqrt5 sqrt5 / (4 * 2) = 2.5. At alpha 1.5
  // the criterion keeps the two and drops the two between them, leaving the origin in two fans; one
  // gap is kept again, and the origin's cells form one fan.
  PointCloud cloud;
  cloud.dimension = 2;
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{
           {-2.0, -1.0}, {-2.0, 1.0}, {0.0, 0.0}, {2.0, -1.0}, {2.0, 1.0}}) {
    cloud.resize(cloud.size() + 1);
    cloud.position[0].back() = x;
    cloud.position[1].back() = y;
  }
  const DelaunayCells formed = form(cloud, 1.0, 1.5);
  EXPECT_EQ(formed.count.triangles, 4u);
  EXPECT_EQ(formed.count.restored, 1u);
  EXPECT_EQ(formed.count.dropped, 1u);
  ASSERT_EQ(formed.cells.cell_count(), 3u);
  // One fan at the origin: its three cells are joined edge to edge, so the outline passes the
  // origin once, on two facets.
  const Outline outline(formed.cells, cloud);
  EXPECT_EQ(outline.facets_at(2).size(), 2u);
  for (std::size_t n = 0; n < cloud.size(); ++n)
    EXPECT_LE(outline.facets_at(n).size(), 2u) << "node " << n;
  // Without the alpha cut nothing is restored.
  EXPECT_EQ(form(cloud, 1.0, 3.0).count.restored, 0u);
}

}  // namespace rktsph::delaunay_cells_test
