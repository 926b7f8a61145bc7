// Cells formed from a node cloud (docs/theory.md §3.9): the Delaunay triangulation of the nodes
// where they are and its alpha trim, as the re-formed configuration of issue 29 would run it
// every step or when a cell's quality falls. The cloud is a square lattice whose nodes are moved
// by up to 0.2 dx (a fixed pseudo-random pattern), as a body that has flowed a little; alpha = 1.
// Compare the time per node with BM_MovingBarWaveStep's time per particle-step.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "rktsph/mesh/delaunay_cells.hpp"
#include "square_lattice.hpp"

namespace rktsph {
namespace {

// A deterministic value in [-1, 1) from an index (a 64-bit mix, splitmix64's finaliser).
double jitter(std::uint64_t index) {
  std::uint64_t z = index + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30U)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27U)) * 0x94d049bb133111ebULL;
  z ^= z >> 31U;
  return static_cast<double>(z >> 11U) * 0x1.0p-52 - 1.0;
}

/// range(0): nodes per side (100, 316, 635: 1e4, 1e5 and BAR-WAVE-2D L's 4e5).
void BM_DelaunayCells(benchmark::State& state) {
  const int per_side = static_cast<int>(state.range(0));
  const double spacing = 1.0 / (per_side - 1);
  PointCloud cloud = bench::square_lattice(per_side, spacing, 0.0);
  for (std::size_t n = 0; n < cloud.size(); ++n)
    for (std::size_t a = 0; a < 2; ++a)
      cloud.position[a][n] += 0.2 * spacing * jitter(2 * n + a);
  const std::vector<double> spacings(cloud.size(), spacing);
  const std::vector<std::int32_t> material(cloud.size(), 0);
  std::size_t cells = 0;
  for (auto _ : state) {
    const DelaunayCells formed = delaunay_cells(cloud, spacings, material, 1.0);
    cells = formed.cells.cell_count();
    benchmark::DoNotOptimize(cells);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(cloud.size()));
  state.counters["nodes"] = static_cast<double>(cloud.size());
  state.counters["cells"] = static_cast<double>(cells);
}

BENCHMARK(BM_DelaunayCells)
    ->Arg(100)
    ->Arg(316)
    ->Arg(635)
    ->ArgName("per_side")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace rktsph
