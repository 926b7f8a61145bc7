// Applying the corrective SPH operators (docs/theory.md §4) on the small-deformation layout of
// docs/theory.md §3.1: SPH nodes on a square lattice, stress points at the cell centres.
// Times one apply_operator call (interpolation and gradient of five fields, the plane-strain
// unknowns v_x, v_y, sigma_xx, sigma_yy, sigma_xy) in each direction of the step: SPH nodes ->
// stress points (step 1) and stress points -> SPH nodes (step 2). The tables are built once,
// outside the timed loop; building them is timed by a separate benchmark.
#include <benchmark/benchmark.h>

#include <algorithm>

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rktsph/case/case_description.hpp"
#include "rktsph/core/field_array.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/sph/kernel.hpp"
#include "rktsph/sph/neighbour_search.hpp"
#include "rktsph/sph/operators.hpp"

namespace rktsph {
namespace {

constexpr int kFieldCount = 5;

// Mirror parities of the five fields (v_x, v_y, sigma_xx, sigma_yy, sigma_xy), so that the
// parity branch of apply_operator runs exactly as in the step when mirror planes are present.
constexpr std::array<Parity, kFieldCount> kParity = {vector_parity(0), vector_parity(1), kEven,
                                                     kEven, tensor_parity(0, 1)};

enum Direction : std::int64_t { kNodesToPoints = 0, kPointsToNodes = 1 };

/// SPH nodes filling the square [0, per_side - 1]^2 with unit spacing (per_side^2 nodes) and the
/// stress points at the centres of its cells. Unit spacing keeps every vertex a lattice point.
NodeSets square_node_sets(int per_side) {
  ShapeSpec square;
  square.kind = ShapeSpec::Kind::Rectangle;
  const double side = static_cast<double>(per_side - 1);
  square.vertices = {Vec3{0.0, 0.0, 0.0}, Vec3{side, side, 0.0}};
  square.material = "solid";
  GeometrySpec geometry;
  geometry.spacing = 1.0;
  geometry.shapes.push_back(square);
  return build_node_sets(geometry, 2, {"solid"});
}

/// Shepard operators with the cubic spline; with `mirrors`, symmetry planes on the bottom and top
/// faces as in BAR-WAVE-2D, so that the tables carry reflected entries.
OperatorOptions operator_options(const NodeSets& nodes, double h_over_dx, bool mirrors) {
  OperatorOptions options;
  options.kernel = Kernel(KernelType::CubicSpline, 2);
  options.smoothing_length = h_over_dx * nodes.spacing;
  if (mirrors) {
    const auto& y = nodes.sph_nodes.position[1];
    const double top = *std::max_element(y.begin(), y.end());
    options.mirrors = {MirrorPlane{1, 0.0}, MirrorPlane{1, top}};
  }
  return options;
}

WeightTable build_table(const NodeSets& nodes, const OperatorOptions& options,
                        Direction direction) {
  const double support = options.kernel.support_radius(options.smoothing_length);
  const PointCloud& targets = direction == kNodesToPoints ? nodes.stress_points : nodes.sph_nodes;
  const PointCloud& sources = direction == kNodesToPoints ? nodes.sph_nodes : nodes.stress_points;
  const CellList cells(sources, support);
  return build_cross_operator(targets, cells, options);
}

/// Smooth, non-zero, non-polynomial values (no denormals, nothing the compiler can fold).
FieldArray smooth_fields(const PointCloud& points) {
  FieldArray fields(kFieldCount, points.size());
  for (int f = 0; f < kFieldCount; ++f)
    for (std::size_t i = 0; i < points.size(); ++i)
      fields(f, i) = 1.0 + std::sin(0.01 * (f + 1) * points.position[0][i]) *
                               std::cos(0.013 * (f + 2) * points.position[1][i]);
  return fields;
}

/// Everything one (per_side, h, mirrors) configuration needs. Kept in a single slot so that the
/// repetitions of a configuration and its two directions reuse the tables, while only one
/// configuration (up to about 2 GB at 10^6 nodes and h = 1.3 dx) is held at a time.
struct OperatorSetup {
  std::array<std::int64_t, 3> key{};
  NodeSets nodes;
  std::array<WeightTable, 2> tables;  // indexed by Direction
  std::array<FieldArray, 2> inputs;   // source fields of each direction
  std::array<FieldArray, 2> values;
  std::array<FieldArray, 2> gradients;
};

OperatorSetup& setup_for(std::int64_t per_side, std::int64_t h_over_dx_percent,
                         std::int64_t mirrors) {
  static std::unique_ptr<OperatorSetup> cached;
  const std::array<std::int64_t, 3> key{per_side, h_over_dx_percent, mirrors};
  if (cached && cached->key == key) return *cached;
  cached.reset();  // free the previous configuration before building the next
  auto setup = std::make_unique<OperatorSetup>();
  setup->key = key;
  setup->nodes = square_node_sets(static_cast<int>(per_side));
  const OperatorOptions options =
      operator_options(setup->nodes, 0.01 * static_cast<double>(h_over_dx_percent), mirrors != 0);
  for (const Direction direction : {kNodesToPoints, kPointsToNodes}) {
    const PointCloud& targets =
        direction == kNodesToPoints ? setup->nodes.stress_points : setup->nodes.sph_nodes;
    const PointCloud& sources =
        direction == kNodesToPoints ? setup->nodes.sph_nodes : setup->nodes.stress_points;
    setup->tables[direction] = build_table(setup->nodes, options, direction);
    setup->inputs[direction] = smooth_fields(sources);
    setup->values[direction] = FieldArray(kFieldCount, targets.size());
    setup->gradients[direction] = FieldArray(kFieldCount * 2, targets.size());
  }
  cached = std::move(setup);
  return *cached;
}

/// Bytes apply_operator must move at least once per call: the whole table (all three gradient
/// arrays are read, also in 2D), the source fields and the outputs. A lower bound on memory
/// traffic, so bytes/s is comparable with the machine's stream bandwidth.
double compulsory_bytes(const WeightTable& table, const FieldArray& input) {
  // Source, reflection, interpolation and a gradient per axis of the table's dimension.
  const double per_entry = sizeof(std::int32_t) + (table.has_reflections ? 1.0 : 0.0) +
                           (1.0 + table.dimension) * sizeof(double);
  const double rows = static_cast<double>(table.rows());
  return static_cast<double>(table.entries()) * per_entry + (rows + 1.0) * sizeof(std::int64_t) +
         static_cast<double>(input.data().size()) * sizeof(double) +
         rows * kFieldCount * (1 + table.dimension) * sizeof(double);
}

/// range(0): SPH nodes per side; range(1): h / dx in hundredths; range(2): mirror planes on the
/// bottom and top faces (0/1); range(3): Direction.
void BM_ApplyOperator(benchmark::State& state) {
  OperatorSetup& setup = setup_for(state.range(0), state.range(1), state.range(2));
  const auto direction = static_cast<Direction>(state.range(3));
  const WeightTable& table = setup.tables[direction];
  const FieldArray& input = setup.inputs[direction];
  FieldArray& values = setup.values[direction];
  FieldArray& gradient = setup.gradients[direction];

  for (auto _ : state) {
    apply_operator(table, input, kParity, &values, &gradient);
    benchmark::ClobberMemory();
  }
  const auto rows = static_cast<std::int64_t>(table.rows());
  state.SetItemsProcessed(state.iterations() * rows);
  state.SetBytesProcessed(static_cast<std::int64_t>(static_cast<double>(state.iterations()) *
                                                    compulsory_bytes(table, input)));
  state.counters["rows"] = static_cast<double>(rows);
  state.counters["entries_per_row"] =
      static_cast<double>(table.entries()) / static_cast<double>(rows);
  state.SetLabel(direction == kNodesToPoints ? "S->V" : "V->S");
}

// 100^2 = 1e4, 316^2 ~ 1e5, 1000^2 = 1e6 SPH nodes; h = 0.75 dx (default) and 1.3 dx; without
// and with the two symmetry planes of BAR-WAVE-2D. Listed so that the direction varies fastest
// (ArgsProduct would vary the first argument fastest): both directions of a configuration then
// run back to back and share its tables.
void apply_operator_arguments(benchmark::internal::Benchmark* benchmark) {
  benchmark->ArgNames({"per_side", "h_over_dx_pct", "mirrors", "to_nodes"});
  for (const std::int64_t per_side : {100, 316, 1000})
    for (const std::int64_t h_over_dx_percent : {75, 130})
      for (const std::int64_t mirrors : {0, 1})
        for (const std::int64_t direction : {kNodesToPoints, kPointsToNodes})
          benchmark->Args({per_side, h_over_dx_percent, mirrors, direction});
}

BENCHMARK(BM_ApplyOperator)
    ->Apply(apply_operator_arguments)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// Building both tables of a configuration (cell lists included); serial code, so this is the
/// cost a large-deformation scheme, whose nodes move, would pay every step.
/// range(0): SPH nodes per side; range(1): h / dx in hundredths.
void BM_BuildOperatorTables(benchmark::State& state) {
  const NodeSets nodes = square_node_sets(static_cast<int>(state.range(0)));
  const OperatorOptions options =
      operator_options(nodes, 0.01 * static_cast<double>(state.range(1)), true);
  std::size_t entries = 0;
  for (auto _ : state) {
    const WeightTable to_points = build_table(nodes, options, kNodesToPoints);
    const WeightTable to_nodes = build_table(nodes, options, kPointsToNodes);
    entries = to_points.entries() + to_nodes.entries();
    benchmark::DoNotOptimize(to_points.source.data());
    benchmark::DoNotOptimize(to_nodes.source.data());
  }
  const auto rows = static_cast<std::int64_t>(nodes.sph_nodes.size() + nodes.stress_points.size());
  state.SetItemsProcessed(state.iterations() * rows);
  state.counters["rows"] = static_cast<double>(rows);
  state.counters["entries_per_row"] = static_cast<double>(entries) / static_cast<double>(rows);
}

BENCHMARK(BM_BuildOperatorTables)
    ->ArgsProduct({{100, 316, 1000}, {75, 130}})
    ->ArgNames({"per_side", "h_over_dx_pct"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace rktsph
