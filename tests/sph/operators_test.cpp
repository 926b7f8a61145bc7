// Corrective SPH operators: constants and linear fields must be reproduced exactly wherever the
// stencil is regular (docs/theory.md §4.2), with and without mirror images; degenerate stencils
// must be reported, not divided by zero.
#include "rktsph/sph/operators.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>

#include "../support/lattices.hpp"
#include "rktsph/geometry/node_sets.hpp"

namespace rktsph::operators_test {
namespace {

using test::bar_lattice;
using test::rectangle_lattice;

// Linear field f = c0 + k . x.
struct LinearField {
  double c0;
  std::array<double, 3> k;
  double operator()(const std::array<double, 3>& x) const {
    return c0 + k[0] * x[0] + k[1] * x[1] + k[2] * x[2];
  }
};

FieldArray sample(const PointCloud& points, const std::vector<LinearField>& fields) {
  FieldArray values(static_cast<int>(fields.size()), points.size());
  for (std::size_t f = 0; f < fields.size(); ++f)
    for (std::size_t i = 0; i < points.size(); ++i)
      values(static_cast<int>(f), i) = fields[f](points.point(i));
  return values;
}

OperatorOptions options_for(int dimension, double h, int order = 0) {
  OperatorOptions options;
  options.kernel = Kernel(KernelType::CubicSpline, dimension);
  options.smoothing_length = h;
  options.interpolation_order = order;
  return options;
}

// Checks interpolation (if requested) and gradient of linear fields on the rows not listed as
// degenerate. Tolerance: 1e-12 relative to the field's scale (values and gradients are O(1-10),
// so round-off of a 4-30 term sum is ~1e-14).
void expect_linear_exact(const WeightTable& table, const PointCloud& sources,
                         const PointCloud& targets, const StencilReport& report,
                         bool check_interpolation) {
  const int d = targets.dimension;
  const std::vector<LinearField> fields = {
      {2.0, {3.0, -5.0, 0.0}}, {-1.5, {0.25, 4.0, 0.0}}, {7.0, {0.0, 0.0, 0.0}}};
  const FieldArray in = sample(sources, fields);
  FieldArray values(3, targets.size()), gradient(3 * d, targets.size());
  const std::vector<Parity> parity(3, kEven);
  apply_operator(table, in, parity, &values, &gradient);
  std::vector<char> degenerate(targets.size(), 0);
  for (auto r : report.degenerate_rows)
    degenerate[static_cast<std::size_t>(r)] = 1;
  std::size_t checked = 0;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (degenerate[i]) continue;
    ++checked;
    for (int f = 0; f < 3; ++f) {
      const double scale = 10.0;
      if (check_interpolation) {
        EXPECT_NEAR(values(f, i), fields[f](targets.point(i)), 1e-12 * scale) << "row " << i;
      }
      for (int c = 0; c < d; ++c)
        EXPECT_NEAR(gradient(f * d + c, i), fields[f].k[c], 1e-12 * scale)
            << "row " << i << " field " << f << " axis " << c;
    }
  }
  EXPECT_GT(checked, 0u);
}

TEST(CrossOperator, ConstantsInterpolatedExactlyEverywhere) {
  const NodeSets nodes = rectangle_lattice(1.0, 0.5, 0.05);
  for (double eta : {0.75, 1.3}) {
    const OperatorOptions options = options_for(2, eta * 0.05);
    const CellList node_cells(nodes.sph_nodes,
                              options.kernel.support_radius(options.smoothing_length));
    const CellList point_cells(nodes.stress_points,
                               options.kernel.support_radius(options.smoothing_length));
    for (const auto& [table, targets, sources] :
         {std::tuple{build_cross_operator(nodes.stress_points, node_cells, options),
                     &nodes.stress_points, &nodes.sph_nodes},
          std::tuple{build_cross_operator(nodes.sph_nodes, point_cells, options), &nodes.sph_nodes,
                     &nodes.stress_points}}) {
      FieldArray in(1, sources->size());
      std::fill(in.data().begin(), in.data().end(), 4.25);
      FieldArray out(1, targets->size());
      const Parity even[] = {kEven};
      apply_operator(table, in, even, &out, nullptr);
      for (std::size_t i = 0; i < targets->size(); ++i)
        EXPECT_NEAR(out(0, i), 4.25, 1e-13);
    }
  }
}

TEST(CrossOperator, LinearGradientExactFromNodesToStressPoints2D) {
  const NodeSets nodes = rectangle_lattice(1.0, 0.5, 0.05);
  for (double eta : {0.75, 1.3}) {
    const OperatorOptions options = options_for(2, eta * 0.05);
    const CellList cells(nodes.sph_nodes, options.kernel.support_radius(options.smoothing_length));
    StencilReport report;
    const WeightTable table = build_cross_operator(nodes.stress_points, cells, options, &report);
    EXPECT_TRUE(report.degenerate_rows.empty()) << "eta " << eta;
    expect_linear_exact(table, nodes.sph_nodes, nodes.stress_points, report, false);
  }
}

TEST(CrossOperator, StressPointsToNodesExactWhereRegularAndEdgesReportedAtCompactSupport) {
  const NodeSets nodes = rectangle_lattice(1.0, 0.5, 0.05);
  // h = 0.75 dx: an edge node sees one row of stress points, so its centroid-referenced stencil is
  // rank one and must be reported; every interior node is regular.
  {
    const OperatorOptions options = options_for(2, 0.75 * 0.05);
    const CellList cells(nodes.stress_points,
                         options.kernel.support_radius(options.smoothing_length));
    StencilReport report;
    const WeightTable table = build_cross_operator(nodes.sph_nodes, cells, options, &report);
    const std::size_t perimeter = 2 * (21 + 11) - 4;
    EXPECT_EQ(report.degenerate_rows.size(), perimeter);
    expect_linear_exact(table, nodes.stress_points, nodes.sph_nodes, report, false);
    for (double w : table.gradient[0])
      EXPECT_TRUE(std::isfinite(w));
  }
  // h = 1.3 dx: every node, corners included, has a regular stencil and an exact gradient.
  {
    const OperatorOptions options = options_for(2, 1.3 * 0.05);
    const CellList cells(nodes.stress_points,
                         options.kernel.support_radius(options.smoothing_length));
    StencilReport report;
    const WeightTable table = build_cross_operator(nodes.sph_nodes, cells, options, &report);
    EXPECT_TRUE(report.degenerate_rows.empty());
    expect_linear_exact(table, nodes.stress_points, nodes.sph_nodes, report, false);
  }
}

TEST(CrossOperator, FirstOrderInterpolationExactForLinearFieldsAtBoundaries) {
  const NodeSets nodes = rectangle_lattice(1.0, 0.5, 0.05);
  const OperatorOptions options = options_for(2, 1.3 * 0.05, 1);
  const CellList cells(nodes.stress_points,
                       options.kernel.support_radius(options.smoothing_length));
  StencilReport report;
  const WeightTable table = build_cross_operator(nodes.sph_nodes, cells, options, &report);
  EXPECT_TRUE(report.degenerate_rows.empty());
  expect_linear_exact(table, nodes.stress_points, nodes.sph_nodes, report, true);

  // Shepard alone is not first order at an edge: this is what order 1 fixes.
  const OperatorOptions shepard = options_for(2, 1.3 * 0.05, 0);
  const WeightTable zeroth = build_cross_operator(nodes.sph_nodes, cells, shepard);
  const FieldArray in = sample(nodes.stress_points, {{0.0, {1.0, 0.0, 0.0}}});
  FieldArray out(1, nodes.sph_nodes.size());
  const Parity even[] = {kEven};
  apply_operator(zeroth, in, even, &out, nullptr);
  EXPECT_GT(std::abs(out(0, 0) - nodes.sph_nodes.position[0][0]), 1e-3);
}

TEST(CrossOperator, OneDimensionalBarAtCompactSupport) {
  const NodeSets nodes = bar_lattice(10.0, 0.5);
  const OperatorOptions options = options_for(1, 0.75 * 0.5);
  const double support = options.kernel.support_radius(options.smoothing_length);
  const CellList node_cells(nodes.sph_nodes, support);
  const CellList point_cells(nodes.stress_points, support);
  StencilReport to_points, to_nodes;
  const WeightTable forward =
      build_cross_operator(nodes.stress_points, node_cells, options, &to_points);
  const WeightTable backward =
      build_cross_operator(nodes.sph_nodes, point_cells, options, &to_nodes);
  EXPECT_TRUE(to_points.degenerate_rows.empty());
  // Only the two end nodes (one stress point each) are degenerate.
  EXPECT_EQ(to_nodes.degenerate_rows, (std::vector<std::int32_t>{0, 20}));
  expect_linear_exact(forward, nodes.sph_nodes, nodes.stress_points, to_points, true);
  expect_linear_exact(backward, nodes.stress_points, nodes.sph_nodes, to_nodes, true);
  // Two-point stencils at a midpoint: the gradient is the central difference (f_R - f_L)/dx.
  EXPECT_EQ(forward.row_start[1] - forward.row_start[0], 2);
}

TEST(SelfReferencedStencil, BoundaryNodesWithOwnValueAreExactInOneAndTwoDimensions) {
  // Step-2 stencil of a boundary node: neighbouring stress points plus the node's own half-step
  // value (column n_stress + i), docs/theory.md §2.2. Exact for linear fields at ends, edges and —
  // with the neighbouring boundary nodes added (docs/theory.md §4.2) — corners.
  for (int dimension : {1, 2}) {
    const NodeSets nodes =
        dimension == 1 ? bar_lattice(10.0, 0.5) : rectangle_lattice(1.0, 0.5, 0.05);
    const double dx = nodes.spacing;
    const OperatorOptions options = options_for(dimension, 0.75 * dx);
    const double support = options.kernel.support_radius(options.smoothing_length);
    const CellList point_cells(nodes.stress_points, support);
    const CellList node_cells(nodes.sph_nodes, support);
    const auto n_points = static_cast<std::int32_t>(nodes.stress_points.size());

    WeightTable table;
    table.dimension = dimension;
    table.row_start.push_back(0);
    std::vector<StencilSource> stencil, extra;
    int degenerate_before_augmenting = 0;
    for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
      const auto x = nodes.sph_nodes.point(i);
      gather_stencil(x, point_cells, options, -1, stencil);
      WeightTable probe = table;
      if (!append_row(probe, x, stencil, options, GradientReference::Self,
                      n_points + static_cast<std::int32_t>(i))) {
        ++degenerate_before_augmenting;
        gather_stencil(x, node_cells, options, static_cast<std::int32_t>(i), extra);
        for (StencilSource s : extra) {
          s.column += n_points;
          stencil.push_back(s);
        }
      }
      ASSERT_TRUE(append_row(table, x, stencil, options, GradientReference::Self,
                             n_points + static_cast<std::int32_t>(i)))
          << "node " << i;
    }
    EXPECT_EQ(degenerate_before_augmenting, dimension == 1 ? 0 : 4);  // the four corners

    // Combined source set: stress points, then SPH nodes.
    PointCloud combined = nodes.stress_points;
    for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i)
      combined.push_back(nodes.sph_nodes.point(i), nodes.sph_nodes.volume[i]);
    expect_linear_exact(table, combined, nodes.sph_nodes, StencilReport{}, true);
  }
}

TEST(CollocatedGradient, ExactForLinearFieldsOnEveryNode) {
  const NodeSets nodes = rectangle_lattice(1.0, 0.5, 0.05);
  const OperatorOptions options = options_for(2, 0.75 * 0.05);
  const CellList cells(nodes.sph_nodes, options.kernel.support_radius(options.smoothing_length));
  StencilReport report;
  const WeightTable table = build_collocated_gradient(nodes.sph_nodes, cells, options, {}, &report);
  EXPECT_TRUE(report.degenerate_rows.empty());
  expect_linear_exact(table, nodes.sph_nodes, nodes.sph_nodes, report, true);
}

TEST(CrossOperator, PerturbedLatticeStaysExactForLinearFields) {
  NodeSets nodes = rectangle_lattice(1.0, 0.5, 0.05);
  std::mt19937 generator(12345);
  std::uniform_real_distribution<double> jitter(-0.1 * 0.05, 0.1 * 0.05);
  for (PointCloud* cloud : {&nodes.sph_nodes, &nodes.stress_points})
    for (int a = 0; a < 2; ++a)
      for (double& x : cloud->position[a])
        x += jitter(generator);
  for (double eta : {1.0, 1.3}) {
    const OperatorOptions options = options_for(2, eta * 0.05, 1);
    const double support = options.kernel.support_radius(options.smoothing_length);
    const CellList node_cells(nodes.sph_nodes, support);
    const CellList point_cells(nodes.stress_points, support);
    StencilReport forward_report, backward_report;
    const WeightTable forward =
        build_cross_operator(nodes.stress_points, node_cells, options, &forward_report);
    const WeightTable backward =
        build_cross_operator(nodes.sph_nodes, point_cells, options, &backward_report);
    EXPECT_TRUE(forward_report.degenerate_rows.empty());
    EXPECT_TRUE(backward_report.degenerate_rows.empty());
    expect_linear_exact(forward, nodes.sph_nodes, nodes.stress_points, forward_report, true);
    expect_linear_exact(backward, nodes.stress_points, nodes.sph_nodes, backward_report, true);
  }
}

TEST(MirrorImages, NodesOnASymmetryPlaneGetFullStencilsWithParity) {
  // Mirror plane y = 0 (bottom face). Even fields are functions of x (plus even functions of y);
  // odd fields vanish on the plane. Their gradients must be exact on and near the plane.
  const NodeSets nodes = rectangle_lattice(1.0, 0.5, 0.05);
  OperatorOptions options = options_for(2, 0.75 * 0.05);
  options.mirrors = {MirrorPlane{1, 0.0}};
  const CellList cells(nodes.stress_points,
                       options.kernel.support_radius(options.smoothing_length));
  StencilReport report;
  const WeightTable table = build_cross_operator(nodes.sph_nodes, cells, options, &report);
  EXPECT_TRUE(table.has_reflections);

  // Bottom-edge nodes (not the two bottom corners, which still miss a side) are now regular.
  for (auto row : report.degenerate_rows)
    EXPECT_GT(std::abs(nodes.sph_nodes.position[1][row]) +
                  (nodes.sph_nodes.position[0][row] < 1e-9 ||
                   nodes.sph_nodes.position[0][row] > 1.0 - 1e-9),
              1e-9)
        << "bottom-edge node " << row << " still degenerate";

  const std::vector<LinearField> fields = {{2.0, {3.0, 0.0, 0.0}}, {0.0, {0.0, -4.0, 0.0}}};
  const std::vector<Parity> parity = {kEven, vector_parity(1)};  // e.g. v_x and v_y
  const FieldArray in = sample(nodes.stress_points, fields);
  FieldArray values(2, nodes.sph_nodes.size()), gradient(4, nodes.sph_nodes.size());
  apply_operator(table, in, parity, &values, &gradient);
  std::vector<char> degenerate(nodes.sph_nodes.size(), 0);
  for (auto r : report.degenerate_rows)
    degenerate[static_cast<std::size_t>(r)] = 1;
  int checked_on_plane = 0;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    if (degenerate[i]) continue;
    if (std::abs(nodes.sph_nodes.position[1][i]) < 1e-9) ++checked_on_plane;
    for (int f = 0; f < 2; ++f)
      for (int c = 0; c < 2; ++c)
        EXPECT_NEAR(gradient(f * 2 + c, i), fields[f].k[c], 1e-11) << "node " << i;
    EXPECT_NEAR(values(1, i), fields[1](nodes.sph_nodes.point(i)), 1e-12);  // odd: 0 on the plane
  }
  EXPECT_EQ(checked_on_plane, 21 - 2);
}

// The filter's tables (first order at h = 1.3 dx, with a mirror plane so that reflected rows are
// exercised): sharing the weights of equal stencils and applying them to node-major values must
// give apply_operator's interpolation to 1e-12 of the O(1) field (rows that share take the first
// row's weights, equal to 1e-13 of the largest weight: ~20 terms of |f| <= 1 give <= 1e-12 with
// the reordered sum), and the interior rows must collapse onto a few stencils.
TEST(SharedWeights, InterleavedApplyMatchesApplyOperatorAndInteriorRowsShareOneStencil) {
  const NodeSets nodes = rectangle_lattice(1.0, 0.5, 0.05);
  OperatorOptions options = options_for(2, 1.3 * 0.05, 1);
  options.mirrors = {MirrorPlane{1, 0.0}};
  const CellList cells(nodes.stress_points,
                       options.kernel.support_radius(options.smoothing_length));
  WeightTable table = build_cross_operator(nodes.sph_nodes, cells, options);
  ASSERT_TRUE(table.has_reflections);
  drop_gradients(table);
  WeightTable shared = table;
  share_row_weights(shared);
  ASSERT_EQ(shared.weight_start.size(), table.rows());
  EXPECT_LT(shared.interpolation.size() * 4, table.interpolation.size());
  EXPECT_EQ(shared.reflection.size(), shared.interpolation.size());
  // Re-sharing is a no-op.
  const std::size_t pool = shared.interpolation.size();
  share_row_weights(shared);
  EXPECT_EQ(shared.interpolation.size(), pool);

  // Two fields with opposite parity under the y-mirror: one even, one odd in y.
  std::mt19937 generator(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const std::size_t sources = nodes.stress_points.size(), targets = nodes.sph_nodes.size();
  FieldArray in(2, sources);
  std::vector<double> interleaved(2 * sources);
  for (std::size_t j = 0; j < sources; ++j)
    for (int f = 0; f < 2; ++f) {
      in(f, j) = uniform(generator);
      interleaved[2 * j + static_cast<std::size_t>(f)] = in(f, j);
    }
  const Parity parity[] = {kEven, vector_parity(1)};
  FieldArray expected(2, targets);
  apply_operator(table, in, parity, &expected, nullptr);
  std::vector<double> out(2 * targets);
  apply_interpolation_interleaved(shared, interleaved, parity, out);
  std::size_t reflected_rows = 0;
  for (std::size_t i = 0; i < targets; ++i) {
    reflected_rows += shared.row_reflects[i];
    for (int f = 0; f < 2; ++f)
      EXPECT_NEAR(out[2 * i + static_cast<std::size_t>(f)], expected(f, i), 1e-12) << i;
  }
  EXPECT_GT(reflected_rows, 0u);
  EXPECT_LT(reflected_rows, targets);
  // The unshared table through the interleaved path gives the same sums, term by term.
  apply_interpolation_interleaved(table, interleaved, parity, out);
  for (std::size_t i = 0; i < targets; ++i)
    for (int f = 0; f < 2; ++f)
      EXPECT_EQ(out[2 * i + static_cast<std::size_t>(f)], expected(f, i)) << i;
}

// The step's tables share their gradient weights too (docs/theory.md §4.7): applied to fields of
// both parities under a mirror plane, the shared table must give the unshared one's values to
// 1e-12 and gradients to 1e-10 (weights equal to 1e-13 of the row's largest, |grad w| ~ 1/dx = 20,
// ~20 terms), and its pools must be a small part of its entries.
TEST(SharedWeights, GradientTablesShareAndApplyAsTheUnsharedOnes) {
  const NodeSets nodes = rectangle_lattice(1.0, 0.5, 0.05);
  OperatorOptions options = options_for(2, 1.3 * 0.05, 1);
  options.mirrors = {MirrorPlane{1, 0.0}};
  const CellList cells(nodes.stress_points,
                       options.kernel.support_radius(options.smoothing_length));
  const WeightTable table = build_cross_operator(nodes.sph_nodes, cells, options);
  WeightTable shared = table;
  share_row_weights(shared);
  ASSERT_TRUE(shared.has_gradient);
  ASSERT_EQ(shared.weight_start.size(), table.rows());
  EXPECT_LT(shared.interpolation.size() * 4, shared.source.size());
  for (int a = 0; a < 2; ++a)
    EXPECT_EQ(shared.gradient[static_cast<std::size_t>(a)].size(), shared.interpolation.size());
  std::mt19937 generator(5);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  FieldArray in(2, nodes.stress_points.size());
  for (double& value : in.data())
    value = uniform(generator);
  const Parity parity[] = {kEven, vector_parity(1)};
  const std::size_t targets = nodes.sph_nodes.size();
  FieldArray values(2, targets), gradient(4, targets), shared_values(2, targets),
      shared_gradient(4, targets);
  apply_operator(table, in, parity, &values, &gradient);
  apply_operator(shared, in, parity, &shared_values, &shared_gradient);
  for (std::size_t i = 0; i < targets; ++i) {
    for (int f = 0; f < 2; ++f)
      EXPECT_NEAR(shared_values(f, i), values(f, i), 1e-12) << i;
    for (int g = 0; g < 4; ++g)
      EXPECT_NEAR(shared_gradient(g, i), gradient(g, i), 1e-10) << i;
  }
}

// The filter's tables built and shared a chunk of rows at a time, with relative sources
// (docs/theory.md §4.7), must hold the table built whole and then shared entry for entry (column,
// weight, reflection bits), whatever the chunk size: chunks of 1, of 37 rows (a boundary inside
// the lattice's rows) and one chunk of everything, which must also agree array for array.
TEST(SharedWeights, ChunkedBuildWithRelativeSourcesHoldsTheWholeTableShared) {
  const NodeSets nodes = rectangle_lattice(1.0, 0.5, 0.05);
  OperatorOptions options = options_for(2, 1.3 * 0.05, 1);
  options.mirrors = {MirrorPlane{1, 0.0}};
  const CellList cells(nodes.stress_points,
                       options.kernel.support_radius(options.smoothing_length));
  WeightTable whole = build_cross_operator(nodes.sph_nodes, cells, options);
  drop_gradients(whole);
  share_row_weights(whole);
  const std::size_t rows = nodes.sph_nodes.size();
  WeightTable single;
  for (std::size_t chunk : {rows, std::size_t{1}, std::size_t{37}}) {
    WeightTable chunked;
    OperatorWorkspace workspace;
    ShareWorkspace share;
    build_shared_cross_operator(nodes.sph_nodes, cells, options, chunked, workspace, share, chunk);
    ASSERT_EQ(chunked.row_start, whole.row_start) << chunk;
    EXPECT_TRUE(chunked.source.empty());
    ASSERT_EQ(chunked.row_base.size(), rows);
    EXPECT_EQ(chunked.row_reflects, whole.row_reflects) << chunk;
    EXPECT_EQ(chunked.has_reflections, whole.has_reflections) << chunk;
    EXPECT_FALSE(chunked.has_gradient);
    std::size_t differences = 0;
    for (std::size_t r = 0; r < rows; ++r)
      for (auto k = static_cast<std::size_t>(whole.row_start[r]);
           k < static_cast<std::size_t>(whole.row_start[r + 1]); ++k) {
        const auto mine =
            static_cast<std::size_t>(static_cast<std::int64_t>(k) + chunked.weight_offset(r));
        const auto theirs =
            static_cast<std::size_t>(static_cast<std::int64_t>(k) + whole.weight_offset(r));
        differences += chunked.source_of(r, k) != whole.source_of(r, k) ||
                       chunked.interpolation[mine] != whole.interpolation[theirs] ||
                       chunked.reflection[mine] != whole.reflection[theirs];
      }
    EXPECT_EQ(differences, 0u) << chunk;
    // A lattice's rows collapse onto a few blocks: the pools are a small part of the entries.
    EXPECT_LT(chunked.interpolation.size() * 4, chunked.entries()) << chunk;
    EXPECT_EQ(chunked.source_offset.size(), chunked.interpolation.size());
    if (chunk == rows) {
      single = chunked;
      // Applied to node-major values of both parities, the two give the same sums term by term.
      std::mt19937 generator(7);
      std::uniform_real_distribution<double> uniform(-1.0, 1.0);
      std::vector<double> in(2 * nodes.stress_points.size());
      for (double& value : in)
        value = uniform(generator);
      const Parity parity[] = {kEven, vector_parity(1)};
      std::vector<double> expected(2 * rows), out(2 * rows);
      apply_interpolation_interleaved(whole, in, parity, expected);
      apply_interpolation_interleaved(chunked, in, parity, out);
      EXPECT_EQ(out, expected);
    } else {
      EXPECT_EQ(chunked.row_base, single.row_base) << chunk;
      EXPECT_EQ(chunked.weight_start, single.weight_start) << chunk;
      EXPECT_EQ(chunked.source_offset, single.source_offset) << chunk;
      EXPECT_EQ(chunked.interpolation, single.interpolation) << chunk;
    }
  }
}

TEST(Degeneracy, EmptyAndSingleSourceStencilsAreReportedWithFiniteWeights) {
  WeightTable table;
  table.dimension = 2;
  table.row_start.push_back(0);
  const OperatorOptions options = options_for(2, 0.75);
  EXPECT_FALSE(
      append_row(table, {0.0, 0.0, 0.0}, {}, options, GradientReference::ShepardCentroid, -1));
  const StencilSource single{0, 0, {0.5, 0.5, 0.0}, 1.0};
  EXPECT_FALSE(append_row(table, {0.0, 0.0, 0.0}, std::span(&single, 1), options,
                          GradientReference::ShepardCentroid, -1));
  EXPECT_FALSE(append_row(table, {0.0, 0.0, 0.0}, std::span(&single, 1), options,
                          GradientReference::Self, 1));
  for (int a = 0; a < 3; ++a)
    for (double w : table.gradient[a])
      EXPECT_TRUE(std::isfinite(w));
  for (double w : table.interpolation)
    EXPECT_TRUE(std::isfinite(w));
}

// A neighbour list with a skin (docs/theory.md §9.5): candidates found within the support plus a
// skin on one configuration, picked at the support on another where every point has moved less
// than half the skin, give exactly the stencil of a fresh search in the cell lists there (the
// same sources, images, positions and volumes; the order may differ), on a lattice with mirror
// planes on two axes (so with images of images) and with the target left out of its own stencil.
TEST(StencilCandidates, PickTheStencilOfAFreshSearchWhilePointsMoveLessThanHalfTheSkin) {
  const NodeSets lattice = rectangle_lattice(3.0, 2.0, 0.25);
  OperatorOptions options = options_for(2, 1.3 * 0.25, 1);
  options.mirrors = {MirrorPlane{0, 0.0}, MirrorPlane{1, 0.0}};
  const double support = options.kernel.support_radius(options.smoothing_length);
  const double skin = 0.1;
  const PointCloud searched = lattice.sph_nodes;
  const CellList searched_cells(searched, support + skin);
  std::vector<std::vector<StencilCandidate>> candidates(searched.size());
  for (std::size_t i = 0; i < searched.size(); ++i)
    gather_candidates(searched.point(i), searched_cells, options, static_cast<std::int32_t>(i),
                      support + skin, candidates[i]);

  // Every point moved by less than skin / 2, in a random direction; the points on a mirror plane
  // stay on it, as the roller that makes the plane holds them.
  PointCloud moved = searched;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (std::size_t i = 0; i < moved.size(); ++i)
    for (std::size_t a = 0; a < 2; ++a)
      if (moved.position[a][i] > 1e-12) moved.position[a][i] += 0.49 * skin * unit(random) / 1.5;
  const CellList fresh_cells(moved, support);
  const auto key = [](const StencilSource& s) {
    return std::make_tuple(s.column, s.reflection, s.position[0], s.position[1], s.volume);
  };
  std::size_t compared = 0, with_images = 0;
  std::vector<StencilSource> picked, fresh;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    gather_stencil(moved.point(i), moved, candidates[i], options, picked);
    gather_stencil(moved.point(i), fresh_cells, options, static_cast<std::int32_t>(i), fresh);
    std::vector<decltype(key(picked[0]))> a, b;
    for (const StencilSource& s : picked)
      a.push_back(key(s));
    for (const StencilSource& s : fresh)
      b.push_back(key(s));
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b) << "point " << i;
    compared += b.size();
    with_images += std::count_if(fresh.begin(), fresh.end(),
                                 [](const StencilSource& s) { return s.reflection == 3; }) > 0;
  }
  EXPECT_GT(compared, 10 * moved.size());
  EXPECT_GT(with_images, 0u) << "some stencils must hold images across both planes";
}

// build_rows computes each thread's rows into a block of its own and copies the blocks into the
// table: the table must be the serial one whatever the thread count, also when one workspace is
// reused across thread counts and sizes (blocks left over from more threads, blocks that grow).
TEST(TableBuild, TablesDoNotDependOnThreadCountOrOnTheWorkspacesEarlierBuilds) {
  const OperatorOptions options = options_for(2, 0.75 * 0.02, 1);
  const NodeSets small = rectangle_lattice(1.0, 1.0, 0.02);  // 2 601 nodes: below the threshold
  const NodeSets large = rectangle_lattice(2.0, 1.5, 0.02);  // 7 676 nodes, 7 500 points
  const auto build = [&](const NodeSets& lattice, int threads, OperatorWorkspace& workspace) {
    const int saved = omp_get_max_threads();
    omp_set_num_threads(threads);
    WeightTable table;
    build_cross_operator(lattice.stress_points,
                         CellList(lattice.sph_nodes, options.kernel.support_radius(0.015)), options,
                         table, workspace);
    omp_set_num_threads(saved);
    return table;
  };
  OperatorWorkspace fresh;
  const WeightTable serial = build(large, 1, fresh);
  ASSERT_GT(serial.rows(), static_cast<std::size_t>(kParallelThreshold));
  OperatorWorkspace reused;
  for (const int threads : {4, 3, 1, 2}) {
    build(small, threads, reused);  // the blocks of a smaller build first
    const WeightTable table = build(large, threads, reused);
    EXPECT_EQ(table.row_start, serial.row_start) << threads << " threads";
    EXPECT_EQ(table.source, serial.source) << threads << " threads";
    EXPECT_EQ(table.reflection, serial.reflection) << threads << " threads";
    EXPECT_EQ(table.interpolation, serial.interpolation) << threads << " threads";
    for (std::size_t a = 0; a < 3; ++a)
      EXPECT_EQ(table.gradient[a], serial.gradient[a]) << threads << " threads, axis " << a;
    EXPECT_EQ(table.has_reflections, serial.has_reflections);
  }
}

}  // namespace
}  // namespace rktsph::operators_test
