// An observer can end a run: StopWhenAtRest (time.stop_when_at_rest) stops a damped block under
// gravity once it has settled, and never stops an undamped one, which keeps vibrating.
#include <gtest/gtest.h>

#include "../support/elastic_block.hpp"
#include "../support/lattices.hpp"
#include "rktsph/simulation/quantities.hpp"
#include "rktsph/simulation/simulation.hpp"
#include "rktsph/simulation/stop_when_at_rest.hpp"

namespace rktsph::stop_when_at_rest_test {
namespace {

CaseDescription settling_block(double damping, double end) {
  test::ElasticBlock block;
  block.shapes = test::ElasticBlock::rectangle(6.0, 4.0);
  block.conditions = {"{group: xmin, roller: x}", "{group: xmax, roller: x}",
                      "{group: ymin, fixed: true}"};
  block.loads =
      "{gravity: {acceleration: [0, -9.81]}, damping: {coefficient: " + std::to_string(damping) +
      "}}";
  CaseDescription description = block.description();
  description.time.end = end;
  return description;
}

TEST(StopWhenAtRest, EndsADampedRunOnceTheBodyHasSettled) {
  Simulation simulation(settling_block(60.0, 5.0));
  StopWhenAtRest stop(1e-3);
  simulation.add_observer(stop);
  EXPECT_EQ(simulation.run(), RunStatus::Completed);
  EXPECT_TRUE(simulation.stopped_early()) << simulation.message();
  EXPECT_LT(simulation.state().time, 5.0);
  EXPECT_NE(simulation.message().find("at rest"), std::string::npos) << simulation.message();
  EXPECT_GE(stop.window_steps(), 1);
  // Settled: the top has the oedometric self-weight settlement rho g H^2 / (2 M) of the column
  // (rollers on the sides), M = E (1 - nu) / ((1 + nu)(1 - 2 nu)).
  const double modulus = 1.0e7 * 0.7 / (1.3 * 0.4);
  const double settlement = 2000.0 * 9.81 * 16.0 / (2.0 * modulus);
  const NodeSets& nodes = simulation.nodes();
  const std::int32_t top = test::lattice_node(nodes, 3, 4);
  ASSERT_GE(top, 0);
  const double u_top = simulation.state().displacement(1, static_cast<std::size_t>(top));
  RecordProperty("settlement_ratio", std::to_string(-u_top / settlement));
  EXPECT_NEAR(-u_top / settlement, 1.0, 0.02);
}

TEST(StopWhenAtRest, IsTheCaseKeyTimeStopWhenAtRest) {
  test::ElasticBlock block;
  std::string text = block.text();
  const std::string end = "time: {end: 1.0}";
  ASSERT_NE(text.find(end), std::string::npos);
  text.replace(text.find(end), end.size(), "time: {end: 1.0, stop_when_at_rest: 1.0e-3}");
  EXPECT_EQ(read_case_text(text, "block.yaml").time.stop_when_at_rest, 1.0e-3);
  text.replace(text.find("1.0e-3"), 6, "1.5");
  EXPECT_THROW(read_case_text(text, "block.yaml"), InputError);
  EXPECT_FALSE(block.description().time.stop_when_at_rest.has_value());
}

TEST(StopWhenAtRest, NeverEndsAnUndampedRun) {
  Simulation simulation(settling_block(0.0, 0.5));
  StopWhenAtRest stop(1e-3);
  simulation.add_observer(stop);
  EXPECT_EQ(simulation.run(), RunStatus::Completed);
  EXPECT_FALSE(simulation.stopped_early()) << simulation.message();
  EXPECT_DOUBLE_EQ(simulation.state().time, 0.5);
}

}  // namespace
}  // namespace rktsph::stop_when_at_rest_test
