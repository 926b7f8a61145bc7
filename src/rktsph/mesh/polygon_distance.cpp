#include "rktsph/mesh/polygon_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rktsph {

PolygonDistance polygon_distance(std::span<const Vec3> vertices, double x, double y) {
  // The nearest point of the outline and whether (x, y) is inside (crossing number).
  double nearest = std::numeric_limits<double>::max();
  double near_x = x, near_y = y, edge_x = 0.0, edge_y = 0.0;
  bool inside = false;
  double twice_area = 0.0;
  const std::size_t n = vertices.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& a = vertices[k];
    const Vec3& b = vertices[(k + 1) % n];
    twice_area += a[0] * b[1] - b[0] * a[1];
    if ((a[1] > y) != (b[1] > y) && x < a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]))
      inside = !inside;
    const double ex = b[0] - a[0], ey = b[1] - a[1];
    const double length2 = ex * ex + ey * ey;
    const double s = std::clamp(((x - a[0]) * ex + (y - a[1]) * ey) / length2, 0.0, 1.0);
    const double px = a[0] + s * ex, py = a[1] + s * ey;
    const double distance = std::hypot(x - px, y - py);
    if (distance < nearest) {
      nearest = distance;
      near_x = px;
      near_y = py;
      edge_x = ex;
      edge_y = ey;
    }
  }
  PolygonDistance result;
  result.depth = inside ? nearest : -nearest;
  // Outside and off the edge's interior (at a corner) the normal points from the outline to the
  // point; otherwise it is the nearest edge's outward normal.
  const double length = std::hypot(edge_x, edge_y);
  const double orientation = twice_area > 0.0 ? 1.0 : -1.0;  // counter-clockwise: +1
  const Vec3 edge_normal{orientation * edge_y / length, -orientation * edge_x / length, 0.0};
  if (!inside && nearest > 0.0) {
    const Vec3 to_point{(x - near_x) / nearest, (y - near_y) / nearest, 0.0};
    result.normal = to_point;
  } else {
    result.normal = edge_normal;
  }
  return result;
}

}  // namespace rktsph
