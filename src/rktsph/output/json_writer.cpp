#include "rktsph/output/json_writer.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include <fmt/format.h>

namespace rktsph {

namespace {

void append_quoted(std::string& out, std::string_view text) {
  out += '"';
  for (const char character : text) {
    switch (character) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        // RFC 8259 forbids raw characters below 0x20 inside strings.
        if (static_cast<unsigned char>(character) < 0x20) {
          fmt::format_to(std::back_inserter(out), "\\u{:04x}",
                         static_cast<unsigned>(static_cast<unsigned char>(character)));
        } else {
          out += character;
        }
    }
  }
  out += '"';
}

void append_number(std::string& out, double value) {
  if (!std::isfinite(value)) {
    out += "null";
    return;
  }
  // fmt's default for doubles is the shortest text that reads back to the same double, and for
  // finite values it is always valid JSON ("1e+20", "0.001").
  const std::size_t start = out.size();
  fmt::format_to(std::back_inserter(out), "{}", value);
  // An integral value would print as "2" or "-0"; readers such as Python's json would then
  // return an integer, and "-0" would lose its sign. The ".0" keeps doubles recognisably real.
  if (out.find_first_of(".eE", start) == std::string::npos) out += ".0";
}

void append_newline_and_indent(std::string& out, int indent, int depth) {
  if (indent <= 0) return;
  out += '\n';
  out.append(static_cast<std::size_t>(indent) * static_cast<std::size_t>(depth), ' ');
}

}  // namespace

JsonValue& JsonValue::set(std::string_view key, JsonValue value) {
  auto* members = std::get_if<Object>(&value_);
  if (members == nullptr) throw std::logic_error("JsonValue::set on a value that is not an object");
  const auto existing = std::find_if(members->begin(), members->end(),
                                     [key](const auto& member) { return member.first == key; });
  if (existing != members->end()) {
    existing->second = std::move(value);
  } else {
    members->emplace_back(std::string(key), std::move(value));
  }
  return *this;
}

JsonValue& JsonValue::push_back(JsonValue value) {
  auto* elements = std::get_if<Array>(&value_);
  if (elements == nullptr) {
    throw std::logic_error("JsonValue::push_back on a value that is not an array");
  }
  elements->push_back(std::move(value));
  return *this;
}

std::string JsonValue::compact() const {
  std::string out;
  write(out, 0, 0);
  return out;
}

std::string JsonValue::pretty(int indent) const {
  std::string out;
  write(out, std::max(indent, 1), 0);
  return out;
}

// indent == 0 means compact output.
void JsonValue::write(std::string& out, int indent, int depth) const {
  if (std::holds_alternative<std::nullptr_t>(value_)) {
    out += "null";
  } else if (const auto* flag = std::get_if<bool>(&value_)) {
    out += *flag ? "true" : "false";
  } else if (const auto* signed_integer = std::get_if<std::int64_t>(&value_)) {
    fmt::format_to(std::back_inserter(out), "{}", *signed_integer);
  } else if (const auto* unsigned_integer = std::get_if<std::uint64_t>(&value_)) {
    fmt::format_to(std::back_inserter(out), "{}", *unsigned_integer);
  } else if (const auto* number = std::get_if<double>(&value_)) {
    append_number(out, *number);
  } else if (const auto* text = std::get_if<std::string>(&value_)) {
    append_quoted(out, *text);
  } else if (const auto* elements = std::get_if<Array>(&value_)) {
    out += '[';
    for (std::size_t index = 0; index < elements->size(); ++index) {
      if (index > 0) out += ',';
      append_newline_and_indent(out, indent, depth + 1);
      (*elements)[index].write(out, indent, depth + 1);
    }
    if (!elements->empty()) append_newline_and_indent(out, indent, depth);
    out += ']';
  } else {
    const auto& members = std::get<Object>(value_);
    out += '{';
    for (std::size_t index = 0; index < members.size(); ++index) {
      if (index > 0) out += ',';
      append_newline_and_indent(out, indent, depth + 1);
      append_quoted(out, members[index].first);
      out += indent > 0 ? ": " : ":";
      members[index].second.write(out, indent, depth + 1);
    }
    if (!members.empty()) append_newline_and_indent(out, indent, depth);
    out += '}';
  }
}

std::string json_quote(std::string_view text) {
  std::string out;
  append_quoted(out, text);
  return out;
}

std::string json_number(double value) {
  std::string out;
  append_number(out, value);
  return out;
}

}  // namespace rktsph
