// The detected free surface against the body's outline (src/rktsph/simulation/surface_watch.*,
// docs/theory.md §9.4): the outline is every node missing a lattice neighbour, also where a
// condition holds the body (a fixed base), since the detector sees only the nodes.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"
#include "rktsph/simulation/surface_watch.hpp"

namespace rktsph::surface_watch_test {
namespace {

// A 6 m x 4 m block at dx = 0.5 m (13 x 9 nodes), fixed at its base, a roller on its left face.
const std::string kBlock =
    "name: block\nmodel: dry_large_deformation\ndimension: 2\nplane: strain\n"
    "geometry:\n  spacing: 0.5\n  shapes: [{rectangle: {min: [0, 0], max: [6, 4]}, material: "
    "soil}]\n"
    "materials:\n  soil: {model: linear_elastic, density: 2000, young_modulus: 1.0e7, "
    "poisson_ratio: 0.3}\n"
    "boundary_conditions:\n  - {group: ymin, fixed: true}\n  - {group: xmin, roller: x}\n"
    "time: {end: 0.01}\n";

TEST(SurfaceWatch, OutlineIsEveryNodeMissingALatticeNeighbourWhateverItsCondition) {
  const Simulation simulation(read_case_text(kBlock, "case.yaml"));
  const std::vector<std::uint8_t> outline = body_perimeter(simulation.nodes());
  std::size_t count = 0;
  for (std::uint8_t on : outline)
    count += on;
  EXPECT_EQ(count, 2u * (13u + 9u) - 4u);
  // The block as built: the detector finds exactly its outline, base and left face included.
  FreeSurface detected;
  detect_current_surface(simulation, detected);
  const SurfaceAgreement agreement = compare_with_perimeter(simulation, detected);
  EXPECT_EQ(agreement.perimeter_nodes, count);
  EXPECT_EQ(agreement.missed, 0u);
  EXPECT_EQ(agreement.false_positive, 0u);
  EXPECT_EQ(agreement.misflagged_fraction(), 0.0);
}

// With cells formed again the field files' surface is the outline's, where the conditions act
// (docs/theory.md §9.17): the top face (13 nodes) and the right face below its corner (8 nodes:
// the fixed base's corner too, whose right facet is not on the face the base condition acts on),
// each with its face's outward normal; not the fixed base, nor the face on rollers, whose normal
// velocity is imposed.
TEST(SurfaceWatch, FormedCellsWriteTheTractionFreeOutlineAsTheFreeSurface) {
  std::string text = kBlock;
  text.replace(text.find("time:"), 5, "numerics: {cells: {policy: reformed}}\ntime:");
  const Simulation simulation(read_case_text(text, "case.yaml"));
  FreeSurface surface;
  field_free_surface(simulation, surface);
  const PointCloud& nodes = simulation.nodes().sph_nodes;
  std::size_t count = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double x = nodes.position[0][i], y = nodes.position[1][i];
    const bool top = y > 4.0 - 1e-9, right = x > 6.0 - 1e-9;
    EXPECT_EQ(surface.on_surface[i], top || right ? 1 : 0) << "node at " << x << ", " << y;
    count += surface.on_surface[i];
    if (top && !right) {
      EXPECT_NEAR(surface.normal[1][i], 1.0, 1e-12);
    } else if (right && !top) {
      EXPECT_NEAR(surface.normal[0][i], 1.0, 1e-12);
    } else if (top && right) {  // the corner: both faces' normals, summed and made unit
      EXPECT_NEAR(surface.normal[0][i], std::sqrt(0.5), 1e-12);
      EXPECT_NEAR(surface.normal[1][i], std::sqrt(0.5), 1e-12);
    }
  }
  EXPECT_EQ(count, 21u);
  // The cells of the start write the detector's surface, as before.
  FreeSurface detected;
  const Simulation moving(read_case_text(kBlock, "case.yaml"));
  field_free_surface(moving, surface);
  detect_current_surface(moving, detected);
  EXPECT_EQ(surface.on_surface, detected.on_surface);
}

}  // namespace
}  // namespace rktsph::surface_watch_test
