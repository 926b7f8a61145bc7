// Issue 30: a run the method cannot continue says where, what happened in physical words and what
// to change, measured to help — here a cell of the large-deformation model folded by a node
// driven through it. The old advice, "reduce the time step or refine the lattice", was wrong on
// both counts: a finer lattice folds sooner (docs/theory.md §9.12) and a smaller step changes
// nothing about a fold that the motion makes.
#include <gtest/gtest.h>

#include <string>

#include "../support/case_text.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::stop_messages_test {
namespace {

// A 4 m x 2 m elastic block on a 1 m lattice (c_p = 268 m/s) whose top-left corner node is driven
// at 200 m/s, down (x held: it passes the node below it and folds the cell between them) or down
// with x free (it slides out past the corner and leaves every stress point behind).
std::string driven_corner(const std::string& velocity) {
  return R"(name: fold
model: dry_large_deformation
dimension: 2
plane: strain
geometry:
  spacing: 1.0
  shapes: [{rectangle: {min: [0, 0], max: [4, 2]}, material: soil}]
materials:
  soil: {model: linear_elastic, density: 2000, young_modulus: 1.0e8, poisson_ratio: 0.3}
groups:
  corner: {point: [0, 2]}
boundary_conditions:
  - {group: ymin, fixed: true}
  - {group: corner, velocity: )" +
         velocity + R"(}
numerics: {hourglass: {stiffness: 0}}
time: {end: 0.05}
)";
}

TEST(StopMessages, AFoldedCellIsPlacedExplainedAndGivenAdviceThatHelps) {
  Simulation simulation(read_case_text(driven_corner("{x: 0.0, y: -200.0}"), "fold.yaml"));
  EXPECT_EQ(simulation.run(), RunStatus::Failed);
  const std::string& message = simulation.message();
  EXPECT_NE(message.find("folded over"), std::string::npos) << message;
  EXPECT_NE(message.find("stress point at (x, y) = "), std::string::npos) << message;
  EXPECT_NE(message.find("finer lattice folds sooner"), std::string::npos) << message;
  EXPECT_NE(message.find("time.end"), std::string::npos) << message;
  EXPECT_EQ(message.find("refine the lattice"), std::string::npos) << message;
}

// The stop a user met as "build_adjoint_operator: node 1079 is in no forward row (zero lumped
// volume)": now where, what and what to change.
TEST(StopMessages, ANodeLeftBehindByItsCellsIsPlacedAndExplained) {
  Simulation simulation(read_case_text(driven_corner("{y: -200.0}"), "slide.yaml"));
  EXPECT_EQ(simulation.run(), RunStatus::Failed);
  const std::string& message = simulation.message();
  EXPECT_NE(message.find("the SPH node at (x, y) = "), std::string::npos) << message;
  EXPECT_NE(message.find("out of reach of every stress point"), std::string::npos) << message;
  EXPECT_NE(message.find("finer lattice fails sooner"), std::string::npos) << message;
  EXPECT_EQ(message.find("forward row"), std::string::npos) << message;
}

}  // namespace
}  // namespace rktsph::stop_messages_test
