// Shapes for geometry tests: a rectangle and a polygon of one material.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "rktsph/case/case_description.hpp"

namespace rktsph::test {

inline ShapeSpec rectangle(double x0, double y0, double x1, double y1,
                           const std::string& material) {
  ShapeSpec shape;
  shape.kind = ShapeSpec::Kind::Rectangle;
  shape.vertices = {{x0, y0, 0.0}, {x1, y1, 0.0}};
  shape.material = material;
  return shape;
}

inline ShapeSpec polygon(std::vector<Vec3> vertices, const std::string& material) {
  ShapeSpec shape;
  shape.kind = ShapeSpec::Kind::Polygon;
  shape.vertices = std::move(vertices);
  shape.material = material;
  return shape;
}

}  // namespace rktsph::test
