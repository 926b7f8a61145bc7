#include "rktsph/driver/run_case.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <memory>
#include <optional>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/core/build_info.hpp"
#include "rktsph/output/atomic_file.hpp"
#include "rktsph/output/checkpoint_writer.hpp"
#include "rktsph/output/output_folder.hpp"
#include "rktsph/output/run_log.hpp"
#include "rktsph/output/run_observers.hpp"
#include "rktsph/simulation/case_warnings.hpp"
#include "rktsph/simulation/stop_when_at_rest.hpp"

namespace rktsph {

namespace {

void log_folder(RunLog& log, const OutputFolder& folder) {
  if (folder.replaced_setup_record())
    log.info("replaced the record of an earlier run that failed before its first field file");
  else if (folder.removed_results() > 0)
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
  else if (outcome.status == RunStatus::Interrupted)  // asked for by the user: no error
    log.info(fmt::format("{}: {}", run_status_name(outcome.status), outcome.message));
  else
    log.error(fmt::format("{}: {}", run_status_name(outcome.status), outcome.message));
}

}  // namespace

RunOutcome run_case(const CaseDescription& description, const std::filesystem::path& directory,
                    const RunOptions& options,
                    const std::function<void(const Simulation&)>& inspect) {
  // The hash covers the resolved case, --set overrides included, so a restart must give both.
  // The checkpoint is read (and refused) before the folder is touched.
  const std::string resolved_case = write_case_yaml(description);
  const std::uint64_t case_hash = fnv1a_64(resolved_case);
  std::optional<CheckpointFile> checkpoint;
  if (options.restart) checkpoint = read_checkpoint(directory, case_hash);
  const OutputFolder folder(directory,
                            options.restart ? ExistingResults::Continue : options.existing_results);
  RunLog log(directory, true);
  log.info(fmt::format("rktsph {} case '{}' from {}", version_text(), description.name,
                       description.file));
  log_folder(log, folder);
  if (!options.restart) {
    // A checkpoint belongs with the results beside it: a new run must not leave an old one there.
    std::error_code ignored;
    std::filesystem::remove(directory / kCheckpointFileName, ignored);
  }

  // From here on the folder is ours: an error before the loop still leaves a summary and a last
  // line in run.log, then goes on to the caller (exit status 2 for input, 3 otherwise).
  std::unique_ptr<Simulation> simulation;
  std::unique_ptr<FieldSeriesWriter> series;
  std::unique_ptr<ProbeRecorder> probes;
  std::vector<std::string> warnings;
  try {
    write_file_atomically(directory / "case.yaml", resolved_case);
    simulation = std::make_unique<Simulation>(description, options.limits);
    log.info(
        fmt::format("{} SPH nodes, {} stress points, {} boundary nodes; dt = {:.6g} s, {} steps, "
                    "{} threads",
                    simulation->nodes().sph_nodes.size(), simulation->cells().stress_points.size(),
                    simulation->step().operators().boundary_nodes.size(), simulation->time_step(),
                    simulation->total_steps(), omp_get_max_threads()));
    warnings = warning_lines(case_warnings(*simulation));
    for (const std::string& warning : warnings) {
      log.warning(warning);
      if (options.progress_stream) *options.progress_stream << "rktsph: " << warning << "\n";
    }
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

  EnergyBudget energy;
  SummaryWriter summary(directory / "summary.json", &energy, warnings);
  simulation->add_observer(*series);
  simulation->add_observer(*probes);
  simulation->add_observer(energy);  // before the summary, which reports its totals
  simulation->add_observer(summary);
  std::unique_ptr<CheckpointWriter> checkpoints;
  if (description.output.checkpoint_interval > 0.0 || checkpoint) {
    checkpoints = std::make_unique<CheckpointWriter>(
        directory / kCheckpointFileName, description.output.checkpoint_interval, case_hash,
        std::vector<CheckpointPart>{{"simulation", simulation.get()},
                                    {"field_series", series.get()},
                                    {"probes", probes.get()},
                                    {"energy_budget", &energy}});
    simulation->add_observer(*checkpoints);  // after the observers whose state it saves
  }
  if (checkpoint) {
    restore_checkpoint_parts(*checkpoint, checkpoints->parts());
    if (checkpoint->rktsph_version != RKTSPH_VERSION)
      log.warning(
          fmt::format("the checkpoint was written by rktsph {}; results continued by {} "
                      "may differ in the last bits from an uninterrupted run",
                      checkpoint->rktsph_version, RKTSPH_VERSION));
    log.info(fmt::format("continuing from {} at step {}, t = {:.6g} s", checkpoint->path.string(),
                         simulation->state().step, simulation->state().time));
  }
  std::unique_ptr<ProgressObserver> progress;
  if (options.progress_stream) {
    progress = std::make_unique<ProgressObserver>(description.time.end, *options.progress_stream,
                                                  options.progress_is_terminal, options.quiet);
    simulation->add_observer(*progress);
  }
  std::unique_ptr<StopWhenAtRest> at_rest;
  if (description.time.stop_when_at_rest) {
    at_rest = std::make_unique<StopWhenAtRest>(*description.time.stop_when_at_rest);
    simulation->add_observer(*at_rest);
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
  if (std::string budget = energy_closure_warning(energy.totals()); !budget.empty()) {
    log.warning(budget);
    if (options.progress_stream) *options.progress_stream << "rktsph: " << budget << "\n";
    warnings.push_back(std::move(budget));
  }
  outcome.warnings = std::move(warnings);
  log_end(log, outcome, simulation->state().time);
  if (inspect) inspect(*simulation);
  return outcome;
}

}  // namespace rktsph
