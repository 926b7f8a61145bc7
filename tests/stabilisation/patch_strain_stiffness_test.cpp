// The patch strain stiffness of triangle meshes (docs/theory.md §3.4, eqs. 3.12-3.13):
// - the patch fit leaves every field linear in space alone, at the surface, on uneven patches and
//   on a mirror plane (even and odd fields), and its residual is the gradient of the patch energy
//   (a finite-difference check), which makes the control conservative;
// - on a damped triangle block under a load with a kink, the static state exists and its surface
//   settlement has a smaller node-to-node part with the control than without;
// - the step on triangles stays stable (spectral radius <= 1 + 1e-8) up to beta = 1 at every
//   allowed Courant number;
// - the case refuses it together with the strain hourglass stiffness;
// - its stress at each stress point follows that point's factor, and the factors follow the flow
//   around a triangle as eq. 3.10's do around a lattice cell (eq. 3.14).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "../support/elastic_block.hpp"
#include "../support/step_matrix.hpp"
#include "rktsph/boundary/boundary_conditions.hpp"
#include "rktsph/core/error.hpp"
#include "rktsph/simulation/simulation.hpp"
#include "rktsph/stabilisation/flow_strength.hpp"
#include "rktsph/stabilisation/patch_fit.hpp"
#include "rktsph/stabilisation/strain_stiffness_control.hpp"
#include "rktsph/validation/rest_checks.hpp"

namespace rktsph::patch_strain_stiffness_test {
namespace {

const Parity kStrainParity[] = {tensor_parity(0, 0), tensor_parity(1, 1), tensor_parity(0, 1)};

// A 6 m x 4 m triangle block with x = 0 a mirror plane (roller), spacing `spacing`.
test::ElasticBlock triangle_block(double spacing) {
  test::ElasticBlock block;
  block.cells = "triangles";
  block.spacing = spacing;
  block.shapes = "[{polygon: [[0, 0], [6.3, 0], [5.1, 4.2], [0, 4.2]], material: soil}]";
  block.conditions = {"{group: xmin, roller: x}", "{group: ymin, fixed: true}"};
  return block;
}

TEST(PatchFit, LeavesEveryFieldLinearInSpaceAloneOnAMirroredTriangleMesh) {
  const Simulation simulation(triangle_block(0.7).description());
  const NodeSets& nodes = simulation.nodes();
  const auto mirror = simulation.boundary_conditions().mirror_axes();
  ASSERT_TRUE(std::any_of(mirror.begin(), mirror.end(), [](std::uint8_t m) { return m != 0; }));
  const PatchFit fit(nodes.cells, nodes.sph_nodes, nodes.stress_points, mirror, kStrainParity);
  const std::size_t points = nodes.stress_points.size();
  FieldArray values(3, points), residual(3, points);
  // Even across x = 0: any linear function of y, and none of x (its image would break it). Odd:
  // proportional to x, so that it vanishes on the plane.
  for (std::size_t p = 0; p < points; ++p) {
    const double x = nodes.stress_points.position[0][p], y = nodes.stress_points.position[1][p];
    values(0, p) = 2.0 - 0.7 * y;
    values(1, p) = -1.5 + 0.3 * y;
    values(2, p) = 0.9 * x;
  }
  fit.residual(values, residual);
  for (int f = 0; f < 3; ++f)
    for (std::size_t p = 0; p < points; ++p)
      EXPECT_NEAR(residual(f, p), 0.0, 1e-12) << "field " << f << " point " << p;
  // A field with an x-slope is linear too away from the plane; the mirror makes it a kink there,
  // which the cells beside the plane must see.
  for (std::size_t p = 0; p < points; ++p)
    values(0, p) = 1.0 + 0.5 * nodes.stress_points.position[0][p];
  fit.residual(values, residual);
  // Only a cell with a corner on the plane sees that corner's fit of the mirrored patch.
  double beside = 0.0, away = 0.0;
  for (std::size_t p = 0; p < points; ++p) {
    const auto corners = nodes.cells.corners(p);
    const bool touches_plane = std::any_of(corners.begin(), corners.end(), [&](std::int32_t n) {
      return mirror[static_cast<std::size_t>(n)] != 0;
    });
    double& largest = touches_plane ? beside : away;
    largest = std::max(largest, std::abs(residual(0, p)));
  }
  EXPECT_GT(beside, 1e-3);
  EXPECT_LT(away, 1e-12);
}

TEST(PatchFit, ResidualIsTheGradientOfThePatchEnergy) {
  const Simulation simulation(triangle_block(0.9).description());
  const NodeSets& nodes = simulation.nodes();
  const auto mirror = simulation.boundary_conditions().mirror_axes();
  const PatchFit fit(nodes.cells, nodes.sph_nodes, nodes.stress_points, mirror, kStrainParity);
  const std::size_t points = nodes.stress_points.size();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  FieldArray values(3, points), residual(3, points);
  for (double& v : values.data())
    v = uniform(random);
  // E = (1/2) sum_P V_P s_P . rho_P for a projection's residual (rho = (I - Pi) s, E = (1/2)
  // |rho|^2 in the patch weights); its derivative along s_P is V_P rho_P (eq. 3.13).
  auto energy = [&](const FieldArray& s) {
    FieldArray r(3, points);
    fit.residual(s, r);
    double e = 0.0;
    for (int f = 0; f < 3; ++f)
      for (std::size_t p = 0; p < points; ++p)
        e += 0.5 * nodes.stress_points.volume[p] * s(f, p) * r(f, p);
    return e;
  };
  fit.residual(values, residual);
  const double h = 1e-6;
  for (std::size_t p : {std::size_t{0}, points / 3, points / 2, points - 1})
    for (int f = 0; f < 3; ++f) {
      FieldArray plus = values, minus = values;
      plus(f, p) += h;
      minus(f, p) -= h;
      const double derivative = (energy(plus) - energy(minus)) / (2.0 * h);
      EXPECT_NEAR(derivative, nodes.stress_points.volume[p] * residual(f, p),
                  1e-6 * std::max(1.0, std::abs(derivative)))
          << "point " << p << " field " << f;
    }
}

// The block of triangle_block on a rough base, with a traction on part of its top that stops at
// a node inside the top edge: a kink the nodal strain average's soft modes answer (theory §4.8).
test::ElasticBlock kinked_triangle_block(double beta, double damping, double spacing = 1.0,
                                         double courant = 0.5) {
  test::ElasticBlock block = triangle_block(spacing);
  block.shapes = "[{polygon: [[0, 0], [7, 0], [7, 4], [3, 4], [0, 4]], material: soil}]";
  block.conditions.push_back("{group: load, traction: {y: -10000.0}}");
  block.groups = "{load: {box: {min: [0, 4], max: [3, 4]}}}";
  block.numerics =
      fmt::format("{{courant: {}, hourglass: {{patch_stiffness: {}}}}}", courant, beta);
  if (damping > 0.0) block.loads = fmt::format("{{damping: {{coefficient: {}}}}}", damping);
  return block;
}

// The damped block run to rest (the load is applied at once; damping 20/s against a lowest mode
// of about 10/s): the odd-even ratio of its top's settlement over 0 <= x <= 7 m, and the largest
// speed left over the largest seen.
double settlement_oddeven_at_rest(double beta, double* speed_left) {
  Simulation simulation(kinked_triangle_block(beta, 20.0, 0.5).description());
  State& state = simulation.state();
  double peak = 0.0, last = 0.0;
  for (int step = 0; step < 3000; ++step) {
    simulation.step().advance(state, simulation.time_step());
    last = 0.0;
    for (int a = 0; a < 2; ++a)
      for (std::size_t i = 0; i < state.fields.point_count(); ++i)
        last = std::max(last, std::abs(state.fields(simulation.model().velocity_field(a), i)));
    peak = std::max(peak, last);
  }
  *speed_left = last / peak;
  const NodeLine top = surface_settlement(simulation, 4.0, 0.0, 7.0);
  double largest = 0.0;
  for (double s : top.value)
    largest = std::max(largest, std::abs(s));
  return oddeven_residual_along(top, true) / largest;
}

TEST(PatchStrainStiffnessSlow, KeepsTheStaticStateOfAKinkedLoadSmoothOnTriangles) {
  double speed_off = 0.0, speed_on = 0.0;
  const double off = settlement_oddeven_at_rest(0.0, &speed_off);
  const double on = settlement_oddeven_at_rest(0.05, &speed_on);
  EXPECT_LT(speed_off, 1e-4);
  EXPECT_LT(speed_on, 1e-4);
  // Measured: 0.23 without, 0.089 with (dx = 0.5 m).
  EXPECT_LT(on, 0.5 * off) << "odd-even ratio without the control " << off << ", with " << on;
}

TEST(PatchStrainStiffnessSlow, StepOnTrianglesStaysStableUpToBetaOneAtEveryCourantNumber) {
  // Measured: radius - 1 <= 6e-11 at C = 0.5, 0.9 and 1 for beta = 0, 0.03, 0.1 and 1.
  for (double courant : {0.5, 1.0})
    for (double beta : {0.03, 1.0}) {
      Simulation simulation(kinked_triangle_block(beta, 0.0, 1.0, courant).description());
      const double r = test::largest_eigenvalue_modulus(test::affine_step(simulation, 1.0).matrix);
      EXPECT_LE(r, 1.0 + 1e-8) << "C " << courant << " beta " << beta
                               << fmt::format(" radius - 1 = {:.3e}", r - 1.0);
    }
}

TEST(PatchStrainStiffness, IsRefusedTogetherWithTheStrainHourglassStiffness) {
  test::ElasticBlock block = triangle_block(1.0);
  block.numerics = "{hourglass: {strain_stiffness: 0.1}}";
  try {
    const Simulation simulation(block.description());
    ADD_FAILURE() << "strain_stiffness with the triangles' default patch stiffness was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("patch_stiffness"), std::string::npos) << error.what();
  }
  block.numerics = "{hourglass: {strain_stiffness: 0.1, patch_stiffness: 0}}";
  EXPECT_NO_THROW(Simulation{block.description()});
}

// Eq. 3.14: the patch form's stress at each stress point is scaled by its factor, so that a cell
// at factor 0 (flowing, psi = 0) gets none and one at factor 1 exactly what it got before.
TEST(PatchStrainStiffness, ScalesEachStressPointsStressByItsFactor) {
  Simulation simulation(triangle_block(1.0).description());
  const RkTaylorStep& step = simulation.step();
  const StrainStiffnessControl* strain = step.control<StrainStiffnessControl>();
  ASSERT_NE(strain, nullptr);
  const StrainHourglassStiffness& control = strain->stiffness();
  ASSERT_TRUE(control.active());
  const PhysicsModel& model = simulation.model();
  const NodeSets& nodes = simulation.nodes();
  const std::size_t n = nodes.sph_nodes.size(), points = nodes.stress_points.size();
  std::mt19937 random(3);
  std::uniform_real_distribution<double> uniform(-1e-3, 1e-3);
  FieldArray displacement(2, n);
  for (double& u : displacement.data())
    u = uniform(random);
  const FieldArray& fields = simulation.state().fields;
  const auto stress_of = [&](std::span<const double> factor) {
    StrainHourglassStiffness copy = control;  // its scratch is mutable state
    FieldArray values(model.field_count(), points + n);
    copy.add_stress(model, step.operators().nodes_to_points, nodes.cells.materials(), displacement,
                    simulation.state().strain, FieldArray(4, points), 1e-3, fields, factor, values);
    return values;
  };
  std::vector<double> factor(points);
  for (std::size_t p = 0; p < points; ++p)
    factor[p] = static_cast<double>(p % 3) * 0.5;  // 0, 0.5, 1
  const FieldArray full = stress_of({}), scaled = stress_of(factor);
  double largest = 0.0;
  for (int k = 0; k < 3; ++k) {
    const int f = model.stress_field(k == 2 ? 0 : k, k == 2 ? 1 : k);
    for (std::size_t p = 0; p < points; ++p) {
      largest = std::max(largest, std::abs(full(f, p)));
      EXPECT_EQ(scaled(f, p), factor[p] * full(f, p)) << "point " << p << " component " << k;
    }
  }
  EXPECT_GT(largest, 0.0) << "the random displacement gave no patch stress to scale";
}

// Eq. 3.14 takes eq. 3.10's rule on triangles: psi r in a flowing cell, r in the cells within
// kFlowNeighbourhood rings of it (cells sharing a node, by a breadth-first walk here), 1 elsewhere;
// a cell that has flowed counts as flow for its neighbours but keeps r itself.
TEST(PatchStrainStiffness, StrengthFollowsTheFlowAroundATriangle) {
  const Simulation simulation(triangle_block(0.8).description());
  const CellComplex& cells = simulation.nodes().cells;
  const std::size_t count = cells.cell_count();
  const std::size_t centre = count / 2;
  // Ring of every cell around `centre` by a breadth-first walk over node-sharing cells.
  std::vector<int> ring(count, -1);
  ring[centre] = 0;
  std::vector<std::size_t> frontier{centre};
  for (int step = 1; step <= kFlowNeighbourhood; ++step) {
    std::vector<std::size_t> next;
    for (const std::size_t cell : frontier)
      for (const std::int32_t node : cells.corners(cell))
        for (const std::int32_t other : cells.cells_of(static_cast<std::size_t>(node)))
          if (ring[static_cast<std::size_t>(other)] < 0) {
            ring[static_cast<std::size_t>(other)] = step;
            next.push_back(static_cast<std::size_t>(other));
          }
    frontier = std::move(next);
  }
  ASSERT_GT(std::count(ring.begin(), ring.end(), kFlowNeighbourhood), 0);
  ASSERT_GT(std::count(ring.begin(), ring.end(), -1), 0) << "the mesh is too small for the test";
  const double ratio = 0.05, psi = 0.3;
  const std::vector<double> near_flow(count, ratio);
  std::vector<std::uint8_t> near_node(cells.node_count(), 0);
  std::vector<double> factor(count, -1.0);
  for (const std::uint8_t state : {std::uint8_t{1}, std::uint8_t{2}}) {  // flows, has flowed
    std::vector<std::uint8_t> flowing(count, 0);
    flowing[centre] = state;
    flow_strength_factors(cells, near_flow, flowing, psi, near_node, factor);
    for (std::size_t p = 0; p < count; ++p) {
      const double expected = p == centre && state == 1 ? psi * ratio : ring[p] >= 0 ? ratio : 1.0;
      EXPECT_DOUBLE_EQ(factor[p], expected) << "cell " << p << " ring " << ring[p];
    }
  }
}

// The block of triangle_block in a Perzyna Von Mises soil held on every side, under a shear stress
// 100 times its yield stress and a little gravity: every stress point flows from the first step
// on, for the whole short run (the fluidity is low enough that the overstress barely relaxes).
Simulation flowing_triangle_block(double beta, double plastic_fraction) {
  test::ElasticBlock block = triangle_block(0.8);
  block.conditions = {"{group: xmin, fixed: true}", "{group: xmax, fixed: true}",
                      "{group: ymin, fixed: true}", "{group: ymax, fixed: true}"};
  block.loads = "{gravity: {acceleration: [0, -0.1]}}";
  block.numerics = fmt::format("{{hourglass: {{patch_stiffness: {}, plastic_fraction: {}}}}}", beta,
                               plastic_fraction);
  std::string text = block.text();
  const std::string elastic = "model: linear_elastic,";
  text.replace(text.find(elastic), elastic.size(),
               "model: perzyna_von_mises, yield_stress: 100.0, hardening_modulus: 0.0, "
               "fluidity: 1.0e-6, exponent: 1.0,");
  text += "initial_conditions: {stress: {xy: 10000.0}}\n";
  return Simulation(read_case_text(text, "block.yaml"));
}

std::vector<double> displacement_after(Simulation simulation, int steps) {
  State& state = simulation.state();
  for (int step = 0; step < steps; ++step)
    simulation.step().advance(state, simulation.time_step());
  return state.displacement.data();
}

// Eq. 3.14 in the step: with psi = 0 a flowing cell gets none of the patch stress, so a body that
// flows everywhere moves as without the control, bit for bit; with psi = 1 it keeps r beta D and
// moves otherwise (which shows that the control had something to act on).
TEST(PatchStrainStiffness, LeavesABodyThatFlowsEverywhereAsWithoutIt) {
  const int steps = 40;
  const std::vector<double> without = displacement_after(flowing_triangle_block(0.0, 0.0), steps);
  const std::vector<double> with = displacement_after(flowing_triangle_block(0.03, 0.0), steps);
  const std::vector<double> stiff = displacement_after(flowing_triangle_block(0.03, 1.0), steps);
  ASSERT_EQ(with.size(), without.size());
  double largest = 0.0, moved = 0.0;
  for (std::size_t i = 0; i < with.size(); ++i) {
    EXPECT_EQ(with[i], without[i]) << "entry " << i;
    largest = std::max(largest, std::abs(without[i]));
    moved = std::max(moved, std::abs(stiff[i] - without[i]));
  }
  EXPECT_GT(largest, 0.0);
  EXPECT_GT(moved, 1e-9 * largest) << "the patch stress at psi = 1 changed nothing";
}

// On triangles the default control is the patch strain stiffness alone (no filter: its round
// trip assumes the lattice's checkerboard; no cell stiffness: it acts on quadrilaterals), and an
// elastic body's control does not follow flow nor carry a received strain.
TEST(PatchStrainStiffness, IsTheOnlyDefaultControlOnTriangles) {
  const Simulation simulation(triangle_block(0.7).description());
  const auto& controls = simulation.step().controls();
  ASSERT_EQ(controls.size(), 1u);
  EXPECT_EQ(controls.front()->name(), "strain hourglass stiffness");
  EXPECT_FALSE(controls.front()->follows_flow());
  EXPECT_FALSE(controls.front()->carries_received_strain());
  EXPECT_EQ(simulation.state().strain.point_count(), 0u);
}

}  // namespace
}  // namespace rktsph::patch_strain_stiffness_test
