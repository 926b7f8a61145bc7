// Two node sets that must be the same to the bit: positions and volumes of both point sets, node
// materials, and every cell's corners and material.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>

#include "rktsph/geometry/node_sets.hpp"

namespace rktsph::test {

inline void expect_same_node_sets(const NodeSets& read, const NodeSets& own) {
  ASSERT_EQ(read.sph_nodes.size(), own.sph_nodes.size());
  ASSERT_EQ(read.cells.cell_count(), own.cells.cell_count());
  for (int a = 0; a < 2; ++a) {
    EXPECT_EQ(read.sph_nodes.position[a], own.sph_nodes.position[a]);
    EXPECT_EQ(read.stress_points.position[a], own.stress_points.position[a]);
  }
  EXPECT_EQ(read.sph_nodes.volume, own.sph_nodes.volume);
  EXPECT_EQ(read.stress_points.volume, own.stress_points.volume);
  EXPECT_EQ(read.node_material, own.node_material);
  for (std::size_t p = 0; p < own.cells.cell_count(); ++p) {
    const auto a = read.cells.corners(p), b = own.cells.corners(p);
    EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << "cell " << p;
    EXPECT_EQ(read.cells.material(p), own.cells.material(p)) << "cell " << p;
  }
}

}  // namespace rktsph::test
