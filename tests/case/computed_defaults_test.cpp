// The defaults the case layer computes for the resolved case (case/computed_defaults.hpp) against
// what the built simulation uses: the stencil width the step operators measure on the lattice,
// and the Laplacian scale of the pressure projection, to the last bit.
#include "rktsph/case/computed_defaults.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"
#include "rktsph/sph/cell_laplacian.hpp"

namespace rktsph::computed_defaults_test {
namespace {

/// A small saturated block (12 x 6 cells in 2D, 12 cells in 1D) with drained top and rollers.
CaseDescription block_case(int dimension, const std::string& kernel, double h_over_dx,
                           double spacing) {
  const std::string shape =
      dimension == 2
          ? fmt::format("rectangle: {{min: [0, 0], max: [{}, {}]}}", 12 * spacing, 6 * spacing)
          : fmt::format("segment: [0, {}]", 12 * spacing);
  const std::string conditions =
      dimension == 2 ? "  - {group: ymin, roller: y}\n  - {group: xmin, roller: x}\n"
                       "  - {group: ymax, pore_pressure: 0.0}\n"
                     : "  - {group: xmin, roller: x}\n  - {group: xmax, pore_pressure: 0.0}\n";
  const std::string text = fmt::format(
      R"(name: block
model: saturated_vpw
dimension: {}
geometry:
  spacing: {}
  shapes:
    - {}
      material: soil
materials:
  soil: {{model: linear_elastic, density: 2000, young_modulus: 1.0e7, poisson_ratio: 0.3}}
pore_fluid: {{bulk_modulus: 2.2e9, density: 1000, porosity: 0.3, hydraulic_conductivity: 1e-3}}
boundary_conditions:
{}numerics:
  kernel: {}
  h_over_dx: {}
  courant: 0.5
  hourglass: {{fields: all}}
time:
  end: 0.01
)",
      dimension, spacing, shape, conditions, kernel, h_over_dx);
  return read_case_text(text, "block.yaml");
}

TEST(ComputedDefaults, StencilWidthIsTheOneTheStepOperatorsMeasure) {
  const std::vector<std::pair<std::string, std::vector<double>>> settings = {
      {"cubic_spline", {0.75, 0.79, 0.8, 1.0, 1.3}},
      {"quintic_spline", {0.51, 0.52, 0.53, 0.75}},
      {"gaussian", {0.51, 0.52, 0.53, 1.0}},
  };
  for (const auto& [kernel, ratios] : settings) {
    for (double h_over_dx : ratios) {
      const CaseDescription description = block_case(2, kernel, h_over_dx, 0.25);
      const Simulation simulation(description);
      EXPECT_EQ(has_wide_stencils(description.numerics, 2),
                !simulation.step().operators().compact_stencils)
          << kernel << ", h_over_dx " << h_over_dx;
    }
  }
}

TEST(ComputedDefaults, LaplacianScaleIsTheOneThePressureProjectionUses) {
  for (int dimension : {1, 2}) {
    for (double spacing : {0.25, 0.1, 0.0125}) {
      const CaseDescription description = block_case(dimension, "cubic_spline", 0.75, spacing);
      const Simulation simulation(description);
      ASSERT_NE(simulation.pressure_projection(), nullptr);
      EXPECT_EQ(default_laplacian_scale(description),
                simulation.pressure_projection()->laplacian().scale)
          << dimension << "D, spacing " << spacing;
    }
  }
}

TEST(ComputedDefaults, LaplacianScaleOnTrianglesIsOneAndTheProjectionTakesTheCellLaplacian) {
  // Off a lattice the pressure solve assembles the cells' P1 Laplacian (docs/theory.md eq. 6.6),
  // which needs no factor: the resolved case says 1, and the projection's matrix and volumes are
  // the cell operator's.
  CaseDescription description = block_case(2, "cubic_spline", 0.75, 0.25);
  description.geometry.cells = CellLayout::Triangles;
  EXPECT_EQ(default_laplacian_scale(description), 1.0);
  const Simulation simulation(description);
  ASSERT_NE(simulation.pressure_projection(), nullptr);
  const LaplacianMatrix& used = simulation.pressure_projection()->laplacian();
  const LaplacianMatrix cells =
      build_cell_laplacian(simulation.nodes().cells, simulation.nodes().sph_nodes, 0.0);
  EXPECT_EQ(used.scale, 1.0);
  EXPECT_EQ((Eigen::SparseMatrix<double>(used.weighted - cells.weighted)).norm(), 0.0);
  EXPECT_EQ(used.effective_volume, cells.effective_volume);
}

TEST(ComputedDefaults, ResolvedCaseHasTheComputedDefaultsAndReadsBackToThem) {
  const CaseDescription description = block_case(2, "cubic_spline", 0.75, 0.25);
  const std::string resolved = write_case_yaml(description);
  EXPECT_NE(resolved.find("stress_update: mean_velocity"), std::string::npos) << resolved;
  EXPECT_NE(resolved.find("fields: all"), std::string::npos) << resolved;
  EXPECT_NE(resolved.find(fmt::format("laplacian_scale: {}", default_laplacian_scale(description))),
            std::string::npos)
      << resolved;
  const CaseDescription again = read_case_text(resolved, "resolved.yaml");
  EXPECT_EQ(again.numerics.stress_update, StressUpdate::MeanVelocity);
  EXPECT_EQ(again.pore_fluid->laplacian_scale, default_laplacian_scale(description));
  EXPECT_EQ(write_case_yaml(again), resolved);
}

TEST(ComputedDefaults, UnsetHourglassFieldsFollowTheStencilWidth) {
  NumericsSpec numerics;
  EXPECT_EQ(default_hourglass_fields(numerics, 2), HourglassFields::Velocity);
  numerics.h_over_dx = 1.0;
  EXPECT_EQ(default_hourglass_fields(numerics, 2), HourglassFields::All);
  EXPECT_EQ(default_stress_update(1), StressUpdate::HalfStep);
  EXPECT_EQ(default_stress_update(2), StressUpdate::MeanVelocity);
}

}  // namespace
}  // namespace rktsph::computed_defaults_test
