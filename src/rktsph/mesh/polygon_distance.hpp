// The signed distance of a point to a simple polygon, with the outward normal at the nearest point
// of its outline (2D): for rigid bodies in contact and for cells that must not cross them
// (docs/theory.md §9.18).
#pragma once

#include <span>

#include "rktsph/core/small_tensor.hpp"

namespace rktsph {

/// Where a point lies against a polygon: its depth inside (negative outside) and the outward unit
/// normal of the polygon at the nearest point of its outline (2D).
struct PolygonDistance {
  double depth = 0.0;
  Vec3 normal{};
};

/// The signed distance of (x, y) to the simple polygon `vertices` (either orientation).
PolygonDistance polygon_distance(std::span<const Vec3> vertices, double x, double y);

}  // namespace rktsph
