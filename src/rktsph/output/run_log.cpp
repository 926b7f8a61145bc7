#include "rktsph/output/run_log.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <ctime>

#include <fmt/format.h>

#include "rktsph/core/error.hpp"
#include "rktsph/output/atomic_file.hpp"

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
  // O_NOFOLLOW: a symlink planted as run.log must not turn the log into a write to another file.
  descriptor_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (descriptor_ < 0) {
    const int open_error = errno;
    throw RunError(fmt::format("cannot open log file '{}': {}", path_.string(),
                               describe_system_error(open_error)));
  }
}

RunLog::~RunLog() {
  ::close(descriptor_);
}

void RunLog::log(LogLevel level, std::string_view message) {
  const std::string timestamp = utc_timestamp_now();
  const std::string_view name = level_name(level);
  std::string text;
  std::size_t line_start = 0;
  while (true) {
    const std::size_t line_end = message.find('\n', line_start);
    const std::string_view line =
        message.substr(line_start, line_end == std::string_view::npos ? std::string_view::npos
                                                                      : line_end - line_start);
    text += fmt::format("{} {} {}\n", timestamp, name, line);
    if (line_end == std::string_view::npos) break;
    line_start = line_end + 1;
  }
  const std::lock_guard lock(mutex_);
  // One write per message (O_APPEND): the lines of a message stay together, and each message is
  // with the kernel, not in a buffer of this process, when this returns, so a kill loses none.
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t count = ::write(descriptor_, text.data() + written, text.size() - written);
    if (count < 0) {
      const int write_error = errno;
      if (write_error == EINTR) continue;
      throw RunError(fmt::format("cannot write log file '{}': {}", path_.string(),
                                 describe_system_error(write_error)));
    }
    written += static_cast<std::size_t>(count);
  }
  if (!quiet_) echo_ << echo_prefix(level) << message << '\n' << std::flush;
}

}  // namespace rktsph
