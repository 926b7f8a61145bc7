#include "rktsph/case/yaml_reader.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <utility>

namespace rktsph {

namespace {

constexpr std::size_t kMaxRenderedLength = 60;

/// Where the nodes being converted come from: a case file (with marks) or a --set value text,
/// whose marks would only count characters inside the override and so are dropped.
struct Origin {
  std::string file;
  bool keep_marks = true;
  std::string override_text;
};

SourceLocation location_of(const YAML::Mark& mark, const Origin& origin) {
  SourceLocation location{origin.file, 0, 0};
  // yaml-cpp marks are 0-based and -1 when unknown; SourceLocation is 1-based with 0 = unknown.
  if (origin.keep_marks && mark.line >= 0) {
    location.line = mark.line + 1;
    location.column = mark.column + 1;
  }
  return location;
}

std::string child_path(const std::string& parent, const std::string& component) {
  return parent.empty() ? component : parent + "." + component;
}

YamlNode convert(const YAML::Node& source, const Origin& origin, const std::string& path,
                 const SourceLocation& key_where);

void convert_map_entries(const YAML::Node& source, const Origin& origin, YamlNode& target) {
  for (const auto& entry : source) {
    // Copies, not references: yaml-cpp's iterator hands out a temporary pair.
    const YAML::Node key_node = entry.first;
    const YAML::Node value_node = entry.second;
    const SourceLocation key_where = location_of(key_node.Mark(), origin);
    if (!key_node.IsScalar()) {
      throw InputError(key_where, target.path, "", "a map key must be a plain word",
                       "keys such as 'spacing' or 'material'");
    }
    const std::string key = key_node.Scalar();
    if (const YamlNode* first = target.find(key)) {
      throw InputError(
          key_where, child_path(target.path, key), key,
          fmt::format("duplicate key (first written at {})", first->key_where.to_string()),
          "each key once per map");
    }
    YamlNode child = convert(value_node, origin, child_path(target.path, key), key_where);
    child.key = key;
    target.children.push_back(std::move(child));
  }
}

/// The size of a document with every alias expanded, as far as it was walked.
struct ExpandedSize {
  std::size_t values = 0;
  bool too_deep = false;
  bool too_large() const { return too_deep || values > kMaxYamlValues; }
};

/// Counts the values of `source` with every alias expanded, stopping once the count passes
/// kMaxYamlValues or the nesting kMaxYamlDepth (a self-referencing alias nests without end);
/// yaml-cpp shares an aliased node, so this walk allocates nothing.
void count_expanded(const YAML::Node& source, int depth, ExpandedSize& size) {
  ++size.values;
  if (depth > kMaxYamlDepth) size.too_deep = true;
  if (size.too_large()) return;
  if (source.IsSequence()) {
    for (const YAML::Node& item : source) {
      count_expanded(item, depth + 1, size);
      if (size.too_large()) return;
    }
  } else if (source.IsMap()) {
    for (const auto& entry : source) {
      count_expanded(entry.second, depth + 1, size);
      if (size.too_large()) return;
    }
  }
}

/// The conversion copies an aliased value at every use, so nested aliases ("billion laughs")
/// would grow without bound: a document larger than kMaxYamlValues, or nested deeper than
/// kMaxYamlDepth, is refused before it is copied.
void refuse_oversized(const YAML::Node& document, const Origin& origin) {
  ExpandedSize size;
  // The error names the top-level key under which the limit is passed: an alias's own mark is
  // that of its anchor, which need not be where the expansion happens.
  YAML::Mark where = document.Mark();
  std::string key;
  if (document.IsMap()) {
    ++size.values;
    for (const auto& entry : document) {
      where = entry.first.Mark();
      key = entry.first.IsScalar() ? entry.first.Scalar() : "";
      count_expanded(entry.second, 1, size);
      if (size.too_large()) break;
    }
  } else {
    count_expanded(document, 0, size);
  }
  if (!size.too_large()) return;
  if (size.too_deep)
    throw InputError(
        location_of(where, origin), key, "",
        fmt::format("the document nests deeper than {} levels (a YAML alias used "
                    "inside its own anchor, such as '&a [*a]', nests without end)",
                    kMaxYamlDepth),
        fmt::format("at most {} levels of nesting; a case needs about six", kMaxYamlDepth));
  throw InputError(location_of(where, origin), key, "",
                   fmt::format("the document expands to more than {} values (each use of a YAML "
                               "alias '*name' copies the whole anchored value)",
                               kMaxYamlValues),
                   fmt::format("at most {} values after expanding aliases; a case needs a few "
                               "hundred, so write long tables out or use fewer nested aliases",
                               kMaxYamlValues));
}

YamlNode convert(const YAML::Node& source, const Origin& origin, const std::string& path,
                 const SourceLocation& key_where) {
  YamlNode node;
  node.path = path;
  node.override_text = origin.override_text;
  // yaml-cpp puts the mark of an empty value on the token after it (often the next line), so an
  // empty value is located at its key instead.
  node.where = source.IsNull() ? key_where : location_of(source.Mark(), origin);
  node.key_where = key_where.file.empty() ? node.where : key_where;
  if (source.IsScalar()) {
    node.kind = YamlNode::Kind::Scalar;
    node.text = source.Scalar();
    node.quoted = source.Tag() == "!";  // yaml-cpp's non-specific tag for quoted scalars
  } else if (source.IsSequence()) {
    node.kind = YamlNode::Kind::Sequence;
    std::size_t index = 0;
    for (const YAML::Node& item : source) {
      const SourceLocation item_where = location_of(item.Mark(), origin);
      node.children.push_back(
          convert(item, origin, child_path(path, std::to_string(index++)), item_where));
    }
  } else if (source.IsMap()) {
    node.kind = YamlNode::Kind::Map;
    convert_map_entries(source, origin, node);
  }
  return node;
}

/// Rewrites `node` and everything below it as coming from a --set override.
void mark_as_override(YamlNode& node, const SourceLocation& where, const std::string& text) {
  node.override_text = text;
  node.where = where;
  node.key_where = where;
  for (YamlNode& child : node.children)
    mark_as_override(child, where, text);
}

/// Gives `node` (and its subtree) the dotted path `path`.
void set_paths(YamlNode& node, const std::string& path) {
  node.path = path;
  for (std::size_t i = 0; i < node.children.size(); ++i) {
    YamlNode& child = node.children[i];
    set_paths(child, child_path(path, node.is_map() ? child.key : std::to_string(i)));
  }
}

std::vector<std::string> split_path(const std::string& key) {
  std::vector<std::string> components;
  std::size_t begin = 0;
  while (true) {
    const std::size_t dot = key.find('.', begin);
    components.push_back(key.substr(begin, dot - begin));
    if (dot == std::string::npos) break;
    begin = dot + 1;
  }
  return components;
}

bool is_index(const std::string& component) {
  return !component.empty() && component.size() < 9 &&
         std::all_of(component.begin(), component.end(),
                     [](char c) { return c >= '0' && c <= '9'; });
}

std::string describe_kind(const YamlNode& node) {
  switch (node.kind) {
    case YamlNode::Kind::Null:
      return "an empty value";
    case YamlNode::Kind::Sequence:
      return "a list";
    case YamlNode::Kind::Map:
      return "a map";
    case YamlNode::Kind::Scalar:
      break;
  }
  return node.quoted ? "a quoted string" : fmt::format("'{}'", node.text);
}

/// The text of a YAML plain scalar that reads as a number: [sign] digits [. digits] [exponent].
bool looks_like_number(std::string_view text) {
  std::size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  std::size_t digits = 0;
  while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])))
    ++i, ++digits;
  if (i < text.size() && text[i] == '.') {
    ++i;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])))
      ++i, ++digits;
  }
  if (digits == 0) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    std::size_t exponent_digits = 0;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) {
      ++i, ++exponent_digits;
    }
    if (exponent_digits == 0) return false;
  }
  return i == text.size();
}

bool looks_like_non_finite(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (!text.empty() && (text[0] == '+' || text[0] == '-')) text.erase(0, 1);
  return text == ".nan" || text == "nan" || text == ".inf" || text == "inf" || text == "infinity";
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // One rolling row of the Levenshtein table; keys are short, so this is cheap.
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const std::size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      row[j] = std::min({above + 1, row[j - 1] + 1, substitution});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string format_bound(double bound) {
  return fmt::format("{}", bound);
}

}  // namespace

const YamlNode* YamlNode::find(std::string_view name) const {
  if (kind != Kind::Map) return nullptr;
  for (const YamlNode& child : children) {
    if (child.key == name) return &child;
  }
  return nullptr;
}

YamlNode* YamlNode::find(std::string_view name) {
  return const_cast<YamlNode*>(std::as_const(*this).find(name));
}

YamlNode parse_yaml(const std::string& text, const std::string& file_name) {
  YAML::Node document;
  try {
    document = YAML::Load(text);
  } catch (const YAML::ParserException& error) {
    throw InputError(location_of(error.mark, Origin{file_name, true, ""}), "", "",
                     fmt::format("YAML syntax error: {}", error.msg),
                     "well-formed YAML (check indentation, brackets and colons)");
  }
  const SourceLocation top{file_name, document.IsNull() ? 0 : document.Mark().line + 1,
                           document.IsNull() ? 0 : document.Mark().column + 1};
  const Origin origin{file_name, true, ""};
  refuse_oversized(document, origin);
  return convert(document, origin, "", top);
}

void apply_override(YamlNode& root, const std::string& key, const std::string& value_text) {
  const std::string override_text = key + "=" + value_text;
  const SourceLocation path_location{"<--set>", 0, 0};
  const SourceLocation value_location{"<--set " + override_text + ">", 0, 0};
  const auto bad_path = [&](const std::string& problem, const std::string& allowed) {
    throw InputError(path_location, key, override_text, problem, allowed);
  };

  YAML::Node parsed;
  try {
    parsed = YAML::Load(value_text);
  } catch (const YAML::ParserException& error) {
    throw InputError(value_location, key, value_text,
                     fmt::format("YAML syntax error in the value: {}", error.msg),
                     "a YAML scalar or flow value, e.g. 0.5, xmax or [0, -9.81]");
  }

  YamlNode* current = &root;
  for (const std::string& component : split_path(key)) {
    if (component.empty()) bad_path("empty component in the key path", "a.b.c");
    if (current->is_null()) {
      current->kind = is_index(component) ? YamlNode::Kind::Sequence : YamlNode::Kind::Map;
    }
    const std::string path = child_path(current->path, component);
    if (current->is_map()) {
      YamlNode* child = current->find(component);
      if (child == nullptr) {
        YamlNode added;
        added.key = component;
        added.path = path;
        added.key_from_override = true;
        mark_as_override(added, value_location, override_text);
        current->children.push_back(std::move(added));
        child = &current->children.back();
      }
      current = child;
    } else if (current->is_sequence()) {
      if (!is_index(component)) {
        bad_path(
            fmt::format("'{}' is a list, so the next key must be an item number", current->path),
            fmt::format("0 to {}", current->children.size()));
      }
      const std::size_t index = std::stoul(component);
      if (index > current->children.size()) {
        bad_path(fmt::format("'{}' has {} items, there is no item {}", current->path,
                             current->children.size(), index),
                 fmt::format("0 to {} (the last one appends)", current->children.size()));
      }
      if (index == current->children.size()) {
        YamlNode added;
        added.path = path;
        added.key_from_override = true;
        mark_as_override(added, value_location, override_text);
        current->children.push_back(std::move(added));
      }
      current = &current->children[index];
    } else {
      bad_path(fmt::format("'{}' is a single value and has no key '{}'", current->path, component),
               "a path to a map or list entry of the case schema");
    }
  }

  const Origin origin{value_location.file, false, override_text};
  refuse_oversized(parsed, origin);
  YamlNode value = convert(parsed, origin, current->path, value_location);
  mark_as_override(value, value_location, override_text);
  set_paths(value, current->path);
  value.key = current->key;
  value.key_from_override = current->key_from_override;
  // A key that was already in the file keeps its file location; the value is the override's.
  if (!current->key.empty() && !current->key_from_override) value.key_where = current->key_where;
  *current = std::move(value);
}

std::string render_value(const YamlNode& node) {
  std::string text;
  switch (node.kind) {
    case YamlNode::Kind::Null:
      return "";
    case YamlNode::Kind::Scalar:
      text = node.text;
      break;
    case YamlNode::Kind::Sequence:
    case YamlNode::Kind::Map: {
      text = node.is_map() ? "{" : "[";
      for (std::size_t i = 0; i < node.children.size() && text.size() <= kMaxRenderedLength; ++i) {
        if (i > 0) text += ", ";
        if (node.is_map()) text += node.children[i].key + ": ";
        text += render_value(node.children[i]);
      }
      text += node.is_map() ? "}" : "]";
      break;
    }
  }
  if (text.size() > kMaxRenderedLength) text = text.substr(0, kMaxRenderedLength - 3) + "...";
  return text;
}

void fail_at(const YamlNode& node, const std::string& problem, const std::string& allowed,
             bool at_key) {
  throw InputError(at_key ? node.key_where : node.where, node.path, render_value(node), problem,
                   allowed);
}

std::string closest_match(std::string_view word, const std::vector<std::string>& candidates) {
  constexpr std::size_t kMaxDistance = 2;
  std::string best;
  std::size_t best_distance = kMaxDistance + 1;
  for (const std::string& candidate : candidates) {
    const std::size_t distance = edit_distance(word, candidate);
    // A distance as long as the word itself means nothing was in common: no suggestion.
    if (distance < best_distance && distance < word.size()) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

std::string quoted_list(const std::vector<std::string>& words) {
  std::string text;
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (i > 0) text += (i + 1 == words.size()) ? " or " : ", ";
    text += "'" + words[i] + "'";
  }
  return text;
}

bool NumberRange::contains(double x) const {
  const bool above_low = low_open ? x > low : x >= low;
  const bool below_high = high_open ? x < high : x <= high;
  return above_low && below_high;
}

std::string NumberRange::describe() const {
  const bool has_low = low > -1e308;
  const bool has_high = high < 1e308;
  if (has_low && has_high) {
    return fmt::format("a number in {}{}, {}{}", low_open ? "(" : "[", format_bound(low),
                       format_bound(high), high_open ? ")" : "]");
  }
  if (has_low) return fmt::format("a number {} {}", low_open ? ">" : ">=", format_bound(low));
  if (has_high) return fmt::format("a number {} {}", high_open ? "<" : "<=", format_bound(high));
  return "a finite number";
}

YamlMap::YamlMap(const YamlNode& node) : node_(node) {
  if (!node.is_map()) {
    fail_at(node,
            fmt::format("found {} where a map (key: value entries) is needed", describe_kind(node)),
            "a map");
  }
}

const SourceLocation& YamlMap::where() const {
  return node_.key.empty() ? node_.where : node_.key_where;
}

void YamlMap::allow_only(std::initializer_list<std::string_view> allowed) const {
  allow_only(std::vector<std::string>(allowed.begin(), allowed.end()));
}

InputError YamlMap::unknown_key_error(const YamlNode& child) const {
  const std::string suggestion = closest_match(child.key, allowed_);
  const std::string hint =
      suggestion.empty() ? "" : fmt::format("; did you mean '{}'?", suggestion);
  const std::string where_text =
      node_.path.empty() ? "at the top level" : fmt::format("in '{}'", node_.path);
  if (child.key_from_override) {
    return InputError(
        SourceLocation{"<--set>", 0, 0}, child.path, child.override_text,
        fmt::format("the --set path does not exist: no key '{}' {}{}", child.key, where_text, hint),
        quoted_list(allowed_));
  }
  return InputError(child.key_where, child.path, child.key,
                    fmt::format("unknown key '{}' {}{}", child.key, where_text, hint),
                    quoted_list(allowed_));
}

void YamlMap::allow_only(const std::vector<std::string>& allowed) const {
  allowed_ = allowed;
  // Every unknown key of the map is reported, not only the first.
  std::vector<InputError> unknown;
  for (const YamlNode& child : node_.children) {
    if (std::find(allowed.begin(), allowed.end(), child.key) == allowed.end())
      unknown.push_back(unknown_key_error(child));
  }
  if (!unknown.empty()) throw InputError::combine(std::move(unknown));
}

const YamlNode& YamlMap::require(std::string_view key) const {
  if (const YamlNode* value = find(key)) return *value;
  // A required key that is missing because it was misspelt is one mistake, not two: the
  // misspelling is reported (InputError::combine drops the copy allow_only reported).
  for (const YamlNode& child : node_.children) {
    const bool unknown = std::find(allowed_.begin(), allowed_.end(), child.key) == allowed_.end();
    if (unknown && !allowed_.empty() && closest_match(child.key, allowed_) == key)
      throw unknown_key_error(child);
  }
  throw InputError(where(), child_path(node_.path, std::string(key)), "",
                   fmt::format("missing required key '{}'", key),
                   fmt::format("add '{}:' to {}", key,
                               node_.path.empty() ? "the top level" : "'" + node_.path + "'"));
}

const YamlNode& YamlMap::require_one_of(const std::vector<std::string>& keys) const {
  const YamlNode* found = nullptr;
  for (const YamlNode& child : node_.children) {
    if (std::find(keys.begin(), keys.end(), child.key) == keys.end()) continue;
    if (found != nullptr) {
      fail_at(child,
              fmt::format("'{}' and '{}' are both given; only one is allowed here", found->key,
                          child.key),
              fmt::format("exactly one of {}", quoted_list(keys)), true);
    }
    found = &child;
  }
  if (found == nullptr) {
    throw InputError(where(), node_.path, "", fmt::format("needs one of {}", quoted_list(keys)),
                     fmt::format("exactly one of {}", quoted_list(keys)));
  }
  return *found;
}

double to_number(const YamlNode& node, const NumberRange& range) {
  if (!node.is_scalar() || node.quoted) {
    fail_at(node, fmt::format("found {} where a number is needed", describe_kind(node)),
            range.describe());
  }
  if (looks_like_non_finite(node.text))
    fail_at(node, "NaN and infinity are not allowed", range.describe());
  if (!looks_like_number(node.text)) {
    fail_at(node, "not a number", range.describe() + ", e.g. 100, 0.5 or 2.0e-3");
  }
  // from_chars does not take a leading '+' and does not depend on the C locale (unlike strtod).
  const std::string_view digits =
      node.text[0] == '+' ? std::string_view(node.text).substr(1) : std::string_view(node.text);
  double value = 0.0;
  const auto [end, status] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (status != std::errc() || end != digits.data() + digits.size() || !std::isfinite(value)) {
    fail_at(node, "number too large (not finite as a double)", range.describe());
  }
  if (!range.contains(value)) fail_at(node, "out of range", range.describe());
  return value;
}

long to_integer(const YamlNode& node, long low, long high) {
  const std::string allowed = fmt::format("an integer in [{}, {}]", low, high);
  const double value = to_number(node);
  if (value != std::floor(value)) fail_at(node, "must be a whole number", allowed);
  if (value < static_cast<double>(low) || value > static_cast<double>(high)) {
    fail_at(node, "out of range", allowed);
  }
  return static_cast<long>(value);
}

bool to_bool(const YamlNode& node) {
  if (node.is_scalar() && !node.quoted) {
    if (node.text == "true" || node.text == "True" || node.text == "TRUE") return true;
    if (node.text == "false" || node.text == "False" || node.text == "FALSE") return false;
  }
  fail_at(node, fmt::format("found {} where true or false is needed", describe_kind(node)),
          "true or false");
}

std::string to_text(const YamlNode& node) {
  if (!node.is_scalar()) {
    fail_at(node, fmt::format("found {} where a single value is needed", describe_kind(node)),
            "a word or text");
  }
  return node.text;
}

std::string to_choice(const YamlNode& node, const std::vector<std::string>& allowed) {
  const std::string text = to_text(node);
  if (std::find(allowed.begin(), allowed.end(), text) != allowed.end()) return text;
  const std::string suggestion = closest_match(text, allowed);
  fail_at(node,
          suggestion.empty()
              ? "not one of the allowed words"
              : fmt::format("not one of the allowed words; did you mean '{}'?", suggestion),
          quoted_list(allowed));
}

std::string to_identifier(const YamlNode& node, std::string_view alphabet,
                          const std::string& alphabet_name) {
  const std::string text = to_text(node);
  const bool valid = !text.empty() && text.find_first_not_of(alphabet) == std::string::npos;
  if (!valid) fail_at(node, "not a valid name", alphabet_name);
  return text;
}

const std::vector<YamlNode>& to_sequence(const YamlNode& node, std::size_t min_items) {
  if (!node.is_sequence()) {
    fail_at(node, fmt::format("found {} where a list is needed", describe_kind(node)),
            min_items > 0 ? fmt::format("a list of at least {} items", min_items) : "a list");
  }
  if (node.children.size() < min_items) {
    fail_at(node, fmt::format("has {} items, too few", node.children.size()),
            fmt::format("a list of at least {} items", min_items));
  }
  return node.children;
}

}  // namespace rktsph
