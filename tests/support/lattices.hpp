// Test lattices: a 1D bar and a 2D rectangle of one material ("soil") at spacing dx.
#pragma once

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

}  // namespace rktsph::test
