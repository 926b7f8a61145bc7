// The band-angle measurement on synthetic fields whose band directions are known by construction:
// Gaussian ridges on a node lattice over a 1 m x 2 m sample (the §4.4 geometry), on a sloping
// background with uniform noise. The ridges cross the sample edges obliquely, as a real band does,
// which is what biases a naive principal-axes fit.
#include "rktsph/validation/band_angle.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "rktsph/core/error.hpp"

namespace rktsph::band_angle_test {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
// The brief asks for the angle within 1 degree on these fields; the ridge fit is exact for a
// straight symmetric ridge, so what is left is noise and lattice sampling.
constexpr double kAngleTolerance = 1.0;

/// A straight ridge through (x0, y0), `tilt_deg` from the vertical (positive: rising to the left,
/// i.e. counter-clockwise from +y), with a Gaussian profile of standard deviation `width`,
/// optionally limited to `along` in [along_min, along_max] from (x0, y0).
struct Ridge {
  double x0, y0, tilt_deg, amplitude, width;
  double along_min = -1e9, along_max = 1e9;

  double direction_x() const { return -std::sin(tilt_deg * kDegree); }
  double direction_y() const { return std::cos(tilt_deg * kDegree); }
  double distance(double x, double y) const {
    return std::abs((x - x0) * direction_y() - (y - y0) * direction_x());
  }
  double value(double x, double y) const {
    const double along = (x - x0) * direction_x() + (y - y0) * direction_y();
    if (along < along_min || along > along_max) return 0.0;
    const double d = distance(x, y);
    return amplitude * std::exp(-0.5 * d * d / (width * width));
  }
};

struct Field {
  std::vector<double> x, y, value;
};

/// Lattice over [0, 1] x [0, 2]; background 0.2 y/2 (a gradient like the loading's) plus uniform
/// noise in [0, noise), plus the ridges.
Field make_field(double spacing, const std::vector<Ridge>& ridges, double noise,
                 unsigned seed = 7) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Field field;
  const int columns = static_cast<int>(std::lround(1.0 / spacing));
  const int rows = static_cast<int>(std::lround(2.0 / spacing));
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= columns; ++i) {
      const double x = i * spacing, y = j * spacing;
      double v = 0.1 * y + noise * uniform(generator);
      for (const Ridge& ridge : ridges)
        v += ridge.value(x, y);
      field.x.push_back(x);
      field.y.push_back(y);
      field.value.push_back(v);
    }
  return field;
}

BandMeasurement measure(const Field& field, const BandAngleOptions& options = {}) {
  return measure_band(field.x, field.y, field.value, options);
}

TEST(BandAngle, StraightBandsAt30_45_60DegreesWithNoiseAndBackground) {
  for (double tilt : {30.0, 45.0, 60.0, -30.0, -45.0, -60.0}) {
    SCOPED_TRACE(tilt);
    const Ridge ridge{0.5, 1.0, tilt, 1.0, 0.04};
    const BandMeasurement band = measure(make_field(0.02, {ridge}, 0.15));
    EXPECT_NEAR(band.primary.angle_deg, std::abs(tilt), kAngleTolerance);
    EXPECT_NEAR(band.primary.direction_deg, tilt, kAngleTolerance);
    // The reported centre lies on the ridge (within one spacing).
    EXPECT_LT(ridge.distance(band.primary.centre_x, band.primary.centre_y), 0.02);
    // A single band holds most of the excess weight and is straight.
    EXPECT_GT(band.primary.weight_fraction, 0.7);
    EXPECT_LT(band.primary.ridge_rms, 0.02);
    EXPECT_FALSE(band.secondary.has_value());
  }
}

TEST(BandAngle, OffLatticeAngleIsNotSnappedToTheLatticeDiagonal) {
  // On a coarse lattice (the quick variant's 0.04 m) a 41 degree band must not read as 45.
  for (double tilt : {41.0, 37.3, 52.6}) {
    SCOPED_TRACE(tilt);
    const Ridge ridge{0.5, 1.0, tilt, 1.0, 0.06};
    const BandMeasurement band = measure(make_field(0.04, {ridge}, 0.1));
    EXPECT_NEAR(band.primary.direction_deg, tilt, kAngleTolerance);
  }
}

TEST(BandAngle, AngleIsMeasuredFromTheGivenAxis) {
  const Ridge ridge{0.5, 1.0, 30.0, 1.0, 0.04};
  BandAngleOptions options;
  options.axis_x = 1.0;  // horizontal: the band is 60 degrees from it
  options.axis_y = 0.0;
  const BandMeasurement band = measure(make_field(0.02, {ridge}, 0.1), options);
  EXPECT_NEAR(band.primary.angle_deg, 60.0, kAngleTolerance);
  // The band direction (-sin 30, cos 30) is 120 degrees counter-clockwise from +x, i.e. -60 as a
  // line.
  EXPECT_NEAR(band.primary.direction_deg, -60.0, kAngleTolerance);
}

TEST(BandAngle, BandStartingFromAWeakCornerAsInTheCompressionSample) {
  // From the bottom-left corner up to the right side at 45 degrees (it meets x = 1 at y = 1),
  // nothing above; a strong blob at the corner (the weak zone) and a hot top edge (early yield
  // under the loading platen) compete for the weight.
  const Ridge band{0.0, 0.0, -45.0, 1.0, 0.04, 0.0, std::sqrt(2.0)};
  Field field = make_field(0.02, {band}, 0.1);
  for (std::size_t i = 0; i < field.value.size(); ++i) {
    const double r2 = field.x[i] * field.x[i] + field.y[i] * field.y[i];
    field.value[i] += 2.0 * std::exp(-r2 / (2.0 * 0.05 * 0.05));
    if (field.y[i] > 1.95) field.value[i] += 0.4;
  }
  const BandMeasurement measured = measure(field);
  EXPECT_NEAR(measured.primary.direction_deg, -45.0, kAngleTolerance);
  EXPECT_LT(band.distance(measured.primary.centre_x, measured.primary.centre_y), 0.02);
}

TEST(BandAngle, SymmetricCrossReportsOneBandAndTheOther) {
  for (double tilt : {45.0, 30.0}) {
    SCOPED_TRACE(tilt);
    const Ridge left{0.5, 1.0, tilt, 1.0, 0.04}, right{0.5, 1.0, -tilt, 1.0, 0.04};
    const BandMeasurement band = measure(make_field(0.02, {left, right}, 0.1));
    EXPECT_NEAR(band.primary.angle_deg, tilt, kAngleTolerance);
    ASSERT_TRUE(band.secondary.has_value());
    EXPECT_NEAR(band.secondary->angle_deg, tilt, kAngleTolerance);
    // One of each sense.
    EXPECT_NEAR(band.primary.direction_deg, -band.secondary->direction_deg, 2.0 * kAngleTolerance);
    // Each arm holds about half of the weight; the two are about as strong.
    EXPECT_GT(band.primary.weight_fraction, 0.3);
    EXPECT_LT(band.primary.weight_fraction, 0.75);
    EXPECT_GT(band.secondary->strength, 0.8);
  }
}

TEST(BandAngle, UnequalCrossPicksTheStrongerBand) {
  const Ridge strong{0.5, 1.0, -40.0, 1.0, 0.04}, weak{0.5, 1.0, 40.0, 0.6, 0.04};
  const BandMeasurement band = measure(make_field(0.02, {strong, weak}, 0.1));
  EXPECT_NEAR(band.primary.direction_deg, -40.0, kAngleTolerance);
  ASSERT_TRUE(band.secondary.has_value());
  EXPECT_NEAR(band.secondary->direction_deg, 40.0, kAngleTolerance);
  EXPECT_LT(band.secondary->strength, 1.0);
}

TEST(BandAngle, ResultDoesNotDependOnTheNoiseRealisation) {
  const Ridge ridge{0.5, 1.0, 45.0, 1.0, 0.04};
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
    SCOPED_TRACE(seed);
    EXPECT_NEAR(measure(make_field(0.02, {ridge}, 0.3, seed)).primary.direction_deg, 45.0,
                kAngleTolerance);
  }
}

TEST(BandAngle, UniformFieldHasNoBand) {
  Field field = make_field(0.05, {}, 0.0);
  std::fill(field.value.begin(), field.value.end(), 0.0);
  EXPECT_THROW(measure(field), RunError);
}

TEST(BandAngle, RejectsInconsistentInput) {
  const std::vector<double> three{0.0, 1.0, 2.0}, two{0.0, 1.0};
  EXPECT_THROW(measure_band(three, two, three), std::invalid_argument);
  EXPECT_THROW(measure_band(three, three, three), std::invalid_argument);  // collinear points
  const std::vector<double> bad{0.0, std::nan(""), 1.0};
  EXPECT_THROW(measure_band(three, bad, three), std::invalid_argument);
}

}  // namespace
}  // namespace rktsph::band_angle_test
