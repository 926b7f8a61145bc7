// The run log: a timestamped, append-only record of a run in <output directory>/run.log.
//
// Unlike every other result file it is appended to rather than replaced, so that the story of a
// run survives a crash and a restart into the same directory continues it. Each line is flushed
// as soon as it is written for the same reason.
#pragma once

#include <filesystem>
#include <iostream>
#include <mutex>
#include <ostream>
#include <string>
#include <string_view>

namespace rktsph {

enum class LogLevel { kInfo, kWarning, kError };

class RunLog {
 public:
  /// Opens (creating if needed) `output_directory`/run.log for appending, never through a
  /// symlink; the directory must exist. Unless `quiet`, each message is also written to `echo`
  /// (normally std::cerr) without the timestamp. Throws RunError if the file cannot be opened.
  RunLog(const std::filesystem::path& output_directory, bool quiet, std::ostream& echo = std::cerr);
  ~RunLog();
  RunLog(const RunLog&) = delete;
  RunLog& operator=(const RunLog&) = delete;

  /// Appends "<UTC time> <LEVEL> <text>" (one such line per line of a multi-line message) and
  /// flushes. Safe to call from several threads. Throws RunError if the write fails.
  void log(LogLevel level, std::string_view message);
  void info(std::string_view message) { log(LogLevel::kInfo, message); }
  void warning(std::string_view message) { log(LogLevel::kWarning, message); }
  void error(std::string_view message) { log(LogLevel::kError, message); }

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  int descriptor_ = -1;
  bool quiet_;
  std::ostream& echo_;
  std::mutex mutex_;
};

/// "2024-05-01T12:34:56.789Z": the current UTC time to the millisecond, used as line prefix.
std::string utc_timestamp_now();

}  // namespace rktsph
