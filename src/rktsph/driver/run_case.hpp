// Runs one case into an output folder with the standard observers: the resolved case, the
// ParaView series, probes.csv, summary.json and run.log (docs/input-reference.md, "Results").
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "rktsph/case/case_description.hpp"
#include "rktsph/output/output_folder.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph {

struct RunOptions {
  bool quiet = false;
  SimulationLimits limits;  ///< checked from the case before anything is built
  bool progress_is_terminal = false;
  std::ostream* progress_stream = nullptr;  // null: no progress display
  /// Further observers of the loop (validation metrics sampled while the run goes), added after
  /// the standard ones; they must outlive the call.
  std::vector<Observer*> observers;
  /// What to do with the results of an earlier run in the folder (see OutputFolder).
  ExistingResults existing_results = ExistingResults::Refuse;
  /// Asked before every step; a non-empty answer interrupts the run there (SIGINT, SIGTERM).
  StopCheck stop_check;
  /// Continue the run in `directory` from its checkpoint.bin instead of starting at t = 0
  /// (`rktsph run --restart`); refused with an InputError, before anything is written, for a
  /// missing or damaged checkpoint, another format version or another case.
  bool restart = false;
};

struct RunOutcome {
  RunStatus status = RunStatus::Completed;
  std::string message;
  std::filesystem::path directory;
  long steps = 0;
  double wall_seconds = 0.0;
  /// The case's plausibility warnings (also in run.log, summary.json and on the progress stream).
  std::vector<std::string> warnings;
};

/// Takes the output folder (see OutputFolder: lock, stale temporaries, earlier results), then
/// builds and runs the case. Throws InputError for a bad case or an unusable folder and RunError
/// when the run cannot be set up or the folder is in use; once the folder is taken such an error
/// also leaves summary.json (status "failed") and its text as the last line of run.log. A run
/// that diverges, fails or is interrupted returns that status (its last good output kept).
/// `inspect`, if given, sees the finished simulation (validation checks read fields from it).
RunOutcome run_case(const CaseDescription& description, const std::filesystem::path& directory,
                    const RunOptions& options,
                    const std::function<void(const Simulation&)>& inspect = {});

}  // namespace rktsph
