// Shapes for geometry tests: a segment, a rectangle and a polygon of one material, and a slope of
// two materials with vertices off any lattice.
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

inline ShapeSpec segment(double x0, double x1, const std::string& material) {
  ShapeSpec shape;
  shape.kind = ShapeSpec::Kind::Segment;
  shape.vertices = {{x0, 0.0, 0.0}, {x1, 0.0, 0.0}};
  shape.material = material;
  return shape;
}

/// A 13.1 m wide slope of "soil" on a 1 m layer of "rock", its crest and toe off any lattice.
inline std::vector<ShapeSpec> two_material_slope() {
  return {polygon({{0.0, 0.0, 0.0},
                   {13.1, 0.0, 0.0},
                   {13.1, 2.3, 0.0},
                   {9.7, 2.3, 0.0},
                   {3.7, 5.3, 0.0},
                   {0.0, 5.3, 0.0}},
                  "soil"),
          rectangle(0.0, 0.0, 13.1, 1.0, "rock")};
}

}  // namespace rktsph::test
