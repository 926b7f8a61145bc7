#include "rktsph/geometry/triangle_node_sets.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>

#include "rktsph/geometry/gmsh_mesh.hpp"
#include "rktsph/mesh/cell_geometry.hpp"

namespace rktsph {

NodeSets triangle_node_sets(const std::vector<Vec3>& points,
                            std::vector<std::int32_t> node_material,
                            std::vector<MeshTriangle> triangles, double spacing,
                            const std::vector<std::string>& material_names) {
  for (MeshTriangle& triangle : triangles)
    std::rotate(triangle.corners.begin(),
                std::min_element(triangle.corners.begin(), triangle.corners.end()),
                triangle.corners.end());
  std::sort(triangles.begin(), triangles.end(),
            [](const MeshTriangle& a, const MeshTriangle& b) { return a.corners < b.corners; });

  NodeSets nodes;
  nodes.dimension = 2;
  nodes.spacing = spacing;
  nodes.layout = CellLayout::Triangles;
  nodes.material_names = material_names;
  nodes.sph_nodes.dimension = 2;
  nodes.stress_points.dimension = 2;
  for (const Vec3& x : points)
    nodes.sph_nodes.push_back(x, 0.0);
  nodes.node_material = std::move(node_material);
  // Stress points at the centroids, with the triangle's area; each node gets a third of the area
  // of each of its triangles (lumped, so the node volumes add up to the body's area, §3.6).
  nodes.cells = CellComplex(2, nodes.sph_nodes.size());
  const PointCloud& corners_of = nodes.sph_nodes;
  for (const MeshTriangle& triangle : triangles) {
    const CellCorners c = gather_corners(corners_of, triangle.corners);
    const double area = cell_measure(CellKind::Triangle, c);
    nodes.stress_points.push_back(cell_centroid(CellKind::Triangle, c), area);
    for (const std::int32_t node : triangle.corners) {
      nodes.sph_nodes.volume[static_cast<std::size_t>(node)] += area / 3.0;
      if (nodes.node_material[static_cast<std::size_t>(node)] < 0)
        nodes.node_material[static_cast<std::size_t>(node)] = triangle.material;
    }
    nodes.cells.add_cell(CellKind::Triangle, triangle.corners, triangle.material);
  }
  nodes.cells.finish(nodes.sph_nodes);
  nodes.outline = Outline(nodes.cells, nodes.sph_nodes);
  return nodes;
}

namespace {

[[noreturn]] void refuse_mesh(const GmshMesh& mesh, int line, const std::string& value,
                              const std::string& problem, const std::string& allowed) {
  throw InputError(SourceLocation{mesh.file.string(), line, 0}, "geometry.mesh", value, problem,
                   allowed);
}

/// Each triangle's material: its physical surface's name among the case's materials.
std::vector<std::int32_t> triangle_materials(const GmshMesh& mesh,
                                             const std::vector<std::string>& material_names) {
  std::vector<std::int32_t> material(mesh.triangles.size(), -1);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const GmshMesh::Triangle& triangle = mesh.triangles[t];
    if (triangle.physical.empty()) {
      if (material_names.size() == 1) {
        material[t] = 0;
        continue;
      }
      refuse_mesh(
          mesh, triangle.line, fmt::format("element {}", triangle.element),
          fmt::format("triangle {} is in no physical surface, and the case has {} materials",
                      triangle.element, material_names.size()),
          "each triangle in a physical surface named after its material (Gmsh: Physical "
          "Surface(\"soil\") = {...};), or a case with one material");
    }
    const auto found = std::find(material_names.begin(), material_names.end(), triangle.physical);
    if (found == material_names.end()) {
      std::string names;
      for (const std::string& name : material_names)
        names += (names.empty() ? "'" : ", '") + name + "'";
      refuse_mesh(
          mesh, triangle.line, triangle.physical,
          fmt::format("triangle {} is in the physical surface '{}', which names no material of "
                      "the case",
                      triangle.element, triangle.physical),
          fmt::format("physical surfaces named after the case's materials: {}", names));
    }
    material[t] = static_cast<std::int32_t>(found - material_names.begin());
  }
  return material;
}

/// The points numbered by (y, x): the new number of each file point. Two points at one position
/// (surfaces meshed apart, their shared curve carrying two sets of nodes) are refused.
std::vector<std::int32_t> number_by_height(const GmshMesh& mesh, double tolerance) {
  std::vector<std::int32_t> order(mesh.points.size());
  std::iota(order.begin(), order.end(), 0);
  const auto& p = mesh.points;
  std::sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    const auto& u = p[static_cast<std::size_t>(a)];
    const auto& v = p[static_cast<std::size_t>(b)];
    return u[1] != v[1] ? u[1] < v[1] : u[0] < v[0];
  });
  std::vector<std::int32_t> number(p.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    number[static_cast<std::size_t>(order[k])] = static_cast<std::int32_t>(k);
    // Near-coincident points sort next to each other unless another point lies between their
    // heights; the exact duplicates that unmerged surfaces give always do.
    if (k == 0) continue;
    const auto& a = p[static_cast<std::size_t>(order[k - 1])];
    const auto& b = p[static_cast<std::size_t>(order[k])];
    if (std::hypot(a[0] - b[0], a[1] - b[1]) <= tolerance) {
      const long first = mesh.node_tags[static_cast<std::size_t>(order[k - 1])];
      const long second = mesh.node_tags[static_cast<std::size_t>(order[k])];
      refuse_mesh(
          mesh, 0, fmt::format("nodes {} and {}", first, second),
          fmt::format("nodes {} and {} lie at the same position ({}, {}): the surfaces on "
                      "either side are not joined, and the body would split along the curve",
                      first, second, b[0], b[1]),
          "surfaces that share their common curves (Gmsh: Coherence; or BooleanFragments "
          "in OpenCASCADE), so that one node stands at each position");
    }
  }
  return number;
}

}  // namespace

NodeSets build_mesh_node_sets(const GeometrySpec& geometry,
                              const std::vector<std::string>& material_names) {
  const GmshMesh mesh = read_gmsh_mesh(geometry.mesh, geometry.mesh_where);
  const std::vector<std::int32_t> material = triangle_materials(mesh, material_names);
  // The spacing is the longest edge, as for the project's own triangles (§3.6).
  double spacing = 0.0, extent = 0.0;
  for (const GmshMesh::Triangle& triangle : mesh.triangles)
    for (std::size_t k = 0; k < 3; ++k) {
      const auto& a = mesh.points[static_cast<std::size_t>(triangle.corners[k])];
      const auto& b = mesh.points[static_cast<std::size_t>(triangle.corners[(k + 1) % 3])];
      spacing = std::max(spacing, std::hypot(a[0] - b[0], a[1] - b[1]));
      extent = std::max({extent, std::abs(a[0]), std::abs(a[1])});
    }
  const std::vector<std::int32_t> number = number_by_height(mesh, 1e-12 * std::max(extent, 1.0));
  std::vector<Vec3> points(mesh.points.size());
  for (std::size_t k = 0; k < mesh.points.size(); ++k)
    points[static_cast<std::size_t>(number[k])] = {mesh.points[k][0], mesh.points[k][1], 0.0};

  std::vector<MeshTriangle> triangles;
  std::map<std::pair<std::int32_t, std::int32_t>, int> edge_use;
  PointCloud cloud;
  cloud.dimension = 2;
  for (const Vec3& x : points)
    cloud.push_back(x, 0.0);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const GmshMesh::Triangle& triangle = mesh.triangles[t];
    MeshTriangle cell{{number[static_cast<std::size_t>(triangle.corners[0])],
                       number[static_cast<std::size_t>(triangle.corners[1])],
                       number[static_cast<std::size_t>(triangle.corners[2])]},
                      material[t]};
    // Gmsh orients a surface's triangles with the surface, so clockwise ones are turned.
    if (cell_measure(CellKind::Triangle, gather_corners(cloud, cell.corners)) < 0.0)
      std::swap(cell.corners[1], cell.corners[2]);
    const CellCorners corners = gather_corners(cloud, cell.corners);
    const double area = cell_measure(CellKind::Triangle, corners);
    const double quality = cell_quality(CellKind::Triangle, corners);
    if (!(area > 0.0) || quality < kMinimumCellQuality)
      refuse_mesh(
          mesh, triangle.line, fmt::format("element {}", triangle.element),
          fmt::format("triangle {} {} (area {:.6g} m^2, smallest corner sine {:.3g})",
                      triangle.element, area > 0.0 ? "is a sliver" : "has no area", area, quality),
          fmt::format("triangles of positive area whose smallest corner has a sine of at least "
                      "{:.3g} (1 degree)",
                      kMinimumCellQuality));
    for (std::size_t k = 0; k < 3; ++k) {
      const auto [low, high] = std::minmax(cell.corners[k], cell.corners[(k + 1) % 3]);
      if (++edge_use[{low, high}] > 2)
        refuse_mesh(mesh, triangle.line, fmt::format("element {}", triangle.element),
                    fmt::format("triangle {} shares an edge with two others: the mesh overlaps "
                                "itself, or a triangle is listed twice",
                                triangle.element),
                    "a conforming mesh, each edge in one or two triangles");
    }
    triangles.push_back(cell);
  }
  NodeSets nodes = triangle_node_sets(points, std::vector<std::int32_t>(points.size(), -1),
                                      std::move(triangles), spacing, material_names);
  for (const auto& [name, members] : mesh.physical_nodes) {
    std::vector<std::int32_t>& group = nodes.mesh_groups[name];
    for (const std::int32_t point : members)
      group.push_back(number[static_cast<std::size_t>(point)]);
    std::sort(group.begin(), group.end());
  }
  return nodes;
}

MeshFileSize mesh_file_size(const GeometrySpec& geometry) {
  const GmshMesh mesh = read_gmsh_mesh(geometry.mesh, geometry.mesh_where);
  return {mesh.points.size(), mesh.triangles.size()};
}

}  // namespace rktsph
