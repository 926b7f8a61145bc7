// Values that several sections of the case file share: vectors, boxes, polygons, time functions,
// references to groups, and how the resolved case writes them (docs/input-reference.md).
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rktsph/case/case_description.hpp"
#include "rktsph/case/yaml_reader.hpp"

namespace rktsph {

// Character sets of names. Case names become file and directory names, hence the narrow set.
inline constexpr std::string_view kCaseNameAlphabet = "abcdefghijklmnopqrstuvwxyz0123456789-";
inline constexpr std::string_view kLabelAlphabet =
    "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-";
inline constexpr std::string_view kFieldAlphabet = "abcdefghijklmnopqrstuvwxyz0123456789_";
inline constexpr const char* kLabelAlphabetName =
    "a non-empty name of letters, digits, '_' and '-'";

/// Most vertices of one polygon; the edge-crossing test costs n^2/2 segment pairs.
inline constexpr std::size_t kMaxPolygonVertices = 10000;

/// Names that are always defined and so may not name a user group. ymin and ymax are reserved
/// in 1D too, so that a 2D case turned into 1D cannot silently change their meaning.
const std::vector<std::string>& reserved_group_names();

std::vector<std::string> edge_names(int dimension);
std::vector<std::string> axis_names(int dimension);
bool contains(const std::vector<std::string>& list, const std::string& word);

/// A vector of `dimension` numbers; in 1D also a plain number.
Vec3 read_vector(const YamlNode& node, int dimension);
/// A simple polygon of 3 to kMaxPolygonVertices vertices with non-zero area (2D).
std::vector<Vec3> read_polygon(const YamlNode& node, int dimension);
/// {min: vector, max: vector}, min < max (`strict`) or min <= max in every component.
void read_box(const YamlNode& node, int dimension, Vec3& min, Vec3& max, bool strict);
/// A number, or a map with `function:` and its parameters (docs, "Time functions").
TimeFunction read_time_function(const YamlNode& node);
/// A map of components x (and y in 2D), each a time function; at least one.
std::array<std::optional<TimeFunction>, 3> read_components(const YamlNode& node, int dimension);
/// The name of a built-in group or of one defined under `groups`.
std::string read_group_reference(const YamlNode& node, const std::vector<GroupSpec>& groups);
/// The key of `node` as a name of kLabelAlphabet.
std::string read_label_key(const YamlNode& node);
/// `what` is the subject with its verb, e.g. "'plane' is".
void reject_unless_2d(const YamlNode& node, int dimension, const std::string& what);

void emit_vector(YAML::Emitter& out, const Vec3& vector, int dimension);
void emit_time_function(YAML::Emitter& out, const TimeFunction& function);
void emit_components(YAML::Emitter& out, const std::array<std::optional<TimeFunction>, 3>& values,
                     int dimension);

}  // namespace rktsph
