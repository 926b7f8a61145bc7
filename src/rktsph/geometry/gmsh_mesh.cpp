#include "rktsph/geometry/gmsh_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <sstream>
#include <string_view>
#include <unordered_map>

namespace rktsph {

namespace {

constexpr int kLineElement = 1, kTriangleElement = 2, kPointElement = 15;

/// The names of the element types a user is likely to export by mistake (Gmsh's numbering).
std::string element_type_name(long type) {
  static const std::map<long, std::string> names = {{3, "4-node quadrangle"},
                                                    {4, "4-node tetrahedron"},
                                                    {5, "8-node hexahedron"},
                                                    {6, "6-node prism"},
                                                    {7, "5-node pyramid"},
                                                    {8, "3-node second-order line"},
                                                    {9, "6-node second-order triangle"},
                                                    {10, "9-node second-order quadrangle"},
                                                    {16, "8-node second-order quadrangle"},
                                                    {21, "10-node third-order triangle"}};
  const auto found = names.find(type);
  return found == names.end() ? fmt::format("element type {}", type) : found->second;
}

/// The file as numbered lines of whitespace-separated tokens, read one at a time, so that every
/// mistake is reported at its line.
class MeshText {
 public:
  MeshText(std::filesystem::path file, const SourceLocation& where) : file_(std::move(file)) {
    // A directory or a device (/dev/zero would be read for ever) is no mesh file.
    std::error_code status;
    if (!std::filesystem::is_regular_file(file_, status))
      throw InputError(where, "geometry.mesh", file_.string(),
                       std::filesystem::exists(file_, status)
                           ? "this is not a regular file"
                           : "no file of this name (relative paths start at the case file's "
                             "folder)",
                       "the path of a Gmsh .msh file");
    std::ifstream in(file_, std::ios::binary);
    if (!in)
      throw InputError(where, "geometry.mesh", file_.string(), "the mesh file cannot be read",
                       "the path of a Gmsh .msh file, relative to the case file's folder");
    std::string line;
    while (std::getline(in, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      lines_.push_back(std::move(line));
    }
  }

  /// False once only blank lines are left.
  bool has_more() {
    while (row_ < lines_.size() && blank(lines_[row_]))
      ++row_;
    return row_ < lines_.size();
  }
  int line_number() const { return static_cast<int>(row_) + 1; }

  /// The next non-empty line, split into tokens; `what` names what it should hold.
  std::vector<std::string_view> next_line(std::string_view what) {
    while (row_ < lines_.size() && blank(lines_[row_]))
      ++row_;
    if (row_ >= lines_.size())
      fail(fmt::format("the file ends where {} should follow", what), "a complete Gmsh mesh");
    current_ = row_++;
    return split(lines_[current_]);
  }

  [[noreturn]] void fail(const std::string& problem, const std::string& allowed) const {
    SourceLocation location{file_.string(), static_cast<int>(current_) + 1, 0};
    throw InputError(location, "geometry.mesh", lines_.empty() ? "" : excerpt(), problem, allowed);
  }

  long integer(std::string_view token, std::string_view what) const {
    long value = 0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (error != std::errc() || end != token.data() + token.size())
      fail(fmt::format("'{}' is not an integer ({})", token, what), "an integer");
    return value;
  }

  double number(std::string_view token, std::string_view what) const {
    // std::from_chars for double is in GCC 12's library; istringstream keeps it portable.
    std::istringstream in{std::string(token)};
    in.imbue(std::locale::classic());
    double value = 0.0;
    in >> value;
    if (!in || !in.eof() || !std::isfinite(value))
      fail(fmt::format("'{}' is not a finite number ({})", token, what), "a finite number");
    return value;
  }

  /// At least `count` tokens on the line, else an error naming what they are.
  void need(const std::vector<std::string_view>& tokens, std::size_t count,
            std::string_view what) const {
    if (tokens.size() < count)
      fail(fmt::format("{} needs {} numbers on this line, found {}", what, count, tokens.size()),
           std::string(what));
  }

  /// Skips to the line `$End<section>`.
  void skip_section(std::string_view section) {
    const std::string end = fmt::format("$End{}", section);
    while (true) {
      const auto tokens = next_line(end);
      if (!tokens.empty() && tokens.front() == end) return;
    }
  }

 private:
  static bool blank(const std::string& line) {
    return line.find_first_not_of(" \t") == std::string::npos;
  }
  static std::vector<std::string_view> split(std::string_view line) {
    std::vector<std::string_view> tokens;
    std::size_t begin = 0;
    while (true) {
      begin = line.find_first_not_of(" \t", begin);
      if (begin == std::string_view::npos) break;
      const std::size_t end = line.find_first_of(" \t", begin);
      tokens.push_back(line.substr(begin, end == std::string_view::npos ? end : end - begin));
      if (end == std::string_view::npos) break;
      begin = end;
    }
    return tokens;
  }
  std::string excerpt() const {
    const std::string& line = lines_[std::min(current_, lines_.size() - 1)];
    return line.size() > 60 ? line.substr(0, 57) + "..." : line;
  }

  std::filesystem::path file_;
  std::vector<std::string> lines_;
  std::size_t row_ = 0;
  std::size_t current_ = 0;
};

/// What the sections hold before the triangles are tied to their nodes.
struct RawMesh {
  int major_version = 0;
  std::map<std::pair<long, long>, std::string> names;  // (dimension, physical tag) -> name
  // 4.1: (dimension, entity tag) -> its physical tags.
  std::map<std::pair<long, long>, std::vector<long>> entity_physicals;
  std::unordered_map<long, std::array<double, 3>> nodes;  // tag -> position
  struct Element {
    std::array<long, 3> nodes;
    long tag, physical;  // physical -1: none
    int line;
  };
  std::vector<Element> triangles;
  // The nodes of physical points and lines, by (dimension, physical tag).
  std::map<std::pair<long, long>, std::vector<long>> tagged_nodes;

  /// A physical group's name: its $PhysicalNames entry, else its tag as text.
  std::string name_of(long dimension, long physical) const {
    const auto found = names.find({dimension, physical});
    return found != names.end() ? found->second : fmt::format("{}", physical);
  }
};

/// A line of four integers: the section and block headers of MSH 4.1, `what` naming them.
std::array<long, 4> four_integers(MeshText& text, std::string_view what) {
  const auto tokens = text.next_line(what);
  text.need(tokens, 4, what);
  std::array<long, 4> values{};
  for (std::size_t k = 0; k < 4; ++k)
    values[k] = text.integer(tokens[k], what);
  return values;
}

void read_format(MeshText& text, RawMesh& mesh) {
  const auto tokens = text.next_line("the format line");
  text.need(tokens, 3, "$MeshFormat (version, file type, data size)");
  const std::string_view version = tokens[0];
  if (version.starts_with("2."))
    mesh.major_version = 2;
  else if (version == "4.1")
    mesh.major_version = 4;
  else
    text.fail(fmt::format("MSH version {} is not read", version),
              "MSH 2.2 or 4.1 (Gmsh: Mesh.MshFileVersion = 2.2 or 4.1)");
  if (tokens[1] != "0")
    text.fail("the mesh is written in binary", "an ASCII mesh (Gmsh: Mesh.Binary = 0)");
  text.skip_section("MeshFormat");
}

void read_physical_names(MeshText& text, RawMesh& mesh) {
  const long count = text.integer(text.next_line("the number of physical names")[0],
                                  "the number of physical names");
  for (long k = 0; k < count; ++k) {
    const auto tokens = text.next_line("a physical name");
    text.need(tokens, 3, "a physical name (dimension, tag, \"name\")");
    const long dimension = text.integer(tokens[0], "the dimension");
    const long tag = text.integer(tokens[1], "the physical tag");
    // The name is quoted and may hold spaces: everything between the first and last quote.
    std::string name;
    for (std::size_t t = 2; t < tokens.size(); ++t)
      name += (t > 2 ? " " : "") + std::string(tokens[t]);
    if (name.size() < 2 || name.front() != '"' || name.back() != '"')
      text.fail("a physical name is written in double quotes", "dimension tag \"name\"");
    mesh.names[{dimension, tag}] = name.substr(1, name.size() - 2);
  }
  text.skip_section("PhysicalNames");
}

/// MSH 4.1: which physical tags each surface entity carries (the elements name their entity).
void read_entities(MeshText& text, RawMesh& mesh) {
  const auto counts = text.next_line("the numbers of entities");
  text.need(counts, 4, "$Entities (points, curves, surfaces, volumes)");
  // A point is "tag x y z", a curve or surface "tag min-x y z max-x y z"; then the number of
  // physical tags and the tags (then bounding entities, not needed).
  for (long dimension = 0; dimension < 3; ++dimension) {
    const long count = text.integer(counts[static_cast<std::size_t>(dimension)], "an entity count");
    const std::size_t at = dimension == 0 ? 4 : 7;
    for (long k = 0; k < count; ++k) {
      const auto tokens = text.next_line("an entity");
      text.need(tokens, at + 1, "an entity (tag, bounds, number of physical tags)");
      const long tag = text.integer(tokens[0], "the entity's tag");
      const long physicals = text.integer(tokens[at], "the number of physical tags");
      if (physicals < 0 || tokens.size() < at + 1 + static_cast<std::size_t>(physicals))
        text.fail("the entity lists fewer physical tags than it says", "a Gmsh 4.1 mesh");
      std::vector<long>& list = mesh.entity_physicals[{dimension, tag}];
      for (long p = 0; p < physicals; ++p)
        list.push_back(
            text.integer(tokens[at + 1 + static_cast<std::size_t>(p)], "a physical tag"));
    }
  }
  text.skip_section("Entities");
}

void add_mesh_node(MeshText& text, RawMesh& mesh, long tag,
                   const std::vector<std::string_view>& xyz, std::size_t first) {
  text.need(xyz, first + 3, "a node (x, y, z)");
  const std::array<double, 3> x{text.number(xyz[first], "x"), text.number(xyz[first + 1], "y"),
                                text.number(xyz[first + 2], "z")};
  if (!mesh.nodes.emplace(tag, x).second)
    text.fail(fmt::format("node {} is defined twice", tag), "one definition per node tag");
}

void read_nodes(MeshText& text, RawMesh& mesh) {
  if (mesh.major_version == 2) {
    const long count = text.integer(text.next_line("the number of nodes")[0], "the node count");
    for (long k = 0; k < count; ++k) {
      const auto tokens = text.next_line("a node");
      add_mesh_node(text, mesh, text.integer(tokens[0], "the node tag"), tokens, 1);
    }
  } else {
    const auto header = four_integers(text, "$Nodes (blocks, nodes, smallest tag, largest tag)");
    for (long b = 0; b < header[0]; ++b) {
      const auto block = four_integers(text, "a node block (dimension, entity, parametric, count)");
      const long parametric = block[2], count = block[3];
      std::vector<long> tags;
      for (long k = 0; k < count; ++k)
        tags.push_back(text.integer(text.next_line("a node tag")[0], "a node tag"));
      for (long k = 0; k < count; ++k) {
        const auto tokens = text.next_line("a node's coordinates");
        if (parametric != 0 && tokens.size() < 4)
          text.fail("a parametric node needs its parametric coordinates", "a Gmsh 4.1 mesh");
        add_mesh_node(text, mesh, tags[static_cast<std::size_t>(k)], tokens, 0);
      }
    }
  }
  text.skip_section("Nodes");
}

/// One element: a triangle is kept, a point or a line is left out, anything else is refused.
void add_element(MeshText& text, RawMesh& mesh, long tag, long type,
                 std::span<const long> physicals, const std::vector<std::string_view>& tokens,
                 std::size_t first) {
  if (type == kPointElement || type == kLineElement) {
    // Kept only as the nodes of their physical groups.
    const std::size_t count = type == kPointElement ? 1 : 2;
    text.need(tokens, first + count, type == kPointElement ? "a point element" : "a line");
    for (const long physical : physicals)
      for (std::size_t k = 0; k < count; ++k)
        mesh.tagged_nodes[{type == kPointElement ? 0 : 1, physical}].push_back(
            text.integer(tokens[first + k], "a node tag"));
    return;
  }
  if (type != kTriangleElement)
    text.fail(fmt::format("element {} is a {}: only 3-node triangles are read", tag,
                          element_type_name(type)),
              "a 2D mesh of first-order triangles (Gmsh: Mesh.ElementOrder = 1, no Recombine)");
  text.need(tokens, first + 3, "a triangle (three node tags)");
  if (physicals.size() > 1)
    text.fail(fmt::format("triangle {} is in {} physical surfaces; it would have more than one "
                          "material",
                          tag, physicals.size()),
              "each surface in at most one physical surface");
  RawMesh::Element element{
      {text.integer(tokens[first], "a node tag"), text.integer(tokens[first + 1], "a node tag"),
       text.integer(tokens[first + 2], "a node tag")},
      tag,
      physicals.empty() ? -1 : physicals.front(),
      text.line_number() - 1};
  mesh.triangles.push_back(element);
}

void read_elements(MeshText& text, RawMesh& mesh) {
  if (mesh.major_version == 2) {
    const long count =
        text.integer(text.next_line("the number of elements")[0], "the element count");
    for (long k = 0; k < count; ++k) {
      const auto tokens = text.next_line("an element");
      text.need(tokens, 3, "an element (tag, type, number of tags)");
      const long tags = text.integer(tokens[2], "the number of tags");
      if (tags < 0) text.fail("a negative number of tags", "a Gmsh 2.2 mesh");
      text.need(tokens, 3 + static_cast<std::size_t>(tags), "an element's tags");
      // MSH 2.2 gives one physical tag per element (0: none).
      const long physical = tags >= 1 ? text.integer(tokens[3], "the physical tag") : 0;
      std::vector<long> physicals;
      if (physical > 0) physicals.push_back(physical);
      add_element(text, mesh, text.integer(tokens[0], "the element tag"),
                  text.integer(tokens[1], "the element type"), physicals, tokens,
                  3 + static_cast<std::size_t>(tags));
    }
  } else {
    const auto header =
        four_integers(text, "$Elements (blocks, elements, smallest tag, largest tag)");
    for (long b = 0; b < header[0]; ++b) {
      const auto block = four_integers(text, "an element block (dimension, entity, type, count)");
      const long dimension = block[0], entity = block[1], type = block[2], count = block[3];
      const auto found = mesh.entity_physicals.find({dimension, entity});
      const std::vector<long> physicals =
          found == mesh.entity_physicals.end() ? std::vector<long>{} : found->second;
      for (long k = 0; k < count; ++k) {
        const auto tokens = text.next_line("an element");
        add_element(text, mesh, text.integer(tokens[0], "the element tag"), type, physicals, tokens,
                    1);
      }
    }
  }
  text.skip_section("Elements");
}

RawMesh read_sections(MeshText& text) {
  RawMesh mesh;
  bool nodes = false, elements = false;
  while (text.has_more()) {
    const std::vector<std::string_view> tokens = text.next_line("a section");
    const std::string_view name = tokens.front();
    if (!name.starts_with("$"))
      text.fail(fmt::format("'{}' is outside any section", name),
                "sections $MeshFormat, $PhysicalNames, $Entities, $Nodes, $Elements");
    const std::string_view section = name.substr(1);
    if (mesh.major_version == 0 && section != "MeshFormat")
      text.fail("the file does not begin with $MeshFormat", "a Gmsh .msh file");
    if (section == "MeshFormat") {
      read_format(text, mesh);
    } else if (section == "PhysicalNames") {
      read_physical_names(text, mesh);
    } else if (section == "Entities") {
      read_entities(text, mesh);
    } else if (section == "Nodes") {
      read_nodes(text, mesh);
      nodes = true;
    } else if (section == "Elements") {
      if (!nodes) text.fail("$Elements comes before $Nodes", "$Nodes first");
      read_elements(text, mesh);
      elements = true;
    } else {
      text.skip_section(section);  // $NodeData, $Periodic, ...: nothing the run needs
    }
  }
  if (!nodes || !elements)
    text.fail(fmt::format("the file has no {} section", nodes ? "$Elements" : "$Nodes"),
              "a Gmsh mesh with $Nodes and $Elements");
  return mesh;
}

}  // namespace

GmshMesh read_gmsh_mesh(const std::filesystem::path& file, const SourceLocation& where) {
  MeshText text(file, where);
  const RawMesh raw = read_sections(text);
  const auto fail_at = [&](int line, const std::string& value, const std::string& problem,
                           const std::string& allowed) -> void {
    throw InputError(SourceLocation{file.string(), line, 0}, "geometry.mesh", value, problem,
                     allowed);
  };
  GmshMesh mesh;
  mesh.file = file;
  if (raw.triangles.empty())
    fail_at(0, "", "the mesh holds no triangle",
            "a 2D mesh of 3-node triangles (Gmsh: Mesh 2, saved with its physical surfaces)");
  // The triangles' nodes, in order of first use, numbered from 0.
  std::unordered_map<long, std::int32_t> index;
  for (const RawMesh::Element& element : raw.triangles) {
    GmshMesh::Triangle triangle;
    triangle.element = element.tag;
    triangle.line = element.line;
    if (element.physical >= 0) triangle.physical = raw.name_of(2, element.physical);
    for (std::size_t k = 0; k < 3; ++k) {
      const long tag = element.nodes[k];
      const auto found = index.find(tag);
      if (found != index.end()) {
        triangle.corners[k] = found->second;
        continue;
      }
      const auto position = raw.nodes.find(tag);
      if (position == raw.nodes.end())
        fail_at(element.line, fmt::format("{}", tag),
                fmt::format("triangle {} names node {}, which $Nodes does not define", element.tag,
                            tag),
                "node tags of $Nodes");
      const auto [x, y, z] = position->second;
      if (z != 0.0)
        fail_at(element.line, fmt::format("z = {}", z),
                fmt::format("node {} of triangle {} lies off the plane z = 0", tag, element.tag),
                "a 2D mesh in the x-y plane (rktsph's plane-strain and plane-stress cases)");
      triangle.corners[k] = static_cast<std::int32_t>(mesh.points.size());
      index.emplace(tag, triangle.corners[k]);
      mesh.points.push_back({x, y});
      mesh.node_tags.push_back(tag);
    }
    mesh.triangles.push_back(std::move(triangle));
  }
  // Physical groups: a surface's triangle corners, a curve's or a point's nodes.
  for (const GmshMesh::Triangle& triangle : mesh.triangles)
    if (!triangle.physical.empty())
      for (const std::int32_t corner : triangle.corners)
        mesh.physical_nodes[triangle.physical].push_back(corner);
  for (const auto& [group, tags] : raw.tagged_nodes) {
    std::vector<std::int32_t>& members =
        mesh.physical_nodes[raw.name_of(group.first, group.second)];
    for (const long tag : tags)
      if (const auto found = index.find(tag); found != index.end())
        members.push_back(found->second);
  }
  for (auto& [name, members] : mesh.physical_nodes) {
    std::sort(members.begin(), members.end());
    members.erase(std::unique(members.begin(), members.end()), members.end());
  }
  return mesh;
}

}  // namespace rktsph
