#include "rktsph/output/run_log.hpp"

#include <cerrno>
#include <chrono>
#include <ctime>
#include <system_error>

#include <fmt/format.h>

#include "rktsph/core/error.hpp"

namespace rktsph {

namespace {

std::string_view level_name(LogLevel level) {
  switch (level) {
    case LogLevel::kInfo:
      return "INFO";
    case LogLevel::kWarning:
      return "WARNING";
    case LogLevel::kError:
      return "ERROR";
  }
  return "INFO";
}

// On the terminal a plain info line needs no label; warnings and errors do, to stand out.
std::string_view echo_prefix(LogLevel level) {
  switch (level) {
    case LogLevel::kInfo:
      return "";
    case LogLevel::kWarning:
      return "warning: ";
    case LogLevel::kError:
      return "error: ";
  }
  return "";
}

std::string describe_errno(int error_number) {
  if (error_number == 0) return "unknown I/O error";
  return std::error_code(error_number, std::generic_category()).message();
}

}  // namespace

std::string utc_timestamp_now() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  const auto milliseconds =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm utc{};
  ::gmtime_r(&seconds, &utc);
  return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}.{:03}Z", utc.tm_year + 1900,
                     utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec,
                     static_cast<int>(milliseconds));
}

RunLog::RunLog(const std::filesystem::path& output_directory, bool quiet, std::ostream& echo)
    : path_(output_directory / "run.log"), quiet_(quiet), echo_(echo) {
  errno = 0;
  file_.open(path_, std::ios::out | std::ios::app);
  if (!file_) {
    throw RunError(
        fmt::format("cannot open log file '{}': {}", path_.string(), describe_errno(errno)));
  }
}

void RunLog::log(LogLevel level, std::string_view message) {
  const std::string timestamp = utc_timestamp_now();
  const std::string_view name = level_name(level);
  const std::lock_guard lock(mutex_);
  std::size_t line_start = 0;
  while (true) {
    const std::size_t line_end = message.find('\n', line_start);
    const std::string_view line =
        message.substr(line_start, line_end == std::string_view::npos ? std::string_view::npos
                                                                      : line_end - line_start);
    file_ << timestamp << ' ' << name << ' ' << line << '\n';
    if (line_end == std::string_view::npos) break;
    line_start = line_end + 1;
  }
  errno = 0;
  file_.flush();
  if (!file_) {
    throw RunError(
        fmt::format("cannot write log file '{}': {}", path_.string(), describe_errno(errno)));
  }
  if (!quiet_) echo_ << echo_prefix(level) << message << '\n' << std::flush;
}

}  // namespace rktsph
