// The motion of the large-deformation configuration (docs/theory.md §9.1) and the incremental
// rotation of its objective stress rate (eq. 9.2), each checked against exact kinematics.
#include "rktsph/physics/configuration_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "../support/lattices.hpp"
#include "rktsph/physics/kinematics/objective_rate.hpp"

namespace rktsph::configuration_motion_test {
namespace {

// Displacement of every node of `nodes` under the map x = F (X - c) + c + t.
FieldArray affine_displacement(const NodeSets& nodes, const std::array<double, 4>& f,
                               const std::array<double, 2>& centre,
                               const std::array<double, 2>& shift) {
  FieldArray u(2, nodes.sph_nodes.size());
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    const double rx = nodes.sph_nodes.position[0][i] - centre[0];
    const double ry = nodes.sph_nodes.position[1][i] - centre[1];
    u(0, i) = f[0] * rx + f[1] * ry - rx + shift[0];
    u(1, i) = f[2] * rx + f[3] * ry - ry + shift[1];
  }
  return u;
}

double total(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0);
}

TEST(ConfigurationMotion, RigidRotationMovesTheCentroidsAndKeepsEveryVolume) {
  const NodeSets nodes = test::rectangle_lattice(3.0, 2.0, 0.5);
  Configuration configuration = reference_configuration(nodes, 0.6);
  ConfigurationMotion motion(nodes);
  const double angle = 1.1;  // about 63 degrees
  const std::array<double, 4> rotation{std::cos(angle), -std::sin(angle), std::sin(angle),
                                       std::cos(angle)};
  motion.move(affine_displacement(nodes, rotation, {1.0, 0.5}, {0.3, -2.0}), configuration);
  for (std::size_t p = 0; p < nodes.stress_points.size(); ++p) {
    const double rx = nodes.stress_points.position[0][p] - 1.0;
    const double ry = nodes.stress_points.position[1][p] - 0.5;
    EXPECT_NEAR(configuration.stress_points.position[0][p],
                rotation[0] * rx + rotation[1] * ry + 1.0 + 0.3, 1e-12);
    EXPECT_NEAR(configuration.stress_points.position[1][p],
                rotation[2] * rx + rotation[3] * ry + 0.5 - 2.0, 1e-12);
    EXPECT_NEAR(configuration.stress_points.volume[p], nodes.stress_points.volume[p], 1e-12);
  }
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i)
    EXPECT_NEAR(configuration.sph_nodes.volume[i], nodes.sph_nodes.volume[i], 1e-12);
  EXPECT_EQ(motion.quality().distorted_cells, 0u);
  EXPECT_EQ(motion.quality().inverted_cells, 0u);
  EXPECT_NEAR(motion.quality().smallest_volume_ratio, 1.0, 1e-12);
}

TEST(ConfigurationMotion, HomogeneousStretchScalesVolumesByTheJacobian) {
  const NodeSets nodes = test::rectangle_lattice(2.0, 2.0, 0.25);
  Configuration configuration = reference_configuration(nodes, 0.3);
  ConfigurationMotion motion(nodes);
  // F = [[1.2, 0.3], [0, 0.9]]: J = 1.08, with shear.
  motion.move(affine_displacement(nodes, {1.2, 0.3, 0.0, 0.9}, {0.0, 0.0}, {0.0, 0.0}),
              configuration);
  for (std::size_t p = 0; p < nodes.stress_points.size(); ++p)
    EXPECT_NEAR(configuration.stress_points.volume[p] / nodes.stress_points.volume[p], 1.08, 1e-12);
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i)
    EXPECT_NEAR(motion.node_volume_ratio()[i], 1.08, 1e-12);
  EXPECT_NEAR(total(configuration.sph_nodes.volume), 1.08 * total(nodes.sph_nodes.volume), 1e-12);
}

TEST(ConfigurationMotion, ReportsDistortedConcaveAndFoldedCells) {
  const NodeSets nodes = test::rectangle_lattice(1.0, 1.0, 0.5);  // 2 x 2 cells
  Configuration configuration = reference_configuration(nodes, 0.6);
  ConfigurationMotion motion(nodes);
  FieldArray u(2, nodes.sph_nodes.size());
  const std::int32_t centre = test::lattice_node(nodes, 1, 1);
  ASSERT_GE(centre, 0);
  // Moving the centre node 0.45 dx towards a corner leaves the cell there at a corner Jacobian of
  // 0.1 (distorted, not folded); 0.6 dx makes it an arrowhead (a negative corner Jacobian, area
  // 0.4 of its reference one: concave, it keeps integrating); 1.2 dx takes the node past the
  // corner, and the cell's area (-0.2 of the reference) inverts it.
  const auto move_centre = [&](double fraction_of_dx) {
    u(0, static_cast<std::size_t>(centre)) = -fraction_of_dx * 0.5;
    u(1, static_cast<std::size_t>(centre)) = -fraction_of_dx * 0.5;
    motion.move(u, configuration);
  };
  move_centre(0.45);
  EXPECT_EQ(motion.quality().inverted_cells, 0u);
  EXPECT_EQ(motion.quality().concave_cells, 0u);
  EXPECT_GE(motion.quality().distorted_cells, 1u);
  move_centre(0.6);
  EXPECT_EQ(motion.quality().inverted_cells, 0u);
  EXPECT_EQ(motion.quality().concave_cells, 1u);
  EXPECT_NEAR(motion.quality().smallest_volume_ratio, 0.4, 1e-12);
  move_centre(1.2);
  EXPECT_EQ(motion.quality().inverted_cells, 1u);
  EXPECT_NEAR(motion.quality().smallest_volume_ratio, -0.2, 1e-12);
}

TEST(ObjectiveRate, HughesWingetRotationIsOrthogonalAndSecondOrder) {
  // A constant spin w for a time T in n steps turns the stress by 2 n atan(w dt / 2), which tends
  // to w T with an error of (w dt)^2 / 12 per unit angle.
  const double w = 3.0, span = 0.5;
  for (int n : {10, 100}) {
    double xx = 2.0, yy = -1.0, xy = 0.5;
    const double dt = span / n;
    for (int k = 0; k < n; ++k) {
      const PlaneRotation q = hughes_winget_rotation(w, dt);
      EXPECT_NEAR(q.c * q.c + q.s * q.s, 1.0, 1e-15);
      rotate_plane_stress(q, xx, yy, xy);
    }
    const double angle = 2.0 * n * std::atan(0.5 * w * dt);
    // The exact rotation of the tensor by the angle: Q = [[c, s], [-s, c]] with W_xy = w > 0.
    const double c = std::cos(angle), s = std::sin(angle);
    EXPECT_NEAR(xx, c * c * 2.0 + 2.0 * c * s * 0.5 + s * s * -1.0, 1e-12);
    EXPECT_NEAR(yy, s * s * 2.0 - 2.0 * c * s * 0.5 + c * c * -1.0, 1e-12);
    EXPECT_NEAR(xy, c * s * (-1.0 - 2.0) + (c * c - s * s) * 0.5, 1e-12);
    EXPECT_NEAR(angle, w * span, std::pow(w * dt, 2) / 12.0 * w * span * 1.01);
    EXPECT_NEAR(xx + yy, 1.0, 1e-13);  // the invariants are kept exactly
    EXPECT_NEAR(xx * yy - xy * xy, -2.25, 1e-12);
  }
}

}  // namespace
}  // namespace rktsph::configuration_motion_test
