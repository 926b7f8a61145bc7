// A re-entrant (concave) corner, e.g. the toe of a vertical cut, keeps the interior stencil
// (rk_taylor_step.cpp, needs_boundary_half_step): the full step on an L-shaped lattice must be
// neutrally stable (spectral radius <= 1, docs/theory.md §5.3). With the corner given the
// boundary half-step instead, the radius was 1.22-1.45 per step.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <Eigen/Dense>

#include "../support/elastic_block.hpp"
#include "../support/lattices.hpp"
#include "../support/step_matrix.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::reentrant_corner_test {
namespace {

using test::spectral_radius;

// A 12 x 8 block with a 6 x 5 notch cut out of its top right: the toe (6, 3) is re-entrant; the
// crest (6, 8) is a free convex corner; rollers on the sides, fixed base.
std::string cut_case(double courant, double damping = 0.0) {
  test::ElasticBlock block;
  block.shapes = "[{polygon: [[0, 0], [12, 0], [12, 3], [6, 3], [6, 8], [0, 8]], material: soil}]";
  block.conditions = {"{group: xmin, roller: x}", "{group: xmax, roller: x}",
                      "{group: ymin, fixed: true}"};
  block.loads = fmt::format("{{damping: {{coefficient: {}}}}}", damping);
  block.numerics = fmt::format("{{courant: {}, hourglass: {{enabled: false}}}}", courant);
  return block.text();
}

TEST(ReentrantCornerSlow, CutLatticeIsNeutrallyStable) {
  for (double courant : {0.3, 0.9}) {
    Simulation simulation(read_case_text(cut_case(courant), "cut.yaml"));
    EXPECT_LE(spectral_radius(simulation), 1.0 + 1e-9) << "courant " << courant;
  }
}

TEST(ReentrantCornerSlow, DampedCutCanOnlyComeToRest) {
  // With damping, every fixed point of the step must be at rest. Before the strain-rate closure
  // of eq. 5.3 three fixed points around the toe kept a velocity (share 0.31-0.38 of the state):
  // the toe of a 20 x 15 m cut kept 0.26 m/s under damping (docs/theory.md §5.3).
  Simulation simulation(read_case_text(cut_case(0.5, 20.0), "cut.yaml"));
  const double impedance = 2000.0 * simulation.model().max_wave_speed();
  EXPECT_LT(test::velocity_in_fixed_points(simulation, impedance), 1e-8);
}

TEST(ReentrantCorner, ToeIsNotABoundaryNodeButItsFaceNeighboursAre) {
  Simulation simulation(read_case_text(cut_case(0.5), "cut.yaml"));
  const NodeSets& nodes = simulation.nodes();
  const auto& to_row = simulation.step().operators().node_to_boundary_row;
  auto row_at = [&](std::int32_t i, std::int32_t j) {
    return to_row[static_cast<std::size_t>(test::lattice_node(nodes, i, j))];
  };
  EXPECT_LT(row_at(6, 3), 0);  // toe: three cells
  EXPECT_GE(row_at(7, 3), 0);  // on the lower free face
  EXPECT_GE(row_at(6, 4), 0);  // on the cut face
  EXPECT_GE(row_at(6, 8), 0);  // crest: one cell
  EXPECT_LT(row_at(3, 2), 0);  // interior
}

}  // namespace
}  // namespace rktsph::reentrant_corner_test
