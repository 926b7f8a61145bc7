#include "rktsph/sph/neighbour_search.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "rktsph/core/point_cloud.hpp"

namespace rktsph::neighbour_search_test {
namespace {

/// Uniform random points in the box [lower, upper]^dimension, unit volumes.
PointCloud random_cloud(int dimension, std::size_t count, double lower, double upper,
                        std::mt19937_64& random) {
  std::uniform_real_distribution<double> coordinate(lower, upper);
  PointCloud cloud;
  cloud.dimension = dimension;
  for (std::size_t i = 0; i < count; ++i) {
    std::array<double, 3> x{0.0, 0.0, 0.0};
    for (int a = 0; a < dimension; ++a)
      x[a] = coordinate(random);
    cloud.push_back(x, 1.0);
  }
  return cloud;
}

/// Square/cubic lattice with `per_side` points of spacing `spacing` per axis, starting at `start`.
PointCloud lattice(int dimension, int per_side, double spacing, double start) {
  PointCloud cloud;
  cloud.dimension = dimension;
  const int nz = dimension == 3 ? per_side : 1;
  const int ny = dimension >= 2 ? per_side : 1;
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < per_side; ++i) {
        cloud.push_back({start + i * spacing, start + j * spacing, start + k * spacing},
                        std::pow(spacing, dimension));
      }
    }
  }
  return cloud;
}

double squared_distance(const PointCloud& targets, std::size_t i, const PointCloud& sources,
                        std::size_t j) {
  double sum = 0.0;
  for (int a = 0; a < targets.dimension; ++a) {
    const double offset = targets.position[a][i] - sources.position[a][j];
    sum += offset * offset;
  }
  return sum;
}

/// Reference: test every pair, O(N M), rows naturally ascending.
std::vector<std::vector<std::int32_t>> brute_force(const PointCloud& targets,
                                                   const PointCloud& sources, double radius,
                                                   bool same_set) {
  std::vector<std::vector<std::int32_t>> rows(targets.size());
  for (std::size_t i = 0; i < targets.size(); ++i) {
    for (std::size_t j = 0; j < sources.size(); ++j) {
      if (same_set && i == j) continue;
      if (squared_distance(targets, i, sources, j) < radius * radius) {
        rows[i].push_back(static_cast<std::int32_t>(j));
      }
    }
  }
  return rows;
}

/// Checks table structure and equality with the reference row by row; returns the pair count.
std::size_t expect_table_equals(const NeighbourTable& table,
                                const std::vector<std::vector<std::int32_t>>& expected,
                                const std::string& label) {
  EXPECT_EQ(table.rows(), expected.size()) << label;
  EXPECT_EQ(table.row_start.size(), expected.size() + 1) << label;
  EXPECT_EQ(table.row_start.front(), 0) << label;
  EXPECT_EQ(table.neighbour.size(), table.total()) << label;
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < std::min(table.rows(), expected.size()); ++i) {
    const auto row = table.row(i);
    EXPECT_TRUE(std::is_sorted(row.begin(), row.end())) << label << " row " << i;
    const std::vector<std::int32_t> actual(row.begin(), row.end());
    EXPECT_EQ(actual, expected[i]) << label << " row " << i;
    EXPECT_EQ(table.count(i), expected[i].size()) << label << " row " << i;
    pairs += expected[i].size();
    if (::testing::Test::HasFailure()) break;  // one failing row is enough to diagnose
  }
  EXPECT_EQ(table.total(), pairs) << label;
  return pairs;
}

TEST(NeighbourSearch, RandomSameSetMatchesBruteForceIn1D2D3D) {
  std::mt19937_64 random(12345);
  // Sizes chosen so that every radius has several neighbours on average.
  const std::array<std::size_t, 3> count = {400, 700, 900};
  for (int dimension = 1; dimension <= 3; ++dimension) {
    const PointCloud cloud = random_cloud(dimension, count[dimension - 1], -1.0, 2.0, random);
    for (double radius : {0.01, 0.17, 0.4, 1.1, 10.0}) {
      const NeighbourTable table = find_neighbours(cloud, cloud, radius, true);
      const std::size_t pairs =
          expect_table_equals(table, brute_force(cloud, cloud, radius, true),
                              std::to_string(dimension) + "D r=" + std::to_string(radius));
      if (radius >= 0.17) {
        EXPECT_GT(pairs, 0u);
      }
    }
  }
}

TEST(NeighbourSearch, RandomCrossSetWithQueriesOutsideTheBox) {
  std::mt19937_64 random(777);
  for (int dimension = 1; dimension <= 3; ++dimension) {
    // Sources in [0, 1]^d; targets in [-0.6, 1.6]^d, so many queries lie outside the binned box,
    // some farther than the radius (empty rows) and some within it (rows from the edge cells).
    const PointCloud sources = random_cloud(dimension, 600, 0.0, 1.0, random);
    const PointCloud targets = random_cloud(dimension, 500, -0.6, 1.6, random);
    for (double radius : {0.05, 0.23, 0.5}) {
      expect_table_equals(find_neighbours(targets, sources, radius, false),
                          brute_force(targets, sources, radius, false),
                          std::to_string(dimension) + "D cross r=" + std::to_string(radius));
    }
  }
}

TEST(NeighbourSearch, RebuiltListFindsWhatAFreshListFinds) {
  // One list rebuilt on clouds of other sizes, dimensions and boxes (a moving configuration
  // rebuilds its lists every step), then on an empty cloud: always the brute-force neighbours.
  std::mt19937_64 random(4242);
  CellList cells;
  for (int round = 0; round < 6; ++round) {
    const int dimension = 1 + round % 3;
    const PointCloud sources = random_cloud(dimension, 200 + 150 * static_cast<std::size_t>(round),
                                            -0.5 * round, 1.0 + round, random);
    const PointCloud targets =
        random_cloud(dimension, 300, -0.5 * round - 0.3, 1.3 + round, random);
    const double radius = 0.1 + 0.05 * round;
    cells.rebuild(sources, radius);
    expect_table_equals(find_neighbours(targets, cells, radius, false),
                        brute_force(targets, sources, radius, false),
                        "round " + std::to_string(round));
  }
  const PointCloud empty = random_cloud(2, 0, 0.0, 1.0, random);
  cells.rebuild(empty, 0.1);
  int visited = 0;
  cells.for_each_within({0.5, 0.5, 0.0}, 10.0,
                        [&](std::int32_t, const auto&, double) { ++visited; });
  EXPECT_EQ(visited, 0);
}

TEST(NeighbourSearch, RadiusLargerThanCellSizeScansEnoughCells) {
  std::mt19937_64 random(4242);
  for (int dimension = 1; dimension <= 3; ++dimension) {
    const PointCloud sources = random_cloud(dimension, 500, 0.0, 1.0, random);
    const PointCloud targets = random_cloud(dimension, 300, -0.3, 1.3, random);
    const CellList cells(sources, 0.07);
    for (double radius : {0.03, 0.07, 0.15, 0.32}) {  // up to ~4.6 cells
      expect_table_equals(find_neighbours(targets, cells, radius, false),
                          brute_force(targets, sources, radius, false),
                          std::to_string(dimension) + "D r/cell=" + std::to_string(radius / 0.07));
    }
  }
}

TEST(NeighbourSearch, LatticeCountsMatchHandCountedShells) {
  const double spacing = 0.1;
  // Radius 1.5 dx: in 2D the 4 edge neighbours (dx) and 4 diagonals (1.414 dx); in 3D the 6 face
  // and 12 edge neighbours (1.414 dx) but not the 8 corners (1.732 dx); in 1D the 2 at dx.
  const std::array<std::size_t, 3> interior = {2, 8, 18};
  for (int dimension = 1; dimension <= 3; ++dimension) {
    const int per_side = dimension == 3 ? 8 : 12;
    const PointCloud cloud = lattice(dimension, per_side, spacing, -0.35);
    const double radius = 1.5 * spacing;
    const NeighbourTable table = find_neighbours(cloud, cloud, radius, true);
    expect_table_equals(table, brute_force(cloud, cloud, radius, true),
                        std::to_string(dimension) + "D lattice");
    // Point (3, 3, 3) of the lattice is interior in every dimension.
    const std::size_t probe =
        3 + (dimension >= 2 ? 3 * per_side : 0) + (dimension == 3 ? 3 * per_side * per_side : 0);
    EXPECT_EQ(table.count(probe), interior[dimension - 1]) << dimension << "D";
    // Corner 0: 1 (1D), 3 (2D: two edges and a diagonal), 6 (3D: 3 faces, 3 edge diagonals).
    const std::array<std::size_t, 3> corner = {1, 3, 6};
    EXPECT_EQ(table.count(0), corner[dimension - 1]) << dimension << "D";
  }
}

TEST(NeighbourSearch, StressPointLayoutCountsFromTheSpec) {
  // docs/theory.md §3.1, §4.6: SPH nodes on a lattice, stress points at cell centres. A cell centre
  // has 4 nodes at 0.707 dx, 8 at 1.58 dx, 4 at 2.12 dx. So support 1.5 dx (h = 0.75 dx) gives 4
  // and support 2.4 dx (h = 1.2 dx) gives 16, for stress points and for interior nodes alike.
  const double spacing = 0.25;
  const int per_side = 10;
  const PointCloud nodes = lattice(2, per_side, spacing, 0.0);
  const PointCloud stress_points = lattice(2, per_side - 1, spacing, 0.5 * spacing);
  for (auto [radius, expected] : {std::pair{1.5 * spacing, 4u}, std::pair{2.4 * spacing, 16u}}) {
    const NeighbourTable node_to_stress = find_neighbours(nodes, stress_points, radius, false);
    const NeighbourTable stress_to_node = find_neighbours(stress_points, nodes, radius, false);
    expect_table_equals(node_to_stress, brute_force(nodes, stress_points, radius, false), "V->S");
    expect_table_equals(stress_to_node, brute_force(stress_points, nodes, radius, false), "S->V");
    const std::size_t interior_node = 5 + 5 * per_side;
    const std::size_t interior_stress_point = 4 + 4 * (per_side - 1);
    EXPECT_EQ(node_to_stress.count(interior_node), expected);
    EXPECT_EQ(stress_to_node.count(interior_stress_point), expected);
    // The two tables are transposes of each other.
    EXPECT_EQ(node_to_stress.total(), stress_to_node.total());
  }
}

TEST(NeighbourSearch, CoincidentPointsAreNeighboursButNotOfThemselves) {
  PointCloud cloud;
  cloud.dimension = 2;
  cloud.push_back({0.5, 0.5, 0.0}, 1.0);
  cloud.push_back({0.5, 0.5, 0.0}, 1.0);
  cloud.push_back({0.9, 0.5, 0.0}, 1.0);
  const NeighbourTable same = find_neighbours(cloud, cloud, 0.3, true);
  expect_table_equals(same, {{1}, {0}, {}}, "same set");
  // The same cloud as a cross set: each point then finds itself.
  const NeighbourTable cross = find_neighbours(cloud, cloud, 0.3, false);
  expect_table_equals(cross, {{0, 1}, {0, 1}, {2}}, "cross set");
}

TEST(NeighbourSearch, RadiusIsStrict) {
  // Exactly representable distances: 0.5 and 0.25 (binary fractions).
  PointCloud cloud;
  cloud.dimension = 1;
  cloud.push_back({0.0, 0.0, 0.0}, 1.0);
  cloud.push_back({0.5, 0.0, 0.0}, 1.0);
  cloud.push_back({0.75, 0.0, 0.0}, 1.0);
  expect_table_equals(find_neighbours(cloud, cloud, 0.5, true), {{}, {2}, {1}}, "r = 0.5");
  expect_table_equals(find_neighbours(cloud, cloud, 0.25, true), {{}, {}, {}}, "r = 0.25");
  expect_table_equals(find_neighbours(cloud, cloud, 0.5000001, true), {{1}, {0, 2}, {1}},
                      "r > 0.5");
}

TEST(NeighbourSearch, EmptyCloudsAndNonPositiveRadius) {
  std::mt19937_64 random(1);
  const PointCloud cloud = random_cloud(2, 50, 0.0, 1.0, random);
  PointCloud empty;
  empty.dimension = 2;

  const NeighbourTable no_targets = find_neighbours(empty, cloud, 0.2, false);
  EXPECT_EQ(no_targets.rows(), 0u);
  EXPECT_EQ(no_targets.total(), 0u);
  ASSERT_EQ(no_targets.row_start.size(), 1u);

  const NeighbourTable no_sources = find_neighbours(cloud, empty, 0.2, false);
  EXPECT_EQ(no_sources.rows(), 50u);
  EXPECT_EQ(no_sources.total(), 0u);

  const NeighbourTable both_empty = find_neighbours(empty, empty, 0.2, true);
  EXPECT_EQ(both_empty.rows(), 0u);

  const NeighbourTable zero_radius = find_neighbours(cloud, cloud, 0.0, false);
  EXPECT_EQ(zero_radius.rows(), 50u);
  EXPECT_EQ(zero_radius.total(), 0u);

  const CellList empty_cells(empty, 0.1);
  int visits = 0;
  empty_cells.for_each_within(
      {0.0, 0.0, 0.0}, 1.0, [&](std::int32_t, const std::array<double, 3>&, double) { ++visits; });
  EXPECT_EQ(visits, 0);

  const NeighbourTable default_table;
  EXPECT_EQ(default_table.rows(), 0u);
  EXPECT_EQ(default_table.total(), 0u);
}

TEST(NeighbourSearch, ForEachWithinReportsOffsetAndSquaredDistance) {
  std::mt19937_64 random(99);
  for (int dimension = 1; dimension <= 3; ++dimension) {
    const PointCloud cloud = random_cloud(dimension, 300, 0.0, 1.0, random);
    const CellList cells(cloud, 0.1);
    EXPECT_EQ(&cells.points(), &cloud);
    const std::array<double, 3> query{0.45, 1.02, -0.03};  // partly outside the box
    std::vector<std::int32_t> visited;
    cells.for_each_within(
        query, 0.25,
        [&](std::int32_t j, const std::array<double, 3>& offset, double distance_squared) {
          visited.push_back(j);
          double sum = 0.0;
          for (int a = 0; a < 3; ++a) {
            const double expected = a < dimension ? query[a] - cloud.position[a][j] : 0.0;
            EXPECT_EQ(offset[a], expected);
            sum += expected * expected;
          }
          EXPECT_DOUBLE_EQ(distance_squared, sum);
        });
    std::sort(visited.begin(), visited.end());
    std::vector<std::int32_t> expected;
    for (std::size_t j = 0; j < cloud.size(); ++j) {
      double sum = 0.0;
      for (int a = 0; a < dimension; ++a) {
        sum += (query[a] - cloud.position[a][j]) * (query[a] - cloud.position[a][j]);
      }
      if (sum < 0.25 * 0.25) expected.push_back(static_cast<std::int32_t>(j));
    }
    EXPECT_EQ(visited, expected) << dimension << "D";
    EXPECT_FALSE(expected.empty());
  }
}

TEST(NeighbourSearch, FarAwayQueriesAndOutliersAreHandled) {
  std::mt19937_64 random(5);
  PointCloud sources = random_cloud(2, 200, 0.0, 1.0, random);
  // One outlier far away: the grid would need ~1e12 cells of size 0.05; it must be coarsened.
  sources.push_back({1e5, -1e5, 0.0}, 1.0);
  const CellList cells(sources, 0.05);
  const auto counts = cells.cell_counts();
  EXPECT_LE(counts[0] * counts[1], 8 * 201 + 4096);
  PointCloud targets = random_cloud(2, 100, -0.2, 1.2, random);
  targets.push_back({1e5 + 0.01, -1e5, 0.0}, 1.0);
  targets.push_back({-1e9, 1e9, 0.0}, 1.0);
  expect_table_equals(find_neighbours(targets, cells, 0.05, false),
                      brute_force(targets, sources, 0.05, false), "outlier");
}

TEST(NeighbourSearch, OutputDoesNotDependOnThreadCount) {
  std::mt19937_64 random(2024);
  const PointCloud cloud = random_cloud(2, 20000, 0.0, 1.0, random);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const NeighbourTable serial = find_neighbours(cloud, cloud, 0.02, true);
  omp_set_num_threads(4);
  const NeighbourTable parallel = find_neighbours(cloud, cloud, 0.02, true);
  omp_set_num_threads(saved);
  EXPECT_EQ(serial.row_start, parallel.row_start);
  EXPECT_EQ(serial.neighbour, parallel.neighbour);
  EXPECT_GT(serial.total(), cloud.size());  // ~ N * pi r^2 N = 25 per point
}

TEST(NeighbourSearch, RejectsInconsistentArguments) {
  std::mt19937_64 random(3);
  const PointCloud planar = random_cloud(2, 10, 0.0, 1.0, random);
  const PointCloud spatial = random_cloud(3, 10, 0.0, 1.0, random);
  const PointCloud fewer = random_cloud(2, 9, 0.0, 1.0, random);
  EXPECT_THROW(find_neighbours(planar, spatial, 0.1, false), std::invalid_argument);
  EXPECT_THROW(find_neighbours(planar, fewer, 0.1, true), std::invalid_argument);
  EXPECT_THROW(CellList(planar, 0.0), std::invalid_argument);
  EXPECT_THROW(CellList(planar, -1.0), std::invalid_argument);
  EXPECT_THROW(CellList(planar, std::nan("")), std::invalid_argument);
  PointCloud broken = planar;
  broken.position[1][4] = std::nan("");
  EXPECT_THROW(CellList(broken, 0.1), std::invalid_argument);
}

}  // namespace
}  // namespace rktsph::neighbour_search_test
