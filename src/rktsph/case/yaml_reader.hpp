// A YAML tree that remembers where every key and value was written, and typed accessors that turn
// every problem into an InputError at the right file, line and column.
//
// yaml-cpp keeps marks on its nodes, but not for keys that are missing, not for values that were
// replaced by a command-line override, and it silently accepts duplicate keys. So the document is
// copied once into YamlNode, which carries its dotted path, the location of its key and of its
// value, and (for --set overrides) the override text in place of a file position.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "rktsph/core/error.hpp"

namespace rktsph {

struct YamlNode {
  enum class Kind { Null, Scalar, Sequence, Map };
  Kind kind = Kind::Null;
  std::string text;     ///< Scalar: the text as written (without quotes)
  bool quoted = false;  ///< Scalar written in quotes: always a string, never a number or bool
  /// Sequence: the items. Map: the values, in document order, each with its `key`.
  std::vector<YamlNode> children;
  std::string key;                 ///< for a map value: its key; empty otherwise
  std::string path;                ///< dotted path from the root, sequence items by index
  SourceLocation where;            ///< of the value
  SourceLocation key_where;        ///< of the key for a map value, else the same as `where`
  std::string override_text;       ///< "key=value" when this node was written by a --set override
  bool key_from_override = false;  ///< the key itself did not exist before the override

  bool is_null() const { return kind == Kind::Null; }
  bool is_scalar() const { return kind == Kind::Scalar; }
  bool is_sequence() const { return kind == Kind::Sequence; }
  bool is_map() const { return kind == Kind::Map; }

  /// Map only: the value stored under `name`, or nullptr.
  const YamlNode* find(std::string_view name) const;
  YamlNode* find(std::string_view name);
};

/// Most values (scalars, lists and maps, counted after YAML aliases are expanded) a document may
/// hold: bundled cases hold a few hundred, and at about 0.4 KB per converted value this keeps a
/// hostile file of nested aliases to some 40 MB and a fraction of a second.
inline constexpr std::size_t kMaxYamlValues = 100000;
/// The deepest nesting a case file may have once aliases are expanded: cases nest about six levels,
/// and an alias inside its own anchor (`&a [*a]`) nests without end, which would overflow the stack
/// of the walks over the tree.
inline constexpr int kMaxYamlDepth = 64;

/// Parses `text` (a whole case file) into a located tree. A syntax error, a duplicate key, a
/// non-scalar map key or more than kMaxYamlValues values becomes an InputError at the offending
/// position of `file_name`.
YamlNode parse_yaml(const std::string& text, const std::string& file_name);

/// Writes `value_text` (YAML scalar or flow text) at the dotted `key` path of `root`, creating maps
/// (and, for a numeric component under a new node, sequences) on the way. A numeric component may
/// address an existing sequence item or the one just past the end (to append). Errors in the path
/// are reported against file "<--set>", errors in the value text against "<--set key=value>".
void apply_override(YamlNode& root, const std::string& key, const std::string& value_text);

/// A short, one-line rendering of a node for error messages ("0.5", "[0, 10]", "{min: [0, 0]}").
std::string render_value(const YamlNode& node);

/// Throws an InputError about `node`: at its value, or at its key when `at_key` is set.
[[noreturn]] void fail_at(const YamlNode& node, const std::string& problem,
                          const std::string& allowed, bool at_key = false);

/// The entry of `candidates` closest to `word` by edit distance, if that distance is <= 2; else "".
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);

/// "'a', 'b' or 'c'"
std::string quoted_list(const std::vector<std::string>& words);

/// A closed/open interval on the real line for range checks, with a readable description.
struct NumberRange {
  double low = -1e308;
  double high = 1e308;
  bool low_open = false;
  bool high_open = false;

  static NumberRange positive() { return {0.0, 1e308, true, false}; }
  static NumberRange non_negative() { return {0.0, 1e308, false, false}; }
  static NumberRange any() { return {}; }

  bool contains(double x) const;
  std::string describe() const;  ///< e.g. "a number in (0, 1.5]" or "a number > 0"
};

/// Reads one map of the case file: checks its keys against the allowed list and hands out values.
class YamlMap {
 public:
  /// InputError (wrong type) if `node` is not a map.
  explicit YamlMap(const YamlNode& node);

  const YamlNode& node() const { return node_; }
  const std::string& path() const { return node_.path; }
  /// Where errors about the map as a whole go: its key if it has one, else its first entry.
  const SourceLocation& where() const;

  /// Every key must be one of `allowed`; otherwise an InputError at that key with the closest
  /// allowed key and the full list. A key added by a --set override is reported as a bad path.
  void allow_only(std::initializer_list<std::string_view> allowed) const;
  void allow_only(const std::vector<std::string>& allowed) const;

  const YamlNode* find(std::string_view key) const { return node_.find(key); }
  /// InputError at the map's location if `key` is missing.
  const YamlNode& require(std::string_view key) const;

  /// Of `keys`, the one present; InputError unless exactly one is (none, or two or more).
  const YamlNode& require_one_of(const std::vector<std::string>& keys) const;

 private:
  InputError unknown_key_error(const YamlNode& child) const;

  const YamlNode& node_;
  /// The keys given to allow_only, if it was called: require() uses them to tell a misspelt
  /// required key from a missing one.
  mutable std::vector<std::string> allowed_;
};

// Typed scalar reads. Each throws an InputError at the value (wrong type or out of range).
double to_number(const YamlNode& node, const NumberRange& range = NumberRange::any());
/// An integer in [low, high]; integral floats such as 1e6 are accepted.
long to_integer(const YamlNode& node, long low, long high);
bool to_bool(const YamlNode& node);
/// Any scalar, as text.
std::string to_text(const YamlNode& node);
/// A scalar that is one of `allowed`.
std::string to_choice(const YamlNode& node, const std::vector<std::string>& allowed);
/// A non-empty scalar made only of the characters in `alphabet` (described by `alphabet_name`).
std::string to_identifier(const YamlNode& node, std::string_view alphabet,
                          const std::string& alphabet_name);
/// The items of a sequence; InputError if it is not one, or if it has fewer than `min_items`.
const std::vector<YamlNode>& to_sequence(const YamlNode& node, std::size_t min_items = 0);

}  // namespace rktsph
