#include "rktsph/mesh/delaunay_cells.hpp"

// CGAL's headers are under /usr/include, a system directory, so their own warnings are not ours.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace rktsph {

namespace {

using DelaunayKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using IndexedVertex = CGAL::Triangulation_vertex_base_with_info_2<std::int32_t, DelaunayKernel>;
using DelaunayStructure =
    CGAL::Triangulation_data_structure_2<IndexedVertex,
                                         CGAL::Triangulation_face_base_2<DelaunayKernel>>;
using NodeTriangulation = CGAL::Delaunay_triangulation_2<DelaunayKernel, DelaunayStructure>;
using DelaunayPoint = DelaunayKernel::Point_2;

void require_input(const PointCloud& nodes, std::span<const double> spacing,
                   std::span<const std::int32_t> node_material, double alpha) {
  if (nodes.dimension != 2)
    throw std::invalid_argument(
        fmt::format("delaunay_cells: the nodes are {}D; cells are formed in 2D", nodes.dimension));
  if (spacing.size() != nodes.size() || node_material.size() != nodes.size())
    throw std::invalid_argument(
        fmt::format("delaunay_cells: {} nodes, {} spacings and {} materials; one of each per node",
                    nodes.size(), spacing.size(), node_material.size()));
  if (!(alpha > 0.0) || !std::isfinite(alpha))
    throw std::invalid_argument(
        fmt::format("delaunay_cells: alpha {} is not a positive number", alpha));
  for (std::size_t n = 0; n < spacing.size(); ++n)
    if (!(spacing[n] > 0.0) || !std::isfinite(spacing[n]))
      throw std::invalid_argument(fmt::format(
          "delaunay_cells: the spacing of node {} is {}, not a positive number", n, spacing[n]));
}

// The circumradius of a triangle from its edges: R = abc / (4 A).
double circumradius(const std::array<DelaunayPoint, 3>& p) {
  const double a = std::sqrt(CGAL::squared_distance(p[1], p[2]));
  const double b = std::sqrt(CGAL::squared_distance(p[2], p[0]));
  const double c = std::sqrt(CGAL::squared_distance(p[0], p[1]));
  const double area = std::abs(CGAL::area(p[0], p[1], p[2]));
  return area > 0.0 ? a * b * c / (4.0 * area) : HUGE_VAL;
}

// The material of at least two corners, else the first corner's in node order.
std::int32_t cell_material(const std::array<std::int32_t, 3>& corner,
                           std::span<const std::int32_t> node_material) {
  const auto m = [&](int k) { return node_material[static_cast<std::size_t>(corner[k])]; };
  if (m(0) == m(1) || m(0) == m(2)) return m(0);
  if (m(1) == m(2)) return m(1);
  int first = 0;
  for (int k = 1; k < 3; ++k)
    if (corner[k] < corner[first]) first = k;
  return m(first);
}

}  // namespace

DelaunayCells delaunay_cells(const PointCloud& nodes, std::span<const double> spacing,
                             std::span<const std::int32_t> node_material, double alpha) {
  require_input(nodes, spacing, node_material, alpha);
  std::vector<std::pair<DelaunayPoint, std::int32_t>> points;
  points.reserve(nodes.size());
  for (std::size_t n = 0; n < nodes.size(); ++n)
    points.emplace_back(DelaunayPoint(nodes.position[0][n], nodes.position[1][n]),
                        static_cast<std::int32_t>(n));
  const NodeTriangulation triangulation(points.begin(), points.end());
  if (triangulation.number_of_vertices() != nodes.size())
    throw std::invalid_argument(fmt::format(
        "delaunay_cells: {} nodes but {} distinct positions; two nodes lie at one position",
        nodes.size(), triangulation.number_of_vertices()));

  DelaunayCells formed{CellComplex(2, nodes.size()), {}};
  // Faces in the triangulation's order, which follows the input: the complex is the same for the
  // same nodes.
  for (auto face = triangulation.finite_faces_begin(); face != triangulation.finite_faces_end();
       ++face) {
    ++formed.count.triangles;
    std::array<std::int32_t, 3> corner{};
    std::array<DelaunayPoint, 3> position{};
    double mean_spacing = 0.0;
    for (int k = 0; k < 3; ++k) {
      corner[static_cast<std::size_t>(k)] = face->vertex(k)->info();
      position[static_cast<std::size_t>(k)] = face->vertex(k)->point();
      mean_spacing += spacing[static_cast<std::size_t>(face->vertex(k)->info())] / 3.0;
    }
    if (circumradius(position) > alpha * mean_spacing) {  // eq. 3.15
      ++formed.count.dropped;
      continue;
    }
    // CGAL's faces are counter-clockwise, as the complex's triangles.
    formed.cells.add_cell(CellKind::Triangle, corner, cell_material(corner, node_material));
  }
  formed.cells.finish(nodes);
  for (std::size_t n = 0; n < nodes.size(); ++n)
    if (formed.cells.cells_of(n).empty()) ++formed.count.isolated_nodes;
  return formed;
}

}  // namespace rktsph
