// The odd-even and rest measures shared by the loaded-body cases (validation/rest_checks.hpp),
// on sequences and fields whose answer is known by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rktsph/validation/rest_checks.hpp"

namespace rktsph::rest_checks_test {
namespace {

TEST(OddEvenResidualTest, ZeroOnALinearSequence) {
  const std::vector<double> linear = {1.0, 3.0, 5.0, 7.0, 9.0, 11.0};
  EXPECT_DOUBLE_EQ(oddeven_residual(linear), 0.0);
}

TEST(OddEvenResidualTest, AmplitudeOfAPureAlternatingSequence) {
  const double amplitude = 0.37;
  std::vector<double> alternating;
  for (int i = 0; i < 9; ++i)
    alternating.push_back(i % 2 == 0 ? amplitude : -amplitude);
  EXPECT_DOUBLE_EQ(oddeven_residual(alternating), amplitude);
  // On top of a linear trend and an offset: the same amplitude.
  for (int i = 0; i < 9; ++i)
    alternating[static_cast<std::size_t>(i)] += 5.0 + 0.1 * i;
  EXPECT_NEAR(oddeven_residual(alternating), amplitude, 1e-12);
}

TEST(OddEvenResidualTest, SmoothQuadraticGivesAQuarterOfItsSecondDifference) {
  // s_i = c (i h)^2: -s_{i-1} + 2 s_i - s_{i+1} = -2 c h^2, so the residual is c h^2 / 2, small
  // against the values (c (n h)^2) when the line has many nodes.
  const double c = 3.0, h = 0.1;
  std::vector<double> quadratic;
  for (int i = 0; i <= 20; ++i)
    quadratic.push_back(c * (i * h) * (i * h));
  EXPECT_NEAR(oddeven_residual(quadratic), c * h * h / 2.0, 1e-12);
  EXPECT_NEAR(oddeven_residual(quadratic) / quadratic.back(), 1.0 / (2.0 * 20 * 20), 1e-12);
}

TEST(OddEvenResidualTest, MirrorAtTheFirstNode) {
  // An even function mirrored at its first node: i = 0 sees s_{-1} = s_1.
  const std::vector<double> even = {0.0, 1.0, 4.0, 9.0};  // s = i^2
  EXPECT_DOUBLE_EQ(oddeven_residual(even, true), 0.5);
  // A pattern alternating from the symmetry plane: the first node counts too.
  const std::vector<double> kink = {1.0, 0.0, 0.0, 0.0};
  EXPECT_DOUBLE_EQ(oddeven_residual(kink), 0.0 + 0.25);
  EXPECT_DOUBLE_EQ(oddeven_residual(kink, true), 0.5);
  EXPECT_DOUBLE_EQ(oddeven_residual(std::vector<double>{1.0, 2.0}), 0.0);
}

TEST(OddEvenResidualAlongTest, UnevenSpacingSeesNoPatternInALinearField) {
  // Gaps of 0.25 and 0.5 m mixed, as a triangle mesh leaves on a refined edge: a linear field is
  // 0 here, while the even-spacing formula would read the gaps as a pattern.
  NodeLine line;
  const std::vector<double> x = {0.0, 0.25, 0.75, 1.0, 1.5, 1.75, 2.25};
  for (double position : x) {
    line.x.push_back(position);
    line.value.push_back(3.0 - 2.0 * position);
  }
  EXPECT_NEAR(oddeven_residual_along(line), 0.0, 1e-14);
  EXPECT_GT(oddeven_residual(line.value), 0.05);
  // An alternating part of amplitude A on that spacing: its full amplitude where the gaps agree.
  const double amplitude = 0.2;
  for (std::size_t i = 0; i < x.size(); ++i)
    line.value[i] += i % 2 == 0 ? amplitude : -amplitude;
  EXPECT_NEAR(oddeven_residual_along(line), amplitude, 1e-12);
}

TEST(OddEvenResidualAlongTest, EvenSpacingIsTheLatticeFormulaToTheLastBit) {
  NodeLine line;
  for (int i = 0; i <= 12; ++i) {
    line.x.push_back(0.1 * i);
    line.value.push_back(std::sin(1.3 * i) + 0.01 * i * i);
  }
  EXPECT_EQ(oddeven_residual_along(line), oddeven_residual(line.value));
  EXPECT_EQ(oddeven_residual_along(line, true), oddeven_residual(line.value, true));
}

TEST(SettlementOddEvenRatioTest, OverTheLoadedSurfaceAndTwoWidthsBeyond) {
  // b = 1: the nodes 0 <= x <= 5 count, those beyond do not.
  NodeLine settlement;
  for (int i = 0; i <= 40; ++i) {
    const double x = 0.25 * i;
    settlement.x.push_back(x);
    settlement.value.push_back(x <= 5.0 ? 2.0 : (i % 2 == 0 ? 10.0 : -10.0));
  }
  EXPECT_DOUBLE_EQ(settlement_oddeven_ratio(settlement, 1.0), 0.0);
  // An alternating part of 0.1 on a settlement of 2: ratio 0.1 / 2.1.
  for (std::size_t k = 0; k < settlement.x.size(); ++k)
    if (settlement.x[k] <= 5.0) settlement.value[k] += (k % 2 == 0 ? 0.1 : -0.1);
  EXPECT_NEAR(settlement_oddeven_ratio(settlement, 1.0), 0.1 / 2.1, 1e-12);
}

TEST(ContactPressureOddEvenRatioTest, UniformAndAlternating) {
  NodeLine pressure{{0.0, 1.0, 2.0, 3.0, 4.0, 5.0}, {9.0, 5.0, 5.0, 5.0, 5.0, 1.0}};
  // The end nodes only enter as neighbours: a uniform interior next to them still sees them.
  EXPECT_NEAR(contact_pressure_oddeven_ratio(pressure), 1.0 / 5.0, 1e-12);
  pressure.value = {5.0, 5.0, 5.0, 5.0, 5.0, 5.0};
  EXPECT_DOUBLE_EQ(contact_pressure_oddeven_ratio(pressure), 0.0);
  pressure.value = {5.2, 4.8, 5.2, 4.8, 5.2, 4.8};
  EXPECT_NEAR(contact_pressure_oddeven_ratio(pressure), 0.2 / 5.0, 1e-12);
}

LatticeField field_of(int columns, int rows, const std::function<double(int, int)>& value) {
  LatticeField field;
  field.columns = columns;
  field.rows = rows;
  field.spacing = 0.5;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i)
      field.value.push_back(value(i, j));
  return field;
}

TEST(CheckerboardAmplitudeTest, PureCheckerboardSmoothAndOneDirectionalFields) {
  const LatticeField checkerboard =
      field_of(6, 5, [](int i, int j) { return (i + j) % 2 == 0 ? 0.3 : -0.3; });
  EXPECT_NEAR(checkerboard_amplitude(checkerboard), 0.3, 1e-12);
  EXPECT_DOUBLE_EQ(max_abs(checkerboard), 0.3);
  // f(x) + g(y): zero, whatever f and g (a boundary layer along a face).
  const LatticeField separable =
      field_of(6, 5, [](int i, int j) { return std::exp(-i) + j * j * j; });
  EXPECT_NEAR(checkerboard_amplitude(separable), 0.0, 1e-12);
  // x y: the mixed fourth derivative is zero too.
  const LatticeField bilinear = field_of(6, 5, [](int i, int j) { return 1.0 * i * j; });
  EXPECT_NEAR(checkerboard_amplitude(bilinear), 0.0, 1e-12);
  // Missing nodes and skipped nodes are left out.
  LatticeField holed = checkerboard;
  for (double& value : holed.value)
    value = std::nan("");
  EXPECT_DOUBLE_EQ(checkerboard_amplitude(holed), 0.0);
  EXPECT_DOUBLE_EQ(checkerboard_amplitude(checkerboard, [](double, double) { return true; }), 0.0);
}

TEST(ResidualVelocityRatioTest, EndOverPeakAfterTheStart) {
  const SpeedHistory history{{0.0, 1.0, 2.0, 3.0, 4.0}, {0.0, 4.0, 1.0, 0.5, 0.002}};
  EXPECT_DOUBLE_EQ(residual_velocity_ratio(history), 0.002 / 4.0);
  EXPECT_DOUBLE_EQ(residual_velocity_ratio(history, 2.0), 0.002 / 1.0);
  EXPECT_TRUE(std::isnan(residual_velocity_ratio(SpeedHistory{})));
}

}  // namespace
}  // namespace rktsph::rest_checks_test
