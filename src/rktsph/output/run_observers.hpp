// Observers that turn a run into files (docs/input-reference.md, "Results"): the ParaView series,
// the probe histories, the summary, and the progress display. None of them is inside the step.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "rktsph/output/probe_csv.hpp"
#include "rktsph/output/progress.hpp"
#include "rktsph/output/pvd_writer.hpp"
#include "rktsph/simulation/quantities.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph {

/// Writes fields/fields_NNNNNN.vtu at t = 0, every `output.interval` and at the end, and keeps
/// series.pvd listing them. After a divergence nothing more is written: the last files are the
/// last good state.
class FieldSeriesWriter final : public Observer {
 public:
  FieldSeriesWriter(const Simulation& simulation, std::filesystem::path directory);
  void on_start(const Simulation& simulation) override;
  void after_step(const Simulation& simulation) override;
  void on_finish(const Simulation& simulation, RunStatus status,
                 const std::string& message) override;
  std::size_t files_written() const { return collection_.entries().size(); }

 private:
  void write(const Simulation& simulation);
  std::filesystem::path directory_;
  PvdCollection collection_;
  std::vector<std::string> selection_;
  double interval_;
  double next_time_ = 0.0;
  double last_written_time_ = -1.0;
};

/// Checks that every probe's group and fields exist in `simulation` (field names depend on the
/// model and materials, so the reader cannot): InputError at the offending field's line, or at its
/// --set argument. `rktsph check` calls it too, so that it refuses what `run` would.
void check_probes(const Simulation& simulation);

/// Records probes (group reductions of named quantities) into probes.csv: one column per probe
/// and field, named "<probe>.<field>". The file is rewritten whole every 2 s of wall time and at
/// the end.
class ProbeRecorder final : public Observer {
 public:
  /// Resolves the probes of the case; InputError at the probe for unknown groups or fields.
  ProbeRecorder(const Simulation& simulation, std::filesystem::path path);
  void on_start(const Simulation& simulation) override;
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
  std::filesystem::path path_;
  std::vector<Column> columns_;
  ProbeCsv table_;
  std::vector<double> row_;
  double interval_;
  double next_time_ = 0.0;
  double last_flush_wall_ = 0.0;
};

/// Writes summary.json when the run ends (also when it diverged).
class SummaryWriter final : public Observer {
 public:
  explicit SummaryWriter(std::filesystem::path path) : path_(std::move(path)) {}
  void on_finish(const Simulation& simulation, RunStatus status,
                 const std::string& message) override;

 private:
  std::filesystem::path path_;
};

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
