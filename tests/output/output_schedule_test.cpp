#include "rktsph/output/output_schedule.hpp"

#include <gtest/gtest.h>

namespace rktsph::output_schedule_test {
namespace {

// Outputs fall on the first step reaching each multiple of the interval, at most one per step.
TEST(OutputSchedule, DueOnceAtTheFirstStepReachingEachMultiple) {
  OutputSchedule schedule(0.25);
  const double dt = 0.1;
  int outputs = 0;
  double first = -1.0;
  for (int step = 1; step <= 10; ++step) {
    if (schedule.due(step * dt, dt)) {
      if (first < 0.0) first = step * dt;
      ++outputs;
    }
  }
  // t = 0.3, 0.5, 0.8, 1.0: the multiples 0.25, 0.5, 0.75, 1.0.
  EXPECT_EQ(outputs, 4);
  EXPECT_DOUBLE_EQ(first, 0.3);
  EXPECT_DOUBLE_EQ(schedule.next_time(), 1.25);
}

// The round-off of t += dt must not make an output one step late.
TEST(OutputSchedule, ATimeAMillionthOfAStepShortCountsAsReached) {
  OutputSchedule schedule(1.0);
  EXPECT_TRUE(schedule.due(1.0 - 1e-9, 0.01));
  EXPECT_FALSE(schedule.due(1.0 + 0.01, 0.01));
}

// Interval 0 is never due, also when a checkpoint written with another interval restores a
// finite next time (before, the writer's loop would have added 0 to it for ever).
TEST(OutputSchedule, IntervalZeroIsNeverDueEvenAfterARestoredNextTime) {
  OutputSchedule schedule(0.0);
  EXPECT_FALSE(schedule.due(5.0, 0.1));
  schedule.set_next_time(1.0);
  EXPECT_FALSE(schedule.due(5.0, 0.1));
}

}  // namespace
}  // namespace rktsph::output_schedule_test
