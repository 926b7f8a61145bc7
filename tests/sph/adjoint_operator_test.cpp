// The lumped adjoint of the stress points' operator (docs/theory.md eqs. 5.2, 5.3): the discrete
// power identity with the velocity gradient and the transpose identity of the interpolation, with
// and without mirror images; equality with the corrected SPH divergence at complete interior
// stencils (h = 0.75 dx); and, through the step, an exact static stress state under a face
// traction is a fixed point.
#include "rktsph/sph/adjoint_operator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "../support/elastic_block.hpp"
#include "../support/lattices.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::adjoint_operator_test {
namespace {

OperatorOptions options_for(double h, std::vector<MirrorPlane> mirrors) {
  OperatorOptions options;
  options.kernel = Kernel(KernelType::CubicSpline, 2);
  options.smoothing_length = h;
  options.mirrors = std::move(mirrors);
  return options;
}

FieldArray random_fields(int count, std::size_t points, std::mt19937& random) {
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  FieldArray fields(count, points);
  for (int f = 0; f < count; ++f)
    for (std::size_t i = 0; i < points; ++i)
      fields(f, i) = value(random);
  return fields;
}

// sum_P V_P sigma_P : grad v_P + sum_n V_n v_n . div sigma_n over a traction-free lattice.
double power_defect(double h, const std::vector<MirrorPlane>& mirrors, double* scale) {
  const NodeSets nodes = test::rectangle_lattice(6.0, 4.0, 1.0);
  const OperatorOptions options = options_for(h, mirrors);
  const CellList node_cells(nodes.sph_nodes, options.kernel.support_radius(h));
  const WeightTable forward = build_cross_operator(nodes.stress_points, node_cells, options);
  std::vector<std::int32_t> all(nodes.sph_nodes.size());
  for (std::size_t i = 0; i < all.size(); ++i)
    all[i] = static_cast<std::int32_t>(i);
  const std::vector<std::int32_t> no_own_value(all.size(), -1);
  const AdjointOperator adjoint =
      build_adjoint_operator(forward, nodes.stress_points.volume, all, no_own_value);
  EXPECT_EQ(adjoint.table.has_reflections, !mirrors.empty());

  std::mt19937 random(7);
  const FieldArray velocity = random_fields(2, nodes.sph_nodes.size(), random);
  const FieldArray stress = random_fields(3, nodes.stress_points.size(), random);  // xx, yy, xy
  const std::vector<Parity> velocity_parity{vector_parity(0), vector_parity(1)};
  const std::vector<Parity> stress_parity{tensor_parity(0, 0), tensor_parity(1, 1),
                                          tensor_parity(0, 1)};
  FieldArray velocity_gradient(4, nodes.stress_points.size());
  apply_operator(forward, velocity, velocity_parity, nullptr, &velocity_gradient);
  FieldArray divergence_terms(6, nodes.sph_nodes.size());
  const std::vector<std::uint8_t> all_fields(3, 1);
  apply_adjoint_gradient(adjoint, stress, stress_parity, all_fields, divergence_terms);

  double stress_power = 0.0, nodal_power = 0.0;
  *scale = 0.0;
  for (std::size_t p = 0; p < nodes.stress_points.size(); ++p) {
    const double term = stress(0, p) * velocity_gradient(0, p) +
                        stress(1, p) * velocity_gradient(3, p) +
                        stress(2, p) * (velocity_gradient(1, p) + velocity_gradient(2, p));
    stress_power += nodes.stress_points.volume[p] * term;
    *scale += nodes.stress_points.volume[p] * std::abs(term);
  }
  for (std::size_t r = 0; r < all.size(); ++r) {
    const double div_x = divergence_terms(0, r) + divergence_terms(5, r);  // xx,x + xy,y
    const double div_y = divergence_terms(4, r) + divergence_terms(3, r);  // xy,x + yy,y
    nodal_power += adjoint.lumped_volume[r] * (velocity(0, r) * div_x + velocity(1, r) * div_y);
  }
  // The interpolation's transpose: sum_P V_P q_P (I f)_P = sum_n V_n f_n (I^T q)_n, for the odd
  // field v_x and the even sigma_xx alike.
  FieldArray interpolated(2, nodes.stress_points.size());
  apply_operator(forward, velocity, velocity_parity, &interpolated, nullptr);
  FieldArray transposed(2, nodes.sph_nodes.size());
  const std::vector<std::uint8_t> both(2, 1);
  FieldArray point_values(2, nodes.stress_points.size());
  for (std::size_t p = 0; p < nodes.stress_points.size(); ++p)
    for (int f = 0; f < 2; ++f)
      point_values(f, p) = stress(f, p);
  add_adjoint_interpolation(adjoint, point_values, velocity_parity, both, transposed);
  for (int f = 0; f < 2; ++f) {
    double on_points = 0.0, on_nodes = 0.0, size = 0.0;
    for (std::size_t p = 0; p < nodes.stress_points.size(); ++p) {
      on_points += nodes.stress_points.volume[p] * point_values(f, p) * interpolated(f, p);
      size += nodes.stress_points.volume[p] * std::abs(point_values(f, p) * interpolated(f, p));
    }
    for (std::size_t r = 0; r < all.size(); ++r)
      on_nodes += adjoint.lumped_volume[r] * velocity(f, r) * transposed(f, r);
    EXPECT_NEAR(on_points, on_nodes, 1e-12 * size) << "field " << f;
  }
  return stress_power + nodal_power;
}

TEST(AdjointOperator, PowerIdentityHoldsOnAFreeLattice) {
  double scale = 0.0;
  const double defect = power_defect(0.75, {}, &scale);
  EXPECT_GT(scale, 1.0);
  EXPECT_NEAR(defect, 0.0, 1e-12 * scale);
}

TEST(AdjointOperator, PowerIdentityHoldsWithReflectedEntries) {
  // h = 1.0 dx reaches the images of the second column across x = 0 and y = 0.
  double scale = 0.0;
  const double defect = power_defect(1.0, {MirrorPlane{0, 0.0}, MirrorPlane{1, 0.0}}, &scale);
  EXPECT_GT(scale, 1.0);
  EXPECT_NEAR(defect, 0.0, 1e-12 * scale);
}

// A 4 x 3 m block at dx = 0.5 m: rollers on the sides, fixed base, 5 kPa pressing on the top.
std::string loaded_block() {
  test::ElasticBlock block;
  block.spacing = 0.5;
  block.shapes = test::ElasticBlock::rectangle(4.0, 3.0);
  block.conditions = {"{group: xmin, roller: x}", "{group: xmax, roller: x}",
                      "{group: ymin, fixed: true}", "{group: ymax, traction: {y: -5000.0}}"};
  block.numerics = "{hourglass: {enabled: false}}";
  return block.text();
}

TEST(AdjointOperator, EqualsTheCorrectedDivergenceAtCompleteStencils) {
  Simulation simulation(read_case_text(loaded_block(), "block.yaml"));
  const StepOperators& ops = simulation.step().operators();
  const NodeSets& nodes = simulation.nodes();
  const std::size_t nv = nodes.stress_points.size(), ns = nodes.sph_nodes.size();
  std::vector<std::int32_t> all(ns);
  for (std::size_t i = 0; i < ns; ++i)
    all[i] = static_cast<std::int32_t>(i);
  const AdjointOperator adjoint = build_adjoint_operator(
      ops.nodes_to_points, nodes.stress_points.volume, all, std::vector<std::int32_t>(ns, -1));
  std::mt19937 random(11);
  FieldArray values = random_fields(1, nv + ns, random);
  const std::vector<Parity> even{kEven};
  FieldArray corrected(2, ns), transposed(2, ns);
  apply_operator(ops.points_to_nodes, values, even, nullptr, &corrected);
  apply_adjoint_gradient(adjoint, values, even, std::vector<std::uint8_t>{1}, transposed);
  int interior = 0;
  for (std::size_t i = 0; i < ns; ++i) {
    if (ops.node_to_boundary_row[i] >= 0) continue;
    const double x = nodes.sph_nodes.position[0][i];
    if (x < 0.25 || x > 3.75) continue;  // the mirror planes' nodes see image stress points
    ++interior;
    for (int c = 0; c < 2; ++c)
      EXPECT_NEAR(transposed(c, i), corrected(c, i), 1e-12) << "node " << i << " axis " << c;
  }
  EXPECT_GT(interior, 10);
}

TEST(AdjointOperator, UniformStressUnderItsTractionIsAFixedPointOfTheStep) {
  // sigma_yy = -5 kPa everywhere balances the top traction exactly; sigma_xx = sigma_zz = K0
  // sigma_yy keeps the rollers and the fixed base free of strain. The closure must see the
  // traction through the node's own half-step value (docs/theory.md eq. 5.2).
  Simulation simulation(read_case_text(loaded_block(), "block.yaml"));
  State& state = simulation.state();
  const PhysicsModel& model = simulation.model();
  const double k0 = 0.3 / 0.7;
  for (std::size_t i = 0; i < simulation.nodes().sph_nodes.size(); ++i) {
    state.fields(model.stress_field(1, 1), i) = -5000.0;
    state.fields(model.stress_field(0, 0), i) = -5000.0 * k0;
    state.fields(model.stress_field(2, 2), i) = -5000.0 * k0;
  }
  for (int s = 0; s < 50; ++s)
    simulation.step().advance(state, simulation.time_step());
  for (std::size_t i = 0; i < simulation.nodes().sph_nodes.size(); ++i) {
    EXPECT_NEAR(state.fields(model.velocity_field(0), i), 0.0, 1e-12);
    EXPECT_NEAR(state.fields(model.velocity_field(1), i), 0.0, 1e-12);
    EXPECT_NEAR(state.fields(model.stress_field(1, 1), i), -5000.0, 1e-7);
  }
}

}  // namespace
}  // namespace rktsph::adjoint_operator_test

namespace rktsph::adjoint_operator_test {
namespace {

// Issue 30: a node no stress point reaches stopped a run with "node 1079 is in no forward row"; the
// builder now names the node (UnreachedNode) and the step says where it is, what happened and what
// to change, without the advice to refine that makes a fixed-cell flow fail sooner.
TEST(AdjointOperatorTest, ANodeNoStressPointReachesIsNamedWithItsPositionAndAdvice) {
  const NodeSets nodes = test::rectangle_lattice(3.0, 2.0, 1.0);
  const OperatorOptions options = options_for(0.75, {});
  const CellList node_cells(nodes.sph_nodes, options.kernel.support_radius(0.75));
  const WeightTable forward = build_cross_operator(nodes.stress_points, node_cells, options);
  // One node more than the lattice holds: no forward row reaches it.
  const auto lone = static_cast<std::int32_t>(nodes.sph_nodes.size());
  const std::vector<std::int32_t> targets{0, lone};
  const std::vector<std::int32_t> no_own_value(targets.size(), -1);
  try {
    build_adjoint_operator(forward, nodes.stress_points.volume, targets, no_own_value);
    FAIL() << "a node out of every row's reach was accepted";
  } catch (const UnreachedNode& unreached) {
    EXPECT_EQ(unreached.node(), lone);
  }
  const std::string message = describe_unreached_node(nodes.sph_nodes, 4);
  EXPECT_NE(message.find(describe_point(nodes.sph_nodes, 4)), std::string::npos) << message;
  EXPECT_NE(message.find("finer lattice fails sooner"), std::string::npos) << message;
  EXPECT_NE(message.find("time.end"), std::string::npos) << message;
  EXPECT_EQ(message.find("refine"), std::string::npos) << message;
}

}  // namespace
}  // namespace rktsph::adjoint_operator_test
