// The traction condition sigma·n = t on any unit normal (docs/theory.md eq. 5.1a): on a tilted
// normal sigma·n reaches the target and the tangential stress is kept; on a coordinate axis the
// lattice face's assignment sigma_ac = sign t_c is reproduced bit for bit.
#include "rktsph/boundary/surface_traction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace rktsph::surface_traction_test {
namespace {

StressTensor plane_stress_state() {
  StressTensor sigma{};
  sigma[0][0] = 3.1e4;
  sigma[1][1] = -2.3e4;
  sigma[0][1] = sigma[1][0] = 1.7e4;
  sigma[2][2] = 0.7e4;  // sigma_zz of plane strain: tangential to every in-plane normal
  return sigma;
}

Vec3 dot(const StressTensor& sigma, const Vec3& n) {
  Vec3 product{};
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t c = 0; c < 3; ++c)
      product[a] += sigma[a][c] * n[c];
  return product;
}

double inner(const Vec3& u, const Vec3& w) {
  return u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
}

const double kCos30 = std::cos(std::numbers::pi / 6.0), kSin30 = std::sin(std::numbers::pi / 6.0);

TEST(SurfaceTraction, ThirtyDegreeNormalReachesTheTargetAndKeepsTheTangentialStress) {
  for (const Vec3 target : {Vec3{0.0, 0.0, 0.0}, Vec3{-4.0e3, 9.0e3, 0.0}}) {
    StressTensor sigma = plane_stress_state();
    const Vec3 n{kCos30, kSin30, 0.0}, tangent{-kSin30, kCos30, 0.0};
    const double tangential_before = inner(tangent, dot(sigma, tangent));
    TractionCondition condition{n, target, 0b11, std::nullopt};
    impose_traction(condition, 2, sigma);
    const Vec3 traction = dot(sigma, n);
    EXPECT_NEAR(traction[0], target[0], 1e-11 * 3.1e4);
    EXPECT_NEAR(traction[1], target[1], 1e-11 * 3.1e4);
    EXPECT_NEAR(inner(tangent, dot(sigma, tangent)), tangential_before, 1e-11 * 3.1e4);
    EXPECT_EQ(sigma[0][1], sigma[1][0]);
    EXPECT_EQ(sigma[2][2], 0.7e4);
  }
}

TEST(SurfaceTraction, SaturatedTractionActsOnTheTotalStress) {
  StressTensor sigma = plane_stress_state();
  const Vec3 n{-kSin30, kCos30, 0.0}, target{1.0e3, -5.0e3, 0.0};
  const double biot_pore_pressure = 2.0e3;
  impose_traction(TractionCondition{n, target, 0b11, biot_pore_pressure}, 2, sigma);
  for (std::size_t a = 0; a < 3; ++a)
    sigma[a][a] -= biot_pore_pressure;  // sigma' - alpha p_w I
  const Vec3 traction = dot(sigma, n);
  EXPECT_NEAR(traction[0], target[0], 1e-11 * 3.1e4);
  EXPECT_NEAR(traction[1], target[1], 1e-11 * 3.1e4);
}

TEST(SurfaceTraction, ComponentsNotImposedKeepTheirSigmaDotN) {
  StressTensor sigma = plane_stress_state();
  const Vec3 n{kCos30, -kSin30, 0.0};
  const double kept = dot(sigma, n)[1];
  impose_traction(TractionCondition{n, {-2.0e3, 0.0, 0.0}, 0b01, std::nullopt}, 2, sigma);
  EXPECT_NEAR(dot(sigma, n)[0], -2.0e3, 1e-11 * 3.1e4);
  EXPECT_NEAR(dot(sigma, n)[1], kept, 1e-11 * 3.1e4);
}

TEST(SurfaceTraction, TiltedNormalInThreeDimensions) {
  StressTensor sigma = plane_stress_state();
  sigma[0][2] = sigma[2][0] = -1.1e4;
  sigma[1][2] = sigma[2][1] = 0.4e4;
  const Vec3 n{1.0 / 3.0, 2.0 / 3.0, -2.0 / 3.0}, target{5.0e2, -1.0e3, 2.5e3};
  const Vec3 u{2.0 / 3.0, 1.0 / 3.0, 2.0 / 3.0}, w{2.0 / 3.0, -2.0 / 3.0, -1.0 / 3.0};
  const double uu = inner(u, dot(sigma, u)), uw = inner(u, dot(sigma, w)),
               ww = inner(w, dot(sigma, w));
  impose_traction(TractionCondition{n, target, 0b111, std::nullopt}, 3, sigma);
  const Vec3 traction = dot(sigma, n);
  for (std::size_t c = 0; c < 3; ++c)
    EXPECT_NEAR(traction[c], target[c], 1e-11 * 3.1e4);
  EXPECT_NEAR(inner(u, dot(sigma, u)), uu, 1e-11 * 3.1e4);
  EXPECT_NEAR(inner(u, dot(sigma, w)), uw, 1e-11 * 3.1e4);
  EXPECT_NEAR(inner(w, dot(sigma, w)), ww, 1e-11 * 3.1e4);
}

// The assignment of a lattice face before unit normals: sigma_ac = sign t_c for each imposed c,
// plus alpha p_w on sigma_aa in the saturated model.
StressTensor per_axis_assignment(StressTensor sigma, int axis, double sign, const Vec3& t,
                                 std::uint8_t components, std::optional<double> biot_pore) {
  const auto a = static_cast<std::size_t>(axis);
  for (std::size_t c = 0; c < 2; ++c) {
    if (!((components >> c) & 1u)) continue;
    double value = sign * t[c];
    if (biot_pore && c == a) value += *biot_pore;
    sigma[a][c] = sigma[c][a] = value;
  }
  return sigma;
}

TEST(SurfaceTraction, AxisNormalsReproduceThePerAxisAssignmentExactly) {
  // Values whose products and sums round: a general formula would not return them exactly.
  const Vec3 t{-1.0e4 / 3.0, 0.1 + 0.2, 0.0};
  for (int axis = 0; axis < 2; ++axis)
    for (double sign : {-1.0, 1.0})
      for (std::uint8_t components : {0b01, 0b10, 0b11})
        for (std::optional<double> biot_pore :
             {std::optional<double>{}, std::optional(7.0 / 3.0)}) {
          Vec3 n{};
          n[static_cast<std::size_t>(axis)] = sign;
          StressTensor sigma = plane_stress_state();
          sigma[0][0] = 1.0 / 3.0;
          const StressTensor expected =
              per_axis_assignment(sigma, axis, sign, t, components, biot_pore);
          impose_traction(TractionCondition{n, t, components, biot_pore}, 2, sigma);
          for (std::size_t a = 0; a < 3; ++a)
            for (std::size_t c = 0; c < 3; ++c)
              EXPECT_EQ(sigma[a][c], expected[a][c]) << "axis " << axis << " sign " << sign;
        }
}

TEST(SurfaceTraction, OnlyCoordinateAxesTakeThePerAxisPath) {
  EXPECT_TRUE(as_axis_normal({0.0, -1.0, 0.0}));
  EXPECT_EQ(as_axis_normal({0.0, -1.0, 0.0})->axis, 1);
  EXPECT_EQ(as_axis_normal({0.0, -1.0, 0.0})->sign, -1.0);
  EXPECT_FALSE(as_axis_normal({kCos30, kSin30, 0.0}));
}

}  // namespace
}  // namespace rktsph::surface_traction_test
