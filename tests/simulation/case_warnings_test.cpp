// The mesh's warning (docs/input-reference.md, "Plausibility warnings"): a triangle far narrower
// than the rest of its mesh sets the Courant step, and is named with where it is and its cost;
// none for an even mesh, a lattice, or a fixed time step.
#include "rktsph/simulation/case_warnings.hpp"

#include <gtest/gtest.h>

#include <string>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::case_warnings_test {
namespace {

// A 9 m x 6 m layer on triangles of edges up to 0.4 m; `top` is the top edge's vertices from
// right to left, which a short edge (2 cm) can split.
std::string layer(const std::string& top, const std::string& extra = "") {
  return "name: layer\ndimension: 2\nplane: strain\ngeometry:\n  cells: triangles\n  spacing: "
         "0.4\n  shapes:\n    - polygon: [[0, 0], [9, 0], " +
         top +
         "]\n      material: clay\nmaterials:\n  clay: {model: linear_elastic, density: 1800.0, "
         "young_modulus: 2.0e7, poisson_ratio: 0.35}\nboundary_conditions:\n  - {group: ymin, "
         "fixed: true}\ntime: {end: 0.01}\n" +
         extra;
}

std::vector<CaseWarning> mesh_warnings(const std::string& text) {
  const Simulation simulation(read_case_text(text, "layer.yaml"));
  std::vector<CaseWarning> warnings = case_warnings(simulation);
  std::erase_if(warnings, [](const CaseWarning& w) { return w.key.rfind("geometry", 0) != 0; });
  return warnings;
}

TEST(CaseWarnings, ATriangleFarNarrowerThanTheMeshIsNamedWithItsPlaceAndCost) {
  // Without the short edge: no warning.
  EXPECT_TRUE(mesh_warnings(layer("[9, 6], [1.5, 6], [0, 6]")).empty());
  const std::vector<CaseWarning> warnings =
      mesh_warnings(layer("[9, 6], [1.52, 6], [1.5, 6], [0, 6]"));
  ASSERT_EQ(warnings.size(), 1u);
  const CaseWarning& warning = warnings.front();
  EXPECT_EQ(warning.key, "geometry.shapes");
  EXPECT_EQ(warning.where.line, 8);  // the polygon's item
  // The narrowest triangle sits at the short edge, within one spacing of (1.51, 6).
  double x = 0.0, y = 0.0;
  ASSERT_EQ(std::sscanf(warning.value.c_str(), "the triangle at (%lf, %lf)", &x, &y), 2)
      << warning.value;
  EXPECT_NEAR(x, 1.51, 0.4);
  EXPECT_NEAR(y, 6.0, 0.4);
  EXPECT_NE(warning.text.find("times narrower than the median cell"), std::string::npos);
  EXPECT_NE(warning.text.find("sets the time step"), std::string::npos);
}

TEST(CaseWarnings, AFixedTimeStepOrALatticeGivesNoMeshWarning) {
  const std::string narrow = layer("[9, 6], [1.52, 6], [1.5, 6], [0, 6]");
  EXPECT_TRUE(mesh_warnings(narrow + "numerics: {time_step: 1.0e-5}\n").empty());
  // On a lattice every cell is a square of the spacing (9.2 m: a whole number of 0.4 m).
  std::string lattice = layer("[9.2, 6], [0, 6]");
  lattice.replace(lattice.find("  cells: triangles\n"), 18, "");
  lattice.replace(lattice.find("[9, 0]"), 6, "[9.2, 0]");
  EXPECT_TRUE(mesh_warnings(lattice).empty());
}

}  // namespace
}  // namespace rktsph::case_warnings_test
