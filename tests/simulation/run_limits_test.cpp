// Derived quantities checked before a run (issue 13): the step count in double against
// time.max_steps, wave speeds finite, the lattice size estimated from the shapes before anything
// is built, and a run that ends exactly at time.end.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../support/elastic_block.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/core/error.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace run_limits_test {
namespace {

using namespace rktsph;

const std::string kBarWave = std::string(RKTSPH_SOURCE_DIR) + "/cases/bar-wave-2d-t/case.yaml";

// The InputError that building the simulation of bar-wave-2d-t with this --set override throws.
InputError error_with(const std::string& override_text, SimulationLimits limits = {}) {
  const CaseDescription description = read_case_file(kBarWave, {parse_override(override_text)});
  try {
    Simulation simulation(description, limits);
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << override_text << " was accepted";
  return InputError({}, "", "", "", "");
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(DerivedQuantities, StepCountBeyondMaxStepsIsRefusedWhereItOverflowedBefore) {
  // 1e14 s / 1e-5 s = 1e19 steps: a long overflowed to a negative count that passed max_steps.
  const InputError error = error_with("time.end=1e14");
  EXPECT_EQ(error.key(), "time.max_steps");
  EXPECT_TRUE(contains(error.problem(), "1e+19 steps")) << error.what();
  EXPECT_TRUE(contains(error.problem(), "numerics.courant 0.3")) << error.what();
}

TEST(DerivedQuantities, HugeYoungModulusNamesTheMaterialInTheStepCount) {
  // c_p = 2.4e152 m/s, dt = 1.2e-155 s.
  const InputError error = error_with("materials.solid.young_modulus=1e308");
  EXPECT_EQ(error.key(), "time.max_steps");
  EXPECT_TRUE(contains(error.problem(), "young_modulus 1e+308")) << error.what();
}

TEST(DerivedQuantities, DensityThatMakesTheWaveSpeedInfiniteIsRefusedAtTheDensity) {
  // c_p = inf and dt = 0 s before.
  const InputError error = error_with("materials.solid.density=1e-308");
  EXPECT_EQ(error.key(), "materials.solid.density");
  EXPECT_EQ(error.value(), "1e-308");
  EXPECT_TRUE(contains(error.problem(), "is inf")) << error.what();
}

TEST(DerivedQuantities, TinyTimeStepIsRefusedByTheStepCount) {
  const InputError error = error_with("numerics.time_step=1e-300");
  EXPECT_EQ(error.key(), "time.max_steps");
  EXPECT_TRUE(contains(error.problem(), "numerics.time_step = 1e-300")) << error.what();
}

TEST(DerivedQuantities, StepCountAtMaxStepsIsAccepted) {
  // 0.01 s / 1e-5 s = 1000 steps (to rounding): exactly max_steps passes, one fewer does not.
  CaseDescription description = read_case_file(kBarWave, {parse_override("time.max_steps=1000")});
  EXPECT_EQ(Simulation(description).total_steps(), 1000);
  EXPECT_EQ(error_with("time.max_steps=999").key(), "time.max_steps");
}

TEST(NodeEstimate, MatchesTheLatticeOfRectanglesAndPolygons) {
  test::ElasticBlock block;
  block.shapes =
      "[{rectangle: {min: [0, 0], max: [12, 5]}, material: soil}, "
      "{polygon: [[12, 0], [20, 0], [20, 5], [18, 7], [14, 7], [12, 5]], material: soil}]";
  const CaseDescription description = block.description();
  const NodeEstimate estimate = estimate_node_sets(description.geometry, 2);
  const Simulation simulation(description);
  const double nodes = static_cast<double>(simulation.nodes().sph_nodes.size());
  // Overlapping edges are counted twice: an upper bound, within a boundary of the truth.
  EXPECT_GE(estimate.sph_nodes, nodes);
  EXPECT_LE(estimate.sph_nodes, nodes * 1.15);
  EXPECT_NEAR(estimate.stress_points, static_cast<double>(simulation.nodes().stress_points.size()),
              8.0);
  EXPECT_EQ(estimate.lattice_points, 21.0 * 8.0);
  EXPECT_EQ(estimate.largest_shape, 0u);
}

TEST(NodeEstimate, WrongSpacingIsRefusedBeforeAnythingIsBuilt) {
  // 2.5e11 nodes: bad_alloc (exit 3, no key) before.
  const InputError error = error_with("geometry.spacing=1e-6");
  EXPECT_EQ(error.key(), "geometry.spacing");
  EXPECT_TRUE(contains(error.problem(), "2.5e+11 SPH nodes")) << error.what();
  EXPECT_TRUE(contains(error.allowed(), "--max-nodes")) << error.what();
}

TEST(NodeEstimate, TheLimitCanBeRaised) {
  // 40,501 nodes at dx = 2.5 mm.
  EXPECT_EQ(error_with("geometry.spacing=0.0025", SimulationLimits{1e4}).key(), "geometry.spacing");
  const CaseDescription description =
      read_case_file(kBarWave, {parse_override("geometry.spacing=0.0025")});
  EXPECT_EQ(Simulation(description, SimulationLimits{1e5}).nodes().sph_nodes.size(), 40501u);
}

TEST(NodeEstimate, FarApartShapesAreRefusedForTheirBoundingBox) {
  test::ElasticBlock block;
  block.shapes =
      "[{rectangle: {min: [0, 0], max: [2, 2]}, material: soil}, "
      "{rectangle: {min: [1000000, 1000000], max: [1000002, 1000002]}, material: soil}]";
  try {
    Simulation simulation(block.description());
    ADD_FAILURE() << "a 1e12-point lattice was accepted";
  } catch (const InputError& error) {
    EXPECT_TRUE(contains(error.problem(), "bounding box")) << error.what();
  }
}

// A bar whose time.end, 0.0105 s, is not a multiple of its dt, 1.118e-3 s.
Simulation bar_ending_between_steps(double end) {
  const std::string text = std::string(R"(name: bar
dimension: 1
geometry: {spacing: 0.5, shapes: [{segment: [0.0, 10.0], material: soil}]}
materials:
  soil: {model: linear_elastic, density: 2000.0, young_modulus: 1.0e8, poisson_ratio: 0.0}
boundary_conditions:
  - {group: xmax, velocity: {x: -0.1}}
numerics: {courant: 0.5}
time: {end: )") + fmt::format("{:.17g}", end) +
                           "}\n";
  return Simulation(read_case_text(text, "bar.yaml"));
}

TEST(RunEnd, EndsExactlyAtTimeEndWithAShorterLastStep) {
  Simulation simulation = bar_ending_between_steps(0.0105);
  const double dt = simulation.time_step();
  ASSERT_GT(std::fmod(0.0105, dt), 0.1 * dt);  // not a multiple
  EXPECT_EQ(simulation.run(), RunStatus::Completed);
  EXPECT_EQ(simulation.state().time, 0.0105);  // to the bit, not up to a step past it
  EXPECT_EQ(simulation.state().step, simulation.total_steps());
  EXPECT_EQ(simulation.total_steps(), static_cast<long>(std::ceil(0.0105 / dt)));
}

TEST(RunEnd, EndsAtTimeEndWhenItIsAMultipleOfTheStep) {
  Simulation probe = bar_ending_between_steps(1.0);
  const double dt = probe.time_step();
  Simulation simulation = bar_ending_between_steps(7 * dt);
  EXPECT_EQ(simulation.run(), RunStatus::Completed);
  EXPECT_EQ(simulation.total_steps(), 7);
  EXPECT_DOUBLE_EQ(simulation.state().time, 7 * dt);
}

}  // namespace
}  // namespace run_limits_test
