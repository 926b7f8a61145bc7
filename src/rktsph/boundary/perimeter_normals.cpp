#include "rktsph/boundary/perimeter_normals.hpp"

#include <cmath>

namespace rktsph {

namespace {

// The tangent from node `from` to node `to` and its perpendicular (t_y, -t_x).
std::array<double, 2> perpendicular(const PointCloud& nodes, std::int32_t from, std::int32_t to) {
  const auto a = static_cast<std::size_t>(from), b = static_cast<std::size_t>(to);
  return {nodes.position[1][b] - nodes.position[1][a],
          -(nodes.position[0][b] - nodes.position[0][a])};
}

}  // namespace

PerimeterNormals::PerimeterNormals(const Outline& outline, const PointCloud& reference,
                                   const SurfaceSet& surface)
    : dimension_(outline.dimension()) {
  if (dimension_ != 2) return;
  ends_.resize(surface.facet_count());
  orientation_.assign(surface.facet_count(), 1.0);
  for (std::size_t k = 0; k < surface.size(); ++k) {
    const std::int32_t node = surface.node[k];
    for (std::int32_t f = surface.facets_begin(k); f < surface.facets_end(k); ++f) {
      const Vec3 normal = surface.facet_normal(f);
      // The neighbours along the face: the far ends of the outline facets the facet gathers,
      // the one lower along the face's axis (the axis the normal mostly is not on) first.
      const std::size_t along = std::abs(normal[0]) > std::abs(normal[1]) ? 1 : 0;
      std::array<std::int32_t, 2> ends{node, node};
      for (const std::int32_t piece : surface.pieces(f)) {
        const std::int32_t other = outline.other_node(static_cast<std::size_t>(piece), node);
        const bool lower = reference.position[along][static_cast<std::size_t>(other)] <
                           reference.position[along][static_cast<std::size_t>(node)];
        ends[lower ? 0 : 1] = other;
      }
      const auto i = static_cast<std::size_t>(f);
      ends_[i] = ends;
      const auto p = perpendicular(reference, ends[0], ends[1]);
      orientation_[i] = p[0] * normal[0] + p[1] * normal[1] >= 0.0 ? 1.0 : -1.0;
    }
  }
}

void PerimeterNormals::update(const PointCloud& nodes, SurfaceSet& surface) const {
  if (dimension_ != 2) return;
  for (std::size_t i = 0; i < ends_.size(); ++i) {
    const auto& [before, after] = ends_[i];
    if (before == after) continue;  // an isolated node: no face to follow
    const auto p = perpendicular(nodes, before, after);
    const double scale = orientation_[i] / std::hypot(p[0], p[1]);
    surface.normal[0][i] = p[0] * scale;
    surface.normal[1][i] = p[1] * scale;
  }
}

}  // namespace rktsph
