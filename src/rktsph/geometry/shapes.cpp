#include "rktsph/geometry/shapes.hpp"

#include <algorithm>
#include <cmath>

namespace rktsph {

namespace {

double distance_to_segment(double px, double py, const Vec3& a, const Vec3& b) {
  const double ex = b[0] - a[0], ey = b[1] - a[1];
  const double length_squared = ex * ex + ey * ey;
  double s = length_squared > 0.0 ? ((px - a[0]) * ex + (py - a[1]) * ey) / length_squared : 0.0;
  s = std::clamp(s, 0.0, 1.0);
  return std::hypot(px - (a[0] + s * ex), py - (a[1] + s * ey));
}

}  // namespace

bool polygon_contains(const std::vector<Vec3>& vertices, double x, double y, double tolerance) {
  const std::size_t n = vertices.size();
  for (std::size_t k = 0; k < n; ++k)
    if (distance_to_segment(x, y, vertices[k], vertices[(k + 1) % n]) <= tolerance) return true;
  // Even-odd ray casting towards +x.
  bool inside = false;
  for (std::size_t k = 0, previous = n - 1; k < n; previous = k++) {
    const Vec3& a = vertices[k];
    const Vec3& b = vertices[previous];
    if ((a[1] > y) != (b[1] > y)) {
      const double crossing = a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
      if (x < crossing) inside = !inside;
    }
  }
  return inside;
}

bool shape_contains(const ShapeSpec& shape, int dimension, const Vec3& x, double tolerance) {
  switch (shape.kind) {
    case ShapeSpec::Kind::Segment:
      return x[0] >= shape.vertices[0][0] - tolerance && x[0] <= shape.vertices[1][0] + tolerance;
    case ShapeSpec::Kind::Rectangle:
      for (int a = 0; a < dimension; ++a)
        if (x[a] < shape.vertices[0][a] - tolerance || x[a] > shape.vertices[1][a] + tolerance)
          return false;
      return true;
    case ShapeSpec::Kind::Polygon:
      return polygon_contains(shape.vertices, x[0], x[1], tolerance);
  }
  return false;
}

int covering_shape(const GeometrySpec& geometry, int dimension, const Vec3& x, double tolerance) {
  for (int s = static_cast<int>(geometry.shapes.size()) - 1; s >= 0; --s)
    if (shape_contains(geometry.shapes[s], dimension, x, tolerance)) return s;
  return -1;
}

std::int32_t shape_material(const GeometrySpec& geometry, int shape,
                            const std::vector<std::string>& material_names) {
  const ShapeSpec& spec = geometry.shapes[static_cast<std::size_t>(shape)];
  const auto it = std::find(material_names.begin(), material_names.end(), spec.material);
  if (it == material_names.end())
    throw InputError(spec.where, "geometry.shapes.material", spec.material, "unknown material",
                     "a name defined under 'materials'");
  return static_cast<std::int32_t>(it - material_names.begin());
}

}  // namespace rktsph
