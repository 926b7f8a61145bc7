#include "rktsph/case/key_spec.hpp"

#include "rktsph/case/sections/sections.hpp"

namespace rktsph {

std::string documented_number(double value) {
  std::string text = number(value);
  const std::size_t exponent = text.find('e');
  if (exponent == std::string::npos) return text;
  std::string digits = text.substr(exponent + 1);
  std::string sign;
  if (digits[0] == '+' || digits[0] == '-') {
    if (digits[0] == '-') sign = "-";
    digits.erase(0, 1);
  }
  digits.erase(0, std::min(digits.find_first_not_of('0'), digits.size() - 1));
  return text.substr(0, exponent + 1) + sign + digits;
}

std::string documented_range(const NumberRange& range) {
  const bool has_low = range.low > -1e308;
  const bool has_high = range.high < 1e308;
  if (has_low && has_high)
    return fmt::format("{}{}, {}{}", range.low_open ? "(" : "[", documented_number(range.low),
                       documented_number(range.high), range.high_open ? ")" : "]");
  if (has_low)
    return fmt::format("{} {}", range.low_open ? ">" : "≥", documented_number(range.low));
  if (has_high)
    return fmt::format("{} {}", range.high_open ? "<" : "≤", documented_number(range.high));
  return "any";
}

std::string documented_integer_range(long low, long high) {
  // Bounds this far out only guard the conversion from a double; the documentation leaves them out.
  constexpr long kNoPracticalBound = 1000000000L;
  if (high - low <= 2) {
    std::vector<std::string> values;
    for (long value = low; value <= high; ++value)
      values.push_back(fmt::format("{}", value));
    return documented_words(values);
  }
  if (high >= kNoPracticalBound) return fmt::format("≥ {}", low);
  return fmt::format("[{}, {}]", low, high);
}

std::string documented_words(const std::vector<std::string>& words) {
  return fmt::format("{}", fmt::join(words, ", "));
}

std::vector<DeclaredKey> declared_case_keys() {
  std::vector<DeclaredKey> list;
  declare(list, "", top_level_keys());
  declare_geometry_keys(list);
  declare_group_keys(list);
  declare_boundary_condition_keys(list);
  declare_loads_keys(list);
  declare_numerics_keys(list);
  declare_pore_fluid_keys(list);
  declare_output_keys(list);
  return list;
}

}  // namespace rktsph
