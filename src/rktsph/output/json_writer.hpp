// A small JSON value type and serialiser for summary.json and `rktsph validate --json` lines.
//
// Only what output needs: build a value, print it. Objects keep keys in insertion order so that
// files are stable and readable. Finite doubles are printed in the shortest form that reads back
// to the same double, with ".0" added to integral values so that readers keep them as reals
// (and keep the sign of -0.0); integers are printed as integers. NaN and infinities have no JSON
// spelling and become null.
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace rktsph {

class JsonValue {
 public:
  using Array = std::vector<JsonValue>;
  using Object = std::vector<std::pair<std::string, JsonValue>>;

  JsonValue() = default;  // null
  JsonValue(std::nullptr_t) {}
  JsonValue(bool value) : value_(value) {}
  JsonValue(double value) : value_(value) {}
  JsonValue(float value) : value_(static_cast<double>(value)) {}
  template <std::signed_integral Integer>
  JsonValue(Integer value) : value_(static_cast<std::int64_t>(value)) {}
  template <std::unsigned_integral Integer>
  requires(!std::same_as<Integer, bool>) JsonValue(Integer value)
      : value_(static_cast<std::uint64_t>(value)) {}
  // Without these a string literal would convert to bool.
  JsonValue(const char* value) : value_(std::string(value)) {}
  JsonValue(std::string_view value) : value_(std::string(value)) {}
  JsonValue(std::string value) : value_(std::move(value)) {}
  JsonValue(Array value) : value_(std::move(value)) {}
  JsonValue(Object value) : value_(std::move(value)) {}

  static JsonValue array() { return JsonValue(Array{}); }
  static JsonValue object() { return JsonValue(Object{}); }

  bool is_null() const { return std::holds_alternative<std::nullptr_t>(value_); }
  bool is_array() const { return std::holds_alternative<Array>(value_); }
  bool is_object() const { return std::holds_alternative<Object>(value_); }

  /// On an object: sets `key`, replacing an existing value in place, else appending. Returns
  /// *this so that calls chain. Throws std::logic_error if this is not an object.
  JsonValue& set(std::string_view key, JsonValue value);
  /// On an array: appends. Returns *this. Throws std::logic_error if this is not an array.
  JsonValue& push_back(JsonValue value);

  /// One line, no spaces: for line-oriented output such as `validate --json`.
  std::string compact() const;
  /// Indented by `indent` spaces per level, one member or element per line, ending without '\n'.
  std::string pretty(int indent = 2) const;

 private:
  void write(std::string& out, int indent, int depth) const;

  std::variant<std::nullptr_t, bool, std::int64_t, std::uint64_t, double, std::string, Array,
               Object>
      value_{nullptr};
};

/// The JSON string literal for `text`, quotes included. Bytes >= 0x80 pass through unchanged
/// (the text is taken to be UTF-8); control characters are escaped.
std::string json_quote(std::string_view text);

/// The JSON number for `value`, or "null" if it is not finite.
std::string json_number(double value);

}  // namespace rktsph
