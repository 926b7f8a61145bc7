// The operators rebuilt before every step on an unchanged configuration give the same step, bit
// for bit, as the operators built once (docs/theory.md §2.6): the builder leaves nothing of a
// previous build behind, and the step re-derives everything it takes from the tables.
#include <gtest/gtest.h>

#include <cstring>

#include "../support/elastic_block.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph {
namespace {

// The cut of reentrant_corner_test.cpp under a ramped strip load, with gravity and a mirror
// (roller) side: boundary rows, a re-entrant corner, reflections, tractions, hourglass forces.
std::string loaded_cut(const std::string& numerics) {
  test::ElasticBlock block;
  block.shapes = "[{polygon: [[0, 0], [12, 0], [12, 3], [6, 3], [6, 8], [0, 8]], material: soil}]";
  block.groups = "{load: {box: {min: [0, 7.9], max: [3, 8.1]}}}";
  block.conditions = {
      "{group: xmin, roller: x, mirror: true}", "{group: xmax, roller: x}",
      "{group: ymin, fixed: true}",
      "{group: load, traction: {y: {function: ramp, value: -1.0e5, duration: 0.05}}}"};
  block.loads = "{gravity: {acceleration: [0, -9.81]}, damping: {coefficient: 5}}";
  block.numerics = numerics;
  return block.text();
}

bool same_bits(const FieldArray& a, const FieldArray& b) {
  if (a.data().size() != b.data().size()) return false;
  return a.data().empty() ||
         std::memcmp(a.data().data(), b.data().data(), a.data().size() * sizeof(double)) == 0;
}

void expect_rebuilt_step_is_identical(const std::string& numerics) {
  const CaseDescription description = read_case_text(loaded_cut(numerics), "cut.yaml");
  Simulation built_once(description), rebuilt(description);
  for (int s = 0; s < 40; ++s) {
    const double dt = built_once.time_step();
    built_once.step().advance(built_once.state(), dt);
    rebuilt.step().rebuild_operators(rebuilt.state().configuration);
    rebuilt.step().advance(rebuilt.state(), dt);
  }
  const State& a = built_once.state();
  const State& b = rebuilt.state();
  ASSERT_GT(a.step, 0);
  EXPECT_TRUE(same_bits(a.fields, b.fields)) << numerics;
  EXPECT_TRUE(same_bits(a.internal, b.internal)) << numerics;
  EXPECT_TRUE(same_bits(a.displacement, b.displacement)) << numerics;
  EXPECT_TRUE(same_bits(a.hourglass_force, b.hourglass_force)) << numerics;
  double largest_speed = 0.0;
  for (std::size_t i = 0; i < a.fields.point_count(); ++i)
    largest_speed = std::max(largest_speed, std::abs(a.fields(1, i)));
  EXPECT_GT(largest_speed, 1e-6) << "the load must set the block moving";
}

TEST(OperatorRebuild, RebuiltEveryStepOnTheSameConfigurationGivesTheSameStepBitForBit) {
  expect_rebuilt_step_is_identical("{}");  // compact stencils, mean-velocity update, stiffness
  expect_rebuilt_step_is_identical("{h_over_dx: 1.3, courant: 0.5}");  // wide stencils
  expect_rebuilt_step_is_identical("{stress_update: half_step, hourglass: {stiffness: 0}}");
}

TEST(OperatorRebuild, ClassifiesBoundaryNodesFromTheCellsAroundThem) {
  // The toe of the cut has three cells (interior closure), the crest one, a node on the mirror
  // side two real cells and their two images (interior), the corner of the mirror and the base
  // one cell and its image (boundary).
  Simulation simulation(read_case_text(loaded_cut("{}"), "cut.yaml"));
  const NodeSets& nodes = simulation.nodes();
  const StepOperators& operators = simulation.step().operators();
  auto row_at = [&](std::int32_t i, std::int32_t j) {
    return operators.node_to_boundary_row[static_cast<std::size_t>(nodes.node_at({i, j, 0}))];
  };
  EXPECT_LT(row_at(6, 3), 0);
  EXPECT_GE(row_at(6, 8), 0);
  EXPECT_LT(row_at(0, 4), 0);
  EXPECT_GE(row_at(0, 0), 0);
  EXPECT_GE(row_at(3, 8), 0);
  const auto& incomplete = operators.incomplete_nodes;
  EXPECT_NE(std::find(incomplete.begin(), incomplete.end(), nodes.node_at({6, 3, 0})),
            incomplete.end());
}

}  // namespace
}  // namespace rktsph
