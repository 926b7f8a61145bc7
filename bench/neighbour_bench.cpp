// Neighbour search on the small-deformation layout (docs/theory.md §3.1): SPH nodes on a square
// lattice of spacing dx, stress points at the cell centres. Times building the SPH-node ->
// stress-point table (targets: nodes, sources: stress points), cell list included, as done once
// per step in a large-deformation scheme, whose nodes move.
#include <benchmark/benchmark.h>

#include <cstdint>

#include "rktsph/core/point_cloud.hpp"
#include "rktsph/sph/neighbour_search.hpp"
#include "square_lattice.hpp"

namespace rktsph {
namespace {

/// range(0): SPH nodes per side; range(1): h / dx in hundredths. Support radius 2h (cubic spline).
void BM_NodeToStressPointTable(benchmark::State& state) {
  const int per_side = static_cast<int>(state.range(0));
  const double spacing = 1.0 / (per_side - 1);
  const double smoothing_length = 0.01 * static_cast<double>(state.range(1)) * spacing;
  const double radius = 2.0 * smoothing_length;
  const PointCloud nodes = bench::square_lattice(per_side, spacing, 0.0);
  const PointCloud stress_points = bench::square_lattice(per_side - 1, spacing, 0.5 * spacing);

  std::size_t pairs = 0;
  for (auto _ : state) {
    const CellList cells(stress_points, radius);
    const NeighbourTable table = find_neighbours(nodes, cells, radius, false);
    pairs = table.total();
    benchmark::DoNotOptimize(table.neighbour.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(nodes.size()));
  state.counters["nodes"] = static_cast<double>(nodes.size());
  state.counters["neighbours_per_node"] =
      static_cast<double>(pairs) / static_cast<double>(nodes.size());
}

// 100^2 = 1e4, 316^2 ~ 1e5, 1000^2 = 1e6 nodes; h = 0.75 dx (default) and 1.3 dx.
BENCHMARK(BM_NodeToStressPointTable)
    ->ArgsProduct({{100, 316, 1000}, {75, 130}})
    ->ArgNames({"per_side", "h_over_dx_pct"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace rktsph
