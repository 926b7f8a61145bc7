// Test lattices: a 1D bar and a 2D rectangle of one material ("soil") at spacing dx.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "rktsph/geometry/node_sets.hpp"

namespace rktsph::test {

inline NodeSets bar_lattice(double length, double dx) {
  GeometrySpec geometry;
  geometry.spacing = dx;
  ShapeSpec shape;
  shape.kind = ShapeSpec::Kind::Segment;
  shape.vertices = {{0.0, 0.0, 0.0}, {length, 0.0, 0.0}};
  shape.material = "soil";
  geometry.shapes.push_back(shape);
  return build_node_sets(geometry, 1, {"soil"});
}

inline NodeSets rectangle_lattice(double width, double height, double dx) {
  GeometrySpec geometry;
  geometry.spacing = dx;
  ShapeSpec shape;
  shape.kind = ShapeSpec::Kind::Rectangle;
  shape.vertices = {{0.0, 0.0, 0.0}, {width, height, 0.0}};
  shape.material = "soil";
  geometry.shapes.push_back(shape);
  return build_node_sets(geometry, 2, {"soil"});
}

/// The smallest coordinates of the nodes: the lattice's origin.
inline std::array<double, 2> lattice_origin(const NodeSets& nodes) {
  const PointCloud& points = nodes.sph_nodes;
  return {*std::min_element(points.position[0].begin(), points.position[0].end()),
          nodes.dimension >= 2
              ? *std::min_element(points.position[1].begin(), points.position[1].end())
              : 0.0};
}

/// Column and row of node k of a lattice body of origin `origin` (lattice_origin), from its
/// position.
inline std::array<std::int32_t, 2> lattice_index(const NodeSets& nodes, std::size_t k,
                                                 const std::array<double, 2>& origin) {
  const PointCloud& points = nodes.sph_nodes;
  return {
      static_cast<std::int32_t>(std::lround((points.position[0][k] - origin[0]) / nodes.spacing)),
      static_cast<std::int32_t>(std::lround((points.position[1][k] - origin[1]) / nodes.spacing))};
}
inline std::array<std::int32_t, 2> lattice_index(const NodeSets& nodes, std::size_t k) {
  return lattice_index(nodes, k, lattice_origin(nodes));
}

/// Columns and rows of the lattice spanned by the nodes.
inline std::array<std::int32_t, 2> lattice_extent(const NodeSets& nodes) {
  const auto origin = lattice_origin(nodes);
  std::array<std::int32_t, 2> extent{0, 0};
  for (std::size_t k = 0; k < nodes.sph_nodes.size(); ++k) {
    const auto index = lattice_index(nodes, k, origin);
    extent = {std::max(extent[0], index[0] + 1), std::max(extent[1], index[1] + 1)};
  }
  return extent;
}

/// The node at column i, row j of a lattice body (x = x_min + i dx, y = y_min + j dx), found by
/// its position: the builder keeps its lattice indices to itself. -1 if there is none.
inline std::int32_t lattice_node(const NodeSets& nodes, std::int32_t i, std::int32_t j) {
  const PointCloud& points = nodes.sph_nodes;
  const auto origin = lattice_origin(nodes);
  const double x = origin[0] + i * nodes.spacing, y = origin[1] + j * nodes.spacing;
  for (std::size_t k = 0; k < points.size(); ++k)
    if (std::abs(points.position[0][k] - x) < 1e-9 * nodes.spacing &&
        std::abs(points.position[1][k] - y) < 1e-9 * nodes.spacing)
      return static_cast<std::int32_t>(k);
  return -1;
}

}  // namespace rktsph::test
