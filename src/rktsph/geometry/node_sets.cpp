#include "rktsph/geometry/node_sets.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "rktsph/core/axes.hpp"
#include "rktsph/geometry/gmsh_mesh.hpp"
#include "rktsph/geometry/triangle_node_sets.hpp"
#include "rktsph/mesh/cell_geometry.hpp"

namespace rktsph {

namespace {

// Tolerance, in units of dx, for "on the lattice" and "on the boundary" decisions.
constexpr double kLatticeTolerance = kSpacingTolerance;

// A triangle mesh of longest edge dx holds about as many triangles as equilateral ones of edge
// kTriangleEdgeFraction dx would (docs/theory.md §3.6; measured on slopes at two spacings, where it
// is 0.67 to 0.70, and taken a little lower so that the estimate errs high): sizes the estimate
// of a mesh before it is built.
constexpr double kTriangleEdgeFraction = 0.66;

// "(x0, y0), (x1, y1), ..." for messages.
std::string describe_corners(const NodeSets& nodes, const CellComplex& cells, std::size_t p) {
  std::string text;
  for (const std::int32_t node : cells.corners(p))
    text += fmt::format("{}({:.6g}, {:.6g})", text.empty() ? "" : ", ",
                        nodes.sph_nodes.position[0][node], nodes.sph_nodes.position[1][node]);
  return text;
}

void check_vertices_on_lattice(const GeometrySpec& geometry, int dimension, const Vec3& origin) {
  const double dx = geometry.spacing;
  // Every coordinate off the lattice at once: moving one vertex onto it often moves the origin,
  // and a user fixing them one run at a time would chase them.
  std::vector<InputError> off_lattice;
  for (std::size_t s = 0; s < geometry.shapes.size(); ++s) {
    const ShapeSpec& shape = geometry.shapes[s];
    for (std::size_t v = 0; v < shape.vertices.size(); ++v)
      for (int a = 0; a < dimension; ++a) {
        const double cells = (shape.vertices[v][a] - origin[a]) / dx;
        if (std::abs(cells - std::round(cells)) <= kLatticeTolerance) continue;
        off_lattice.emplace_back(
            shape.where, fmt::format("geometry.shapes.{}", s),
            fmt::format("{}", shape.vertices[v][a]),
            fmt::format("{} of vertex {} is not on the lattice of spacing {} starting at {} (it "
                        "is {:.6f} spacings from it)",
                        axis_letter(a), v, dx, origin[a], cells),
            "coordinates that differ from the smallest coordinate of all shapes by a whole "
            "number of spacings");
      }
  }
  if (!off_lattice.empty()) throw InputError::combine(std::move(off_lattice));
  // A segment or rectangle thinner than a spacing passes the test above (its vertices round to
  // one lattice line) but has no cell, so nothing would move its nodes.
  for (const ShapeSpec& shape : geometry.shapes) {
    if (shape.kind == ShapeSpec::Kind::Polygon) continue;
    for (int a = 0; a < dimension; ++a) {
      const double width = shape.vertices[1][a] - shape.vertices[0][a];
      if (std::round(width / dx) >= 1.0) continue;  // (lround of an overflowing ratio is UB)
      throw InputError(shape.where, "geometry.shapes", fmt::format("{}", width),
                       fmt::format("the shape is {} m wide along {}, less than one spacing ({})",
                                   width, axis_letter(a), dx),
                       "shapes at least one spacing wide along every axis");
    }
  }
}

// True if (x, y) lies in a cell of the complex or within `distance` of one.
bool near_a_cell(const NodeSets& nodes, double x, double y, double distance) {
  std::vector<Vec3> corners;
  for (std::size_t p = 0; p < nodes.cells.cell_count(); ++p) {
    corners.clear();
    for (const std::int32_t node : nodes.cells.corners(p))
      corners.push_back(nodes.sph_nodes.point(static_cast<std::size_t>(node)));
    if (polygon_contains(corners, x, y, distance)) return true;
  }
  return false;
}

/// A point group picks its nearest node; a point more than half a spacing from the body lies
/// outside it or in a hole, and snapping it would silently move it. On the lattice, "from the
/// body" is "along some axis from every node". Triangle nodes are not on a grid: a point inside a
/// triangle may lie farther than h/2 along an axis from each of its corners, so there the test is
/// the distance to the cells (docs/theory.md §3.6).
void refuse_point_off_the_body(const NodeSets& nodes, const GroupSpec& group, std::size_t nearest) {
  const PointCloud& points = nodes.sph_nodes;
  const double half = 0.5 * nodes.spacing * (1.0 + kLatticeTolerance);
  double distance_squared = 0.0;
  bool within = true;
  for (int a = 0; a < nodes.dimension; ++a) {
    const double offset = points.position[a][nearest] - group.point[a];
    distance_squared += offset * offset;
    if (std::abs(offset) > half) within = false;
  }
  const bool lattice = nodes.on_lattice();
  if (!lattice) within = near_a_cell(nodes, group.point[0], group.point[1], half);
  if (within) return;
  const auto coordinates = [&](auto&& coordinate) {
    std::string text;
    for (int a = 0; a < nodes.dimension; ++a)
      text += fmt::format("{}{}", a > 0 ? ", " : "", coordinate(a));
    return nodes.dimension == 1 ? text : "[" + text + "]";
  };
  throw InputError(
      group.where, "groups." + group.name + ".point",
      coordinates([&](int a) { return group.point[a]; }),
      fmt::format("the point is {:.6g} m from the nearest node (at {}), more than half a spacing "
                  "(dx/2 = {:.6g} m) {}: it lies outside the body",
                  std::sqrt(distance_squared),
                  coordinates([&](int a) { return points.position[a][nearest]; }),
                  0.5 * nodes.spacing, lattice ? "along an axis" : "from every cell"),
      lattice ? "a point within half a spacing, along every axis, of a node of the body"
              : "a point within half a spacing of a cell of the body");
}

// Length (1D) or area (2D) of a shape, and its boundary length (2D).
std::pair<double, double> shape_measure(const ShapeSpec& shape, int dimension) {
  const std::vector<Vec3>& v = shape.vertices;
  if (dimension < 2 || shape.kind == ShapeSpec::Kind::Segment)
    return {std::abs(v[1][0] - v[0][0]), 0.0};
  if (shape.kind == ShapeSpec::Kind::Rectangle) {
    const double w = std::abs(v[1][0] - v[0][0]), h = std::abs(v[1][1] - v[0][1]);
    return {w * h, 2.0 * (w + h)};
  }
  double twice_area = 0.0, perimeter = 0.0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const Vec3& a = v[k];
    const Vec3& b = v[(k + 1) % v.size()];
    twice_area += a[0] * b[1] - b[0] * a[1];
    perimeter += std::hypot(b[0] - a[0], b[1] - a[1]);
  }
  return {0.5 * std::abs(twice_area), perimeter};
}

// The lattice the builder fills, private to it: an index per axis, and the node at each index.
using LatticeIndex = std::array<std::int32_t, 3>;
struct Lattice {
  int dimension = 1;
  std::array<std::int32_t, 3> size{1, 1, 1};  // extent, in nodes, per axis
  std::vector<std::int32_t> node;             // node at each index (x fastest), -1 where none

  std::int32_t at(const LatticeIndex& index) const {
    std::size_t flat = 0;
    for (int a = dimension - 1; a >= 0; --a) {
      if (index[a] < 0 || index[a] >= size[a]) return -1;
      flat = flat * static_cast<std::size_t>(size[a]) + static_cast<std::size_t>(index[a]);
    }
    return node[flat];
  }
};

}  // namespace

Box bounding_box(const GeometrySpec& geometry, int dimension) {
  Box box;
  const auto include = [&](const Vec3& point) {
    for (int a = 0; a < dimension; ++a) {
      box.min[a] = std::min(box.min[a], point[a]);
      box.max[a] = std::max(box.max[a], point[a]);
    }
  };
  for (const ShapeSpec& shape : geometry.shapes)
    for (const Vec3& vertex : shape.vertices)
      include(vertex);
  if (!geometry.mesh.empty())
    for (const auto& point : read_gmsh_mesh(geometry.mesh, geometry.mesh_where).points)
      include({point[0], point[1], 0.0});
  return box;
}

NodeEstimate estimate_node_sets(const GeometrySpec& geometry, int dimension) {
  NodeEstimate estimate;
  if (!geometry.mesh.empty()) {  // a mesh file: its own counts (§3.8)
    const MeshFileSize size = mesh_file_size(geometry);
    estimate.sph_nodes = estimate.largest_shape_nodes = static_cast<double>(size.nodes);
    estimate.stress_points = static_cast<double>(size.triangles);
    return estimate;
  }
  const double dx = geometry.spacing;
  const bool triangles = geometry.cells == CellLayout::Triangles && dimension >= 2;
  // Triangles: near-equilateral ones of edge a = kTriangleEdgeFraction dx (measured, §3.6), each
  // of area sqrt(3)/4 a^2; Euler's formula gives nodes = (triangles + boundary nodes) / 2 + 1.
  const double edge = kTriangleEdgeFraction * dx;
  for (std::size_t s = 0; s < geometry.shapes.size(); ++s) {
    const auto [measure, boundary] = shape_measure(geometry.shapes[s], dimension);
    const double cells = triangles ? measure / (0.25 * std::sqrt(3.0) * edge * edge)
                                   : measure / std::pow(dx, dimension);
    const double nodes = triangles       ? 0.5 * (cells + boundary / edge) + 1.0
                         : dimension < 2 ? cells + 1.0
                                         : cells + 0.5 * boundary / dx + 1.0;
    estimate.sph_nodes += nodes;
    estimate.stress_points += cells;
    if (nodes > estimate.largest_shape_nodes) {
      estimate.largest_shape_nodes = nodes;
      estimate.largest_shape = s;
    }
  }
  if (triangles) return estimate;  // no lattice, no lookup over the bounding box
  const Box box = bounding_box(geometry, dimension);
  estimate.lattice_points = 1.0;
  for (int a = 0; a < dimension; ++a)
    estimate.lattice_points *= std::floor((box.max[a] - box.min[a]) / dx + 0.5) + 1.0;
  estimate.sph_nodes = std::min(estimate.sph_nodes, estimate.lattice_points);
  estimate.stress_points = std::min(estimate.stress_points, estimate.lattice_points);
  return estimate;
}

void check_cells(const NodeSets& nodes, const GeometrySpec& geometry) {
  const CellComplex& cells = nodes.cells;
  for (std::size_t p = 0; p < cells.cell_count(); ++p) {
    const CellCorners corners = cells.corner_positions(nodes.sph_nodes, p);
    const double measure = cell_measure(cells.kind(p), corners);
    const double quality = cell_quality(cells.kind(p), corners);
    if (measure > 0.0 && quality >= kMinimumCellQuality) continue;
    const auto centroid = cell_centroid(cells.kind(p), corners);
    const int shape =
        covering_shape(geometry, nodes.dimension, centroid, kSpacingTolerance * nodes.spacing);
    const SourceLocation& where = shape >= 0 ? geometry.shapes[shape].where : geometry.where;
    throw InputError(
        where, "geometry.shapes", shape >= 0 ? fmt::format("shape {}", shape + 1) : "",
        fmt::format("the {} {} with corners {} {} (signed measure {:.6g} m^{}, smallest corner "
                    "sine {:.3g})",
                    kind_name(cells.kind(p)), p, describe_corners(nodes, cells, p),
                    measure <= 0.0 ? "is degenerate or inverted" : "is a sliver", measure,
                    nodes.dimension, quality),
        fmt::format("cells of positive measure whose smallest corner has a sine of at least {:.3g} "
                    "(1 degree): a finer spacing, or no vertex angle that sharp",
                    kMinimumCellQuality));
  }
}

NodeSets build_node_sets(const GeometrySpec& geometry, int dimension,
                         const std::vector<std::string>& material_names) {
  NodeSets nodes;
  nodes.dimension = dimension;
  nodes.spacing = geometry.spacing;
  nodes.material_names = material_names;
  nodes.sph_nodes.dimension = dimension;
  nodes.stress_points.dimension = dimension;

  const double dx = geometry.spacing;
  const double tolerance = kLatticeTolerance * dx;
  const Box box = bounding_box(geometry, dimension);
  const Vec3 origin = box.min;  // the position of lattice index (0, 0, 0)
  check_vertices_on_lattice(geometry, dimension, origin);
  Lattice lattice;
  lattice.dimension = dimension;
  for (int a = 0; a < dimension; ++a)
    lattice.size[a] = static_cast<std::int32_t>(std::lround((box.max[a] - box.min[a]) / dx)) + 1;

  auto material_of_shape = [&](int shape) {
    return shape_material(geometry, shape, material_names);
  };
  auto lattice_position = [&](const LatticeIndex& index, double shift) {
    Vec3 x{};
    for (int a = 0; a < dimension; ++a)
      x[a] = origin[a] + (index[a] + shift) * dx;
    return x;
  };

  const std::int32_t nx = lattice.size[0];
  const std::int32_t ny = dimension >= 2 ? lattice.size[1] : 1;
  lattice.node.assign(static_cast<std::size_t>(nx) * ny, -1);
  const double node_volume = std::pow(dx, dimension);
  for (std::int32_t j = 0; j < ny; ++j)
    for (std::int32_t i = 0; i < nx; ++i) {
      const LatticeIndex index{i, j, 0};
      const Vec3 x = lattice_position(index, 0.0);
      const int shape = covering_shape(geometry, dimension, x, tolerance);
      if (shape < 0) continue;
      lattice.node[static_cast<std::size_t>(j) * nx + i] =
          static_cast<std::int32_t>(nodes.sph_nodes.size());
      nodes.sph_nodes.push_back(x, node_volume);
      nodes.node_material.push_back(material_of_shape(shape));
    }

  // A stress point sits at the centre of every lattice cell whose corners are all nodes and whose
  // centre lies inside the body (the second test matters only for concave outlines).
  const std::int32_t cells_y = dimension >= 2 ? ny - 1 : 1;
  std::vector<std::int32_t> cell_material;
  std::vector<LatticeIndex> lower_corner;  // of each cell
  for (std::int32_t j = 0; j < cells_y; ++j)
    for (std::int32_t i = 0; i + 1 < nx; ++i) {
      bool complete = true;
      for (std::int32_t dj = 0; dj <= (dimension >= 2 ? 1 : 0); ++dj)
        for (std::int32_t di = 0; di <= 1; ++di)
          if (lattice.at({i + di, j + dj, 0}) < 0) complete = false;
      if (!complete) continue;
      const LatticeIndex index{i, j, 0};
      Vec3 centre = lattice_position(index, 0.5);
      if (dimension < 2) centre[1] = 0.0;
      const int shape = covering_shape(geometry, dimension, centre, tolerance);
      if (shape < 0) continue;
      nodes.stress_points.push_back(centre, node_volume);
      lower_corner.push_back(index);
      cell_material.push_back(material_of_shape(shape));
    }
  // The lattice cells as a complex: corners counter-clockwise from the lower left (2D), left to
  // right (1D).
  nodes.cells = CellComplex(dimension, nodes.sph_nodes.size());
  for (std::size_t p = 0; p < nodes.stress_points.size(); ++p) {
    const LatticeIndex& lower = lower_corner[p];
    if (dimension < 2) {
      const std::array<std::int32_t, 2> corners{lattice.at(lower),
                                                lattice.at({lower[0] + 1, 0, 0})};
      nodes.cells.add_cell(CellKind::Segment, corners, cell_material[p]);
    } else {
      const std::array<std::int32_t, 4> corners{
          lattice.at(lower), lattice.at({lower[0] + 1, lower[1], 0}),
          lattice.at({lower[0] + 1, lower[1] + 1, 0}), lattice.at({lower[0], lower[1] + 1, 0})};
      nodes.cells.add_cell(CellKind::Quadrilateral, corners, cell_material[p]);
    }
  }
  nodes.cells.finish(nodes.sph_nodes);
  nodes.outline = Outline(nodes.cells, nodes.sph_nodes);

  if (nodes.sph_nodes.size() < 2)
    throw InputError(geometry.where, "geometry.spacing", fmt::format("{}", dx),
                     "the shapes hold fewer than two nodes at this spacing",
                     "a spacing smaller than the shapes");
  return nodes;
}

std::map<std::string, std::vector<std::int32_t>> select_groups(
    const NodeSets& nodes, const std::vector<GroupSpec>& groups) {
  std::map<std::string, std::vector<std::int32_t>> selected;
  const PointCloud& points = nodes.sph_nodes;
  const std::size_t n = points.size();
  const double tolerance = kLatticeTolerance * nodes.spacing;

  auto select_if = [&](auto&& predicate) {
    std::vector<std::int32_t> members;
    for (std::size_t i = 0; i < n; ++i)
      if (predicate(i)) members.push_back(static_cast<std::int32_t>(i));
    return members;
  };
  auto edge = [&](int axis, bool upper) {
    const auto [lo, hi] =
        std::minmax_element(points.position[axis].begin(), points.position[axis].end());
    const double target = upper ? *hi : *lo;
    return select_if(
        [&](std::size_t i) { return std::abs(points.position[axis][i] - target) <= tolerance; });
  };

  selected["all"] = select_if([](std::size_t) { return true; });
  selected["xmin"] = edge(0, false);
  selected["xmax"] = edge(0, true);
  if (nodes.dimension >= 2) {
    selected["ymin"] = edge(1, false);
    selected["ymax"] = edge(1, true);
  }

  for (const GroupSpec& group : groups) {
    std::vector<std::int32_t> members;
    switch (group.kind) {
      case GroupSpec::Kind::All:
        members = selected["all"];
        break;
      case GroupSpec::Kind::Edge: {
        const int axis = group.edge[0] == 'x' ? 0 : 1;
        members = edge(axis, group.edge.substr(1) == "max");
        break;
      }
      case GroupSpec::Kind::Box:
        members = select_if([&](std::size_t i) {
          for (int a = 0; a < nodes.dimension; ++a)
            if (points.position[a][i] < group.min[a] - tolerance ||
                points.position[a][i] > group.max[a] + tolerance)
              return false;
          return true;
        });
        break;
      case GroupSpec::Kind::Polygon:
        members = select_if([&](std::size_t i) {
          return polygon_contains(group.vertices, points.position[0][i], points.position[1][i],
                                  tolerance);
        });
        break;
      case GroupSpec::Kind::Physical: {
        const auto found = nodes.mesh_groups.find(group.physical);
        if (found == nodes.mesh_groups.end()) {
          std::string names;
          for (const auto& [name, group_nodes] : nodes.mesh_groups)
            names += (names.empty() ? "'" : ", '") + name + "'";
          throw InputError(
              group.where, "groups." + group.name + ".physical", group.physical,
              "the mesh file has no physical group of this name (with nodes)",
              names.empty() ? "none: the mesh file defines no physical group" : "one of " + names);
        }
        members = found->second;
        break;
      }
      case GroupSpec::Kind::Point: {
        std::size_t nearest = 0;
        double best = std::numeric_limits<double>::max();
        for (std::size_t i = 0; i < n; ++i) {
          double distance_squared = 0.0;
          for (int a = 0; a < nodes.dimension; ++a)
            distance_squared += std::pow(points.position[a][i] - group.point[a], 2);
          if (distance_squared < best) {
            best = distance_squared;
            nearest = i;
          }
        }
        refuse_point_off_the_body(nodes, group, nearest);
        members = {static_cast<std::int32_t>(nearest)};
        break;
      }
    }
    if (members.empty())
      throw InputError(group.where, "groups." + group.name, "", "the group selects no SPH node",
                       "a selector that contains at least one node of the lattice");
    selected[group.name] = std::move(members);
  }
  return selected;
}

}  // namespace rktsph
