// The full RK-TSPH step (docs/theory.md §2.2) on BAR-WAVE-2D (docs/theory.md §8.11),
// sizes S, M, L, XL, read from cases/bar-wave-2d-<size>/case.yaml. Only
// `step().advance(state, dt)` is timed: no setup, no output, no probes. The step counts per
// measurement are the benchmark's timing protocol (200 / 100 / 50 / 50).
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"

#ifndef RKTSPH_SOURCE_DIR
#define RKTSPH_SOURCE_DIR "."
#endif

namespace rktsph {
namespace {

/// The case file of a bundled folder; RKTSPH_CASES_DIR (if set) replaces the source tree's cases/.
std::string bundled_case(const std::string& folder) {
  const char* override_dir = std::getenv("RKTSPH_CASES_DIR");
  const std::string cases_dir =
      override_dir ? std::string(override_dir) : std::string(RKTSPH_SOURCE_DIR) + "/cases";
  return cases_dir + "/" + folder + "/case.yaml";
}

/// The case file of one size of the bar.
std::string case_path(const std::string& size) {
  return bundled_case("bar-wave-2d-" + size);
}

/// One simulation at a time (XL holds about a gigabyte), reused across the repetitions of its
/// case so that setup is paid once. The state keeps advancing from one repetition to the next,
/// which does not change the cost of a linear elastic step.
Simulation& cached_simulation(const std::string& path, const std::vector<CaseOverride>& overrides) {
  static std::unique_ptr<Simulation> cached;
  static std::string cached_key;
  std::string key = path;
  for (const CaseOverride& change : overrides)
    key += " " + change.key + "=" + change.value;
  if (cached && cached_key == key) return *cached;
  cached.reset();
  cached = std::make_unique<Simulation>(read_case_file(path, overrides));
  cached_key = key;
  return *cached;
}

/// The bar of one size; `model` overrides the case's (the large-deformation model on the same
/// bar).
Simulation& simulation_for(const std::string& size, const std::string& model = "") {
  std::vector<CaseOverride> overrides;
  if (!model.empty()) overrides.push_back({"model", model});
  return cached_simulation(case_path(size), overrides);
}

bool all_finite(const FieldArray& fields) {
  for (const double value : fields.data())
    if (!std::isfinite(value)) return false;
  return true;
}

// The shares of the timed steps' wall time (docs/theory.md §9.5), in per cent: the cell lists of
// the neighbour search, the operator tables (stencils and weights), moving the configuration and
// its faces, and the rest of the step. The first two are zero on a fixed configuration.
void report_time_split(benchmark::State& bench_state, const StepTimeSplit& before,
                       const StepTimeSplit& after) {
  const double total = after.total() - before.total();
  if (!(total > 0.0)) return;
  auto share = [&](double StepTimeSplit::*part) {
    return 100.0 * (after.*part - before.*part) / total;
  };
  bench_state.counters["pct_cell_lists"] = share(&StepTimeSplit::cell_lists);
  bench_state.counters["pct_tables"] = share(&StepTimeSplit::operator_tables);
  bench_state.counters["pct_surface"] = share(&StepTimeSplit::surface);
  bench_state.counters["pct_integration"] = share(&StepTimeSplit::integration);
}

void step_benchmark(benchmark::State& bench_state,
                    const std::function<Simulation&()>& make_simulation) {
  Simulation* simulation = nullptr;
  try {
    simulation = &make_simulation();
  } catch (const std::exception& error) {
    bench_state.SkipWithError(error.what());
    return;
  }
  RkTaylorStep& step = simulation->step();
  State& state = simulation->state();
  const double dt = simulation->time_step();

  const StepTimeSplit before = step.time_split();
  const long searches_before = step.neighbour_searches();
  for (auto _ : bench_state) {
    step.advance(state, dt);
    benchmark::ClobberMemory();
  }
  report_time_split(bench_state, before, step.time_split());
  // Moving configurations: how many of the timed steps searched the stencils again and rebuilt
  // the filter (docs/theory.md §9.5).
  bench_state.counters["neighbour_searches"] =
      static_cast<double>(step.neighbour_searches() - searches_before);

  if (!all_finite(state.fields)) {
    bench_state.SkipWithError("the state became non-finite");
    return;
  }
  const auto nodes = static_cast<std::int64_t>(simulation->nodes().sph_nodes.size());
  bench_state.SetItemsProcessed(bench_state.iterations() * nodes);  // particle-steps
  bench_state.counters["nodes"] = static_cast<double>(nodes);
  bench_state.counters["threads"] = static_cast<double>(omp_get_max_threads());
  bench_state.counters["dt_us"] = dt * 1e6;
}

void BM_BarWaveStep(benchmark::State& bench_state, const std::string& size) {
  step_benchmark(bench_state, [&]() -> Simulation& { return simulation_for(size); });
}

/// BAR-WAVE-2D on a triangle mesh (cases/triangles-bar-wave-2d, docs/theory.md §8.11): size S as
/// the case gives it, L at the lattice's L spacing (edges at most 1.25 mm). The same step on
/// cells of another shape: about 2.5 times the lattice's nodes at one dx, and per-row tables.
void BM_TriangleBarWaveStep(benchmark::State& bench_state, const std::string& spacing) {
  step_benchmark(bench_state, [&]() -> Simulation& {
    std::vector<CaseOverride> overrides;
    if (!spacing.empty()) overrides.push_back({"geometry.spacing", spacing});
    return cached_simulation(bundled_case("triangles-bar-wave-2d"), overrides);
  });
}

/// The same bar with the large-deformation model (docs/theory.md §9): the nodes move, and every
/// step rebuilds its operators and turns its faces on the new configuration.
void BM_MovingBarWaveStep(benchmark::State& bench_state, const std::string& size) {
  step_benchmark(bench_state,
                 [&]() -> Simulation& { return simulation_for(size, "dry_large_deformation"); });
}

/// The same moving bar on cells formed again from its nodes (numerics.cells.policy: reformed,
/// docs/theory.md §9.17): the loop's step (Simulation::take_step), which forms the cells again
/// where one has distorted and takes a step in parts where a formed cell is narrower than the one
/// that set dt. Its Delaunay triangles are twice the lattice's squares, and dt is that of their
/// width dx/sqrt 2: per unit of simulated time about 2.8 times the stress-point steps.
void BM_ReformedBarWaveStep(benchmark::State& bench_state, const std::string& size) {
  Simulation* simulation = nullptr;
  try {
    simulation = &cached_simulation(case_path(size), {{"model", "dry_large_deformation"},
                                                      {"numerics.cells.policy", "reformed"}});
  } catch (const std::exception& error) {
    bench_state.SkipWithError(error.what());
    return;
  }
  const long formings_before = simulation->assembly().cell_forming().formings;
  for (auto _ : bench_state) {
    simulation->take_step();
    benchmark::ClobberMemory();
  }
  if (!all_finite(simulation->state().fields)) {
    bench_state.SkipWithError("the state became non-finite");
    return;
  }
  const auto nodes = static_cast<std::int64_t>(simulation->nodes().sph_nodes.size());
  bench_state.SetItemsProcessed(bench_state.iterations() * nodes);  // particle-steps
  bench_state.counters["nodes"] = static_cast<double>(nodes);
  bench_state.counters["stress_points"] =
      static_cast<double>(simulation->cells().stress_points.size());
  bench_state.counters["formings"] =
      static_cast<double>(simulation->assembly().cell_forming().formings - formings_before);
  bench_state.counters["threads"] = static_cast<double>(omp_get_max_threads());
  bench_state.counters["dt_us"] = simulation->time_step() * 1e6;
}

/// The first steps of the collapsing low-cohesion block (cases/ld-slope-low-cohesion,
/// docs/theory.md §9.14) at `spacing`: a viscoplastic body flowing under gravity, with its rigid
/// base found again after every move.
void BM_LowCohesionSlopeStep(benchmark::State& bench_state, const std::string& spacing) {
  step_benchmark(bench_state, [&]() -> Simulation& {
    return cached_simulation(bundled_case("ld-slope-low-cohesion"),
                             {{"geometry.spacing", spacing}, {"output.interval", "0"}});
  });
}

BENCHMARK_CAPTURE(BM_BarWaveStep, s, std::string("s"))
    ->Iterations(200)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_BarWaveStep, m, std::string("m"))
    ->Iterations(100)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_BarWaveStep, l, std::string("l"))
    ->Iterations(50)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_BarWaveStep, xl, std::string("xl"))
    ->Iterations(50)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The timing protocol's step counts of S and L (200, 50).
BENCHMARK_CAPTURE(BM_TriangleBarWaveStep, s, std::string())
    ->Iterations(200)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_TriangleBarWaveStep, l, std::string("0.00125"))
    ->Iterations(50)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_CAPTURE(BM_MovingBarWaveStep, s, std::string("s"))
    ->Iterations(20)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_MovingBarWaveStep, m, std::string("m"))
    ->Iterations(10)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_MovingBarWaveStep, l, std::string("l"))
    ->Iterations(5)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_CAPTURE(BM_ReformedBarWaveStep, s, std::string("s"))
    ->Iterations(20)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_ReformedBarWaveStep, l, std::string("l"))
    ->Iterations(5)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// 10,201 and 40,401 nodes (dx = 0.1 m and 0.05 m on the 10 m block).
BENCHMARK_CAPTURE(BM_LowCohesionSlopeStep, s, std::string("0.1"))
    ->Iterations(20)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_LowCohesionSlopeStep, m, std::string("0.05"))
    ->Iterations(10)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// One rebuild of every operator table of the step on the unchanged configuration, and what the
/// step derives from them (docs/theory.md §2.6): the cost a large-deformation step pays each step.
void BM_StepOperatorRebuild(benchmark::State& bench_state, const std::string& size) {
  Simulation* simulation = nullptr;
  try {
    simulation = &simulation_for(size);
  } catch (const std::exception& error) {
    bench_state.SkipWithError(error.what());
    return;
  }
  RkTaylorStep& step = simulation->step();
  const Configuration& configuration = simulation->state().configuration;
  for (auto _ : bench_state) {
    step.rebuild_operators(configuration);
    benchmark::ClobberMemory();
  }
  const auto nodes = static_cast<std::int64_t>(simulation->nodes().sph_nodes.size());
  bench_state.SetItemsProcessed(bench_state.iterations() * nodes);  // nodes rebuilt
  bench_state.counters["nodes"] = static_cast<double>(nodes);
}

BENCHMARK_CAPTURE(BM_StepOperatorRebuild, s, std::string("s"))
    ->Iterations(10)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_StepOperatorRebuild, m, std::string("m"))
    ->Iterations(5)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_StepOperatorRebuild, l, std::string("l"))
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace rktsph
