// Free-surface detection (boundary/free_surface_detection.hpp) on a square block of SPH nodes, as
// the large-deformation run does once per step: the timed loop is detect_free_surface alone, on a
// cell list built outside it (the step builds one for its neighbour tables anyway).
#include <benchmark/benchmark.h>

#include <cstdint>

#include "rktsph/boundary/free_surface_detection.hpp"
#include "rktsph/core/point_cloud.hpp"
#include "rktsph/sph/neighbour_search.hpp"
#include "square_lattice.hpp"

namespace rktsph {
namespace {

/// `per_side` x `per_side` nodes; h = 1.3 dx, cubic spline.
void BM_FreeSurfaceDetection(benchmark::State& state, int per_side) {
  const double spacing = 0.01;
  const PointCloud nodes = bench::square_lattice(per_side, spacing, 0.0);
  FreeSurfaceOptions options;
  options.smoothing_length = 1.3 * spacing;
  options.lattice_spacing = spacing;
  const CellList cells(nodes, 2.0 * options.smoothing_length);
  FreeSurface surface;
  for (auto _ : state) {
    detect_free_surface(nodes, cells, options, surface);
    benchmark::DoNotOptimize(surface.on_surface.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(nodes.size()));
  state.counters["nodes"] = static_cast<double>(nodes.size());
  state.counters["candidates"] = static_cast<double>(surface.candidates);
}

// s, m, l: 100^2, 200^2 and 400^2 nodes.
BENCHMARK_CAPTURE(BM_FreeSurfaceDetection, s, 100)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_FreeSurfaceDetection, m, 200)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_FreeSurfaceDetection, l, 400)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace rktsph
