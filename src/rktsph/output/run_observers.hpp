// Observers that turn a run into files (docs/input-reference.md, "Results"): the ParaView series,
// the probe histories, the summary, and the progress display. None of them is inside the step.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "rktsph/output/output_schedule.hpp"
#include "rktsph/output/probe_csv.hpp"
#include "rktsph/output/progress.hpp"
#include "rktsph/output/pvd_writer.hpp"
#include "rktsph/simulation/energy_budget.hpp"
#include "rktsph/simulation/quantities.hpp"
#include "rktsph/simulation/simulation.hpp"
#include "rktsph/simulation/surface_watch.hpp"

namespace rktsph {

/// Everything the standard observers of a run check in their constructors (output fields, probe
/// groups and fields), without writing anything: `check` runs it so that it refuses what `run`
/// refuses, with the same message.
void check_run_observers(const Simulation& simulation);

/// Writes fields/fields_NNNNNN.vtu at t = 0, when OutputSchedule(output.interval) says, and at
/// the end, and keeps series.pvd listing them. After a divergence or a failure nothing more is
/// written: the last files are the last good state. An interrupted run writes its last step.
class FieldSeriesWriter final : public Observer, public Checkpointed {
 public:
  FieldSeriesWriter(const Simulation& simulation, std::filesystem::path directory);
  void on_start(const Simulation& simulation) override;
  /// Rewrites series.pvd with the checkpoint's entries and removes the VTU files it does not
  /// list (written after the checkpoint by the run that was killed).
  void on_resume(const Simulation& simulation) override;
  void save_checkpoint(CheckpointOut& out) const override;
  void restore_checkpoint(CheckpointIn& in) override;
  void after_step(const Simulation& simulation) override;
  void on_finish(const Simulation& simulation, RunStatus status,
                 const std::string& message) override;
  std::size_t files_written() const { return collection_.entries().size(); }

 private:
  /// Writes `state` (the simulation's, or its last good one) as the next field file.
  void write(const Simulation& simulation, const State& state);
  std::filesystem::path directory_;
  PvdCollection collection_;
  std::vector<std::string> selection_;
  OutputSchedule schedule_;
  double last_written_time_ = -1.0;
  FreeSurface detected_;  // the free_surface and surface_normal fields (moving models)
  double detected_time_ = -1.0;
};

/// Checks that every probe's group and fields exist in `simulation` (field names depend on the
/// model and materials, so the reader cannot): InputError at the offending field's line, or at its
/// --set argument. `rktsph check` calls it too, so that it refuses what `run` would.
void check_probes(const Simulation& simulation);

/// Records probes (group reductions of named quantities) into probes.csv: one column per probe
/// and field, named "<probe>.<field>". The file is rewritten whole with every field output (the
/// same schedule as FieldSeriesWriter), every 2 s of wall time and at the end.
class ProbeRecorder final : public Observer, public Checkpointed {
 public:
  /// Resolves the probes of the case; InputError at the probe for unknown groups or fields.
  ProbeRecorder(const Simulation& simulation, std::filesystem::path path);
  void on_start(const Simulation& simulation) override;
  /// Rewrites probes.csv with the checkpoint's rows, dropping any recorded after it.
  void on_resume(const Simulation& simulation) override;
  /// The rows themselves (bit-exact doubles), not a position in probes.csv: the file is only
  /// flushed now and then, so the checkpoint cannot rely on what is on disk.
  void save_checkpoint(CheckpointOut& out) const override;
  void restore_checkpoint(CheckpointIn& in) override;
  void after_step(const Simulation& simulation) override;
  void on_finish(const Simulation& simulation, RunStatus status,
                 const std::string& message) override;
  const ProbeCsv& table() const { return table_; }

 private:
  struct Column {
    const std::vector<std::int32_t>* nodes;
    NodeQuantity quantity;
    ProbeSpec::Reduction reduction;
  };
  void record(const Simulation& simulation);
  /// Adds each rigid body's force times the step to body_impulse_ (eq. 9.15).
  void integrate_body_forces(const Simulation& simulation);
  std::filesystem::path path_;
  std::vector<Column> columns_;
  ProbeCsv table_;
  std::vector<double> row_;
  bool every_step_;  // probe_interval 0
  OutputSchedule records_;
  OutputSchedule field_outputs_;
  double last_flush_wall_ = 0.0;
  // The rigid bodies' columns are the mean force since the last row: its time integral since
  // then [N s/m] per body and axis, the time of that row and of the last step.
  std::vector<double> body_impulse_;
  double impulse_since_ = 0.0;
  double last_step_time_ = 0.0;
};

/// Writes summary.json when the run ends, however it ends (status, message, counts, program),
/// with the energy budget of `energy` when given (its totals at the last step it observed).
class SummaryWriter final : public Observer {
 public:
  /// `warnings`: the case's plausibility warnings, listed as `warnings` (empty: none).
  explicit SummaryWriter(std::filesystem::path path, const EnergyBudget* energy = nullptr,
                         std::vector<std::string> warnings = {})
      : path_(std::move(path)), energy_(energy), warnings_(std::move(warnings)) {}
  void on_finish(const Simulation& simulation, RunStatus status,
                 const std::string& message) override;

 private:
  std::filesystem::path path_;
  const EnergyBudget* energy_;
  std::vector<std::string> warnings_;
};

/// summary.json for a run that failed before its loop started (a setup or input error found after
/// the output folder was taken): status "failed", the error text as message, 0 steps.
void write_setup_failure_summary(const std::filesystem::path& path,
                                 const CaseDescription& description, const std::string& message);

/// Progress bar on a terminal, periodic lines otherwise, nothing when quiet.
class ProgressObserver final : public Observer {
 public:
  ProgressObserver(double end_time, std::ostream& out, bool is_terminal, bool quiet)
      : progress_(end_time, out, is_terminal, quiet) {}
  void after_step(const Simulation& simulation) override {
    progress_.update(simulation.state().time, simulation.state().step);
  }
  void on_finish(const Simulation&, RunStatus, const std::string&) override { progress_.finish(); }

 private:
  Progress progress_;
};

}  // namespace rktsph
