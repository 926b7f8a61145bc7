// Cells formed again from the moving nodes (numerics.cells.policy: reformed, docs/theory.md
// §9.17): the formed cells tile the body with its area and mass; a body in equilibrium stays at
// its dynamics however often its cells are formed again, which it would not if a forming changed
// the nodes' densities; a restart forms the cells the run had and continues to the bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "../support/validation_runs.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/core/checkpoint.hpp"
#include "rktsph/core/error.hpp"
#include "rktsph/simulation/case_warnings.hpp"
#include "rktsph/simulation/simulation.hpp"
#include "rktsph/validation/validation_case.hpp"

namespace rktsph::reformed_cells_test {
namespace {

// A 2 m x 4 m elastic column at dx = 0.25 m under its weight, rollers on its sides, fixed at its
// base; with the geostatic stress of its weight (K0 = nu / (1 - nu)) in equilibrium from t = 0.
std::string column(const std::string& cells, bool geostatic = true) {
  return std::string(
             "name: column\nmodel: dry_large_deformation\ndimension: 2\nplane: strain\n"
             "geometry:\n  spacing: 0.25\n  shapes: [{rectangle: {min: [0, 0], max: [2, 4]}, "
             "material: soil}]\n"
             "materials:\n  soil: {model: linear_elastic, density: 2000, young_modulus: 2.0e7, "
             "poisson_ratio: 0.3}\n"
             "boundary_conditions:\n  - {group: ymin, fixed: true}\n  - {group: xmin, roller: x}\n"
             "  - {group: xmax, roller: x}\n"
             "loads:\n  gravity: {acceleration: [0, -9.81]}\n") +
         (geostatic ? "initial_conditions:\n  geostatic: {surface: 4.0}\n" : "") +
         "numerics:\n  cells: " + cells + "\ntime: {end: 0.1}\n";
}

TEST(ReformedCells, FormsDelaunayCellsOfTheBodyWithItsAreaAndMass) {
  const Simulation simulation(read_case_text(column("{policy: reformed}"), "case.yaml"));
  // 8 x 16 lattice squares: their Delaunay triangles, two per square, none dropped at alpha 1.
  EXPECT_EQ(simulation.nodes().stress_points.size(), 128u);
  EXPECT_EQ(simulation.cells().stress_points.size(), 256u);
  EXPECT_EQ(simulation.assembly().cell_forming().formings, 1);
  EXPECT_EQ(simulation.assembly().cell_forming().triangles_dropped, 0);
  // The cells tile the column; the nodes keep their volumes, so their densities and masses.
  const Configuration& now = simulation.state().configuration;
  double area = 0.0;
  for (double volume : now.stress_points.volume)
    area += volume;
  EXPECT_NEAR(area, 8.0, 1e-12);
  for (std::size_t i = 0; i < now.sph_nodes.size(); ++i)
    ASSERT_EQ(now.sph_nodes.volume[i], simulation.nodes().sph_nodes.volume[i]) << "node " << i;
  // The moving cells of the start are the lattice's, as before.
  const Simulation moving(read_case_text(column("{policy: moving}"), "case.yaml"));
  EXPECT_EQ(moving.cells().stress_points.size(), 128u);
  EXPECT_EQ(moving.assembly().cell_forming().formings, 0);
}

// The column released under its weight from zero stress (no geostatic stress): a step load on a
// fixed-free column, whose top moves down and back as a sawtooth with the largest settlement
// twice the static one, rho g H^2 / M (M the constrained modulus), at t = 2H/c_p (the waves of
// the wave equation with a uniform source). With reform_below 1 the cells are formed again at
// nearly every step, each time with other diagonals where the lattice's four nodes are
// cocircular. A forming that changed a node's density (its mass over a volume shared out anew by
// the new cells, four to eight triangles at a node) would add or take a weight of tens of per
// cent at alternate nodes and show in the settlement.
double largest_settlement(const std::string& cells, long* formings) {
  Simulation simulation(read_case_text(column(cells, false), "case.yaml"));
  std::vector<std::size_t> top;
  for (std::size_t i = 0; i < simulation.nodes().sph_nodes.size(); ++i)
    if (simulation.nodes().sph_nodes.position[1][i] > 4.0 - 1e-9) top.push_back(i);
  const double modulus = 2.0e7 * 0.7 / (1.3 * 0.4);
  const double end = 2.2 * 4.0 / std::sqrt(modulus / 2000.0);
  double largest = 0.0;
  while (simulation.state().time < end) {
    simulation.take_step();
    double settlement = 0.0;
    for (std::size_t i : top)
      settlement -= simulation.state().displacement(1, i) / static_cast<double>(top.size());
    largest = std::max(largest, settlement);
  }
  if (formings) *formings = simulation.assembly().cell_forming().formings;
  return largest;
}

TEST(ReformedCells,
     AColumnReleasedUnderItsWeightSettlesTwiceItsStaticSettlementWhileItsCellsAreFormedAgain) {
  const double modulus = 2.0e7 * 0.7 / (1.3 * 0.4);
  const double twice_static = 2000.0 * 9.81 * 16.0 / modulus;
  long formings = 0;
  const double reformed = largest_settlement("{policy: reformed, reform_below: 1.0}", &formings);
  const double moving = largest_settlement("{policy: moving}", nullptr);
  EXPECT_GT(formings, 20) << "the test needs the cells formed again during the run";
  // 2 %: both capture the sawtooth's peak on 16 cells over the height to 0.4 % (measured).
  EXPECT_NEAR(reformed / twice_static, 1.0, 0.02);
  EXPECT_NEAR(moving / twice_static, 1.0, 0.02);
}

std::uint64_t bits_of(double value) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

std::size_t different_values(const FieldArray& a, const FieldArray& b) {
  EXPECT_EQ(a.data().size(), b.data().size());
  std::size_t different = 0;
  for (std::size_t i = 0; i < std::min(a.data().size(), b.data().size()); ++i)
    different += bits_of(a.data()[i]) != bits_of(b.data()[i]);
  return different;
}

// The collapsing block of ld-slope-low-cohesion on a coarse lattice with its cells formed again:
// a restart from a checkpoint between formings forms the cells where the run last did and takes
// the same steps.
TEST(ReformedCells, ARestartFormsTheCellsOfTheRunAndContinuesToTheBit) {
  const CaseDescription description = read_case_file(
      std::string(RKTSPH_TEST_DATA_DIR) + "/../../cases/ld-slope-low-cohesion/case.yaml",
      {{"geometry.spacing", "2.0"},
       {"time.end", "2.0"},
       {"numerics.cells.policy", "reformed"},
       {"numerics.cells.alpha", "2.5"},
       {"numerics.cells.reform_below", "0.8"}});
  Simulation original(description);
  for (int s = 0; s < 85; ++s)
    original.take_step();
  const long formings_at_checkpoint = original.assembly().cell_forming().formings;
  ASSERT_GT(formings_at_checkpoint, 1) << "the checkpoint must follow a forming mid-run";
  const std::string bytes = encode_checkpoint(1, {{"simulation", &original}});

  Simulation restored(description);
  restore_checkpoint_parts(decode_checkpoint(bytes, "memory", 1), {{"simulation", &restored}});
  EXPECT_EQ(restored.cells().stress_points.size(), original.cells().stress_points.size());
  EXPECT_EQ(restored.assembly().cell_forming().formings, formings_at_checkpoint);
  for (int s = 0; s < 75; ++s) {
    original.take_step();
    restored.take_step();
  }
  EXPECT_GT(original.assembly().cell_forming().formings, formings_at_checkpoint)
      << "the cells must be formed again after the restart too";
  EXPECT_EQ(restored.assembly().cell_forming().formings,
            original.assembly().cell_forming().formings);
  EXPECT_EQ(bits_of(restored.state().time), bits_of(original.state().time));
  EXPECT_EQ(different_values(restored.state().fields, original.state().fields), 0u);
  EXPECT_EQ(different_values(restored.state().displacement, original.state().displacement), 0u);
}

TEST(ReformedCells, AQuadrilateralStiffnessTheFormedTrianglesIgnoreIsWarnedOf) {
  const Simulation quiet(read_case_text(column("{policy: reformed}"), "case.yaml"));
  EXPECT_FALSE(formed_cells_stiffness_warning(quiet));
  std::string text = column("{policy: reformed}");
  text.replace(text.find("numerics:\n"), 10, "numerics:\n  hourglass: {stiffness: 0.3}\n");
  const Simulation warned(read_case_text(text, "case.yaml"));
  const auto warning = formed_cells_stiffness_warning(warned);
  ASSERT_TRUE(warning);
  EXPECT_EQ(warning->key, "numerics.hourglass.stiffness");
  EXPECT_NE(warning->text.find("triangles"), std::string::npos) << warning->text;
  // With the cells of the start it acts, and nothing is said.
  std::string moving = text;
  moving.replace(moving.find("policy: reformed"), 16, "policy: moving");
  EXPECT_FALSE(formed_cells_stiffness_warning(Simulation(read_case_text(moving, "case.yaml"))));
}

// The rigid strip footing of ld-footing-penetration on its quick lattice: the cells of the start
// fold beside the footing's edge at 0.61 B (docs/theory.md §9.16); formed again, the soil follows
// the footing to the case's end at 1 B and beyond, the deep settlement the case asks for.
TEST(ReformedCellsSlow, TheRigidFootingIsPushedToOneWidthOnFormedCells) {
  const test::OneOpenMpThread one_thread;
  const ValidationCase* validation = test::bundled_validation("ld-footing-penetration");
  ASSERT_NE(validation, nullptr);
  ValidationContext context = test::quick_validation_context("rktsph_reformed_");
  context.overrides = {{"numerics.cells.policy", "reformed"}};
  const ValidationResult result = run_validation(*validation, context);
  std::filesystem::remove_all(context.output_directory);
  EXPECT_TRUE(result.error.empty()) << result.error;
  const auto settlement =
      std::find_if(result.checks.begin(), result.checks.end(),
                   [](const CheckResult& check) { return check.name == "settlement_reached"; });
  ASSERT_NE(settlement, result.checks.end());
  EXPECT_TRUE(settlement->passed) << "settlement " << settlement->value << " B";
}

TEST(ReformedCells, AnAlphaOutsideItsRangeIsRefusedAtItsKey) {
  try {
    (void)read_case_text(column("{policy: reformed, alpha: 0.3}"), "case.yaml");
    FAIL() << "alpha 0.3 was accepted";
  } catch (const InputError& error) {
    const std::string text = error.what();
    EXPECT_NE(text.find("numerics.cells.alpha"), std::string::npos) << text;
    EXPECT_NE(text.find("0.3"), std::string::npos) << text;
  }
}

}  // namespace
}  // namespace rktsph::reformed_cells_test
