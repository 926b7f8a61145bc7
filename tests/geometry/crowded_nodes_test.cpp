// spread_crowded_nodes (docs/theory.md §9.19, eq. 9.16): a node closer to a neighbour than the
// fraction of its spacing moves to the centroid of its neighbours in the cells, a surface node to
// the midpoint of its two outline neighbours (a straight face stays straight), a held component
// stays, nodes that are not crowded do not move, and no node is moved into a rigid body.
#include "rktsph/geometry/crowded_nodes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "rktsph/mesh/delaunay_cells.hpp"

namespace rktsph::crowded_nodes_test {
namespace {

struct Patch {
  PointCloud nodes;
  DelaunayCells formed;
  Outline outline;
};

// The Delaunay cells of the 5 x 5 lattice of spacing 1, node (i, j) = 5 j + i.
Patch lattice_patch() {
  Patch patch;
  patch.nodes.dimension = 2;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i)
      patch.nodes.push_back({static_cast<double>(i), static_cast<double>(j), 0.0}, 1.0);
  const std::vector<double> spacing(25, 1.0);
  const std::vector<std::int32_t> material(25, 0);
  patch.formed = delaunay_cells(patch.nodes, spacing, material, 1.0);
  patch.outline = Outline(patch.formed.cells, patch.nodes);
  return patch;
}

TEST(CrowdedNodes, ACrowdedInnerNodeMovesToTheCentroidOfItsNeighbours) {
  const Patch patch = lattice_patch();
  PointCloud moved = patch.nodes;
  moved.position[0][12] = 2.05;  // node (2, 2) within 0.05 of node (2, 3)
  moved.position[1][12] = 2.95;
  const std::vector<double> spacing(25, 1.0);
  const std::vector<std::uint8_t> held(25, 0);
  FieldArray shift(2, 25);
  const std::size_t count =
      spread_crowded_nodes(patch.formed.cells, patch.outline, moved, spacing, 0.3, held, {}, shift);
  // (2, 2) moves first; then (2, 3), each other's crowded neighbour, is no longer crowded.
  EXPECT_EQ(count, 1u);
  EXPECT_EQ(shift(0, 17), 0.0);
  EXPECT_EQ(shift(1, 17), 0.0);
  std::vector<std::int32_t> ring;
  for (std::int32_t cell : patch.formed.cells.cells_of(12))
    for (std::int32_t corner : patch.formed.cells.corners(static_cast<std::size_t>(cell)))
      if (corner != 12) ring.push_back(corner);
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  double cx = 0.0, cy = 0.0;
  for (std::int32_t j : ring) {
    cx += moved.position[0][static_cast<std::size_t>(j)] / static_cast<double>(ring.size());
    cy += moved.position[1][static_cast<std::size_t>(j)] / static_cast<double>(ring.size());
  }
  EXPECT_NEAR(moved.position[0][12] + shift(0, 12), cx, 1e-14);
  EXPECT_NEAR(moved.position[1][12] + shift(1, 12), cy, 1e-14);
  // Away from the pair nothing moves.
  for (std::size_t i : {0u, 6u, 8u, 20u, 24u}) {
    EXPECT_EQ(shift(0, i), 0.0) << i;
    EXPECT_EQ(shift(1, i), 0.0) << i;
  }
}

TEST(CrowdedNodes, ASurfaceNodeMovesAlongItsFaceAndAHeldComponentStays) {
  const Patch patch = lattice_patch();
  PointCloud moved = patch.nodes;
  moved.position[0][2] = 2.95;  // node (2, 0) on the base within 0.05 of node (3, 0)
  const std::vector<double> spacing(25, 1.0);
  std::vector<std::uint8_t> held(25, 0);
  FieldArray shift(2, 25);
  spread_crowded_nodes(patch.formed.cells, patch.outline, moved, spacing, 0.3, held, {}, shift);
  // The midpoint of its outline neighbours (1, 0)-(3, 0): the face stays y = 0, and (3, 0) is
  // then no longer crowded.
  EXPECT_NEAR(moved.position[0][2] + shift(0, 2), 2.0, 1e-15);
  EXPECT_EQ(shift(1, 2), 0.0);
  EXPECT_EQ(shift(0, 3), 0.0);
  held[2] = 0b01;  // x imposed at node (2, 0): it stays, and (3, 0) moves off it instead, to the
                   // midpoint of (2.95, 0)-(4, 0)
  spread_crowded_nodes(patch.formed.cells, patch.outline, moved, spacing, 0.3, held, {}, shift);
  EXPECT_EQ(shift(0, 2), 0.0);
  EXPECT_NEAR(moved.position[0][3] + shift(0, 3), 3.475, 1e-15);
  EXPECT_EQ(shift(1, 3), 0.0);
  // Not crowded below the fraction: 0.05 apart is not closer than 0.04 of the spacing.
  EXPECT_EQ(spread_crowded_nodes(patch.formed.cells, patch.outline, moved, spacing, 0.04, held, {},
                                 shift),
            0u);
}

TEST(CrowdedNodes, NoNodeIsMovedIntoARigidBodyNorOntoAnother) {
  // The corner node (4, 4), crowded by (4, 3.9), held there, would move to the midpoint of its
  // outline neighbours, (3.5, 3.95); a body there (as one the soil wraps at its corner) keeps
  // it where it is.
  const Patch patch = lattice_patch();
  PointCloud moved = patch.nodes;
  moved.position[1][19] = 3.9;
  const std::vector<double> spacing(25, 1.0);
  std::vector<std::uint8_t> held(25, 0);
  held[19] = 0b11;
  FieldArray shift(2, 25);
  EXPECT_EQ(
      spread_crowded_nodes(patch.formed.cells, patch.outline, moved, spacing, 0.3, held, {}, shift),
      1u);
  EXPECT_NEAR(moved.position[0][24] + shift(0, 24), 3.5, 1e-15);
  EXPECT_NEAR(moved.position[1][24] + shift(1, 24), 3.95, 1e-15);
  const std::vector<std::vector<Vec3>> body = {
      {{3.3, 3.8, 0.0}, {3.7, 3.8, 0.0}, {3.7, 4.2, 0.0}, {3.3, 4.2, 0.0}}};
  EXPECT_EQ(spread_crowded_nodes(patch.formed.cells, patch.outline, moved, spacing, 0.3, held, body,
                                 shift),
            0u);
  EXPECT_EQ(shift(0, 24), 0.0);
  EXPECT_EQ(shift(1, 24), 0.0);
  // Two neighbours on the base crowded on each other move one after the other: (1, 0) and (2, 0)
  // at 1.48 and 1.52 m; (1, 0) goes to the midpoint of (0, 0) and (1.52, 0), and (2, 0), then
  // 0.76 m from it, stays (moved at once from the old positions both would move).
  moved = patch.nodes;
  moved.position[0][1] = 1.48;
  moved.position[0][2] = 1.52;
  held.assign(25, 0);
  EXPECT_EQ(
      spread_crowded_nodes(patch.formed.cells, patch.outline, moved, spacing, 0.3, held, {}, shift),
      1u);
  EXPECT_NEAR(moved.position[0][1] + shift(0, 1), 0.76, 1e-15);
  EXPECT_EQ(shift(0, 2), 0.0);
}

}  // namespace
}  // namespace rktsph::crowded_nodes_test
