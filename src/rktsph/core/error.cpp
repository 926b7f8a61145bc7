#include "rktsph/core/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string_view>

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

namespace {
/// Case-file errors come first, by line and column; errors of --set arguments (whose location is
/// "<--set ...>") after them, in the order they were found (the sort is stable).
bool earlier_in_file(const InputError& a, const InputError& b) {
  const auto rank = [](const InputError& e) { return e.location().file.rfind("<--set", 0) == 0; };
  if (rank(a) != rank(b)) return rank(a) < rank(b);
  if (a.location().line != b.location().line) return a.location().line < b.location().line;
  return a.location().column < b.location().column;
}
}  // namespace

InputError InputError::combine(std::vector<InputError> errors) {
  std::vector<InputError> flat;
  for (InputError& error : errors)
    for (InputError& single : error.errors())
      flat.push_back(std::move(single));
  std::stable_sort(flat.begin(), flat.end(), earlier_in_file);
  // One mistake found twice (an unknown key, and the required key it misspells) is listed once.
  const auto same = [](const InputError& a, const InputError& b) {
    return std::string_view(a.what()) == b.what();
  };
  flat.erase(std::unique(flat.begin(), flat.end(), same), flat.end());
  if (flat.size() == 1) return flat.front();
  InputError result = flat.front();
  std::string message = fmt::format("{} errors:", flat.size());
  for (std::size_t i = 0; i < flat.size() && i < kMaxReportedInputErrors; ++i)
    message.append("\n").append(flat[i].what());
  if (flat.size() > kMaxReportedInputErrors)
    message += fmt::format("\nand {} more", flat.size() - kMaxReportedInputErrors);
  static_cast<std::runtime_error&>(result) = std::runtime_error(message);
  result.combined_ = std::move(flat);
  return result;
}

std::vector<InputError> InputError::errors() const {
  if (combined_.empty()) return {*this};
  return combined_;
}

}  // namespace rktsph
