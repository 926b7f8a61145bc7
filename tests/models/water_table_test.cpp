// The water table of the saturated model (docs/theory.md §6.8): the table's height, the K0 start
// (eq. 6.9) with the hydrostatic pore pressure (6.6), the body-force weights (6.8), the drained
// soil above the table, a start that stays at rest, and a model without a table left as it was.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/physics/water_table.hpp"
#include "rktsph/simulation/quantities.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::water_table_test {
namespace {

constexpr double kDensity = 2000.0, kWater = 1000.0, kPorosity = 0.4, kGravity = 9.81;
constexpr double kTop = 10.0, kTable = 5.0, kK0 = 0.5, kSpacing = 0.5;

// A layer 2 m wide and 10 m deep between mirror sides on a fixed impermeable base, E = 20 MPa,
// nu = 0.3, rho = 2000 kg/m3, n = 0.4, starting geostatic with K0 = 0.5; `table` is the
// water_table entry (empty: none), `end` the run's length.
CaseDescription layer_case(const std::string& table, double end) {
  const std::string text = fmt::format(
      R"(
name: water-table-layer
model: saturated_vpw
dimension: 2
geometry:
  spacing: {spacing}
  shapes:
    - rectangle: {{min: [0.0, 0.0], max: [2.0, {top}]}}
      material: soil
materials:
  soil: {{model: linear_elastic, density: {density}, young_modulus: 2.0e7, poisson_ratio: 0.3}}
pore_fluid:
  bulk_modulus: 2.2e9
  density: {water}
  porosity: {porosity}
  hydraulic_conductivity: 1.0e-3{table}
boundary_conditions:
  - {{group: xmin, roller: x}}
  - {{group: xmax, roller: x}}
  - {{group: ymin, fixed: true}}
loads:
  gravity: {{acceleration: [0, -{g}]}}
initial_conditions:
  geostatic: {{surface: {top}, k0: {k0}}}
numerics:
  courant: 0.5
time:
  end: {end}
)",
      fmt::arg("spacing", kSpacing), fmt::arg("top", kTop), fmt::arg("density", kDensity),
      fmt::arg("water", kWater), fmt::arg("porosity", kPorosity),
      fmt::arg("table", table.empty() ? std::string() : "\n  water_table: " + table),
      fmt::arg("g", kGravity), fmt::arg("k0", kK0), fmt::arg("end", end));
  return read_case_text(text, "water-table-layer.yaml");
}

// -sigma'_v of eq. 6.9 for the level table at kTable (compression positive).
double effective_overburden(double y, double table) {
  const double dry = std::max(0.0, kTop - std::max(y, table));
  const double wet = std::max(0.0, std::min(kTop, table) - y);
  return kGravity * ((kDensity - kPorosity * kWater) * dry + (kDensity - kWater) * wet);
}

int internal_index(const Simulation& simulation, const std::string& name) {
  const auto& names = simulation.model().internal_names();
  const auto found = std::find(names.begin(), names.end(), name);
  return found == names.end() ? -1 : static_cast<int>(found - names.begin());
}

TEST(WaterTable, HeightAndSlopeOfALevelAndOfAPolyline) {
  const WaterTable flat = WaterTable::level(3.0);
  EXPECT_EQ(flat.height(-100.0), 3.0);
  EXPECT_EQ(flat.slope(7.0), 0.0);
  EXPECT_EQ(flat.depth_below(1.0, 1.0), 2.0);
  EXPECT_EQ(flat.depth_below(1.0, 4.0), 0.0);
  const WaterTable polyline = WaterTable::polyline({{0.0, 8.0}, {20.0, 8.0}, {40.0, 2.0}});
  EXPECT_EQ(polyline.height(-5.0), 8.0);  // constant beyond the ends
  EXPECT_EQ(polyline.height(50.0), 2.0);
  EXPECT_DOUBLE_EQ(polyline.height(30.0), 5.0);
  EXPECT_DOUBLE_EQ(polyline.slope(30.0), -0.3);
  EXPECT_EQ(polyline.slope(10.0), 0.0);
  EXPECT_EQ(polyline.slope(45.0), 0.0);
}

TEST(WaterTable, GeostaticStartIsHydrostaticWithTheEffectiveOverburden) {
  const Simulation simulation(layer_case("{level: 5.0}", 0.01));
  const PointCloud& nodes = simulation.nodes().sph_nodes;
  const State& state = simulation.state();
  const int xx = simulation.model().stress_field(0, 0), yy = simulation.model().stress_field(1, 1);
  const NodeQuantity pore_pressure = find_quantity(simulation, "pore_pressure");
  const int excess = simulation.model().pore_pressure_field();
  const int weight = internal_index(simulation, "gravity_weight");
  const int seepage = internal_index(simulation, "seepage_weight");
  ASSERT_GE(weight, 0);
  ASSERT_EQ(seepage, weight + 1);
  const double wet = (kDensity - kWater) / kDensity,
               dry = (kDensity - kPorosity * kWater) / kDensity;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double y = nodes.position[1][i];
    const double reference = effective_overburden(y, kTable);
    EXPECT_NEAR(pore_pressure(state, i), kWater * kGravity * std::max(0.0, kTable - y), 1e-9)
        << "y = " << y;
    EXPECT_EQ(state.fields(excess, i), 0.0);
    EXPECT_NEAR(-state.fields(yy, i), reference, 1e-9 * reference + 1e-9) << "y = " << y;
    EXPECT_NEAR(state.fields(xx, i), kK0 * state.fields(yy, i), 1e-9 * reference + 1e-9);
    // The mean weight over the node's span y -+ dx/2 (eq. 6.8): half and half on the table.
    const double expected = y < kTable - 1e-9 ? wet : (y > kTable + 1e-9 ? dry : 0.5 * (wet + dry));
    EXPECT_NEAR(state.internal(weight, i), expected, 1e-15) << "y = " << y;
    EXPECT_EQ(state.internal(seepage, i), 0.0);
  }
  // Drained: every node at or above the table, none below it.
  const auto& drained = simulation.boundary_conditions().drained_nodes();
  std::size_t above = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes.position[1][i] >= kTable - 1e-9) ++above;
  EXPECT_EQ(drained.size(), above);
  for (std::int32_t node : drained)
    EXPECT_GE(nodes.position[1][static_cast<std::size_t>(node)], kTable - 1e-9);
}

TEST(WaterTable, GeostaticStartStaysAtRest) {
  // 0.3 s is 3.5 transits of the layer (c_p = 116 m/s): an unbalanced start would move it at
  // about g H / c_p = 0.85 m/s per unit imbalance.
  Simulation simulation(layer_case("{level: 5.0}", 0.3));
  ASSERT_EQ(simulation.run(), RunStatus::Completed) << simulation.message();
  const PointCloud& nodes = simulation.nodes().sph_nodes;
  const State& state = simulation.state();
  const int yy = simulation.model().stress_field(1, 1);
  const NodeQuantity pore_pressure = find_quantity(simulation, "pore_pressure");
  const double base_stress = effective_overburden(0.0, kTable);
  EXPECT_LT(largest_speed(simulation), 1e-4 * kGravity * kTop / 116.0);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double y = nodes.position[1][i];
    EXPECT_NEAR(-state.fields(yy, i), effective_overburden(y, kTable), 1e-4 * base_stress)
        << "y = " << y;
    EXPECT_NEAR(pore_pressure(state, i), kWater * kGravity * std::max(0.0, kTable - y),
                1e-4 * kWater * kGravity * kTable)
        << "y = " << y;
  }
}

TEST(WaterTable, ATableAboveTheSurfaceSubmergesTheBody) {
  const Simulation simulation(layer_case("{level: 12.0}", 0.01));
  const PointCloud& nodes = simulation.nodes().sph_nodes;
  const int yy = simulation.model().stress_field(1, 1);
  const NodeQuantity pore_pressure = find_quantity(simulation, "pore_pressure");
  // Drained: the free top face only, which touches the water above it.
  for (std::int32_t node : simulation.boundary_conditions().drained_nodes())
    EXPECT_EQ(nodes.position[1][static_cast<std::size_t>(node)], kTop);
  EXPECT_EQ(simulation.boundary_conditions().drained_nodes().size(),
            static_cast<std::size_t>(std::lround(2.0 / kSpacing)) + 1);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double y = nodes.position[1][i];
    EXPECT_NEAR(-simulation.state().fields(yy, i), (kDensity - kWater) * kGravity * (kTop - y),
                1e-6);
    EXPECT_NEAR(pore_pressure(simulation.state(), i), kWater * kGravity * (12.0 - y), 1e-6);
  }
}

TEST(WaterTable, WithoutATableTheModelIsAsBefore) {
  const Simulation simulation(layer_case("", 0.01));
  EXPECT_FALSE(simulation.model().has_water_table());
  EXPECT_EQ(internal_index(simulation, "gravity_weight"), -1);
  EXPECT_TRUE(simulation.boundary_conditions().drained_nodes().empty());
  const PointCloud& nodes = simulation.nodes().sph_nodes;
  const int yy = simulation.model().stress_field(1, 1);
  for (std::size_t i = 0; i < nodes.size(); ++i)
    EXPECT_EQ(simulation.state().fields(yy, i),
              kDensity * -kGravity * (kTop - nodes.position[1][i]));
}

TEST(WaterTable, NeedsDownwardGravity) {
  CaseDescription description = layer_case("{level: 5.0}", 0.01);
  description.gravity->acceleration = {1.0, -9.81, 0.0};
  try {
    const Simulation simulation(description);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "pore_fluid.water_table");
    EXPECT_NE(error.allowed().find("[0, -g]"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace rktsph::water_table_test
