// The Flamant strip solution (references/strip_elastic.*) against values derived by hand:
//   centre line, z = b:        α = π/2, sin α = 1  → σ_z = q(1/2 + 1/π), σ_x = q(1/2 − 1/π);
//   centre line, z = b/√3:     α = 2π/3            → σ_z = q(2/3 + √3/(2π)), σ_x = q(2/3 −
//   √3/(2π)); under the edge x = b, z = 2b: α = atan(2b/2b) − atan(0) = π/4, δ = 0
//                              → σ_z = q(1/4 + 1/(2π)), σ_x = q(1/4 − 1/(2π)), τ = q/(2π);
// and limits: at the surface under the strip σ_z → q, far down the line load 2qb of Flamant,
// σ_z → 2(2qb)/(π z); the largest shear (σ_1 − σ_3)/2 = (q/π) sin α everywhere.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "rktsph/validation/references/strip_elastic.hpp"

namespace rktsph::references::strip_elastic_test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLoad = 5.0e4, kHalfWidth = 2.0;

TEST(FlamantStripTest, CentreLineAtDepthB) {
  EXPECT_NEAR(flamant_centre_line_vertical_stress(kLoad, kHalfWidth, kHalfWidth),
              kLoad * (0.5 + 1.0 / kPi), 1e-9 * kLoad);
  EXPECT_NEAR(flamant_centre_line_horizontal_stress(kLoad, kHalfWidth, kHalfWidth),
              kLoad * (0.5 - 1.0 / kPi), 1e-9 * kLoad);
  // 0.818310 and 0.181690 of q, as strip_elastic.py prints at z/b = 1.
  EXPECT_NEAR(flamant_centre_line_vertical_stress(1.0, kHalfWidth, kHalfWidth), 0.81831, 1e-5);
  EXPECT_NEAR(flamant_centre_line_horizontal_stress(1.0, kHalfWidth, kHalfWidth), 0.18169, 1e-5);
}

TEST(FlamantStripTest, CentreLineWhereTheStripSubtends120Degrees) {
  const double z = kHalfWidth / std::sqrt(3.0);
  EXPECT_NEAR(flamant_centre_line_vertical_stress(kLoad, kHalfWidth, z),
              kLoad * (2.0 / 3.0 + std::sqrt(3.0) / (2.0 * kPi)), 1e-9 * kLoad);
  EXPECT_NEAR(flamant_centre_line_horizontal_stress(kLoad, kHalfWidth, z),
              kLoad * (2.0 / 3.0 - std::sqrt(3.0) / (2.0 * kPi)), 1e-9 * kLoad);
}

TEST(FlamantStripTest, GeneralFormulaUnderTheEdge) {
  const StripStress s = flamant_strip_stress(kLoad, kHalfWidth, kHalfWidth, 2.0 * kHalfWidth);
  EXPECT_NEAR(s.sigma_z, kLoad * (0.25 + 0.5 / kPi), 1e-9 * kLoad);
  EXPECT_NEAR(s.sigma_x, kLoad * (0.25 - 0.5 / kPi), 1e-9 * kLoad);
  EXPECT_NEAR(std::abs(s.tau_xz), kLoad * 0.5 / kPi, 1e-9 * kLoad);
  // Mirror symmetry: normal stresses even in x, shear odd.
  const StripStress m = flamant_strip_stress(kLoad, kHalfWidth, -kHalfWidth, 2.0 * kHalfWidth);
  EXPECT_NEAR(m.sigma_z, s.sigma_z, 1e-9 * kLoad);
  EXPECT_NEAR(m.sigma_x, s.sigma_x, 1e-9 * kLoad);
  EXPECT_NEAR(m.tau_xz, -s.tau_xz, 1e-9 * kLoad);
}

TEST(FlamantStripTest, GeneralFormulaAgreesWithTheCentreLine) {
  for (double z : {0.3, 1.0, 2.0, 4.0, 9.0}) {
    const StripStress s = flamant_strip_stress(kLoad, kHalfWidth, 0.0, z);
    EXPECT_NEAR(s.sigma_z, flamant_centre_line_vertical_stress(kLoad, kHalfWidth, z), 1e-9 * kLoad);
    EXPECT_NEAR(s.sigma_x, flamant_centre_line_horizontal_stress(kLoad, kHalfWidth, z),
                1e-9 * kLoad);
    EXPECT_NEAR(s.tau_xz, 0.0, 1e-9 * kLoad);
  }
}

TEST(FlamantStripTest, Limits) {
  // Just under the strip at the surface: σ_z = q, σ_x = q (α → π, sin α → 0).
  const StripStress top = flamant_strip_stress(kLoad, kHalfWidth, 0.5, 1e-9);
  EXPECT_NEAR(top.sigma_z, kLoad, 1e-6 * kLoad);
  EXPECT_NEAR(top.sigma_x, kLoad, 1e-6 * kLoad);
  // Beside the strip at the surface: unloaded.
  const StripStress beside = flamant_strip_stress(kLoad, kHalfWidth, 3.0 * kHalfWidth, 1e-9);
  EXPECT_NEAR(beside.sigma_z, 0.0, 1e-6 * kLoad);
  // Far down: the Flamant line load P = 2qb, σ_z = 2P/(π z) on its axis, to O((b/z)^2).
  const double z = 1000.0 * kHalfWidth;
  EXPECT_NEAR(flamant_centre_line_vertical_stress(kLoad, kHalfWidth, z) /
                  (4.0 * kLoad * kHalfWidth / (kPi * z)),
              1.0, 1e-5);
  // The largest shear is (q/π) sin α at any point.
  for (double x : {-3.0, -1.0, 0.5, 2.0, 5.0})
    for (double depth : {0.2, 1.5, 4.0}) {
      const StripStress s = flamant_strip_stress(kLoad, kHalfWidth, x, depth);
      const double alpha =
          std::atan((x + kHalfWidth) / depth) - std::atan((x - kHalfWidth) / depth);
      EXPECT_NEAR(std::hypot(0.5 * (s.sigma_z - s.sigma_x), s.tau_xz),
                  kLoad / kPi * std::sin(alpha), 1e-9 * kLoad);
    }
  EXPECT_THROW(flamant_strip_stress(kLoad, kHalfWidth, 0.0, 0.0), std::invalid_argument);
}

// The strip on a layer between smooth walls (the bundled half model's box).
TEST(SmoothLayerStripTest, LoadOverTheWholeWidthIsTheOedometricState) {
  // b = W: every cosine term vanishes (sin(n pi) = 0) and the layer is laterally confined:
  // sigma_z = q, sigma_x = K0 q = nu/(1 - nu) q at every point.
  const SmoothLayer layer{24.0, 24.0, 0.3};
  for (double x : {0.0, 7.0, 24.0})
    for (double z : {0.5, 12.0, 24.0}) {
      const StripStress s = strip_on_smooth_layer_stress(kLoad, 24.0, layer, x, z);
      EXPECT_NEAR(s.sigma_z, kLoad, 1e-9 * kLoad);
      EXPECT_NEAR(s.sigma_x, 0.3 / 0.7 * kLoad, 1e-9 * kLoad);
    }
}

TEST(SmoothLayerStripTest, SurfaceTractionIsTheStripLoad) {
  // Just below the surface: sigma_z = q under the strip and 0 beside it, as the load series.
  const SmoothLayer layer{24.0, 24.0, 0.3};
  EXPECT_NEAR(strip_on_smooth_layer_stress(kLoad, kHalfWidth, layer, 1.0, 1e-3).sigma_z, kLoad,
              2e-3 * kLoad);
  EXPECT_NEAR(strip_on_smooth_layer_stress(kLoad, kHalfWidth, layer, 3.0, 1e-3).sigma_z, 0.0,
              2e-3 * kLoad);
  EXPECT_THROW(strip_on_smooth_layer_stress(kLoad, kHalfWidth, layer, 25.0, 1.0),
               std::invalid_argument);
}

TEST(SmoothLayerStripTest, TendsToFlamantLikeBOverW) {
  // sigma_z converges fast; sigma_x differs by c q b/W with c nearly constant (the walls carry
  // the load the Flamant field spreads as 1/r).
  std::vector<double> scaled;
  for (double w : {48.0, 96.0, 192.0}) {
    const SmoothLayer layer{w, w, 0.3};
    const StripStress s = strip_on_smooth_layer_stress(kLoad, kHalfWidth, layer, 0.0, kHalfWidth);
    EXPECT_NEAR(s.sigma_z, flamant_centre_line_vertical_stress(kLoad, kHalfWidth, kHalfWidth),
                1e-3 * kLoad);
    const double difference =
        flamant_centre_line_horizontal_stress(kLoad, kHalfWidth, kHalfWidth) - s.sigma_x;
    scaled.push_back(difference / kLoad * w / kHalfWidth);
  }
  EXPECT_GT(scaled[0], 0.0);
  EXPECT_NEAR(scaled[1] / scaled[0], 1.0, 0.1);
  EXPECT_NEAR(scaled[2] / scaled[1], 1.0, 0.1);
}

TEST(SmoothLayerStripTest, SettlementOfAUniformLoadIsTheOedometerOne) {
  // b = W: s = q H / M, M = E (1 - nu) / ((1 + nu)(1 - 2 nu)), at every x.
  const double modulus = 1.0e7, nu = 0.3;
  const SmoothLayer layer{24.0, 24.0, nu};
  const double oedometric = modulus * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
  for (double s :
       strip_on_smooth_layer_surface_settlement(kLoad, 24.0, layer, modulus, {0.0, 5.0, 24.0}))
    EXPECT_NEAR(s, kLoad * 24.0 / oedometric, 1e-9 * kLoad * 24.0 / oedometric);
}

TEST(SmoothLayerStripTest, DifferentialSettlementTendsToTheHalfPlane) {
  // Half-plane: u_z = -(2 (1 - nu^2) q / (pi E)) [(x+b) ln|x+b| - (x-b) ln|x-b|] + const, so
  // s(0) - s(b) = (2 (1 - nu^2) q / (pi E)) (2b ln 2b - 2b ln b) = 4 ln2 (1 - nu^2) q b / (pi E).
  const double modulus = 1.0e7, nu = 0.3;
  const double half_plane =
      4.0 * std::log(2.0) * (1.0 - nu * nu) * kLoad * kHalfWidth / (kPi * modulus);
  const SmoothLayer layer{96.0, 96.0, nu};
  const std::vector<double> s = strip_on_smooth_layer_surface_settlement(
      kLoad, kHalfWidth, layer, modulus, {0.0, kHalfWidth}, 8000);
  EXPECT_NEAR((s[0] - s[1]) / half_plane, 1.0, 2e-3);
}

}  // namespace
}  // namespace rktsph::references::strip_elastic_test
