// The `geometry` section: the spacing, the kind of cells and the shapes they fill
// (docs/input-reference.md, "geometry").
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "rktsph/case/sections/sections.hpp"
#include "rktsph/case/sections/value_readers.hpp"

namespace rktsph {

namespace {

const std::vector<std::string> kOutlines = {"segment", "rectangle", "polygon"};

void read_segment(const YamlNode& outline, ShapeSpec& shape, Reading& reading) {
  if (reading.so_far.dimension != 1) {
    fail_at(outline, "'segment' shapes exist only in 1D", "'rectangle' or 'polygon' in 2D", true);
  }
  const std::vector<YamlNode>& ends = to_sequence(outline, 2);
  if (ends.size() != 2) fail_at(outline, "a segment has exactly two ends", "[from, to]");
  const double from = to_number(ends[0]);
  const double to = to_number(ends[1]);
  if (!(from < to))
    fail_at(outline, "the segment is empty or reversed", "[from, to] with from < to");
  shape.kind = ShapeSpec::Kind::Segment;
  shape.vertices = {Vec3{from, 0.0, 0.0}, Vec3{to, 0.0, 0.0}};
}

void read_rectangle(const YamlNode& outline, ShapeSpec& shape, Reading& reading) {
  reject_unless_2d(outline, reading.so_far.dimension, "'rectangle' shapes are");
  Vec3 min{}, max{};
  read_box(outline, reading.so_far.dimension, min, max, true);
  shape.kind = ShapeSpec::Kind::Rectangle;
  shape.vertices = {min, max};
}

void read_polygon_outline(const YamlNode& outline, ShapeSpec& shape, Reading& reading) {
  reject_unless_2d(outline, reading.so_far.dimension, "'polygon' shapes are");
  shape.kind = ShapeSpec::Kind::Polygon;
  shape.vertices = read_polygon(outline, reading.so_far.dimension);
}

void read_shape_material(const YamlNode& material, ShapeSpec& shape, Reading& reading) {
  shape.material = to_text(material);
  const auto& materials = reading.so_far.materials;
  if (!reading.materials_complete || materials.count(shape.material) != 0) return;
  std::vector<std::string> names;
  for (const auto& [name, block] : materials)
    names.push_back(name);
  const std::string suggestion = closest_match(shape.material, names);
  fail_at(material,
          suggestion.empty() ? "no material of this name is defined in 'materials'"
                             : fmt::format("no material of this name is defined in "
                                           "'materials'; did you mean '{}'?",
                                           suggestion),
          quoted_list(names));
}

void emit_segment(YAML::Emitter& out, const ShapeSpec& shape, const CaseDescription&) {
  if (shape.kind != ShapeSpec::Kind::Segment) return;
  out << YAML::Key << "segment" << YAML::Value << YAML::Flow << YAML::BeginSeq
      << number(shape.vertices.at(0)[0]) << number(shape.vertices.at(1)[0]) << YAML::EndSeq;
}

void emit_rectangle(YAML::Emitter& out, const ShapeSpec& shape,
                    const CaseDescription& description) {
  if (shape.kind != ShapeSpec::Kind::Rectangle) return;
  out << YAML::Key << "rectangle" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "min" << YAML::Value;
  emit_vector(out, shape.vertices.at(0), description.dimension);
  out << YAML::Key << "max" << YAML::Value;
  emit_vector(out, shape.vertices.at(1), description.dimension);
  out << YAML::EndMap;
}

void emit_shape_polygon(YAML::Emitter& out, const ShapeSpec& shape,
                        const CaseDescription& description) {
  if (shape.kind != ShapeSpec::Kind::Polygon) return;
  out << YAML::Key << "polygon" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const Vec3& vertex : shape.vertices)
    emit_vector(out, vertex, description.dimension);
  out << YAML::EndSeq;
}

const KeyTable<ShapeSpec>& shape_keys() {
  static const KeyTable<ShapeSpec> keys = {
      in_unit(section_key<ShapeSpec>("segment", "[from, to]", "one outline", "1D only; from < to",
                                     "The interval [from, to] of x.", read_segment, emit_segment),
              "m"),
      in_unit(section_key<ShapeSpec>("rectangle", "{min: vector, max: vector}", "one outline",
                                     "2D only; min < max in x and in y", "Axis-aligned rectangle.",
                                     read_rectangle, emit_rectangle),
              "m"),
      in_unit(section_key<ShapeSpec>("polygon", "list of vectors", "one outline",
                                     "2D only; 3 to 10 000 vertices, non-zero area, simple",
                                     "Vertices in order, either sense; the outline is closed "
                                     "automatically.",
                                     read_polygon_outline, emit_shape_polygon),
              "m"),
      section_key<ShapeSpec>(
          "material", "word", "required", "a key of materials", "The material of the shape.",
          read_shape_material,
          [](YAML::Emitter& out, const ShapeSpec& shape, const CaseDescription&) {
            out << YAML::Key << "material" << YAML::Value << shape.material;
          }),
  };
  return keys;
}

ShapeSpec read_shape(const YamlNode& node, Reading& reading) {
  const YamlMap item(node);
  // A misspelt key first, then the outline: a shape with a wrong outline is not read further.
  item.allow_only(key_names(shape_keys()));
  item.require_one_of(kOutlines);
  ShapeSpec shape;
  shape.where = item.where();
  ErrorList errors;
  Reading shape_reading{reading.so_far, errors, reading.materials_complete};
  read_keys(node, shape_keys(), shape, shape_reading);
  if (!errors.empty()) throw InputError::combine(errors.take());
  return shape;
}

// The cells the shapes are cut into (docs/theory.md §3.1, §3.6); triangles are 2D only.
Key<GeometrySpec> cells_key() {
  Key<GeometrySpec> key = choice_key<GeometrySpec, CellLayout>(
      "cells", &GeometrySpec::cells,
      {{"lattice", CellLayout::Lattice}, {"triangles", CellLayout::Triangles}},
      "Square lattice cells (shape vertices on lattice points), or triangles of edges at most "
      "spacing with vertices anywhere (2D only).");
  const auto read_choice = key.read;
  key.read = [read_choice](const YamlNode& node, GeometrySpec& geometry, Reading& reading) {
    read_choice(node, geometry, reading);
    if (geometry.cells == CellLayout::Triangles)
      reject_unless_2d(node, reading.so_far.dimension, "'cells: triangles' is");
  };
  return key;
}

// The spacing: required with shapes; with a mesh file it is the mesh's own (its longest edge),
// so it is neither given nor written back.
Key<GeometrySpec> spacing_key() {
  Key<GeometrySpec> key = number_key<GeometrySpec>(
      "spacing", &GeometrySpec::spacing, NumberRange::positive(), "m",
      "Lattice spacing dx; with cells: triangles, the longest edge; not given with mesh (the "
      "mesh's longest edge).");
  key.default_value = "required with shapes";
  const auto emit_number = key.emit;
  key.emit = [emit_number](YAML::Emitter& out, const GeometrySpec& geometry,
                           const CaseDescription& description) {
    if (geometry.mesh.empty()) emit_number(out, geometry, description);
  };
  return key;
}

// A Gmsh mesh file instead of shapes (docs/theory.md §3.8). The path is resolved against the case
// file's folder when read, and written back resolved, so that the copy of the case in a run's
// folder names the same file.
Key<GeometrySpec> mesh_key() {
  return section_key<GeometrySpec>(
      "mesh", "text", "none", "a Gmsh .msh file (MSH 2.2 or 4.1, ASCII) of 3-node triangles",
      "Instead of shapes: the triangles of a Gmsh mesh, each of the material its physical surface "
      "names; a path relative to the case file's folder.",
      [](const YamlNode& node, GeometrySpec& geometry, Reading& reading) {
        const std::string text = to_text(node);
        if (text.empty()) fail_at(node, "the mesh file's path is empty", "a path to a .msh file");
        std::filesystem::path path(text);
        if (path.is_relative() && !reading.so_far.file.empty())
          path = std::filesystem::path(reading.so_far.file).parent_path() / path;
        geometry.mesh = path.lexically_normal().string();
        geometry.mesh_where = node.where;
      },
      [](YAML::Emitter& out, const GeometrySpec& geometry, const CaseDescription&) {
        if (geometry.mesh.empty()) return;
        out << YAML::Key << "mesh" << YAML::Value
            << std::filesystem::absolute(geometry.mesh).lexically_normal().string();
      });
}

const KeyTable<GeometrySpec>& geometry_keys();

/// Shapes or a mesh, and what each asks of the other keys.
void check_shapes_or_mesh(const YamlNode& node, GeometrySpec& geometry, Reading& reading) {
  const YamlMap map(node);
  map.require_one_of({"shapes", "mesh"});
  if (geometry.mesh.empty()) {
    // A misspelt spacing is reported as such by read_keys; not again as missing.
    const std::vector<std::string> known = key_names(geometry_keys());
    const bool misspelt =
        std::any_of(node.children.begin(), node.children.end(), [&](const YamlNode& child) {
          return std::find(known.begin(), known.end(), child.key) == known.end();
        });
    if (!misspelt) map.require("spacing");
    return;
  }
  if (const YamlNode* spacing = map.find("spacing"))
    fail_at(*spacing, "a mesh file brings its own spacing (its longest edge)",
            "no spacing with mesh; refine the mesh in Gmsh instead");
  if (const YamlNode* cells = map.find("cells"); cells && geometry.cells != CellLayout::Triangles)
    fail_at(*cells, "a mesh file holds triangles", "cells: triangles, or no cells key with mesh");
  if (reading.so_far.dimension != 2)
    fail_at(*map.find("mesh"), "a mesh file is read in 2D cases only", "dimension: 2");
  geometry.cells = CellLayout::Triangles;
}

const KeyTable<GeometrySpec>& geometry_keys() {
  static const KeyTable<GeometrySpec> keys = {
      spacing_key(),
      cells_key(),
      mesh_key(),
      section_key<GeometrySpec>(
          "shapes", "list", "required without mesh", "≥ 1 item",
          "The shapes, in order; where they overlap, the later shape's material wins.",
          [](const YamlNode& node, GeometrySpec& geometry, Reading& reading) {
            for (const YamlNode& item : to_sequence(node, 1))
              reading.errors.attempt([&] { geometry.shapes.push_back(read_shape(item, reading)); });
          },
          [](YAML::Emitter& out, const GeometrySpec& geometry, const CaseDescription& description) {
            if (geometry.shapes.empty()) return;  // a mesh file instead
            out << YAML::Key << "shapes" << YAML::Value << YAML::BeginSeq;
            for (const ShapeSpec& shape : geometry.shapes) {
              out << YAML::BeginMap;
              emit_keys(out, shape_keys(), shape, description);
              out << YAML::EndMap;
            }
            out << YAML::EndSeq;
          }),
  };
  return keys;
}

}  // namespace

Key<CaseDescription> geometry_section() {
  return section_key<CaseDescription>(
      "geometry", "map", "required", "",
      "The cells: a lattice or triangles filling shapes, or a mesh file.",
      [](const YamlNode& node, CaseDescription& description, Reading& reading) {
        description.geometry.where = YamlMap(node).where();
        read_keys(node, geometry_keys(), description.geometry, reading);
        reading.errors.attempt([&] { check_shapes_or_mesh(node, description.geometry, reading); });
      },
      [](YAML::Emitter& out, const CaseDescription& description, const CaseDescription&) {
        out << YAML::Key << "geometry" << YAML::Value << YAML::BeginMap;
        emit_keys(out, geometry_keys(), description.geometry, description);
        out << YAML::EndMap;
      });
}

void declare_geometry_keys(std::vector<DeclaredKey>& list) {
  declare(list, "geometry.", geometry_keys());
  declare(list, "geometry.shapes[].", shape_keys());
}

}  // namespace rktsph
