#include "rktsph/driver/run_case.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <memory>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/core/build_info.hpp"
#include "rktsph/output/atomic_file.hpp"
#include "rktsph/output/output_folder.hpp"
#include "rktsph/output/run_log.hpp"
#include "rktsph/output/run_observers.hpp"

namespace rktsph {

namespace {

void log_folder(RunLog& log, const OutputFolder& folder) {
  if (folder.removed_results() > 0)
    log.info(fmt::format("--overwrite: removed {} result files of an earlier run",
                         folder.removed_results()));
  if (folder.removed_temporaries() > 0)
    log.info(fmt::format("removed {} temporary files left by a killed run",
                         folder.removed_temporaries()));
}

// The last line of run.log says how the run ended.
void log_end(RunLog& log, const RunOutcome& outcome, double simulated_time) {
  if (outcome.status == RunStatus::Completed)
    log.info(fmt::format("completed {} steps to t = {:.6g} s in {:.3f} s wall", outcome.steps,
                         simulated_time, outcome.wall_seconds));
  else
    log.error(fmt::format("{}: {}", run_status_name(outcome.status), outcome.message));
}

}  // namespace

RunOutcome run_case(const CaseDescription& description, const std::filesystem::path& directory,
                    const RunOptions& options,
                    const std::function<void(const Simulation&)>& inspect) {
  const OutputFolder folder(directory, options.existing_results);
  RunLog log(directory, true);
  log.info(fmt::format("rktsph {} case '{}' from {}", version_text(), description.name,
                       description.file));
  log_folder(log, folder);

  // From here on the folder is ours: an error before the loop still leaves a summary and a last
  // line in run.log, then goes on to the caller (exit status 2 for input, 3 otherwise).
  std::unique_ptr<Simulation> simulation;
  std::unique_ptr<FieldSeriesWriter> series;
  std::unique_ptr<ProbeRecorder> probes;
  try {
    write_file_atomically(directory / "case.yaml", write_case_yaml(description));
    simulation = std::make_unique<Simulation>(description);
    log.info(
        fmt::format("{} SPH nodes, {} stress points, {} boundary nodes; dt = {:.6g} s, {} steps, "
                    "{} threads",
                    simulation->nodes().sph_nodes.size(), simulation->nodes().stress_points.size(),
                    simulation->step().operators().boundary_nodes.size(), simulation->time_step(),
                    simulation->total_steps(), omp_get_max_threads()));
    series = std::make_unique<FieldSeriesWriter>(*simulation, directory);
    probes = std::make_unique<ProbeRecorder>(*simulation, directory / "probes.csv");
  } catch (const std::exception& error) {
    log.error(fmt::format("failed: {}", error.what()));
    try {
      write_setup_failure_summary(directory / "summary.json", description, error.what());
    } catch (const std::exception& summary_error) {
      log.error(summary_error.what());
    }
    throw;
  }

  SummaryWriter summary(directory / "summary.json");
  simulation->add_observer(*series);
  simulation->add_observer(*probes);
  simulation->add_observer(summary);
  std::unique_ptr<ProgressObserver> progress;
  if (options.progress_stream) {
    progress = std::make_unique<ProgressObserver>(description.time.end, *options.progress_stream,
                                                  options.progress_is_terminal, options.quiet);
    simulation->add_observer(*progress);
  }
  for (Observer* observer : options.observers)
    simulation->add_observer(*observer);
  if (options.stop_check) simulation->set_stop_check(options.stop_check);

  RunOutcome outcome;
  outcome.status = simulation->run();
  outcome.message = simulation->message();
  outcome.directory = directory;
  outcome.steps = simulation->state().step;
  outcome.wall_seconds = simulation->wall_seconds();
  log_end(log, outcome, simulation->state().time);
  if (inspect) inspect(*simulation);
  return outcome;
}

}  // namespace rktsph
