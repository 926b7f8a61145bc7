// Facet normals that follow the moving configuration (docs/theory.md §9.7): under an affine map
// x = F X every straight face stays straight and its outward normal is F^-T N / |F^-T N|.
#include "rktsph/boundary/perimeter_normals.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "../support/lattices.hpp"

namespace rktsph::perimeter_normals_test {
namespace {

TEST(PerimeterNormals, FollowAnAffineMapOfTheBodyExactly) {
  const NodeSets nodes = test::rectangle_lattice(3.0, 2.0, 0.5);
  const std::vector<std::uint8_t> no_mirrors(nodes.sph_nodes.size(), 0);
  SurfaceSet surface;
  outline_surface(nodes.cells, nodes.outline, nodes.sph_nodes, no_mirrors, surface);
  const SurfaceSet reference = surface;
  const PerimeterNormals perimeter(nodes.outline, nodes.sph_nodes, surface);
  // F = R(40 deg) [[1.3, 0.4], [0, 0.8]]: rotation, stretch and shear.
  const double angle = 40.0 * std::acos(-1.0) / 180.0;
  const double c = std::cos(angle), s = std::sin(angle);
  const double f[4] = {c * 1.3, c * 0.4 - s * 0.8, s * 1.3, s * 0.4 + c * 0.8};
  PointCloud moved = nodes.sph_nodes;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    const double x = nodes.sph_nodes.position[0][i], y = nodes.sph_nodes.position[1][i];
    moved.position[0][i] = f[0] * x + f[1] * y;
    moved.position[1][i] = f[2] * x + f[3] * y;
  }
  perimeter.update(moved, surface);
  const double det = f[0] * f[3] - f[1] * f[2];
  for (std::size_t k = 0; k < reference.facet_count(); ++k) {
    const Vec3 n = reference.facet_normal(static_cast<std::int32_t>(k));
    // F^-T N = (1/det) [[f3, -f2], [-f1, f0]] N.
    double mx = (f[3] * n[0] - f[2] * n[1]) / det, my = (-f[1] * n[0] + f[0] * n[1]) / det;
    const double length = std::hypot(mx, my);
    mx /= length;
    my /= length;
    EXPECT_NEAR(surface.normal[0][k], mx, 1e-12) << "facet " << k;
    EXPECT_NEAR(surface.normal[1][k], my, 1e-12) << "facet " << k;
    EXPECT_EQ(surface.reactions[k], reference.reactions[k]);
  }
}

TEST(PerimeterNormals, ABentFaceTakesTheChordOfItsNeighbours) {
  const NodeSets nodes = test::rectangle_lattice(2.0, 1.0, 0.5);
  const std::vector<std::uint8_t> no_mirrors(nodes.sph_nodes.size(), 0);
  SurfaceSet surface;
  outline_surface(nodes.cells, nodes.outline, nodes.sph_nodes, no_mirrors, surface);
  const PerimeterNormals perimeter(nodes.outline, nodes.sph_nodes, surface);
  // Lift the middle node of the top face by dx/2: its neighbours along the face stay, so its
  // normal stays +y, while each neighbour's turns towards the bump by atan(0.25 / 1).
  PointCloud moved = nodes.sph_nodes;
  const std::int32_t top_middle = test::lattice_node(nodes, 2, 2);
  const std::int32_t top_right = test::lattice_node(nodes, 3, 2);
  moved.position[1][static_cast<std::size_t>(top_middle)] += 0.25;
  perimeter.update(moved, surface);
  for (std::size_t k = 0; k < surface.size(); ++k) {
    if (surface.node[k] != top_middle && surface.node[k] != top_right) continue;
    const std::int32_t f = surface.facets_begin(k);
    const double expected = surface.node[k] == top_middle ? 0.0 : std::atan(0.25);
    EXPECT_NEAR(std::atan2(surface.normal[0][static_cast<std::size_t>(f)],
                           surface.normal[1][static_cast<std::size_t>(f)]),
                expected, 1e-12);
  }
}

}  // namespace
}  // namespace rktsph::perimeter_normals_test
