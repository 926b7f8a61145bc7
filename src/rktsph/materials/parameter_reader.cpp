#include "rktsph/materials/parameter_reader.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "rktsph/case/yaml_reader.hpp"

namespace rktsph {

namespace {
std::string range_text(double min, double max, bool open_min, bool open_max) {
  const std::string low =
      std::isinf(min) ? "(-inf" : fmt::format("{}{}", open_min ? "(" : "[", min);
  const std::string high =
      std::isinf(max) ? "+inf)" : fmt::format("{}{}", max, open_max ? ")" : "]");
  return fmt::format("a number in {}, {}", low, high);
}

// A value strictly inside the range, returned in place of a missing or rejected one: the
// material is still built (its other keys checked) but never run, since the errors are thrown.
double stand_in(double min, double max) {
  if (std::isfinite(min) && std::isfinite(max)) return 0.5 * (min + max);
  if (std::isfinite(min)) return min + std::max(1.0, std::abs(min));
  if (std::isfinite(max)) return max - std::max(1.0, std::abs(max));
  return 0.0;
}
}  // namespace

double ParameterReader::checked(const std::string& key, const Parameter& p, double min, double max,
                                bool open_min, bool open_max) {
  const bool below = open_min ? p.value <= min : p.value < min;
  const bool above = open_max ? p.value >= max : p.value > max;
  if (below || above || !std::isfinite(p.value)) {
    errors_.emplace_back(p.where, block_.path + "." + key, fmt::format("{}", p.value),
                         "value out of range", range_text(min, max, open_min, open_max));
    return stand_in(min, max);
  }
  return p.value;
}

bool ParameterReader::reject_word(const std::string& key, double min, double max, bool open_min,
                                  bool open_max) {
  const auto word = block_.words.find(key);
  if (word == block_.words.end()) return false;
  errors_.emplace_back(word->second.second, block_.path + "." + key, word->second.first,
                       "found a word where a number is needed",
                       range_text(min, max, open_min, open_max));
  return true;
}

std::string ParameterReader::misspelling_of(const std::string& key) const {
  std::vector<std::string> written;
  for (const auto& entry : block_.values)
    written.push_back(entry.first);
  return closest_match(key, written);
}

double ParameterReader::required(const std::string& key, double min, double max, bool open_min,
                                 bool open_max) {
  asked_.insert(key);
  if (reject_word(key, min, max, open_min, open_max)) return stand_in(min, max);
  const auto it = block_.values.find(key);
  if (it == block_.values.end()) {
    const std::string written = misspelling_of(key);
    const std::string problem =
        written.empty()
            ? std::string("missing required key")
            : fmt::format("missing required key ('{}' is written; a misspelling?)", written);
    errors_.emplace_back(block_.where, block_.path + "." + key, "", problem,
                         range_text(min, max, open_min, open_max));
    return stand_in(min, max);
  }
  return checked(key, it->second, min, max, open_min, open_max);
}

double ParameterReader::optional(const std::string& key, double fallback, double min, double max,
                                 bool open_min, bool open_max) {
  asked_.insert(key);
  if (reject_word(key, min, max, open_min, open_max)) return fallback;
  const auto it = block_.values.find(key);
  if (it == block_.values.end()) return fallback;
  return checked(key, it->second, min, max, open_min, open_max);
}

std::string ParameterReader::optional_word(const std::string& key, const std::string& fallback,
                                           const std::vector<std::string>& allowed) {
  asked_.insert(key);
  const std::string allowed_text = fmt::format("one of {}", fmt::join(allowed, ", "));
  const auto number = block_.values.find(key);
  if (number != block_.values.end()) {
    errors_.emplace_back(number->second.where, block_.path + "." + key,
                         fmt::format("{}", number->second.value),
                         "found a number where a word is needed", allowed_text);
    return fallback;
  }
  const auto word = block_.words.find(key);
  if (word == block_.words.end()) return fallback;
  if (std::find(allowed.begin(), allowed.end(), word->second.first) == allowed.end()) {
    errors_.emplace_back(word->second.second, block_.path + "." + key, word->second.first,
                         "unknown value", allowed_text);
    return fallback;
  }
  return word->second.first;
}

void ParameterReader::reject_block(const std::string& problem, const std::string& expected) {
  errors_.emplace_back(block_.where, block_.path, "", problem, expected);
}

void ParameterReader::reject_unknown_keys() {
  const std::vector<std::string> known(asked_.begin(), asked_.end());
  const std::string allowed = "model, " + quoted_list(known);
  const auto unknown = [&](const std::string& key) {
    const std::string suggestion = closest_match(key, known);
    return suggestion.empty()
               ? std::string("unknown key for this material model")
               : fmt::format("unknown key for this material model; did you mean '{}'?", suggestion);
  };
  for (const auto& [key, parameter] : block_.values)
    if (!asked_.count(key))
      errors_.emplace_back(parameter.where, block_.path + "." + key,
                           fmt::format("{}", parameter.value), unknown(key), allowed);
  for (const auto& [key, word] : block_.words)
    if (key != "model" && !asked_.count(key))
      errors_.emplace_back(word.second, block_.path + "." + key, word.first, unknown(key), allowed);
}

}  // namespace rktsph
