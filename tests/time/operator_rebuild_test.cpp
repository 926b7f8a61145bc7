// The operators rebuilt before every step on an unchanged configuration give the same step, bit
// for bit, as the operators built once (docs/theory.md §2.6): the builder leaves nothing of a
// previous build behind, and the step re-derives everything it takes from the tables.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "../support/elastic_block.hpp"
#include "../support/lattices.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::operator_rebuild_test {
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

bool same_table(const WeightTable& a, const WeightTable& b) {
  return a.dimension == b.dimension && a.row_start == b.row_start && a.source == b.source &&
         a.reflection == b.reflection && a.interpolation == b.interpolation &&
         a.gradient == b.gradient && a.has_reflections == b.has_reflections &&
         a.has_gradient == b.has_gradient && a.weight_start == b.weight_start &&
         a.row_reflects == b.row_reflects && a.row_base == b.row_base &&
         a.source_offset == b.source_offset;
}

// Every array of the operators, with where its data lives and its capacity.
std::vector<std::pair<const void*, std::size_t>> buffers(const StepOperators& ops) {
  std::vector<std::pair<const void*, std::size_t>> result;
  auto add = [&](const auto& vector) { result.emplace_back(vector.data(), vector.capacity()); };
  for (const WeightTable* t :
       {&ops.nodes_to_points, &ops.points_to_nodes, &ops.boundary_gradient,
        &ops.incomplete_closure.table, &ops.filter_to_points, &ops.filter_to_nodes}) {
    add(t->row_start);
    add(t->source);
    add(t->reflection);
    add(t->interpolation);
    for (const auto& g : t->gradient)
      add(g);
    add(t->weight_start);
    add(t->row_reflects);
  }
  add(ops.boundary_nodes);
  add(ops.node_to_boundary_row);
  add(ops.incomplete_nodes);
  add(ops.incomplete_closure.target);
  add(ops.incomplete_closure.self_column);
  add(ops.incomplete_closure.lumped_volume);
  return result;
}

// On a moving configuration the one builder of the step rebuilds its tables in place, in parallel
// rows, without computing what a fixed topology does not change: the tables must be those a fresh
// builder makes on the same configuration, bit for bit, and from the second rebuild on no array
// may be reallocated.
TEST(OperatorRebuild, RebuildsOnMovedConfigurationsEqualFreshBuildsAndDoNotReallocate) {
  for (const std::string numerics : {"{}", "{h_over_dx: 1.3, courant: 0.5}"}) {
    Simulation moving(
        read_case_text(loaded_cut(numerics), "cut.yaml", {{"model", "dry_large_deformation"}}));
    const BoundaryConditions& conditions = moving.boundary_conditions();
    const StepOptions& options = moving.step().options();
    // As the step keeps them on a moving configuration: a weight per row (docs/theory.md §4.7).
    StepOperatorBuilder reused(moving.nodes(), options, conditions.mirror_planes(),
                               conditions.mirror_axes());
    reused.keep_weights_per_row();
    StepOperators rebuilt;
    std::vector<std::pair<const void*, std::size_t>> second;
    for (int build = 0; build < 4; ++build) {
      for (int s = 0; s < 10; ++s)
        moving.step().advance(moving.state(), moving.time_step());
      const Configuration& configuration = moving.state().configuration;
      reused.build(configuration, rebuilt);
      StepOperatorBuilder fresh(moving.nodes(), options, conditions.mirror_planes(),
                                conditions.mirror_axes());
      fresh.keep_weights_per_row();
      StepOperators expected;
      fresh.build(configuration, expected);
      SCOPED_TRACE(numerics + ", build " + std::to_string(build));
      EXPECT_TRUE(same_table(rebuilt.nodes_to_points, expected.nodes_to_points));
      EXPECT_TRUE(same_table(rebuilt.points_to_nodes, expected.points_to_nodes));
      EXPECT_TRUE(same_table(rebuilt.boundary_gradient, expected.boundary_gradient));
      EXPECT_TRUE(same_table(rebuilt.incomplete_closure.table, expected.incomplete_closure.table));
      EXPECT_EQ(rebuilt.incomplete_closure.lumped_volume,
                expected.incomplete_closure.lumped_volume);
      EXPECT_EQ(rebuilt.incomplete_closure.self_column, expected.incomplete_closure.self_column);
      EXPECT_TRUE(same_table(rebuilt.filter_to_points, expected.filter_to_points));
      EXPECT_TRUE(same_table(rebuilt.filter_to_nodes, expected.filter_to_nodes));
      EXPECT_EQ(rebuilt.boundary_nodes, expected.boundary_nodes);
      EXPECT_EQ(rebuilt.incomplete_nodes, expected.incomplete_nodes);
      EXPECT_EQ(rebuilt.compact_stencils, expected.compact_stencils);
      EXPECT_FALSE(rebuilt.filter_to_nodes.has_gradient);
      EXPECT_TRUE(rebuilt.filter_to_nodes.weight_start.empty());
      EXPECT_TRUE(rebuilt.points_to_nodes.weight_start.empty());
      if (build == 1) second = buffers(rebuilt);
      if (build > 1) {
        EXPECT_EQ(buffers(rebuilt), second) << "an array was reallocated";
      }
    }
    double largest_displacement = 0.0;
    for (const double u : moving.state().displacement.data())
      largest_displacement = std::max(largest_displacement, std::abs(u));
    EXPECT_GT(largest_displacement, 0.0) << "the configuration must move";
  }
}

// On a moving configuration the stencils are searched again (and the filter rebuilt) exactly when
// some node has moved more than neighbour_search_distance dx from where it was at the last search
// (docs/theory.md §9.5): the test keeps its own copy of those positions and checks every step's
// decision against it. With the distance 0 they are searched before every step.
TEST(OperatorRebuild, MovingStencilsAreSearchedAgainOnceANodeHasMovedTheSearchDistance) {
  const double distance = 2e-5;  // over dx: the ramped load moves the cut by a few 1e-4 dx
  Simulation moving(
      read_case_text(loaded_cut("{neighbour_search_distance: " + std::to_string(distance) + "}"),
                     "cut.yaml", {{"model", "dry_large_deformation"}}));
  const double limit = distance * moving.nodes().spacing;
  PointCloud built_at = moving.state().configuration.sph_nodes;
  int rebuilt = 0, kept = 0;
  for (int s = 0; s < 60; ++s) {
    const PointCloud& now = moving.state().configuration.sph_nodes;
    double largest = 0.0;
    for (std::size_t i = 0; i < now.size(); ++i)
      largest = std::max(largest, std::hypot(now.position[0][i] - built_at.position[0][i],
                                             now.position[1][i] - built_at.position[1][i]));
    const PointCloud before = now;
    const long builds = moving.step().neighbour_searches();
    moving.step().advance(moving.state(), moving.time_step());
    if (moving.step().neighbour_searches() > builds) {
      EXPECT_GT(largest, limit) << "step " << s;
      built_at = before;
      ++rebuilt;
    } else {
      EXPECT_LE(largest, limit) << "step " << s;
      ++kept;
    }
  }
  EXPECT_GT(rebuilt, 0);
  EXPECT_GT(kept, 0);

  Simulation every_step(read_case_text(loaded_cut("{neighbour_search_distance: 0}"), "cut.yaml",
                                       {{"model", "dry_large_deformation"}}));
  const long at_start = every_step.step().neighbour_searches();
  for (int s = 0; s < 5; ++s)
    every_step.step().advance(every_step.state(), every_step.time_step());
  EXPECT_EQ(every_step.step().neighbour_searches() - at_start, 5);
}

// Between searches the step's own tables come from the candidates of the last search, picked at
// the current positions (docs/theory.md §9.5): every row must hold the sources and weights of a
// fresh build on the same configuration. The entries may come in another order, and a weight may
// then differ by the rounding of its sums (1e-12 of the row's largest weight bounds that).
TEST(OperatorRebuild, StepTablesBetweenSearchesAreThoseOfAFreshBuild) {
  Simulation moving(read_case_text(loaded_cut("{neighbour_search_distance: 0.5}"), "cut.yaml",
                                   {{"model", "dry_large_deformation"}}));
  const long searches = moving.step().neighbour_searches();
  for (int s = 0; s < 30; ++s)
    moving.step().advance(moving.state(), moving.time_step());
  const Configuration& configuration = moving.state().configuration;
  moving.step().rebuild_operators(configuration);
  ASSERT_EQ(moving.step().neighbour_searches(), searches) << "no search may have happened";
  double largest_displacement = 0.0;
  for (const double u : moving.state().displacement.data())
    largest_displacement = std::max(largest_displacement, std::abs(u));
  ASSERT_GT(largest_displacement, 1e-6 * moving.nodes().spacing) << "the nodes must have moved";

  const BoundaryConditions& conditions = moving.boundary_conditions();
  StepOperatorBuilder fresh(moving.nodes(), moving.step().options(), conditions.mirror_planes(),
                            conditions.mirror_axes());
  fresh.keep_weights_per_row();  // as the step keeps them on a moving configuration
  StepOperators expected;
  fresh.build(configuration, expected);
  const StepOperators& picked = moving.step().operators();
  for (const auto& [name, a, b] :
       {std::tuple{"nodes_to_points", &picked.nodes_to_points, &expected.nodes_to_points},
        std::tuple{"points_to_nodes", &picked.points_to_nodes, &expected.points_to_nodes},
        std::tuple{"boundary_gradient", &picked.boundary_gradient, &expected.boundary_gradient}}) {
    SCOPED_TRACE(name);
    ASSERT_EQ(a->row_start, b->row_start);
    for (std::size_t r = 0; r + 1 < a->row_start.size(); ++r) {
      using Entry = std::tuple<std::int32_t, std::uint8_t, double, double, double>;
      auto entries = [r](const WeightTable& t) {
        std::vector<Entry> row;
        for (auto k = t.row_start[r]; k < t.row_start[r + 1]; ++k) {
          const auto e = static_cast<std::size_t>(k);
          row.emplace_back(t.source[e], t.reflection[e], t.interpolation[e], t.gradient[0][e],
                           t.gradient[1][e]);
        }
        std::sort(row.begin(), row.end(), [](const Entry& p, const Entry& q) {
          return std::tie(std::get<0>(p), std::get<1>(p)) <
                 std::tie(std::get<0>(q), std::get<1>(q));
        });
        return row;
      };
      const std::vector<Entry> got = entries(*a), want = entries(*b);
      double scale = 0.0;
      for (const Entry& e : want)
        scale = std::max(
            {scale, std::abs(std::get<2>(e)), std::abs(std::get<3>(e)), std::abs(std::get<4>(e))});
      for (std::size_t k = 0; k < want.size(); ++k) {
        ASSERT_EQ(std::get<0>(got[k]), std::get<0>(want[k])) << "row " << r;
        ASSERT_EQ(std::get<1>(got[k]), std::get<1>(want[k])) << "row " << r;
        EXPECT_NEAR(std::get<2>(got[k]), std::get<2>(want[k]), 1e-12 * scale) << "row " << r;
        EXPECT_NEAR(std::get<3>(got[k]), std::get<3>(want[k]), 1e-12 * scale) << "row " << r;
        EXPECT_NEAR(std::get<4>(got[k]), std::get<4>(want[k]), 1e-12 * scale) << "row " << r;
      }
    }
  }
}

// The row-parallel table builders give the tables of append_row, row by row, on a lattice large
// enough for the parallel loops (above kParallelThreshold rows).
TEST(OperatorRebuild, ParallelCrossOperatorEqualsRowByRowAppend) {
  test::ElasticBlock block;  // the cut of loaded_cut, finer, with its mirror side
  block.spacing = 0.1;
  block.shapes = "[{polygon: [[0, 0], [12, 0], [12, 3], [6, 3], [6, 8], [0, 8]], material: soil}]";
  block.conditions = {"{group: xmin, roller: x, mirror: true}", "{group: ymin, fixed: true}"};
  block.numerics = "{h_over_dx: 1.3, courant: 0.5}";
  Simulation simulation(block.description());
  const Configuration& configuration = simulation.state().configuration;
  const OperatorOptions& options = simulation.step().operator_options();
  const CellList cells(configuration.sph_nodes,
                       options.kernel.support_radius(options.smoothing_length));
  WeightTable serial;
  reset_table(serial, 2);
  std::vector<StencilSource> stencil;
  for (std::size_t p = 0; p < configuration.stress_points.size(); ++p) {
    const auto x = configuration.stress_points.point(p);
    gather_stencil(x, cells, options, -1, stencil);
    append_row(serial, x, stencil, options, GradientReference::ShepardCentroid, -1);
  }
  ASSERT_TRUE(serial.has_reflections);
  ASSERT_GT(static_cast<std::int64_t>(serial.rows()), kParallelThreshold);
  WeightTable parallel;
  OperatorWorkspace workspace;
  build_cross_operator(configuration.stress_points, cells, options, parallel, workspace);
  EXPECT_TRUE(same_table(parallel, serial));
  // Interpolation only: the weights of the full table without its gradients.
  build_cross_operator(configuration.stress_points, cells, options, parallel, workspace, nullptr,
                       TableWeights::InterpolationOnly);
  drop_gradients(serial);
  EXPECT_TRUE(same_table(parallel, serial));
}

TEST(OperatorRebuild, ClassifiesBoundaryNodesFromTheCellsAroundThem) {
  // The toe of the cut has three cells (interior closure), the crest one, a node on the mirror
  // side two real cells and their two images (interior), the corner of the mirror and the base
  // one cell and its image (boundary).
  Simulation simulation(read_case_text(loaded_cut("{}"), "cut.yaml"));
  const NodeSets& nodes = simulation.nodes();
  const StepOperators& operators = simulation.step().operators();
  auto row_at = [&](std::int32_t i, std::int32_t j) {
    return operators
        .node_to_boundary_row[static_cast<std::size_t>(test::lattice_node(nodes, i, j))];
  };
  EXPECT_LT(row_at(6, 3), 0);
  EXPECT_GE(row_at(6, 8), 0);
  EXPECT_LT(row_at(0, 4), 0);
  EXPECT_GE(row_at(0, 0), 0);
  EXPECT_GE(row_at(3, 8), 0);
  const auto& incomplete = operators.incomplete_nodes;
  EXPECT_NE(std::find(incomplete.begin(), incomplete.end(), test::lattice_node(nodes, 6, 3)),
            incomplete.end());
}

// The time split of docs/theory.md §9.5: a fixed configuration builds its tables once, before the
// run, so its steps spend nothing on cell lists, tables or moving; a moving one spends on each
// (here searching its stencils before every step, as it does after enough motion).
// The parts are pieces of the steps, so together they cannot exceed the loop's wall time.
TEST(StepTimeSplit, OnlyAMovingConfigurationRebuildsAndTheSplitFitsInTheSteps) {
  for (const bool moving : {false, true}) {
    const std::vector<CaseOverride> overrides =
        moving ? std::vector<CaseOverride>{{"model", "dry_large_deformation"}}
               : std::vector<CaseOverride>{};
    Simulation simulation(
        read_case_text(loaded_cut("{neighbour_search_distance: 0}"), "cut.yaml", overrides));
    const auto start = std::chrono::steady_clock::now();
    for (int s = 0; s < 10; ++s)
      simulation.step().advance(simulation.state(), simulation.time_step());
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const StepTimeSplit split = simulation.step().time_split();
    SCOPED_TRACE(moving ? "moving" : "fixed");
    EXPECT_GT(split.integration, 0.0);
    EXPECT_LE(split.total(), wall);
    if (moving) {
      EXPECT_GT(split.cell_lists, 0.0);
      EXPECT_GT(split.operator_tables, 0.0);
      EXPECT_GT(split.surface, 0.0);
    } else {
      EXPECT_EQ(split.cell_lists, 0.0);
      EXPECT_EQ(split.operator_tables, 0.0);
      EXPECT_EQ(split.surface, 0.0);
    }
  }
}

}  // namespace
}  // namespace rktsph::operator_rebuild_test
