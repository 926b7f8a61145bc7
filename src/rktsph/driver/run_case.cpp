#include "rktsph/driver/run_case.hpp"

#include <fmt/format.h>
#include <omp.h>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/output/atomic_file.hpp"
#include "rktsph/output/run_log.hpp"
#include "rktsph/output/run_observers.hpp"

namespace rktsph {

RunOutcome run_case(const CaseDescription& description, const std::filesystem::path& directory,
                    const RunOptions& options,
                    const std::function<void(const Simulation&)>& inspect) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error)
    throw RunError(
        fmt::format("cannot create the output folder {}: {}", directory.string(), error.message()));
  RunLog log(directory, true);
  log.info(fmt::format("rktsph {} case '{}' from {}", RKTSPH_VERSION, description.name,
                       description.file));
  write_file_atomically(directory / "case.yaml", write_case_yaml(description));

  Simulation simulation(description, options.limits);
  log.info(
      fmt::format("{} SPH nodes, {} stress points, {} boundary nodes; dt = {:.6g} s, {} steps, "
                  "{} threads",
                  simulation.nodes().sph_nodes.size(), simulation.nodes().stress_points.size(),
                  simulation.step().operators().boundary_nodes.size(), simulation.time_step(),
                  simulation.total_steps(), omp_get_max_threads()));

  FieldSeriesWriter series(simulation, directory);
  ProbeRecorder probes(simulation, directory / "probes.csv");
  SummaryWriter summary(directory / "summary.json");
  simulation.add_observer(series);
  simulation.add_observer(probes);
  simulation.add_observer(summary);
  std::unique_ptr<ProgressObserver> progress;
  if (options.progress_stream) {
    progress = std::make_unique<ProgressObserver>(description.time.end, *options.progress_stream,
                                                  options.progress_is_terminal, options.quiet);
    simulation.add_observer(*progress);
  }
  for (Observer* observer : options.observers)
    simulation.add_observer(*observer);

  RunOutcome outcome;
  outcome.status = simulation.run();
  outcome.message = simulation.message();
  outcome.directory = directory;
  outcome.steps = simulation.state().step;
  outcome.wall_seconds = simulation.wall_seconds();
  if (outcome.status == RunStatus::Completed)
    log.info(fmt::format("completed {} steps to t = {:.6g} s in {:.3f} s wall", outcome.steps,
                         simulation.state().time, outcome.wall_seconds));
  else
    log.error(outcome.message);
  if (inspect) inspect(simulation);
  return outcome;
}

}  // namespace rktsph
