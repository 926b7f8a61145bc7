// The output folder of a run, held for the run: created if needed, locked so that no second run
// writes into it at the same time, cleared of the temporaries of killed runs, and protected from
// mixing two runs' results (docs/input-reference.md, "Results").
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rktsph {

/// What to do when the folder already holds rktsph results (summary.json, run.log, field
/// files, ...).
enum class ExistingResults {
  Refuse,     ///< InputError: the user asks for --overwrite or another folder (but the record of
              ///< a run that failed before its first field file is replaced)
  Overwrite,  ///< remove rktsph's own result files first (never other files)
  Continue,   ///< keep them (a run that continues the folder's run, e.g. a restart)
};

/// The name of the lock file inside an output folder.
inline constexpr const char* kOutputLockName = ".rktsph.lock";

class OutputFolder {
 public:
  /// Creates `directory` if needed and takes its lock (flock on `directory`/.rktsph.lock, held
  /// until destruction), then removes the temporaries killed runs left ("<name>.tmp-<pid>") and
  /// handles earlier results as `existing` says.
  /// Throws InputError (exit 2) if the folder cannot be created or written, or holds results and
  /// `existing` is Refuse; RunError (exit 3) if another process holds the lock, naming its PID.
  OutputFolder(std::filesystem::path directory, ExistingResults existing);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& directory() const { return directory_; }
  /// Stale temporaries removed when the folder was taken.
  std::size_t removed_temporaries() const { return removed_temporaries_; }
  /// Result files of an earlier run removed (with ExistingResults::Overwrite).
  std::size_t removed_results() const { return removed_results_; }
  /// True if the folder held only the record of a run whose case or setup failed (summary.json,
  /// case.yaml, run.log, no field file), which was replaced without --overwrite.
  bool replaced_setup_record() const { return replaced_setup_record_; }

 private:
  void remove_stale_temporaries();
  void handle_existing_results(ExistingResults existing);

  std::filesystem::path directory_;
  int lock_descriptor_ = -1;
  std::size_t removed_temporaries_ = 0;
  std::size_t removed_results_ = 0;
  bool replaced_setup_record_ = false;
};

/// The files in `directory` that rktsph writes for a run (summary.json, case.yaml, series.pvd,
/// probes.csv, run.log, checkpoint.bin, fields/fields_NNNNNN.vtu) and that exist, in that order.
std::vector<std::filesystem::path> run_result_files(const std::filesystem::path& directory);

}  // namespace rktsph
