// Runs one case into an output folder with the standard observers: the resolved case, the
// ParaView series, probes.csv, summary.json and run.log (docs/input-reference.md, "Results").
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "rktsph/case/case_description.hpp"
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
};

struct RunOutcome {
  RunStatus status = RunStatus::Completed;
  std::string message;
  std::filesystem::path directory;
  long steps = 0;
  double wall_seconds = 0.0;
};

/// Throws InputError for a bad case and RunError when the run cannot be set up; a diverging run
/// returns status Diverged (its last good output kept). `inspect`, if given, sees the finished
/// simulation (validation checks read fields from it).
RunOutcome run_case(const CaseDescription& description, const std::filesystem::path& directory,
                    const RunOptions& options,
                    const std::function<void(const Simulation&)>& inspect = {});

}  // namespace rktsph
