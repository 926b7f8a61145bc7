// The `groups` section: named sets of nodes, each chosen by exactly one selector, and the built-in
// groups (docs/input-reference.md, "groups").
#include <fmt/format.h>

#include "rktsph/case/sections/sections.hpp"
#include "rktsph/case/sections/value_readers.hpp"

namespace rktsph {

namespace {

const std::vector<std::string> kSelectors = {"edge", "box", "polygon", "point", "physical"};

void read_edge(const YamlNode& edge, GroupSpec& group, Reading& reading) {
  const int dimension = reading.so_far.dimension;
  if (dimension == 1 && (to_text(edge) == "ymin" || to_text(edge) == "ymax")) {
    fail_at(edge, "edges ymin and ymax exist only in 2D", quoted_list(edge_names(1)));
  }
  group.kind = GroupSpec::Kind::Edge;
  group.edge = to_choice(edge, edge_names(dimension));
}

void emit_edge(YAML::Emitter& out, const GroupSpec& group, const CaseDescription&) {
  if (group.kind == GroupSpec::Kind::Edge) out << YAML::Key << "edge" << YAML::Value << group.edge;
}

void emit_box(YAML::Emitter& out, const GroupSpec& group, const CaseDescription& description) {
  if (group.kind != GroupSpec::Kind::Box) return;
  out << YAML::Key << "box" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "min" << YAML::Value;
  emit_vector(out, group.min, description.dimension);
  out << YAML::Key << "max" << YAML::Value;
  emit_vector(out, group.max, description.dimension);
  out << YAML::EndMap;
}

void emit_group_polygon(YAML::Emitter& out, const GroupSpec& group,
                        const CaseDescription& description) {
  if (group.kind != GroupSpec::Kind::Polygon) return;
  out << YAML::Key << "polygon" << YAML::Value << YAML::BeginSeq;
  for (const Vec3& vertex : group.vertices)
    emit_vector(out, vertex, description.dimension);
  out << YAML::EndSeq;
}

void emit_point(YAML::Emitter& out, const GroupSpec& group, const CaseDescription& description) {
  if (group.kind != GroupSpec::Kind::Point) return;
  out << YAML::Key << "point" << YAML::Value;
  emit_vector(out, group.point, description.dimension);
}

const KeyTable<GroupSpec>& group_keys() {
  static const KeyTable<GroupSpec> keys = {
      section_key<GroupSpec>("edge", "word", "one selector", "xmin, xmax; ymin, ymax 2D only",
                             "The nodes on that side of the body's bounding box.", read_edge,
                             emit_edge),
      in_unit(
          section_key<GroupSpec>(
              "box", "{min: vector, max: vector}", "one selector", "min ≤ max in every component",
              "Nodes inside the box, boundary included (tolerance 1e-6 dx).",
              [](const YamlNode& node, GroupSpec& group, Reading& reading) {
                group.kind = GroupSpec::Kind::Box;
                read_box(node, reading.so_far.dimension, group.min, group.max, false);
              },
              emit_box),
          "m"),
      in_unit(section_key<GroupSpec>(
                  "polygon", "list of vectors", "one selector",
                  "2D only; ≥ 3 vertices, non-zero area, simple",
                  "Nodes inside the polygon, boundary included.",
                  [](const YamlNode& node, GroupSpec& group, Reading& reading) {
                    reject_unless_2d(node, reading.so_far.dimension, "polygon groups are");
                    group.kind = GroupSpec::Kind::Polygon;
                    group.vertices = read_polygon(node, reading.so_far.dimension);
                  },
                  emit_group_polygon),
              "m"),
      in_unit(
          section_key<GroupSpec>(
              "point", "vector", "one selector", "within half a spacing of a node along every axis",
              "The one node nearest to the point.",
              [](const YamlNode& node, GroupSpec& group, Reading& reading) {
                group.kind = GroupSpec::Kind::Point;
                group.point = read_vector(node, reading.so_far.dimension);
              },
              emit_point),
          "m"),
      section_key<GroupSpec>(
          "physical", "text", "one selector", "the name of a physical group of geometry.mesh",
          "The nodes of the mesh file's physical point, curve or surface of that name.",
          [](const YamlNode& node, GroupSpec& group, Reading& reading) {
            if (reading.so_far.geometry.mesh.empty())
              fail_at(node, "physical groups belong to a mesh file, and the case has none",
                      "box, polygon, point or edge; or geometry.mesh");
            group.kind = GroupSpec::Kind::Physical;
            group.physical = to_text(node);
          },
          [](YAML::Emitter& out, const GroupSpec& group, const CaseDescription&) {
            if (group.kind == GroupSpec::Kind::Physical)
              out << YAML::Key << "physical" << YAML::Value << group.physical;
          }),
  };
  return keys;
}

GroupSpec read_group(const YamlNode& node, Reading& reading) {
  GroupSpec group;
  group.name = read_label_key(node);
  if (contains(reserved_group_names(), group.name)) {
    throw InputError(
        node.key_where, node.path, group.name,
        "this is a built-in group name and may not be redefined",
        fmt::format("any other name; built-in groups are {}", quoted_list(reserved_group_names())));
  }
  const YamlMap selector_map(node);
  selector_map.allow_only(kSelectors);
  group.where = selector_map.where();
  const YamlNode& selector = selector_map.require_one_of(kSelectors);
  for (const Key<GroupSpec>& key : group_keys())
    if (key.name == selector.key) key.read(selector, group, reading);
  return group;
}

void read_groups(const YamlNode& node, CaseDescription& description, Reading& reading) {
  const YamlMap groups(node);
  for (const YamlNode& entry : node.children) {
    try {
      description.groups.push_back(read_group(entry, reading));
    } catch (const InputError& error) {
      reading.errors.add(error);
      // Known by name all the same, so that conditions and probes using it add no second error.
      GroupSpec placeholder;
      placeholder.name = entry.key;
      description.groups.push_back(placeholder);
    }
  }
}

void emit_groups(YAML::Emitter& out, const CaseDescription& description, const CaseDescription&) {
  std::vector<const GroupSpec*> defined;
  for (const GroupSpec& group : description.groups) {
    if (!contains(reserved_group_names(), group.name)) defined.push_back(&group);
  }
  if (defined.empty()) return;
  out << YAML::Key << "groups" << YAML::Value << YAML::BeginMap;
  for (const GroupSpec* group : defined) {
    out << YAML::Key << group->name << YAML::Value << YAML::Flow << YAML::BeginMap;
    emit_keys(out, group_keys(), *group, description);
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

}  // namespace

Key<CaseDescription> groups_section() {
  return section_key<CaseDescription>(
      "groups", "map", "the built-in groups", "names of letters, digits, _ and -",
      "Named sets of nodes, for boundary conditions and probes.", read_groups, emit_groups);
}

void add_built_in_groups(CaseDescription& description) {
  const SourceLocation built_in{description.file, 0, 0};
  GroupSpec all;
  all.name = "all";
  all.kind = GroupSpec::Kind::All;
  all.where = built_in;
  description.groups.push_back(all);
  for (const std::string& edge : edge_names(description.dimension)) {
    GroupSpec group;
    group.name = group.edge = edge;
    group.kind = GroupSpec::Kind::Edge;
    group.where = built_in;
    description.groups.push_back(group);
  }
}

void declare_group_keys(std::vector<DeclaredKey>& list) {
  declare(list, "groups.<name>.", group_keys());
}

}  // namespace rktsph
