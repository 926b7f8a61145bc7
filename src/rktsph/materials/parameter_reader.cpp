#include "rktsph/materials/parameter_reader.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

namespace rktsph {

namespace {
std::string range_text(double min, double max, bool open_min, bool open_max) {
  const std::string low =
      std::isinf(min) ? "(-inf" : fmt::format("{}{}", open_min ? "(" : "[", min);
  const std::string high =
      std::isinf(max) ? "+inf)" : fmt::format("{}{}", max, open_max ? ")" : "]");
  return fmt::format("a number in {}, {}", low, high);
}
}  // namespace

double ParameterReader::checked(const std::string& key, const Parameter& p, double min, double max,
                                bool open_min, bool open_max) const {
  const bool below = open_min ? p.value <= min : p.value < min;
  const bool above = open_max ? p.value >= max : p.value > max;
  if (below || above || !std::isfinite(p.value))
    throw InputError(p.where, block_.path + "." + key, fmt::format("{}", p.value),
                     "value out of range", range_text(min, max, open_min, open_max));
  return p.value;
}

void ParameterReader::reject_word(const std::string& key, double min, double max, bool open_min,
                                  bool open_max) const {
  const auto word = block_.words.find(key);
  if (word != block_.words.end())
    throw InputError(word->second.second, block_.path + "." + key, word->second.first,
                     "found a word where a number is needed",
                     range_text(min, max, open_min, open_max));
}

double ParameterReader::required(const std::string& key, double min, double max, bool open_min,
                                 bool open_max) {
  asked_.insert(key);
  reject_word(key, min, max, open_min, open_max);
  const auto it = block_.values.find(key);
  if (it == block_.values.end())
    throw InputError(block_.where, block_.path + "." + key, "", "missing required key",
                     range_text(min, max, open_min, open_max));
  return checked(key, it->second, min, max, open_min, open_max);
}

double ParameterReader::optional(const std::string& key, double fallback, double min, double max,
                                 bool open_min, bool open_max) {
  asked_.insert(key);
  reject_word(key, min, max, open_min, open_max);
  const auto it = block_.values.find(key);
  if (it == block_.values.end()) return fallback;
  return checked(key, it->second, min, max, open_min, open_max);
}

std::string ParameterReader::optional_word(const std::string& key, const std::string& fallback,
                                           const std::vector<std::string>& allowed) {
  asked_.insert(key);
  const std::string allowed_text = fmt::format("one of {}", fmt::join(allowed, ", "));
  const auto number = block_.values.find(key);
  if (number != block_.values.end())
    throw InputError(number->second.where, block_.path + "." + key,
                     fmt::format("{}", number->second.value),
                     "found a number where a word is needed", allowed_text);
  const auto word = block_.words.find(key);
  if (word == block_.words.end()) return fallback;
  if (std::find(allowed.begin(), allowed.end(), word->second.first) == allowed.end())
    throw InputError(word->second.second, block_.path + "." + key, word->second.first,
                     "unknown value", allowed_text);
  return word->second.first;
}

void ParameterReader::reject_unknown_keys() const {
  std::string allowed;
  for (const std::string& key : asked_)
    allowed += (allowed.empty() ? "" : ", ") + key;
  for (const auto& [key, parameter] : block_.values)
    if (!asked_.count(key))
      throw InputError(parameter.where, block_.path + "." + key, fmt::format("{}", parameter.value),
                       "unknown key for this material model", "model, " + allowed);
  for (const auto& [key, word] : block_.words)
    if (key != "model" && !asked_.count(key))
      throw InputError(word.second, block_.path + "." + key, word.first,
                       "unknown key for this material model", "model, " + allowed);
}

}  // namespace rktsph
