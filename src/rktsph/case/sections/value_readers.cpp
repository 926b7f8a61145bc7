#include "rktsph/case/sections/value_readers.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "rktsph/case/key_spec.hpp"
#include "rktsph/core/axes.hpp"

namespace rktsph {

namespace {

/// Twice the signed area of a polygon (shoelace formula); zero for degenerate vertex lists.
double twice_signed_area(const std::vector<Vec3>& vertices) {
  double sum = 0.0;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const Vec3& a = vertices[i];
    const Vec3& b = vertices[(i + 1) % vertices.size()];
    sum += a[0] * b[1] - b[0] * a[1];
  }
  return sum;
}

std::string vertex_text(const Vec3& vertex) {
  return fmt::format("[{}, {}]", vertex[0], vertex[1]);
}

/// "edge 2 ([4, 0] to [4, 3], line 12)": edge k joins vertex k and vertex k+1 (the last closes
/// the outline); the line is that of its first vertex.
std::string edge_text(const YamlNode& polygon, const std::vector<Vec3>& vertices, std::size_t k) {
  const SourceLocation& where = polygon.children[k].where;
  const std::string line = where.line > 0 ? fmt::format(", line {}", where.line) : std::string();
  return fmt::format("edge {} ({} to {}{})", k, vertex_text(vertices[k]),
                     vertex_text(vertices[(k + 1) % vertices.size()]), line);
}

/// Sign of the turn a -> b -> c: +1 left, -1 right, 0 collinear.
int orientation(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  return (cross > 0.0) - (cross < 0.0);
}

/// True if every vertex lies on the line through the first two (which differ: no vertex repeats).
bool all_on_one_line(const std::vector<Vec3>& vertices) {
  for (std::size_t k = 2; k < vertices.size(); ++k)
    if (orientation(vertices[0], vertices[1], vertices[k]) != 0) return false;
  return true;
}

/// For p collinear with segment [a, b]: p lies within its bounding box, i.e. on the segment.
bool on_segment(const Vec3& a, const Vec3& b, const Vec3& p) {
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) &&
         std::min(a[1], b[1]) <= p[1] && p[1] <= std::max(a[1], b[1]);
}

/// True if the closed segments [a, b] and [c, d] have a point in common.
bool segments_meet(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const int o1 = orientation(a, b, c), o2 = orientation(a, b, d);
  const int o3 = orientation(c, d, a), o4 = orientation(c, d, b);
  if (o1 != o2 && o3 != o4) return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
         (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}

/// Two vertices at the same place make a zero-length edge or a pinched outline.
void refuse_repeated_vertex(const YamlNode& polygon, const std::vector<Vec3>& vertices) {
  for (std::size_t i = 0; i < vertices.size(); ++i)
    for (std::size_t j = i + 1; j < vertices.size(); ++j) {
      if (vertices[i][0] != vertices[j][0] || vertices[i][1] != vertices[j][1]) continue;
      fail_at(polygon.children[j],
              fmt::format("vertex {} repeats vertex {} ({}, at {})", j, i, vertex_text(vertices[i]),
                          polygon.children[i].where.to_string()),
              "a simple polygon: every vertex once, the outline is closed automatically");
    }
}

/// A self-intersecting outline has no well-defined inside (the even-odd fill of the node
/// generator and the area sum then disagree), so two edges may meet only at their shared vertex.
void refuse_crossing_edges(const YamlNode& polygon, const std::vector<Vec3>& vertices) {
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& a = vertices[i];
    const Vec3& b = vertices[(i + 1) % n];
    for (std::size_t j = i + 1; j < n; ++j) {
      const Vec3& c = vertices[j];
      const Vec3& d = vertices[(j + 1) % n];
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      bool crossing = false;
      if (!adjacent) {
        crossing = segments_meet(a, b, c, d);
      } else {
        // Adjacent edges share one vertex; they overlap only if they fold back along one line.
        const Vec3& shared = j == i + 1 ? b : a;
        const Vec3& far_i = j == i + 1 ? a : b;
        const Vec3& far_j = j == i + 1 ? d : c;
        crossing = orientation(far_i, shared, far_j) == 0 &&
                   (far_i[0] - shared[0]) * (far_j[0] - shared[0]) +
                           (far_i[1] - shared[1]) * (far_j[1] - shared[1]) >
                       0.0;
      }
      if (crossing)
        fail_at(polygon,
                fmt::format("the polygon intersects itself: {} and {} cross or overlap",
                            edge_text(polygon, vertices, i), edge_text(polygon, vertices, j)),
                "a simple polygon (edges meet only at their shared vertices); split a "
                "crossing outline into several shapes");
    }
  }
}

}  // namespace

const std::vector<std::string>& reserved_group_names() {
  static const std::vector<std::string> names = {"all", "xmin", "xmax", "ymin", "ymax"};
  return names;
}

std::vector<std::string> edge_names(int dimension) {
  if (dimension == 1) return {"xmin", "xmax"};
  return {"xmin", "xmax", "ymin", "ymax"};
}

std::vector<std::string> axis_names(int dimension) {
  if (dimension == 1) return {"x"};
  return {"x", "y"};
}

bool contains(const std::vector<std::string>& list, const std::string& word) {
  return std::find(list.begin(), list.end(), word) != list.end();
}

Vec3 read_vector(const YamlNode& node, int dimension) {
  Vec3 vector{};
  // A 1-vector may be written as a plain number (e.g. `point: 10.0` in 1D).
  if (dimension == 1 && node.is_scalar()) {
    vector[0] = to_number(node);
    return vector;
  }
  const std::string allowed =
      dimension == 1 ? "one number, or a list of one number" : "a list of 2 numbers [x, y]";
  if (!node.is_sequence()) fail_at(node, "not a vector", allowed);
  const std::vector<YamlNode>& components = node.children;
  if (components.size() != static_cast<std::size_t>(dimension)) {
    fail_at(node,
            fmt::format("has {} components but the case is {}D", components.size(), dimension),
            allowed);
  }
  for (std::size_t i = 0; i < components.size(); ++i)
    vector[i] = to_number(components[i]);
  return vector;
}

std::vector<Vec3> read_polygon(const YamlNode& node, int dimension) {
  const std::vector<YamlNode>& items = to_sequence(node, 3);
  if (items.size() > kMaxPolygonVertices) {
    fail_at(node, fmt::format("the polygon has {} vertices", items.size()),
            fmt::format("at most {} vertices", kMaxPolygonVertices));
  }
  std::vector<Vec3> vertices;
  for (const YamlNode& vertex : items)
    vertices.push_back(read_vector(vertex, dimension));
  refuse_repeated_vertex(node, vertices);
  const auto zero_area = [&] {
    fail_at(node, "the polygon has zero area", "at least 3 vertices that are not all on one line");
  };
  if (all_on_one_line(vertices)) zero_area();
  // Before the area: a symmetric bow-tie's two loops cancel to zero area, and the crossing is
  // what the user must be told about.
  refuse_crossing_edges(node, vertices);
  if (twice_signed_area(vertices) == 0.0) zero_area();
  return vertices;
}

void read_box(const YamlNode& node, int dimension, Vec3& min, Vec3& max, bool strict) {
  const YamlMap box(node);
  box.allow_only({"min", "max"});
  min = read_vector(box.require("min"), dimension);
  max = read_vector(box.require("max"), dimension);
  for (int axis = 0; axis < dimension; ++axis) {
    const bool ordered = strict ? min[axis] < max[axis] : min[axis] <= max[axis];
    if (!ordered) {
      fail_at(*box.find("max"),
              fmt::format("max is not {} min in {}", strict ? "above" : "at or above",
                          axis_letter(axis)),
              strict ? "min < max in every component" : "min <= max in every component");
    }
  }
}

TimeFunction read_time_function(const YamlNode& node) {
  if (node.is_scalar()) return TimeFunction::constant(to_number(node));
  if (!node.is_map()) {
    fail_at(node, "not a time function",
            "a number, or a map such as {function: ramp, value: 1, duration: 0.5}");
  }
  const YamlMap map(node);
  // First against every key any form uses, so that a misspelt key gets its suggestion before
  // the form-specific checks below complain about what is missing.
  map.allow_only({"function", "value", "start", "duration", "points", "amplitude", "period",
                  "phase", "offset"});
  const std::string form =
      to_choice(map.require("function"), {"constant", "step", "ramp", "table", "harmonic"});
  TimeFunction function;
  const auto optional_number = [&map](const char* key, double fallback) {
    const YamlNode* value = map.find(key);
    return value ? to_number(*value) : fallback;
  };
  if (form == "constant") {
    map.allow_only({"function", "value"});
    function.kind = TimeFunction::Kind::Constant;
    function.value = to_number(map.require("value"));
  } else if (form == "step") {
    map.allow_only({"function", "value", "start"});
    function.kind = TimeFunction::Kind::Step;
    function.value = to_number(map.require("value"));
    function.start = optional_number("start", 0.0);
  } else if (form == "ramp") {
    map.allow_only({"function", "value", "start", "duration"});
    function.kind = TimeFunction::Kind::LinearRamp;
    function.value = to_number(map.require("value"));
    function.start = optional_number("start", 0.0);
    function.duration = to_number(map.require("duration"), NumberRange::positive());
  } else if (form == "table") {
    map.allow_only({"function", "points"});
    function.kind = TimeFunction::Kind::Table;
    for (const YamlNode& point : to_sequence(map.require("points"), 2)) {
      if (!point.is_sequence() || point.children.size() != 2) {
        fail_at(point, "a table point is a pair", "[time, value]");
      }
      const double time = to_number(point.children[0]);
      if (!function.table.empty() && !(time > function.table.back().first)) {
        fail_at(point.children[0], "times of a table must increase strictly",
                fmt::format("a time > {}", function.table.back().first));
      }
      function.table.emplace_back(time, to_number(point.children[1]));
    }
  } else {
    map.allow_only({"function", "amplitude", "period", "phase", "offset", "start"});
    function.kind = TimeFunction::Kind::Harmonic;
    function.amplitude = to_number(map.require("amplitude"));
    function.period = to_number(map.require("period"), NumberRange::positive());
    function.phase = optional_number("phase", 0.0);
    function.offset = optional_number("offset", 0.0);
    function.start = optional_number("start", 0.0);
  }
  return function;
}

std::array<std::optional<TimeFunction>, 3> read_components(const YamlNode& node, int dimension) {
  const YamlMap map(node);
  if (dimension == 1) {
    if (const YamlNode* y = map.find("y")) {
      fail_at(*y, "a 'y' component exists only in 2D", "'x'", true);
    }
  }
  const std::vector<std::string> axes = axis_names(dimension);
  map.allow_only(axes);
  if (node.children.empty()) {
    fail_at(node, "no component given", fmt::format("at least one of {}", quoted_list(axes)));
  }
  std::array<std::optional<TimeFunction>, 3> components;
  for (std::size_t axis = 0; axis < axes.size(); ++axis) {
    if (const YamlNode* component = map.find(axes[axis])) {
      components[axis] = read_time_function(*component);
    }
  }
  return components;
}

std::string read_group_reference(const YamlNode& node, const std::vector<GroupSpec>& groups) {
  const std::string name = to_text(node);
  std::vector<std::string> names;
  for (const GroupSpec& group : groups)
    names.push_back(group.name);
  if (contains(names, name)) return name;
  const std::string suggestion = closest_match(name, names);
  fail_at(node,
          suggestion.empty()
              ? "no group of this name is defined"
              : fmt::format("no group of this name is defined; did you mean '{}'?", suggestion),
          fmt::format("a built-in group or one defined under 'groups': {}", quoted_list(names)));
}

std::string read_label_key(const YamlNode& node) {
  const bool valid =
      !node.key.empty() && node.key.find_first_not_of(kLabelAlphabet) == std::string::npos;
  if (!valid) {
    throw InputError(node.key_where, node.path, node.key, "not a valid name", kLabelAlphabetName);
  }
  return node.key;
}

void reject_unless_2d(const YamlNode& node, int dimension, const std::string& what) {
  if (dimension != 2) {
    fail_at(node, fmt::format("{} only allowed in 2D cases", what),
            "remove it, or set dimension: 2", true);
  }
}

void emit_vector(YAML::Emitter& out, const Vec3& vector, int dimension) {
  out << YAML::Flow << YAML::BeginSeq;
  for (int axis = 0; axis < dimension; ++axis)
    out << number(vector[axis]);
  out << YAML::EndSeq;
}

void emit_time_function(YAML::Emitter& out, const TimeFunction& function) {
  if (function.kind == TimeFunction::Kind::Constant) {
    out << number(function.value);
    return;
  }
  out << YAML::Flow << YAML::BeginMap;
  switch (function.kind) {
    case TimeFunction::Kind::Constant:
      break;
    case TimeFunction::Kind::Step:
      out << YAML::Key << "function" << YAML::Value << "step";
      out << YAML::Key << "value" << YAML::Value << number(function.value);
      out << YAML::Key << "start" << YAML::Value << number(function.start);
      break;
    case TimeFunction::Kind::LinearRamp:
      out << YAML::Key << "function" << YAML::Value << "ramp";
      out << YAML::Key << "value" << YAML::Value << number(function.value);
      out << YAML::Key << "start" << YAML::Value << number(function.start);
      out << YAML::Key << "duration" << YAML::Value << number(function.duration);
      break;
    case TimeFunction::Kind::Table:
      out << YAML::Key << "function" << YAML::Value << "table";
      out << YAML::Key << "points" << YAML::Value << YAML::BeginSeq;
      for (const auto& [time, value] : function.table) {
        out << YAML::Flow << YAML::BeginSeq << number(time) << number(value) << YAML::EndSeq;
      }
      out << YAML::EndSeq;
      break;
    case TimeFunction::Kind::Harmonic:
      out << YAML::Key << "function" << YAML::Value << "harmonic";
      out << YAML::Key << "amplitude" << YAML::Value << number(function.amplitude);
      out << YAML::Key << "period" << YAML::Value << number(function.period);
      out << YAML::Key << "phase" << YAML::Value << number(function.phase);
      out << YAML::Key << "offset" << YAML::Value << number(function.offset);
      out << YAML::Key << "start" << YAML::Value << number(function.start);
      break;
  }
  out << YAML::EndMap;
}

void emit_components(YAML::Emitter& out, const std::array<std::optional<TimeFunction>, 3>& values,
                     int dimension) {
  static const char* const kAxes[] = {"x", "y", "z"};
  out << YAML::BeginMap;
  for (int axis = 0; axis < dimension; ++axis) {
    if (!values[axis]) continue;
    out << YAML::Key << kAxes[axis] << YAML::Value;
    emit_time_function(out, *values[axis]);
  }
  out << YAML::EndMap;
}

}  // namespace rktsph
