#include "rktsph/mesh/delaunay_cells.hpp"
#include "rktsph/mesh/polygon_distance.hpp"

// CGAL's headers are under /usr/include, a system directory, so their own warnings are not ours.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
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
// A face's info: its mark (kDropped, kKept, kInSolid).
using FlaggedFace = CGAL::Triangulation_face_base_with_info_2<int, DelaunayKernel>;
using DelaunayStructure = CGAL::Triangulation_data_structure_2<IndexedVertex, FlaggedFace>;
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
// A face's mark: a cell, left out by the alpha criterion (the repairs may keep it again), or
// crossing a solid (never kept).
constexpr int kDropped = 0, kKept = 1, kInSolid = 2;
// How deep, in spacings, a triangle's centroid or edge midpoint may lie inside a solid: nodes in
// contact sit on its face to within a step's motion.
constexpr double kSolidTolerance = 0.03;

// A triangle crosses a solid when its centroid or the midpoint of an edge lies inside it deeper
// than `tolerance`: a triangle spanning a body's corner from the nodes under it to those beside it
// does; one whose edge lies along the body's face, its nodes in contact, does not.
bool crosses_a_solid(const std::array<DelaunayPoint, 3>& p,
                     std::span<const std::vector<Vec3>> solids, double tolerance) {
  for (const std::vector<Vec3>& polygon : solids) {
    const double cx = (p[0].x() + p[1].x() + p[2].x()) / 3.0;
    const double cy = (p[0].y() + p[1].y() + p[2].y()) / 3.0;
    if (polygon_distance(polygon, cx, cy).depth > tolerance) return true;
    for (std::size_t k = 0; k < 3; ++k) {
      const DelaunayPoint& a = p[k];
      const DelaunayPoint& b = p[(k + 1) % 3];
      const double depth =
          polygon_distance(polygon, 0.5 * (a.x() + b.x()), 0.5 * (a.y() + b.y())).depth;
      if (depth > tolerance) return true;
    }
  }
  return false;
}

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

// Where the kept faces around a node form more than one fan (two parts of the body touching at a
// node, or a notch closing on it), the outline passes the node twice and its surface has no
// single side: the dropped faces of the smallest gap that is not the outside are kept again,
// until every node has one fan (docs/theory.md §3.9). Returns how many faces were kept again.
std::size_t join_fans(NodeTriangulation& triangulation) {
  std::size_t restored = 0;
  if (triangulation.dimension() < 2) return restored;  // nodes on a line: no face
  for (bool changed = true; changed;) {
    changed = false;
    for (auto vertex = triangulation.finite_vertices_begin();
         vertex != triangulation.finite_vertices_end(); ++vertex) {
      std::vector<NodeTriangulation::Face_handle> around;
      auto face = triangulation.incident_faces(vertex), end = face;
      do {
        around.push_back(face);
      } while (++face != end);
      const auto kept = [&](std::size_t k) {
        return !triangulation.is_infinite(around[k]) && around[k]->info() == kKept;
      };
      const std::size_t n = around.size();
      std::size_t start = n;  // a kept face that follows a gap
      std::size_t fans = 0;
      for (std::size_t k = 0; k < n; ++k)
        if (kept(k) && !kept((k + n - 1) % n)) {
          ++fans;
          if (start == n) start = k;
        }
      if (fans < 2) continue;
      // The gaps in order from `start`; the smallest one of finite faces is filled.
      std::size_t best_begin = n, best_length = n + 1;
      for (std::size_t k = 0; k < n;) {
        const std::size_t at = (start + k) % n;
        if (kept(at)) {
          ++k;
          continue;
        }
        std::size_t length = 0;
        bool outside = false;
        while (k + length < n && !kept((start + k + length) % n)) {
          const auto gap = around[(start + k + length) % n];
          outside = outside || triangulation.is_infinite(gap) || gap->info() == kInSolid;
          ++length;
        }
        if (!outside && length < best_length) {
          best_begin = at;
          best_length = length;
        }
        k += length;
      }
      if (best_begin == n) continue;
      for (std::size_t k = 0; k < best_length; ++k)
        around[(best_begin + k) % n]->info() = kKept;
      restored += best_length;
      changed = true;
    }
  }
  return restored;
}

// A node the alpha criterion left in no cell keeps the Delaunay triangle at it with the smallest
// circumradius (docs/theory.md §9.17): a node at the thinned front of a flow stays in the body,
// held by a stretched cell. Returns how many faces were kept again.
std::size_t keep_every_node(NodeTriangulation& triangulation) {
  std::size_t restored = 0;
  if (triangulation.dimension() < 2) return restored;
  for (auto vertex = triangulation.finite_vertices_begin();
       vertex != triangulation.finite_vertices_end(); ++vertex) {
    NodeTriangulation::Face_handle best;
    double smallest = HUGE_VAL;
    auto face = triangulation.incident_faces(vertex), end = face;
    bool in_a_cell = false;
    do {
      if (triangulation.is_infinite(face) || face->info() == kInSolid) continue;
      if (face->info() == kKept) {
        in_a_cell = true;
        break;
      }
      const double radius = circumradius(
          {face->vertex(0)->point(), face->vertex(1)->point(), face->vertex(2)->point()});
      if (radius < smallest) {
        smallest = radius;
        best = face;
      }
    } while (++face != end);
    if (in_a_cell || best == NodeTriangulation::Face_handle()) continue;
    best->info() = kKept;
    ++restored;
  }
  return restored;
}

}  // namespace

DelaunayCells delaunay_cells(const PointCloud& nodes, std::span<const double> spacing,
                             std::span<const std::int32_t> node_material, double alpha,
                             bool every_node_in_a_cell, std::span<const std::vector<Vec3>> solids) {
  require_input(nodes, spacing, node_material, alpha);
  std::vector<std::pair<DelaunayPoint, std::int32_t>> points;
  points.reserve(nodes.size());
  for (std::size_t n = 0; n < nodes.size(); ++n)
    points.emplace_back(DelaunayPoint(nodes.position[0][n], nodes.position[1][n]),
                        static_cast<std::int32_t>(n));
  NodeTriangulation triangulation(points.begin(), points.end());
  if (triangulation.number_of_vertices() != nodes.size())
    throw std::invalid_argument(fmt::format(
        "delaunay_cells: {} nodes but {} distinct positions; two nodes lie at one position",
        nodes.size(), triangulation.number_of_vertices()));

  DelaunayCells formed{CellComplex(2, nodes.size()), {}};
  for (auto face = triangulation.finite_faces_begin(); face != triangulation.finite_faces_end();
       ++face) {
    ++formed.count.triangles;
    std::array<DelaunayPoint, 3> position{};
    double mean_spacing = 0.0;
    for (int k = 0; k < 3; ++k) {
      position[static_cast<std::size_t>(k)] = face->vertex(k)->point();
      mean_spacing += spacing[static_cast<std::size_t>(face->vertex(k)->info())] / 3.0;
    }
    face->info() = circumradius(position) <= alpha * mean_spacing ? kKept : kDropped;  // (3.15)
    if (crosses_a_solid(position, solids, kSolidTolerance * mean_spacing)) face->info() = kInSolid;
  }
  if (every_node_in_a_cell) formed.count.restored += keep_every_node(triangulation);
  formed.count.restored += join_fans(triangulation);
  // Faces in the triangulation's order, which follows the input: the complex is the same for the
  // same nodes.
  for (auto face = triangulation.finite_faces_begin(); face != triangulation.finite_faces_end();
       ++face) {
    if (face->info() != kKept) {
      ++formed.count.dropped;
      continue;
    }
    std::array<std::int32_t, 3> corner{};
    for (int k = 0; k < 3; ++k)
      corner[static_cast<std::size_t>(k)] = face->vertex(k)->info();
    // CGAL's faces are counter-clockwise, as the complex's triangles.
    formed.cells.add_cell(CellKind::Triangle, corner, cell_material(corner, node_material));
  }
  formed.cells.finish(nodes);
  for (std::size_t n = 0; n < nodes.size(); ++n)
    if (formed.cells.cells_of(n).empty()) ++formed.count.isolated_nodes;
  return formed;
}

}  // namespace rktsph
