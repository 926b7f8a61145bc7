#include "rktsph/core/error.hpp"

#include <fmt/format.h>

namespace rktsph {

std::string SourceLocation::to_string() const {
  if (line > 0 && column > 0) return fmt::format("{}:{}:{}", file, line, column);
  if (line > 0) return fmt::format("{}:{}", file, line);
  return file;
}

namespace {
std::string compose(const SourceLocation& location, const std::string& key,
                    const std::string& value, const std::string& problem,
                    const std::string& allowed) {
  std::string message = location.to_string();
  if (!message.empty()) message += ": ";
  message += "error: ";
  if (!key.empty()) message += fmt::format("key '{}': ", key);
  message += problem;
  if (!value.empty()) message += fmt::format(" (found '{}')", value);
  if (!allowed.empty()) message += fmt::format("; allowed: {}", allowed);
  return message;
}
}  // namespace

InputError::InputError(SourceLocation location, std::string key, std::string value,
                       std::string problem, std::string allowed)
    : std::runtime_error(compose(location, key, value, problem, allowed)),
      location_(std::move(location)),
      key_(std::move(key)),
      value_(std::move(value)),
      problem_(std::move(problem)),
      allowed_(std::move(allowed)) {}

}  // namespace rktsph
