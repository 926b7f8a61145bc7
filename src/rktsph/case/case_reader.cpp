#include "rktsph/case/case_reader.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "rktsph/case/yaml_reader.hpp"
#include "rktsph/sph/kernel.hpp"

namespace rktsph {

namespace {

// Character sets of names. Case names become file and directory names, hence the narrow set.
constexpr std::string_view kCaseNameAlphabet = "abcdefghijklmnopqrstuvwxyz0123456789-";
constexpr std::string_view kLabelAlphabet =
    "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-";
constexpr std::string_view kFieldAlphabet = "abcdefghijklmnopqrstuvwxyz0123456789_";
const std::string kLabelAlphabetName = "a non-empty name of letters, digits, '_' and '-'";

/// DampingSpec::end when no end is given: damping stays on for the whole run.
constexpr double kForever = 1e300;
/// Upper bound of integer counts; far beyond any run, and exactly representable as a double.
constexpr long kMaxCount = 1000000000000000L;

const NumberRange kSmoothingRatioRange{0.5, 3.0, true, false};  // h/dx, docs/input-reference.md
// The two-step Lax-Wendroff limit; lower limits for the options that lower it are checked when the
// simulation is built (docs/theory.md §2.5: 1.2 and 1.5 diverged on a plain block).
const NumberRange kCourantRange{0.0, 1.0, true, false};
const NumberRange kUnitInterval{0.0, 1.0, false, false};

const std::vector<std::string> kShapeKinds = {"segment", "rectangle", "polygon"};
const std::vector<std::string> kGroupSelectors = {"edge", "box", "polygon", "point"};
const std::vector<std::string> kBoundaryKinds = {"velocity", "fixed", "roller", "traction",
                                                 "pore_pressure"};
const std::vector<std::string> kOutputFields = {"velocity",      "displacement",      "stress",
                                                "pressure",      "deviatoric_stress", "eps_vp",
                                                "pore_pressure", "total_stress",      "material"};
const std::vector<std::string> kReductions = {"mean", "min", "max", "max_abs"};
const std::vector<std::string> kKernels = {"cubic_spline", "quintic_spline", "gaussian"};

std::vector<std::string> edge_names(int dimension) {
  if (dimension == 1) return {"xmin", "xmax"};
  return {"xmin", "xmax", "ymin", "ymax"};
}

std::vector<std::string> axis_names(int dimension) {
  if (dimension == 1) return {"x"};
  return {"x", "y"};
}

/// Names that are always defined and so may not name a user group. ymin and ymax are reserved
/// in 1D too, so that a 2D case turned into 1D cannot silently change their meaning.
const std::vector<std::string> kReservedGroupNames = {"all", "xmin", "xmax", "ymin", "ymax"};

bool contains(const std::vector<std::string>& list, const std::string& word) {
  return std::find(list.begin(), list.end(), word) != list.end();
}

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

/// Most vertices of one polygon; the edge-crossing test costs n^2/2 segment pairs.
constexpr std::size_t kMaxPolygonVertices = 10000;

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

class CaseReader {
 public:
  CaseReader(const YamlNode& root, std::string file) : root_(root), file_(std::move(file)) {}

  CaseDescription read();

 private:
  void read_header(const YamlMap& top);
  void read_materials(const YamlNode& node);
  void read_geometry(const YamlNode& node);
  ShapeSpec read_shape(const YamlNode& node) const;
  void read_groups(const YamlNode* node);
  GroupSpec read_group(const YamlNode& node) const;
  BoundaryConditionSpec read_boundary_condition(const YamlNode& node) const;
  void read_loads(const YamlNode& node);
  GravitySpec read_gravity(const YamlNode& node) const;
  DampingSpec read_damping(const YamlNode& node) const;
  void read_initial_conditions(const YamlNode& node);
  void read_numerics(const YamlNode& node);
  void read_pore_fluid(const YamlNode& node);
  void read_time(const YamlNode& node);
  void read_output(const YamlNode& node);
  ProbeSpec read_probe(const YamlNode& node) const;

  Vec3 read_vector(const YamlNode& node) const;
  std::vector<Vec3> read_polygon(const YamlNode& node) const;
  void read_box(const YamlNode& node, Vec3& min, Vec3& max, bool strict) const;
  TimeFunction read_time_function(const YamlNode& node) const;
  std::array<std::optional<TimeFunction>, 3> read_components(const YamlNode& node) const;
  std::string read_group_reference(const YamlNode& node) const;
  std::string read_label_key(const YamlNode& node) const;
  /// `what` is the subject with its verb, e.g. "'plane' is".
  void reject_unless_2d(const YamlNode& node, const std::string& what) const;

  /// Runs one independent part of the reading; its InputError is kept and reading goes on, so
  /// that one pass reports every mistake (CaseReader::read throws them all together).
  template <typename Part>
  void attempt(Part&& part) {
    try {
      part();
    } catch (const InputError& error) {
      errors_.push_back(error);
    }
  }
  void read_sections(const YamlMap& top);
  void read_probes(const YamlNode& node);

  const YamlNode& root_;
  std::string file_;
  CaseDescription out_;
  std::vector<InputError> errors_;
  /// False once a material block failed: a shape naming a material is then not checked against
  /// the list, which would only repeat that mistake.
  bool materials_complete_ = false;
};

CaseDescription CaseReader::read() {
  if (root_.is_null()) {
    throw InputError(SourceLocation{file_, 0, 0}, "", "", "the case file is empty",
                     "a map with at least name, dimension, geometry, materials and time");
  }
  const YamlMap top(root_);
  out_.file = file_;
  const SourceLocation absent{file_, 0, 0};
  out_.initial.where = out_.numerics.where = out_.output.where = absent;
  // A mistake that the rest depends on (the dimension) ends the reading early; the others are
  // collected by attempt().
  try {
    read_sections(top);
  } catch (const InputError& error) {
    errors_.push_back(error);
  }
  if (!errors_.empty()) throw InputError::combine(std::move(errors_));
  return std::move(out_);
}

void CaseReader::read_sections(const YamlMap& top) {
  attempt([&] {
    top.allow_only({"name", "description", "model", "dimension", "plane", "geometry", "materials",
                    "groups", "boundary_conditions", "loads", "initial_conditions", "numerics",
                    "pore_fluid", "time", "output", "probes"});
  });
  read_header(top);
  attempt([&] { read_materials(top.require("materials")); });
  attempt([&] { read_geometry(top.require("geometry")); });
  attempt([&] { read_groups(top.find("groups")); });
  if (const YamlNode* list = top.find("boundary_conditions")) {
    attempt([&] {
      for (const YamlNode& item : to_sequence(*list))
        attempt([&] { out_.boundary_conditions.push_back(read_boundary_condition(item)); });
    });
  }
  if (const YamlNode* loads = top.find("loads")) attempt([&] { read_loads(*loads); });
  if (const YamlNode* initial = top.find("initial_conditions"))
    attempt([&] { read_initial_conditions(*initial); });
  if (const YamlNode* numerics = top.find("numerics")) attempt([&] { read_numerics(*numerics); });
  const YamlNode* pore_fluid = top.find("pore_fluid");
  if (out_.model == ModelKind::SaturatedVpw) {
    attempt([&] { read_pore_fluid(top.require("pore_fluid")); });
  } else if (pore_fluid != nullptr) {
    attempt([&] {
      fail_at(*pore_fluid, "'pore_fluid' only applies to the saturated model",
              "model: saturated_vpw, or remove 'pore_fluid'", true);
    });
  }
  for (const BoundaryConditionSpec& condition : out_.boundary_conditions)
    if (condition.kind == BoundaryConditionSpec::Kind::PorePressure &&
        out_.model != ModelKind::SaturatedVpw)
      errors_.emplace_back(condition.where, "boundary_conditions.pore_pressure", "",
                           "a pore-pressure condition needs the saturated model",
                           "model: saturated_vpw");
  attempt([&] { read_time(top.require("time")); });
  if (const YamlNode* output = top.find("output")) attempt([&] { read_output(*output); });
  if (const YamlNode* probes = top.find("probes")) attempt([&] { read_probes(*probes); });
}

void CaseReader::read_probes(const YamlNode& node) {
  std::set<std::string> names;
  for (const YamlNode& item : to_sequence(node)) {
    attempt([&] {
      ProbeSpec probe = read_probe(item);
      if (!names.insert(probe.name).second) {
        fail_at(*YamlMap(item).find("name"), "a probe with this name is already defined",
                "a unique probe name");
      }
      out_.probes.push_back(std::move(probe));
    });
  }
}

void CaseReader::read_header(const YamlMap& top) {
  // The dimension comes first: vectors, shapes, edges and `plane` all depend on it.
  out_.dimension = static_cast<int>(to_integer(top.require("dimension"), 1, 2));
  attempt([&] {
    out_.name = to_identifier(top.require("name"), kCaseNameAlphabet,
                              "lower-case letters, digits and '-' (e.g. bar1d-elastic)");
  });
  if (const YamlNode* text = top.find("description"))
    attempt([&] { out_.description = to_text(*text); });
  if (const YamlNode* model = top.find("model")) {
    // A model that cannot be read is taken as the default, which at most adds a pore_fluid error.
    attempt([&] {
      out_.model = to_choice(*model, {"dry_solid", "saturated_vpw"}) == "dry_solid"
                       ? ModelKind::DrySolid
                       : ModelKind::SaturatedVpw;
    });
  }
  if (const YamlNode* plane = top.find("plane")) {
    attempt([&] {
      reject_unless_2d(*plane, "'plane' is");
      out_.plane = to_choice(*plane, {"strain", "stress"}) == "strain" ? PlaneKind::Strain
                                                                       : PlaneKind::Stress;
    });
  }
}

void CaseReader::read_materials(const YamlNode& node) {
  const YamlMap materials(node);
  if (node.children.empty()) {
    fail_at(node, "no material is defined", "at least one named material block");
  }
  bool complete = true;
  for (const YamlNode& entry : node.children) {
    const std::size_t errors_before = errors_.size();
    ParameterBlock parameters;
    attempt([&] {
      read_label_key(entry);
      const YamlMap block(entry);
      parameters.path = entry.path;
      parameters.where = block.where();
      const YamlNode& model = block.require("model");
      parameters.words["model"] = {
          to_identifier(model, kFieldAlphabet, "a material model name such as linear_elastic"),
          model.where};
    });
    // Parameter names and ranges belong to each material; here they only have to be numbers.
    if (entry.is_map()) {
      for (const YamlNode& value : entry.children) {
        if (value.key == "model") continue;
        attempt([&] { parameters.values[value.key] = Parameter{to_number(value), value.where}; });
      }
    }
    if (errors_.size() != errors_before) complete = false;
    out_.materials[entry.key] = std::move(parameters);
  }
  materials_complete_ = complete;
}

void CaseReader::read_geometry(const YamlNode& node) {
  const YamlMap geometry(node);
  attempt([&] { geometry.allow_only({"spacing", "shapes"}); });
  out_.geometry.where = geometry.where();
  attempt([&] {
    out_.geometry.spacing = to_number(geometry.require("spacing"), NumberRange::positive());
  });
  for (const YamlNode& item : to_sequence(geometry.require("shapes"), 1))
    attempt([&] { out_.geometry.shapes.push_back(read_shape(item)); });
}

ShapeSpec CaseReader::read_shape(const YamlNode& node) const {
  const YamlMap item(node);
  item.allow_only({"segment", "rectangle", "polygon", "material"});
  ShapeSpec shape;
  shape.where = item.where();
  const YamlNode& outline = item.require_one_of(kShapeKinds);
  if (outline.key == "segment") {
    if (out_.dimension != 1) {
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
  } else if (outline.key == "rectangle") {
    reject_unless_2d(outline, "'rectangle' shapes are");
    Vec3 min{}, max{};
    read_box(outline, min, max, true);
    shape.kind = ShapeSpec::Kind::Rectangle;
    shape.vertices = {min, max};
  } else {
    reject_unless_2d(outline, "'polygon' shapes are");
    shape.kind = ShapeSpec::Kind::Polygon;
    shape.vertices = read_polygon(outline);
  }
  const YamlNode& material = item.require("material");
  shape.material = to_text(material);
  if (materials_complete_ && out_.materials.count(shape.material) == 0) {
    std::vector<std::string> names;
    for (const auto& [name, block] : out_.materials)
      names.push_back(name);
    const std::string suggestion = closest_match(shape.material, names);
    fail_at(material,
            suggestion.empty() ? "no material of this name is defined in 'materials'"
                               : fmt::format("no material of this name is defined in "
                                             "'materials'; did you mean '{}'?",
                                             suggestion),
            quoted_list(names));
  }
  return shape;
}

void CaseReader::read_groups(const YamlNode* node) {
  // Built-in groups first, so that later stages can look every group name up in one list.
  const SourceLocation built_in{file_, 0, 0};
  GroupSpec all;
  all.name = "all";
  all.kind = GroupSpec::Kind::All;
  all.where = built_in;
  out_.groups.push_back(all);
  for (const std::string& edge : edge_names(out_.dimension)) {
    GroupSpec group;
    group.name = group.edge = edge;
    group.kind = GroupSpec::Kind::Edge;
    group.where = built_in;
    out_.groups.push_back(group);
  }
  if (node == nullptr) return;
  const YamlMap groups(*node);
  for (const YamlNode& entry : node->children) {
    try {
      out_.groups.push_back(read_group(entry));
    } catch (const InputError& error) {
      errors_.push_back(error);
      // Known by name all the same, so that conditions and probes using it add no second error.
      GroupSpec placeholder;
      placeholder.name = entry.key;
      out_.groups.push_back(placeholder);
    }
  }
}

GroupSpec CaseReader::read_group(const YamlNode& node) const {
  GroupSpec group;
  group.name = read_label_key(node);
  if (contains(kReservedGroupNames, group.name)) {
    throw InputError(
        node.key_where, node.path, group.name,
        "this is a built-in group name and may not be redefined",
        fmt::format("any other name; built-in groups are {}", quoted_list(kReservedGroupNames)));
  }
  const YamlMap selector_map(node);
  selector_map.allow_only(kGroupSelectors);
  group.where = selector_map.where();
  const YamlNode& selector = selector_map.require_one_of(kGroupSelectors);
  if (selector.key == "edge") {
    const YamlNode& edge = selector;
    if (out_.dimension == 1 && (to_text(edge) == "ymin" || to_text(edge) == "ymax")) {
      fail_at(edge, "edges ymin and ymax exist only in 2D", quoted_list(edge_names(1)));
    }
    group.kind = GroupSpec::Kind::Edge;
    group.edge = to_choice(edge, edge_names(out_.dimension));
  } else if (selector.key == "box") {
    group.kind = GroupSpec::Kind::Box;
    read_box(selector, group.min, group.max, false);
  } else if (selector.key == "polygon") {
    reject_unless_2d(selector, "polygon groups are");
    group.kind = GroupSpec::Kind::Polygon;
    group.vertices = read_polygon(selector);
  } else {
    group.kind = GroupSpec::Kind::Point;
    group.point = read_vector(selector);
  }
  return group;
}

BoundaryConditionSpec CaseReader::read_boundary_condition(const YamlNode& node) const {
  const YamlMap item(node);
  item.allow_only({"group", "velocity", "fixed", "roller", "mirror", "traction", "pore_pressure"});
  BoundaryConditionSpec condition;
  condition.where = item.where();
  condition.group = read_group_reference(item.require("group"));
  const YamlNode& kind = item.require_one_of(kBoundaryKinds);
  const YamlNode* mirror = item.find("mirror");
  if (mirror != nullptr && kind.key != "roller") {
    fail_at(*mirror, "'mirror' only applies to a 'roller' condition", "remove 'mirror'", true);
  }
  if (kind.key == "velocity") {
    condition.kind = BoundaryConditionSpec::Kind::Velocity;
    condition.velocity = read_components(kind);
  } else if (kind.key == "traction") {
    condition.kind = BoundaryConditionSpec::Kind::Traction;
    condition.traction = read_components(kind);
  } else if (kind.key == "pore_pressure") {
    condition.kind = BoundaryConditionSpec::Kind::PorePressure;
    condition.pore_pressure = read_time_function(kind);
  } else if (kind.key == "fixed") {
    if (!to_bool(kind)) fail_at(kind, "'fixed' can only be true", "true (or leave it out)");
    condition.kind = BoundaryConditionSpec::Kind::Fixed;
  } else {
    if (out_.dimension == 1 && to_text(kind) == "y") {
      fail_at(kind, "a roller normal to y exists only in 2D", "'x'");
    }
    condition.kind = BoundaryConditionSpec::Kind::Roller;
    condition.axis = to_choice(kind, axis_names(out_.dimension)) == "x" ? 0 : 1;
    if (mirror != nullptr) condition.mirror = to_bool(*mirror);
  }
  return condition;
}

void CaseReader::read_loads(const YamlNode& node) {
  const YamlMap loads(node);
  attempt([&] { loads.allow_only({"gravity", "damping"}); });
  if (const YamlNode* gravity = loads.find("gravity")) out_.gravity = read_gravity(*gravity);
  if (const YamlNode* damping = loads.find("damping")) out_.damping = read_damping(*damping);
}

GravitySpec CaseReader::read_gravity(const YamlNode& node) const {
  const YamlMap map(node);
  map.allow_only({"acceleration", "factor"});
  GravitySpec gravity;
  gravity.where = map.where();
  gravity.acceleration = read_vector(map.require("acceleration"));
  if (const YamlNode* factor = map.find("factor")) gravity.factor = read_time_function(*factor);
  return gravity;
}

DampingSpec CaseReader::read_damping(const YamlNode& node) const {
  const YamlMap map(node);
  map.allow_only({"coefficient", "start", "end"});
  DampingSpec damping;
  damping.where = map.where();
  damping.coefficient = to_number(map.require("coefficient"), NumberRange::non_negative());
  if (const YamlNode* start = map.find("start")) {
    damping.start = to_number(*start, NumberRange::non_negative());
  }
  if (const YamlNode* end = map.find("end")) {
    NumberRange after_start = NumberRange::positive();
    after_start.low = damping.start;
    damping.end = to_number(*end, after_start);
  }
  return damping;
}

void CaseReader::read_initial_conditions(const YamlNode& node) {
  const YamlMap initial(node);
  attempt([&] { initial.allow_only({"velocity", "geostatic"}); });
  out_.initial.where = initial.where();
  if (const YamlNode* velocity = initial.find("velocity")) {
    out_.initial.velocity = read_vector(*velocity);
  }
  if (const YamlNode* geostatic_node = initial.find("geostatic")) {
    const YamlMap geostatic(*geostatic_node);
    geostatic.allow_only({"surface", "k0"});
    out_.initial.geostatic_surface = to_number(geostatic.require("surface"));
    if (const YamlNode* k0 = geostatic.find("k0")) {
      out_.initial.k0 = to_number(*k0, NumberRange::positive());
    }
  }
}

void CaseReader::read_numerics(const YamlNode& node) {
  const YamlMap map(node);
  attempt([&] {
    map.allow_only({"kernel", "h_over_dx", "interpolation_order", "courant", "time_step",
                    "source_coupling", "rk_substep_factor", "rk_max_substeps", "hourglass",
                    "artificial_viscosity", "stress_update"});
  });
  NumericsSpec& numerics = out_.numerics;
  numerics.where = map.where();
  if (const YamlNode* kernel = map.find("kernel")) {
    numerics.kernel = kernel_type_from_name(to_choice(*kernel, kKernels));
  }
  if (const YamlNode* ratio = map.find("h_over_dx")) {
    numerics.h_over_dx = to_number(*ratio, kSmoothingRatioRange);
  }
  if (const YamlNode* order = map.find("interpolation_order")) {
    numerics.interpolation_order = static_cast<int>(to_integer(*order, 0, 1));
  }
  if (const YamlNode* courant = map.find("courant")) {
    numerics.courant = to_number(*courant, kCourantRange);
  }
  if (const YamlNode* step = map.find("time_step")) {
    numerics.time_step = to_number(*step, NumberRange::positive());
  }
  if (const YamlNode* coupling = map.find("source_coupling")) {
    numerics.frozen_flux_source =
        to_choice(*coupling, {"frozen_flux", "additive"}) == "frozen_flux";
  }
  if (const YamlNode* factor = map.find("rk_substep_factor")) {
    numerics.rk_substep_factor = to_number(*factor, NumberRange::positive());
  }
  if (const YamlNode* substeps = map.find("rk_max_substeps")) {
    numerics.rk_max_substeps =
        static_cast<int>(to_integer(*substeps, 1, std::numeric_limits<int>::max()));
  }
  if (const YamlNode* update = map.find("stress_update")) {
    numerics.stress_update = to_choice(*update, {"mean_velocity", "half_step"}) == "half_step"
                                 ? StressUpdate::HalfStep
                                 : StressUpdate::MeanVelocity;
  }
  if (const YamlNode* hourglass_node = map.find("hourglass")) {
    const YamlMap hourglass(*hourglass_node);
    hourglass.allow_only({"enabled", "kappa", "h_over_dx", "fields", "stiffness",
                          "plastic_fraction", "strain_stiffness"});
    if (const YamlNode* enabled = hourglass.find("enabled")) {
      numerics.hourglass_filter = to_bool(*enabled);
    }
    if (const YamlNode* kappa = hourglass.find("kappa")) {
      numerics.hourglass_kappa = to_number(*kappa, kUnitInterval);
    }
    if (const YamlNode* ratio = hourglass.find("h_over_dx")) {
      numerics.hourglass_h_over_dx = to_number(*ratio, kSmoothingRatioRange);
    }
    if (const YamlNode* fields = hourglass.find("fields")) {
      numerics.hourglass_fields = to_choice(*fields, {"velocity", "all"}) == "all"
                                      ? HourglassFields::All
                                      : HourglassFields::Velocity;
    }
    if (const YamlNode* stiffness = hourglass.find("stiffness")) {
      numerics.hourglass_stiffness = to_number(*stiffness, kUnitInterval);
    }
    if (const YamlNode* fraction = hourglass.find("plastic_fraction")) {
      numerics.hourglass_plastic_fraction = to_number(*fraction, kUnitInterval);
    }
    if (const YamlNode* stiffness = hourglass.find("strain_stiffness")) {
      numerics.strain_hourglass_stiffness = to_number(*stiffness, kUnitInterval);
    }
  }
  if (const YamlNode* viscosity = map.find("artificial_viscosity")) {
    numerics.artificial_viscosity = to_number(*viscosity, NumberRange::non_negative());
  }
}

void CaseReader::read_pore_fluid(const YamlNode& node) {
  const YamlMap map(node);
  attempt([&] {
    map.allow_only({"bulk_modulus", "density", "porosity", "hydraulic_conductivity", "gravity",
                    "biot_coefficient", "projection_beta", "preconditioner", "solver_tolerance",
                    "solver_max_iterations", "laplacian_scale", "checkerboard_stabilisation"});
  });
  PoreFluidSpec fluid;
  fluid.where = map.where();
  fluid.bulk_modulus = to_number(map.require("bulk_modulus"), NumberRange::positive());
  fluid.density = to_number(map.require("density"), NumberRange::positive());
  NumberRange fraction = NumberRange::positive();
  fraction.high = 1.0;
  fraction.high_open = true;
  fluid.porosity = to_number(map.require("porosity"), fraction);
  fluid.hydraulic_conductivity =
      to_number(map.require("hydraulic_conductivity"), NumberRange::non_negative());
  if (const YamlNode* g = map.find("gravity"))
    fluid.gravity = to_number(*g, NumberRange::positive());
  if (const YamlNode* alpha = map.find("biot_coefficient")) {
    NumberRange biot = NumberRange::positive();
    biot.high = 1.0;
    fluid.biot_coefficient = to_number(*alpha, biot);
  }
  if (const YamlNode* beta = map.find("projection_beta")) {
    // beta = 0 adds a spurious permeability of about dt/rho (docs/theory.md §6.2): not offered.
    fluid.projection_beta = static_cast<double>(to_integer(*beta, 1, 1));
  }
  if (const YamlNode* preconditioner = map.find("preconditioner")) {
    fluid.incomplete_cholesky =
        to_choice(*preconditioner, {"jacobi", "incomplete_cholesky"}) == "incomplete_cholesky";
  }
  if (const YamlNode* tolerance = map.find("solver_tolerance")) {
    NumberRange range = NumberRange::positive();
    range.high = 1e-3;
    fluid.solver_tolerance = to_number(*tolerance, range);
  }
  if (const YamlNode* iterations = map.find("solver_max_iterations")) {
    fluid.solver_max_iterations = to_integer(*iterations, 1, 100000000);
  }
  if (const YamlNode* scale = map.find("laplacian_scale")) {
    fluid.laplacian_scale = to_number(*scale, NumberRange::positive());
  }
  if (const YamlNode* theta = map.find("checkerboard_stabilisation")) {
    fluid.checkerboard_stabilisation = to_number(*theta, NumberRange::non_negative());
  }
  out_.pore_fluid = fluid;
}

void CaseReader::read_time(const YamlNode& node) {
  const YamlMap time(node);
  attempt([&] { time.allow_only({"end", "max_steps"}); });
  out_.time.where = time.where();
  out_.time.end = to_number(time.require("end"), NumberRange::positive());
  if (const YamlNode* steps = time.find("max_steps")) {
    out_.time.max_steps = to_integer(*steps, 1, kMaxCount);
  }
}

void CaseReader::read_output(const YamlNode& node) {
  const YamlMap output(node);
  attempt([&] {
    output.allow_only({"interval", "probe_interval", "checkpoint_interval", "fields"});
  });
  out_.output.where = output.where();
  if (const YamlNode* interval = output.find("interval")) {
    out_.output.interval = to_number(*interval, NumberRange::non_negative());
  }
  if (const YamlNode* interval = output.find("probe_interval")) {
    out_.output.probe_interval = to_number(*interval, NumberRange::non_negative());
  }
  if (const YamlNode* interval = output.find("checkpoint_interval")) {
    out_.output.checkpoint_interval = to_number(*interval, NumberRange::non_negative());
  }
  if (const YamlNode* fields = output.find("fields")) {
    for (const YamlNode& field : to_sequence(*fields)) {
      const std::string name = to_choice(field, kOutputFields);
      if (contains(out_.output.fields, name)) {
        fail_at(field, "field listed twice", "each field once");
      }
      out_.output.fields.push_back(name);
    }
  }
}

ProbeSpec CaseReader::read_probe(const YamlNode& node) const {
  const YamlMap item(node);
  item.allow_only({"name", "group", "fields", "reduction"});
  ProbeSpec probe;
  probe.where = item.where();
  probe.name = to_identifier(item.require("name"), kLabelAlphabet, kLabelAlphabetName);
  probe.group = read_group_reference(item.require("group"));
  // Which fields exist depends on the model; the model checks the names when it sets up probes.
  probe.path = node.path;
  for (const YamlNode& field : to_sequence(item.require("fields"), 1)) {
    probe.fields.push_back(
        to_identifier(field, kFieldAlphabet, "a field name of a-z, 0-9 and '_' (e.g. stress_xx)"));
    probe.field_where.push_back(field.where);
  }
  if (const YamlNode* reduction = item.find("reduction")) {
    const std::string name = to_choice(*reduction, kReductions);
    probe.reduction = name == "mean"  ? ProbeSpec::Reduction::Mean
                      : name == "min" ? ProbeSpec::Reduction::Min
                      : name == "max" ? ProbeSpec::Reduction::Max
                                      : ProbeSpec::Reduction::MaxAbs;
  }
  return probe;
}

Vec3 CaseReader::read_vector(const YamlNode& node) const {
  Vec3 vector{};
  // A 1-vector may be written as a plain number (e.g. `point: 10.0` in 1D).
  if (out_.dimension == 1 && node.is_scalar()) {
    vector[0] = to_number(node);
    return vector;
  }
  const std::string allowed =
      out_.dimension == 1 ? "one number, or a list of one number" : "a list of 2 numbers [x, y]";
  if (!node.is_sequence()) fail_at(node, "not a vector", allowed);
  const std::vector<YamlNode>& components = node.children;
  if (components.size() != static_cast<std::size_t>(out_.dimension)) {
    fail_at(node,
            fmt::format("has {} components but the case is {}D", components.size(), out_.dimension),
            allowed);
  }
  for (std::size_t i = 0; i < components.size(); ++i)
    vector[i] = to_number(components[i]);
  return vector;
}

std::vector<Vec3> CaseReader::read_polygon(const YamlNode& node) const {
  const std::vector<YamlNode>& items = to_sequence(node, 3);
  if (items.size() > kMaxPolygonVertices) {
    fail_at(node, fmt::format("the polygon has {} vertices", items.size()),
            fmt::format("at most {} vertices", kMaxPolygonVertices));
  }
  std::vector<Vec3> vertices;
  for (const YamlNode& vertex : items)
    vertices.push_back(read_vector(vertex));
  refuse_repeated_vertex(node, vertices);
  if (twice_signed_area(vertices) == 0.0) {
    fail_at(node, "the polygon has zero area", "at least 3 vertices that are not all on one line");
  }
  refuse_crossing_edges(node, vertices);
  return vertices;
}

void CaseReader::read_box(const YamlNode& node, Vec3& min, Vec3& max, bool strict) const {
  const YamlMap box(node);
  box.allow_only({"min", "max"});
  min = read_vector(box.require("min"));
  max = read_vector(box.require("max"));
  for (int axis = 0; axis < out_.dimension; ++axis) {
    const bool ordered = strict ? min[axis] < max[axis] : min[axis] <= max[axis];
    if (!ordered) {
      fail_at(*box.find("max"),
              fmt::format("max is not {} min in {}", strict ? "above" : "at or above",
                          axis == 0 ? "x" : "y"),
              strict ? "min < max in every component" : "min <= max in every component");
    }
  }
}

TimeFunction CaseReader::read_time_function(const YamlNode& node) const {
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

std::array<std::optional<TimeFunction>, 3> CaseReader::read_components(const YamlNode& node) const {
  const YamlMap map(node);
  if (out_.dimension == 1) {
    if (const YamlNode* y = map.find("y")) {
      fail_at(*y, "a 'y' component exists only in 2D", "'x'", true);
    }
  }
  const std::vector<std::string> axes = axis_names(out_.dimension);
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

std::string CaseReader::read_group_reference(const YamlNode& node) const {
  const std::string name = to_text(node);
  std::vector<std::string> names;
  for (const GroupSpec& group : out_.groups)
    names.push_back(group.name);
  if (contains(names, name)) return name;
  const std::string suggestion = closest_match(name, names);
  fail_at(node,
          suggestion.empty()
              ? "no group of this name is defined"
              : fmt::format("no group of this name is defined; did you mean '{}'?", suggestion),
          fmt::format("a built-in group or one defined under 'groups': {}", quoted_list(names)));
}

std::string CaseReader::read_label_key(const YamlNode& node) const {
  const bool valid =
      !node.key.empty() && node.key.find_first_not_of(kLabelAlphabet) == std::string::npos;
  if (!valid) {
    throw InputError(node.key_where, node.path, node.key, "not a valid name", kLabelAlphabetName);
  }
  return node.key;
}

void CaseReader::reject_unless_2d(const YamlNode& node, const std::string& what) const {
  if (out_.dimension != 2) {
    fail_at(node, fmt::format("{} only allowed in 2D cases", what),
            "remove it, or set dimension: 2", true);
  }
}

// ---------------------------------------------------------------------------------------------
// Writing

std::string number(double value) {
  // fmt's default formatting is the shortest text that reads back to the same double.
  return fmt::format("{}", value);
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

void emit_geometry(YAML::Emitter& out, const CaseDescription& description) {
  out << YAML::Key << "geometry" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "spacing" << YAML::Value << number(description.geometry.spacing);
  out << YAML::Key << "shapes" << YAML::Value << YAML::BeginSeq;
  for (const ShapeSpec& shape : description.geometry.shapes) {
    out << YAML::BeginMap;
    if (shape.kind == ShapeSpec::Kind::Segment) {
      out << YAML::Key << "segment" << YAML::Value << YAML::Flow << YAML::BeginSeq
          << number(shape.vertices.at(0)[0]) << number(shape.vertices.at(1)[0]) << YAML::EndSeq;
    } else if (shape.kind == ShapeSpec::Kind::Rectangle) {
      out << YAML::Key << "rectangle" << YAML::Value << YAML::Flow << YAML::BeginMap;
      out << YAML::Key << "min" << YAML::Value;
      emit_vector(out, shape.vertices.at(0), description.dimension);
      out << YAML::Key << "max" << YAML::Value;
      emit_vector(out, shape.vertices.at(1), description.dimension);
      out << YAML::EndMap;
    } else {
      out << YAML::Key << "polygon" << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (const Vec3& vertex : shape.vertices)
        emit_vector(out, vertex, description.dimension);
      out << YAML::EndSeq;
    }
    out << YAML::Key << "material" << YAML::Value << shape.material;
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
}

void emit_materials(YAML::Emitter& out, const CaseDescription& description) {
  out << YAML::Key << "materials" << YAML::Value << YAML::BeginMap;
  for (const auto& [name, block] : description.materials) {
    out << YAML::Key << name << YAML::Value << YAML::BeginMap;
    for (const auto& [key, word] : block.words) {
      out << YAML::Key << key << YAML::Value << word.first;
    }
    for (const auto& [key, parameter] : block.values) {
      out << YAML::Key << key << YAML::Value << number(parameter.value);
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

void emit_groups(YAML::Emitter& out, const CaseDescription& description) {
  std::vector<const GroupSpec*> defined;
  for (const GroupSpec& group : description.groups) {
    if (!contains(kReservedGroupNames, group.name)) defined.push_back(&group);
  }
  if (defined.empty()) return;
  out << YAML::Key << "groups" << YAML::Value << YAML::BeginMap;
  for (const GroupSpec* group : defined) {
    out << YAML::Key << group->name << YAML::Value << YAML::Flow << YAML::BeginMap;
    switch (group->kind) {
      case GroupSpec::Kind::Edge:
        out << YAML::Key << "edge" << YAML::Value << group->edge;
        break;
      case GroupSpec::Kind::Box:
        out << YAML::Key << "box" << YAML::Value << YAML::BeginMap;
        out << YAML::Key << "min" << YAML::Value;
        emit_vector(out, group->min, description.dimension);
        out << YAML::Key << "max" << YAML::Value;
        emit_vector(out, group->max, description.dimension);
        out << YAML::EndMap;
        break;
      case GroupSpec::Kind::Polygon:
        out << YAML::Key << "polygon" << YAML::Value << YAML::BeginSeq;
        for (const Vec3& vertex : group->vertices)
          emit_vector(out, vertex, description.dimension);
        out << YAML::EndSeq;
        break;
      case GroupSpec::Kind::Point:
      case GroupSpec::Kind::All:  // only the built-in "all", never written
        out << YAML::Key << "point" << YAML::Value;
        emit_vector(out, group->point, description.dimension);
        break;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

void emit_boundary_conditions(YAML::Emitter& out, const CaseDescription& description) {
  if (description.boundary_conditions.empty()) return;
  out << YAML::Key << "boundary_conditions" << YAML::Value << YAML::BeginSeq;
  for (const BoundaryConditionSpec& condition : description.boundary_conditions) {
    out << YAML::BeginMap << YAML::Key << "group" << YAML::Value << condition.group;
    switch (condition.kind) {
      case BoundaryConditionSpec::Kind::Velocity:
        out << YAML::Key << "velocity" << YAML::Value;
        emit_components(out, condition.velocity, description.dimension);
        break;
      case BoundaryConditionSpec::Kind::Traction:
        out << YAML::Key << "traction" << YAML::Value;
        emit_components(out, condition.traction, description.dimension);
        break;
      case BoundaryConditionSpec::Kind::Fixed:
        out << YAML::Key << "fixed" << YAML::Value << "true";
        break;
      case BoundaryConditionSpec::Kind::PorePressure:
        out << YAML::Key << "pore_pressure" << YAML::Value;
        emit_time_function(out, *condition.pore_pressure);
        break;
      case BoundaryConditionSpec::Kind::Roller:
        out << YAML::Key << "roller" << YAML::Value << (condition.axis == 0 ? "x" : "y");
        out << YAML::Key << "mirror" << YAML::Value << (condition.mirror ? "true" : "false");
        break;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

void emit_loads_and_initial(YAML::Emitter& out, const CaseDescription& description) {
  if (description.gravity || description.damping) {
    out << YAML::Key << "loads" << YAML::Value << YAML::BeginMap;
    if (const auto& gravity = description.gravity) {
      out << YAML::Key << "gravity" << YAML::Value << YAML::BeginMap;
      out << YAML::Key << "acceleration" << YAML::Value;
      emit_vector(out, gravity->acceleration, description.dimension);
      out << YAML::Key << "factor" << YAML::Value;
      emit_time_function(out, gravity->factor);
      out << YAML::EndMap;
    }
    if (const auto& damping = description.damping) {
      out << YAML::Key << "damping" << YAML::Value << YAML::BeginMap;
      out << YAML::Key << "coefficient" << YAML::Value << number(damping->coefficient);
      out << YAML::Key << "start" << YAML::Value << number(damping->start);
      if (damping->end < kForever) out << YAML::Key << "end" << YAML::Value << number(damping->end);
      out << YAML::EndMap;
    }
    out << YAML::EndMap;
  }
  const InitialConditionsSpec& initial = description.initial;
  out << YAML::Key << "initial_conditions" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "velocity" << YAML::Value;
  emit_vector(out, initial.velocity, description.dimension);
  if (initial.geostatic_surface) {
    out << YAML::Key << "geostatic" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "surface" << YAML::Value << number(*initial.geostatic_surface);
    if (initial.k0) out << YAML::Key << "k0" << YAML::Value << number(*initial.k0);
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

void emit_numerics(YAML::Emitter& out, const NumericsSpec& numerics) {
  out << YAML::Key << "numerics" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "kernel" << YAML::Value << kernel_type_name(numerics.kernel);
  out << YAML::Key << "h_over_dx" << YAML::Value << number(numerics.h_over_dx);
  out << YAML::Key << "interpolation_order" << YAML::Value << numerics.interpolation_order;
  out << YAML::Key << "courant" << YAML::Value << number(numerics.courant);
  if (numerics.time_step) {
    out << YAML::Key << "time_step" << YAML::Value << number(*numerics.time_step);
  }
  out << YAML::Key << "source_coupling" << YAML::Value
      << (numerics.frozen_flux_source ? "frozen_flux" : "additive");
  out << YAML::Key << "rk_substep_factor" << YAML::Value << number(numerics.rk_substep_factor);
  out << YAML::Key << "rk_max_substeps" << YAML::Value << numerics.rk_max_substeps;
  if (numerics.stress_update) {
    out << YAML::Key << "stress_update" << YAML::Value
        << (*numerics.stress_update == StressUpdate::HalfStep ? "half_step" : "mean_velocity");
  }
  out << YAML::Key << "hourglass" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "enabled" << YAML::Value << (numerics.hourglass_filter ? "true" : "false");
  out << YAML::Key << "kappa" << YAML::Value << number(numerics.hourglass_kappa);
  out << YAML::Key << "h_over_dx" << YAML::Value << number(numerics.hourglass_h_over_dx);
  if (numerics.hourglass_stiffness) {
    out << YAML::Key << "stiffness" << YAML::Value << number(*numerics.hourglass_stiffness);
  }
  out << YAML::Key << "plastic_fraction" << YAML::Value
      << number(numerics.hourglass_plastic_fraction);
  out << YAML::Key << "strain_stiffness" << YAML::Value
      << number(numerics.strain_hourglass_stiffness);
  if (numerics.hourglass_fields) {
    out << YAML::Key << "fields" << YAML::Value
        << (*numerics.hourglass_fields == HourglassFields::All ? "all" : "velocity");
  }
  out << YAML::EndMap;
  out << YAML::Key << "artificial_viscosity" << YAML::Value
      << number(numerics.artificial_viscosity);
  out << YAML::EndMap;
}

void emit_output_and_probes(YAML::Emitter& out, const CaseDescription& description) {
  const OutputSpec& output = description.output;
  out << YAML::Key << "output" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "interval" << YAML::Value << number(output.interval);
  out << YAML::Key << "probe_interval" << YAML::Value << number(output.probe_interval);
  if (output.checkpoint_interval > 0.0) {  // only when on: older resolved cases keep their text
    out << YAML::Key << "checkpoint_interval" << YAML::Value << number(output.checkpoint_interval);
  }
  if (!output.fields.empty()) {
    out << YAML::Key << "fields" << YAML::Value << YAML::Flow << output.fields;
  }
  out << YAML::EndMap;
  if (description.probes.empty()) return;
  static const char* const kReductionNames[] = {"mean", "min", "max", "max_abs"};
  out << YAML::Key << "probes" << YAML::Value << YAML::BeginSeq;
  for (const ProbeSpec& probe : description.probes) {
    out << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "name" << YAML::Value << probe.name;
    out << YAML::Key << "group" << YAML::Value << probe.group;
    out << YAML::Key << "fields" << YAML::Value << YAML::Flow << probe.fields;
    out << YAML::Key << "reduction" << YAML::Value
        << kReductionNames[static_cast<int>(probe.reduction)];
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

/// The whole text of the case file. A directory (which an ifstream opens and reads as empty on
/// Linux) and a file that cannot be read are named as such, with the system's reason.
std::string read_case_bytes(const std::string& path) {
  const SourceLocation where{path, 0, 0};
  std::error_code status_error;
  const auto status = std::filesystem::status(path, status_error);
  if (std::filesystem::is_directory(status)) {
    throw InputError(where, "", "", "this is a directory, not a case file",
                     "the path of a YAML case file, e.g. " +
                         (std::filesystem::path(path) / "case.yaml").string());
  }
  errno = 0;
  std::ifstream stream(path, std::ios::binary);
  if (!stream) {
    const int reason = errno != 0 ? errno : ENOENT;
    throw InputError(where, "", "",
                     fmt::format("cannot open the case file: {}", std::strerror(reason)),
                     "a readable YAML file");
  }
  std::ostringstream text;
  text << stream.rdbuf();
  if (stream.bad()) {
    throw InputError(where, "", "",
                     fmt::format("cannot read the case file: {}", std::strerror(errno)),
                     "a readable YAML file");
  }
  return text.str();
}

}  // namespace

CaseOverride parse_override(const std::string& text) {
  const SourceLocation where{"<--set>", 0, 0};
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos) {
    throw InputError(where, "", text, "an override needs the form key=value",
                     "e.g. --set numerics.courant=0.3");
  }
  CaseOverride result{text.substr(0, equals), text.substr(equals + 1)};
  const bool empty_component = result.key.empty() || result.key.front() == '.' ||
                               result.key.back() == '.' ||
                               result.key.find("..") != std::string::npos;
  if (empty_component || result.key.find_first_of(" \t") != std::string::npos) {
    throw InputError(where, result.key, text, "the key of an override is empty or malformed",
                     "a dotted path such as numerics.courant or boundary_conditions.0.group");
  }
  return result;
}

CaseDescription read_case_file(const std::string& path,
                               const std::vector<CaseOverride>& overrides) {
  return read_case_text(read_case_bytes(path), path, overrides);
}

CaseDescription read_case_text(const std::string& text, const std::string& file_name,
                               const std::vector<CaseOverride>& overrides) {
  YamlNode root = parse_yaml(text, file_name);
  for (const CaseOverride& override_entry : overrides) {
    apply_override(root, override_entry.key, override_entry.value);
  }
  return CaseReader(root, file_name).read();
}

std::string write_case_yaml(const CaseDescription& description) {
  YAML::Emitter out;
  out.SetIndent(2);
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << description.name;
  if (!description.description.empty()) {
    out << YAML::Key << "description" << YAML::Value << YAML::DoubleQuoted
        << description.description;
  }
  out << YAML::Key << "model" << YAML::Value
      << (description.model == ModelKind::DrySolid ? "dry_solid" : "saturated_vpw");
  out << YAML::Key << "dimension" << YAML::Value << description.dimension;
  if (description.dimension == 2) {
    out << YAML::Key << "plane" << YAML::Value
        << (description.plane == PlaneKind::Strain ? "strain" : "stress");
  }
  emit_geometry(out, description);
  emit_materials(out, description);
  emit_groups(out, description);
  emit_boundary_conditions(out, description);
  emit_loads_and_initial(out, description);
  emit_numerics(out, description.numerics);
  if (const auto& fluid = description.pore_fluid) {
    out << YAML::Key << "pore_fluid" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "bulk_modulus" << YAML::Value << number(fluid->bulk_modulus);
    out << YAML::Key << "density" << YAML::Value << number(fluid->density);
    out << YAML::Key << "porosity" << YAML::Value << number(fluid->porosity);
    out << YAML::Key << "hydraulic_conductivity" << YAML::Value
        << number(fluid->hydraulic_conductivity);
    out << YAML::Key << "gravity" << YAML::Value << number(fluid->gravity);
    out << YAML::Key << "biot_coefficient" << YAML::Value << number(fluid->biot_coefficient);
    out << YAML::Key << "projection_beta" << YAML::Value
        << static_cast<int>(fluid->projection_beta);
    out << YAML::Key << "preconditioner" << YAML::Value
        << (fluid->incomplete_cholesky ? "incomplete_cholesky" : "jacobi");
    out << YAML::Key << "solver_tolerance" << YAML::Value << number(fluid->solver_tolerance);
    if (fluid->solver_max_iterations > 0)
      out << YAML::Key << "solver_max_iterations" << YAML::Value << fluid->solver_max_iterations;
    if (fluid->laplacian_scale > 0)
      out << YAML::Key << "laplacian_scale" << YAML::Value << number(fluid->laplacian_scale);
    out << YAML::Key << "checkerboard_stabilisation" << YAML::Value
        << number(fluid->checkerboard_stabilisation);
    out << YAML::EndMap;
  }
  out << YAML::Key << "time" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "end" << YAML::Value << number(description.time.end);
  out << YAML::Key << "max_steps" << YAML::Value << description.time.max_steps;
  out << YAML::EndMap;
  emit_output_and_probes(out, description);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace rktsph
