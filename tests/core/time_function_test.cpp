// TimeFunction::operator() against values worked out by hand from the definitions in
// time_function.hpp. Tolerances: exact where the arithmetic is exact in binary floating point
// (comparisons, values held constant), a few ulps of the result elsewhere.
#include "rktsph/core/time_function.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace rktsph::time_function_test {
namespace {

constexpr double kRoundOff = 1e-14;

TEST(TimeFunction, ConstantIsTheSameAtAllTimes) {
  const TimeFunction function = TimeFunction::constant(-3.5);
  EXPECT_EQ(function(-1.0), -3.5);
  EXPECT_EQ(function(0.0), -3.5);
  EXPECT_EQ(function(1e6), -3.5);
}

TEST(TimeFunction, StepSwitchesOnExactlyAtStart) {
  TimeFunction step;
  step.kind = TimeFunction::Kind::Step;
  step.value = 2.0;
  step.start = 0.25;
  EXPECT_EQ(step(0.0), 0.0);
  EXPECT_EQ(step(std::nextafter(0.25, 0.0)), 0.0);  // just before the edge
  EXPECT_EQ(step(0.25), 2.0);                       // the edge itself belongs to "on"
  EXPECT_EQ(step(10.0), 2.0);
}

TEST(TimeFunction, RampIsZeroBeforeLinearDuringAndFlatAfter) {
  TimeFunction ramp;
  ramp.kind = TimeFunction::Kind::LinearRamp;
  ramp.value = -10000.0;
  ramp.start = 0.1;
  ramp.duration = 0.4;
  EXPECT_EQ(ramp(0.05), 0.0);
  EXPECT_EQ(ramp(0.1), 0.0);
  // Midpoint t = 0.1 + 0.2: half the value. A quarter in: a quarter of it.
  EXPECT_NEAR(ramp(0.3), -5000.0, 5000.0 * kRoundOff);
  EXPECT_NEAR(ramp(0.2), -2500.0, 2500.0 * kRoundOff);
  EXPECT_EQ(ramp(0.5), -10000.0);
  EXPECT_EQ(ramp(3.0), -10000.0);
}

TEST(TimeFunction, TableInterpolatesLinearlyAndHoldsItsEndValues) {
  TimeFunction table;
  table.kind = TimeFunction::Kind::Table;
  table.table = {{0.0, 0.0}, {0.1, 1.5}, {0.3, -0.5}};
  EXPECT_EQ(table(0.0), 0.0);
  EXPECT_NEAR(table(0.05), 0.75, kRoundOff);  // halfway up the first segment
  EXPECT_EQ(table(0.1), 1.5);                 // on an interior point
  // Second segment: slope (-0.5 - 1.5) / 0.2 = -10, so at 0.25: 1.5 - 10 * 0.15 = 0.
  EXPECT_NEAR(table(0.25), 0.0, kRoundOff);
  EXPECT_NEAR(table(0.2), 0.5, kRoundOff);
  // Beyond the ends the first and last values are held.
  EXPECT_EQ(table(-1.0), 0.0);
  EXPECT_EQ(table(0.3), -0.5);
  EXPECT_EQ(table(7.0), -0.5);
}

TEST(TimeFunction, TableStartingLaterHoldsItsFirstValueBefore) {
  TimeFunction table;
  table.kind = TimeFunction::Kind::Table;
  table.table = {{1.0, 4.0}, {2.0, 6.0}};
  EXPECT_EQ(table(0.0), 4.0);
  EXPECT_NEAR(table(1.75), 5.5, kRoundOff);
}

TEST(TimeFunction, HarmonicPeaksAtAQuarterPeriodAndIsOffsetBeforeStart) {
  TimeFunction wave;
  wave.kind = TimeFunction::Kind::Harmonic;
  wave.amplitude = 0.2;
  wave.period = 0.5;
  wave.offset = 0.05;
  wave.start = 0.01;
  EXPECT_EQ(wave(0.0), 0.05);                              // before start: the offset
  EXPECT_NEAR(wave(0.01), 0.05, kRoundOff);                // sin(0)
  EXPECT_NEAR(wave(0.01 + 0.125), 0.25, kRoundOff);        // sin(pi/2) = 1
  EXPECT_NEAR(wave(0.01 + 0.25), 0.05, kRoundOff);         // sin(pi) = 0
  EXPECT_NEAR(wave(0.01 + 0.375), -0.15, kRoundOff);       // sin(3 pi/2) = -1
  EXPECT_NEAR(wave(0.01 + 0.5 + 0.125), 0.25, kRoundOff);  // periodic
}

TEST(TimeFunction, HarmonicPhaseShiftsTheWave) {
  TimeFunction wave;
  wave.kind = TimeFunction::Kind::Harmonic;
  wave.amplitude = 1.0;
  wave.period = 2.0;
  wave.phase = std::numbers::pi / 2.0;  // turns the sine into a cosine
  EXPECT_NEAR(wave(0.0), 1.0, kRoundOff);
  EXPECT_NEAR(wave(0.5), 0.0, kRoundOff);
  EXPECT_NEAR(wave(1.0), -1.0, kRoundOff);
}

/// The integral over [a, b] by the midpoint rule on 200 000 pieces, an independent reference.
double midpoint_integral(const TimeFunction& function, double a, double b) {
  const int pieces = 200000;
  const double h = (b - a) / pieces;
  double sum = 0.0;
  for (int k = 0; k < pieces; ++k)
    sum += function(a + (k + 0.5) * h) * h;
  return sum;
}

TEST(TimeFunction, IntegralIsTheAreaUnderEveryKind) {
  TimeFunction step;
  step.kind = TimeFunction::Kind::Step;
  step.value = 2.0;
  step.start = 0.25;
  EXPECT_NEAR(step.integral(1.0), 1.5, kRoundOff);  // 2 x 0.75
  TimeFunction ramp;
  ramp.kind = TimeFunction::Kind::LinearRamp;
  ramp.value = -4.0;
  ramp.start = 0.1;
  ramp.duration = 0.4;
  EXPECT_NEAR(ramp.integral(0.3), -4.0 * 0.2 * 0.2 / 0.8, kRoundOff);  // inside the ramp
  EXPECT_NEAR(ramp.integral(1.0), -4.0 * (0.2 + 0.5), kRoundOff);      // triangle + flat part
  TimeFunction table;
  table.kind = TimeFunction::Kind::Table;
  table.table = {{0.5, 1.0}, {1.0, 3.0}, {2.0, -1.0}};
  EXPECT_NEAR(table.integral(0.25), 0.25, kRoundOff);  // held at 1 before its first point
  EXPECT_NEAR(table.integral(1.5), 0.5 + 1.0 + 0.25 * (3.0 + 1.0), kRoundOff);
  EXPECT_NEAR(table.integral(3.0), 0.5 + 1.0 + 1.0 - 1.0, kRoundOff);  // held at -1 after
  TimeFunction wave;
  wave.kind = TimeFunction::Kind::Harmonic;
  wave.amplitude = 2.0;
  wave.period = 0.4;
  wave.phase = 0.3;
  wave.offset = 0.5;
  wave.start = 0.1;
  // Split at the start, where the function jumps from its offset to the wave.
  EXPECT_NEAR(wave.integral(0.05), midpoint_integral(wave, 0.0, 0.05), 1e-12);
  for (double t : {0.37, 1.23})
    EXPECT_NEAR(wave.integral(t),
                midpoint_integral(wave, 0.0, 0.1) + midpoint_integral(wave, 0.1, t), 1e-9)
        << t;
  EXPECT_NEAR(TimeFunction::constant(-3.5).integral(2.0), -7.0, kRoundOff);
}

}  // namespace
}  // namespace rktsph::time_function_test
