// The RK-TSPH step against exact solutions, and its stability (docs/theory.md §2.4):
// - the 1D bar at Courant 1 reproduces the characteristics solution exactly (staggered
//   Lax-Wendroff at h = 0.75 dx, docs/theory.md §2.4);
// - a 2D plane wave keeps the uniaxial-strain plateau and zero transverse velocity;
// - the spectral radius of the full linear step, every boundary type included, is <= 1;
// - a seeded checkerboard is neutral without the hourglass filter and decays as (1 - kappa)^n
//   with it.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

#include "../support/elastic_block.hpp"
#include "../support/lattices.hpp"
#include "../support/step_matrix.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"
#include "rktsph/stabilisation/hourglass_filter.hpp"

namespace rktsph::rk_taylor_step_test {
namespace {

using test::spectral_radius;

// The step's hourglass filter; throws (failing the test) where none acts.
HourglassFilter& filter_of(const Simulation& simulation) {
  HourglassFilter* filter = simulation.step().control<HourglassFilter>();
  if (filter == nullptr) throw std::runtime_error("the step has no hourglass filter");
  return *filter;
}

const char* kBar = R"(
name: bar
dimension: 1
geometry:
  spacing: 0.5
  shapes: [{segment: [0.0, 10.0], material: soil}]
materials:
  soil: {model: linear_elastic, density: 2000.0, young_modulus: 1.0e8, poisson_ratio: 0.0}
boundary_conditions:
  - {group: xmax, velocity: {x: -0.1}}
numerics: {h_over_dx: 0.75, courant: 1.0}
time: {end: 0.36}
)";

TEST(RkTaylorStep, ElasticBarAtCourantOneIsExact) {
  Simulation simulation(read_case_text(kBar, "bar.yaml"));
  const double c = std::sqrt(1e8 / 2000.0), impedance = 2000.0 * c, v0 = 0.1, length = 10.0;
  const double dt = simulation.time_step();
  ASSERT_NEAR(dt, 0.5 / c, 1e-15);
  // Exact (characteristics): free-end velocity 0 for t < L/c, -2 V0 until 3L/c, 0 until 5L/c;
  // mid-bar stress -Z V0 in (L/2c, 3L/2c), 0, then +Z V0 in (5L/2c, 7L/2c) (tension).
  auto exact_free_end = [&](double t) {
    const double phase = std::fmod(t * c / length, 4.0);
    return (phase > 1.0 && phase < 3.0) ? -2.0 * v0 : 0.0;
  };
  auto exact_mid_stress = [&](double t) {
    const double phase = std::fmod(t * c / length - 0.5, 4.0);
    if (phase > 0.0 && phase < 1.0) return -impedance * v0;
    if (phase > 2.0 && phase < 3.0) return impedance * v0;
    return 0.0;
  };
  const std::size_t free_end = 0, middle = 10;
  const int velocity_x = simulation.model().velocity_field(0);
  const int stress_xx = simulation.model().stress_field(0, 0);
  int compared = 0;
  for (long s = 0; s < simulation.total_steps(); ++s) {
    simulation.step().advance(simulation.state(), dt);
    const State& state = simulation.state();
    const double t = state.time;
    // Compare away from the instants when a front sits exactly on the node (half-way values).
    const double front_phase = std::fmod(t * c / length, 1.0);
    if (std::abs(front_phase) < 0.06 || std::abs(front_phase - 1.0) < 0.06 ||
        std::abs(front_phase - 0.5) < 0.06)
      continue;
    EXPECT_NEAR(state.fields(velocity_x, free_end), exact_free_end(t), 1e-12) << "t = " << t;
    EXPECT_NEAR(state.fields(stress_xx, middle), exact_mid_stress(t), 1e-6 * impedance * v0)
        << "t = " << t;
    ++compared;
  }
  EXPECT_GT(compared, 100);
}

TEST(RkTaylorStep, DisplacementIsTheTimeIntegralOfTheVelocity) {
  // The driven end moves at exactly -V0 from t = 0, so its displacement is -V0 t (trapezoidal
  // integration of a constant is exact); the free end is still at rest before L/c.
  Simulation simulation(read_case_text(kBar, "bar.yaml"));
  const double dt = simulation.time_step();
  for (int s = 0; s < 15; ++s)
    simulation.step().advance(simulation.state(), dt);
  const State& state = simulation.state();
  const std::size_t driven = simulation.nodes().sph_nodes.size() - 1;
  EXPECT_NEAR(state.displacement(0, driven), -0.1 * state.time, 1e-15);
  EXPECT_EQ(state.displacement(0, 0), 0.0);
}

std::string plane_wave_case(double courant) {
  return fmt::format(R"(
name: wave
dimension: 2
plane: strain
geometry:
  spacing: 0.02
  shapes: [{{rectangle: {{min: [0, 0], max: [1.0, 0.2]}}, material: solid}}]
materials:
  solid: {{model: linear_elastic, density: 2000.0, young_modulus: 1.5e8, poisson_ratio: 0.25}}
boundary_conditions:
  - {{group: xmin, velocity: {{x: 0.3, y: 0.0}}}}
  - {{group: ymin, roller: y}}
  - {{group: ymax, roller: y}}
numerics: {{courant: {}}}
time: {{end: 0.0045}}
)",
                     courant);
}

TEST(RkTaylorStep, PlaneWaveKeepsUniaxialStrainAndNoTransverseMotion) {
  Simulation simulation(read_case_text(plane_wave_case(0.6), "wave.yaml"));
  simulation.run();
  const State& state = simulation.state();
  const NodeSets& nodes = simulation.nodes();
  const double c = 300.0, v0 = 0.3, impedance = 2000.0 * c;
  const double front = c * state.time;  // 1.35 m: reflected from the free end at 1 m
  (void)front;
  const PhysicsModel& model = simulation.model();
  const int vx = model.velocity_field(0), vy = model.velocity_field(1);
  const int xx = model.stress_field(0, 0), yy = model.stress_field(1, 1),
            zz = model.stress_field(2, 2);
  double max_vy = 0.0;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i)
    max_vy = std::max(max_vy, std::abs(state.fields(vy, i)));
  EXPECT_LT(max_vy / v0, 1e-10);
  // At t = 4.5 ms the unloading wave from the free end (x = 1) has reached x = 0.65 m: between
  // x = 0.2 and 0.5 the state is still the first plateau v = V0, sigma_xx = -Z V0,
  // sigma_yy = sigma_zz = nu/(1-nu) sigma_xx (uniaxial strain).
  int checked = 0;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    const double x = nodes.sph_nodes.position[0][i];
    if (x < 0.2 || x > 0.5) continue;
    EXPECT_NEAR(state.fields(vx, i) / v0, 1.0, 2e-2);
    EXPECT_NEAR(state.fields(xx, i) / (-impedance * v0), 1.0, 2e-2);
    EXPECT_NEAR(state.fields(yy, i) / state.fields(xx, i), 1.0 / 3.0, 1e-9);
    EXPECT_NEAR(state.fields(zz, i) / state.fields(xx, i), 1.0 / 3.0, 1e-9);
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

// Free top, fixed left, roller (mirror) bottom, free right: every boundary type and corner mix.
test::ElasticBlock stability_block(double courant, bool filter) {
  test::ElasticBlock block;
  block.conditions = {"{group: xmin, fixed: true}", "{group: ymin, roller: y}"};
  block.numerics = fmt::format("{{courant: {}, hourglass: {{enabled: {}}}}}", courant,
                               filter ? "true" : "false");
  return block;
}

TEST(RkTaylorStepSlow, SpectralRadiusOfTheFullStepWithEveryBoundaryTypeIsAtMostOne) {
  for (bool filter : {true, false})
    for (double courant : {0.3, 0.5, 0.9}) {
      Simulation simulation(stability_block(courant, filter).description());
      EXPECT_LE(spectral_radius(simulation), 1.0 + 1e-9)
          << "courant " << courant << " filter " << filter;
    }
}

TEST(RkTaylorStepSlow, DampedLatticeWithEveryBoundaryTypeCanOnlyComeToRest) {
  // With damping the only velocity in a fixed point of the step is zero (docs/theory.md §5.3):
  // before the adjoint closure, the free corners forced a checkerboard that stayed.
  for (bool filter : {true, false}) {
    test::ElasticBlock block = stability_block(0.5, filter);
    block.loads = "{damping: {coefficient: 20}}";
    Simulation simulation(block.description());
    const double impedance = 2000.0 * simulation.model().max_wave_speed();
    EXPECT_LT(test::velocity_in_fixed_points(simulation, impedance), 1e-8) << "filter " << filter;
  }
}

TEST(RkTaylorStepSlow, WiderStencilsFilterEveryFieldAndStayStable) {
  // h = 1.0 and 1.3 dx: a stress point sees beyond its cell, the velocity-only filter would leave
  // radii of 1.00003-1.001; by default the filter then acts on every field (docs/theory.md §3.3).
  for (const char* h : {"1.0", "1.3"}) {
    test::ElasticBlock block = stability_block(0.5, true);
    block.numerics = fmt::format("{{h_over_dx: {}, courant: 0.5}}", h);
    Simulation simulation(block.description());
    EXPECT_FALSE(simulation.step().operators().compact_stencils) << h;
    EXPECT_EQ(filter_of(simulation).fields(), HourglassFields::All) << h;
    EXPECT_LE(spectral_radius(simulation), 1.0 + 1e-9) << "h/dx " << h;
  }
}

TEST(RkTaylorStep, VelocityOnlyFilterIsTheDefaultOnCompactStencilsAndRejectedOnWideOnes) {
  Simulation compact(stability_block(0.5, true).description());
  EXPECT_TRUE(compact.step().operators().compact_stencils);
  EXPECT_EQ(filter_of(compact).fields(), HourglassFields::Velocity);
  test::ElasticBlock block = stability_block(0.5, true);
  block.numerics = "{h_over_dx: 1.3, courant: 0.5, hourglass: {fields: velocity}}";
  try {
    Simulation wide(block.description());
    ADD_FAILURE() << "velocity-only filter accepted at h = 1.3 dx";
  } catch (const InputError& error) {
    EXPECT_EQ(error.key(), "numerics.hourglass.fields");
    EXPECT_NE(error.allowed().find("all"), std::string::npos) << error.what();
    EXPECT_NE(error.problem().find("1.3"), std::string::npos) << error.what();
  }
}

TEST(RkTaylorStep, ANodeInNoCellIsReportedWithItsPosition) {
  // The apex of a triangle one cell high touches no cell: nothing can move it.
  test::ElasticBlock block = stability_block(0.5, true);
  block.shapes =
      "[{polygon: [[0, 0], [12, 0], [12, 5], [7, 5], [6, 6], [5, 5], [0, 5]], "
      "material: soil}]";
  try {
    Simulation simulation(block.description());
    ADD_FAILURE() << "a node in no cell was accepted";
  } catch (const RunError& error) {
    EXPECT_NE(std::string(error.what()).find("(6, 6)"), std::string::npos) << error.what();
  }
}

TEST(RkTaylorStepSlow, SpectralRadiusExceedsOneBeyondTheCourantLimit) {
  // Sanity of the test above: the same tool must see the instability at C = 1.1 (limit 1.0),
  // which a case may no longer ask for, so the step is probed with dt = 1.1 / 0.5 of C = 0.5's.
  Simulation simulation(stability_block(0.5, false).description());
  EXPECT_GT(spectral_radius(simulation, 2.2 * simulation.time_step()), 1.01);
}

// Rollers (mirror planes) on every side: no incomplete node, a checkerboard stays exact.
Simulation box(bool filter, const std::string& fields) {
  test::ElasticBlock block;
  block.shapes = test::ElasticBlock::rectangle(12.0, 8.0);
  block.conditions = {"{group: xmin, roller: x}", "{group: xmax, roller: x}",
                      "{group: ymin, roller: y}", "{group: ymax, roller: y}"};
  block.numerics =
      fmt::format("{{courant: 0.5, hourglass: {{enabled: {}, kappa: 0.1, fields: {}}}}}",
                  filter ? "true" : "false", fields);
  return Simulation(block.description());
}

double checkerboard_sign(const NodeSets& nodes, std::size_t i) {
  const auto index = test::lattice_index(nodes, i);
  return (index[0] + index[1]) % 2 ? -1.0 : 1.0;
}

// Sets field to amplitude * (-1)^(i+j) and runs `steps` steps.
void run_from_checkerboard(Simulation& simulation, int field, double amplitude, int steps) {
  State& state = simulation.state();
  for (std::size_t i = 0; i < simulation.nodes().sph_nodes.size(); ++i)
    state.fields(field, i) = checkerboard_sign(simulation.nodes(), i) * amplitude;
  for (int s = 0; s < steps; ++s)
    simulation.step().advance(state, simulation.time_step());
}

double checkerboard_amplitude(const Simulation& simulation, int field) {
  const NodeSets& nodes = simulation.nodes();
  double projection = 0.0;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i)
    projection += checkerboard_sign(nodes, i) * simulation.state().fields(field, i);
  return projection / static_cast<double>(nodes.sph_nodes.size());
}

TEST(RkTaylorStep, StressCheckerboardIsNeutralUnlessTheFilterActsOnEveryField) {
  // With cell-centre stress points the checkerboard is invisible to both operators (amplification
  // exactly 1); the filter on every field removes it as (1 - kappa)^n (docs/theory.md eq. 3.1).
  for (const auto& [filter, fields, decays] :
       {std::tuple{false, "all", false}, {true, "velocity", false}, {true, "all", true}}) {
    Simulation simulation = box(filter, fields);
    const int sigma_xx = simulation.model().stress_field(0, 0);
    const int steps = 20;
    run_from_checkerboard(simulation, sigma_xx, 1000.0, steps);
    const double ratio = checkerboard_amplitude(simulation, sigma_xx) / 1000.0;
    EXPECT_NEAR(ratio, decays ? std::pow(0.9, steps) : 1.0, 1e-9)
        << "filter " << filter << " on " << fields;
  }
}

TEST(RkTaylorStep, StressCheckerboardExertsNoForceThroughFreeFacesAndCorners) {
  // Free top and sides, fixed base: the momentum closure of the incomplete nodes is the adjoint of
  // the stress points' gradient (docs/theory.md eq. 5.2), so a stress checkerboard, which no stress
  // point sees, moves nothing even where the faces cut it. Visible, 1 kPa would give ~6 mm/s.
  test::ElasticBlock block = stability_block(0.5, true);
  block.conditions = {"{group: ymin, fixed: true}"};
  Simulation simulation(block.description());
  run_from_checkerboard(simulation, simulation.model().stress_field(0, 0), 1000.0, 20);
  const State& state = simulation.state();
  double speed = 0.0;
  for (std::size_t i = 0; i < simulation.nodes().sph_nodes.size(); ++i)
    for (int a = 0; a < 2; ++a)
      speed = std::max(speed, std::abs(state.fields(simulation.model().velocity_field(a), i)));
  EXPECT_LT(speed, 1e-12);
}

TEST(RkTaylorStep, FilterRemovesTheVelocityCheckerboardAndKeepsTheStressWhenAskedTo) {
  // The filter alone on a free block: far from the faces (beyond the reach of the two round
  // trips) a checkerboard is scaled by exactly 1 - kappa, on the fields the filter acts on only.
  for (const std::string fields : {"velocity", "all"}) {
    test::ElasticBlock block;
    block.shapes = test::ElasticBlock::rectangle(24.0, 24.0);
    block.numerics = "{hourglass: {kappa: 0.25, fields: " + fields + "}}";
    Simulation simulation(block.description());
    const NodeSets& nodes = simulation.nodes();
    FieldArray& values = simulation.state().fields;
    const int v_x = simulation.model().velocity_field(0);
    const int sigma_xy = simulation.model().stress_field(0, 1);
    for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
      values(v_x, i) = checkerboard_sign(nodes, i) * 0.01;
      values(sigma_xy, i) = checkerboard_sign(nodes, i) * 1000.0;
    }
    filter_of(simulation).filter(FilteredPart::All, values);
    int checked = 0;
    for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
      const double x = nodes.sph_nodes.position[0][i], y = nodes.sph_nodes.position[1][i];
      if (std::min({x, y, 24.0 - x, 24.0 - y}) < 9.0) continue;
      ++checked;
      const double sign = checkerboard_sign(nodes, i);
      EXPECT_NEAR(values(v_x, i), 0.75 * sign * 0.01, 1e-14);
      EXPECT_NEAR(values(sigma_xy, i), (fields == "all" ? 0.75 : 1.0) * sign * 1000.0, 1e-9)
          << fields;
    }
    EXPECT_GT(checked, 0);
  }
}

}  // namespace
}  // namespace rktsph::rk_taylor_step_test
