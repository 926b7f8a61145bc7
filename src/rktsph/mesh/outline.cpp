#include "rktsph/mesh/outline.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "rktsph/mesh/cell_geometry.hpp"

namespace rktsph {

Outline::Outline(const CellComplex& cells, const PointCloud& nodes)
    : dimension_(cells.dimension()) {
  // Every face of every cell, keyed by its sorted nodes; a key seen once is a boundary facet.
  struct Face {
    std::int32_t low, high;  // sorted nodes (1D: the node twice)
    std::int32_t first, second;
  };
  std::vector<Face> faces;
  for (std::size_t p = 0; p < cells.cell_count(); ++p) {
    const auto corners = cells.corners(p);
    for (const CellFace& face : cell_faces(cells.kind(p))) {
      const std::int32_t a = corners[static_cast<std::size_t>(face.corner[0])];
      if (face.count == 1) {
        // 1D: the end node, and the cell's other node, which says on which side the body is.
        const std::int32_t other = corners[static_cast<std::size_t>(1 - face.corner[0])];
        faces.push_back({a, a, a, other});
      } else {
        const std::int32_t b = corners[static_cast<std::size_t>(face.corner[1])];
        faces.push_back({std::min(a, b), std::max(a, b), a, b});
      }
    }
  }
  std::sort(faces.begin(), faces.end(), [](const Face& u, const Face& v) {
    return std::tie(u.low, u.high, u.first) < std::tie(v.low, v.high, v.first);
  });
  for (std::size_t k = 0; k < faces.size();) {
    std::size_t end = k + 1;
    while (end < faces.size() && faces[end].low == faces[k].low && faces[end].high == faces[k].high)
      ++end;
    if (end == k + 1) {
      first_.push_back(faces[k].first);
      second_.push_back(faces[k].second);
    }
    k = end;
  }
  // Node -> facets by a counting sort.
  const std::size_t n = cells.node_count();
  node_start_.assign(n + 1, 0);
  for (std::size_t f = 0; f < facet_count(); ++f) {
    ++node_start_[static_cast<std::size_t>(first_[f]) + 1];
    if (dimension_ >= 2) ++node_start_[static_cast<std::size_t>(second_[f]) + 1];
  }
  for (std::size_t i = 0; i < n; ++i)
    node_start_[i + 1] += node_start_[i];
  node_facet_.assign(static_cast<std::size_t>(node_start_[n]), 0);
  std::vector<std::int32_t> next(node_start_.begin(), node_start_.end() - 1);
  for (std::size_t f = 0; f < facet_count(); ++f) {
    node_facet_[static_cast<std::size_t>(next[static_cast<std::size_t>(first_[f])]++)] =
        static_cast<std::int32_t>(f);
    if (dimension_ >= 2)
      node_facet_[static_cast<std::size_t>(next[static_cast<std::size_t>(second_[f])]++)] =
          static_cast<std::int32_t>(f);
  }
  update(nodes);
}

void Outline::update(const PointCloud& nodes) {
  const std::size_t count = facet_count();
  for (auto& component : normal_)
    component.resize(count);
  measure_.resize(count);
  for (std::size_t f = 0; f < count; ++f) {
    const auto a = static_cast<std::size_t>(first_[f]), b = static_cast<std::size_t>(second_[f]);
    if (dimension_ < 2) {
      // Outward: away from the cell's other node.
      normal_[0][f] = nodes.position[0][a] >= nodes.position[0][b] ? 1.0 : -1.0;
      normal_[1][f] = 0.0;
      measure_[f] = 1.0;
      continue;
    }
    // The body lies left of a -> b, so the outward normal is the tangent turned clockwise.
    const double tx = nodes.position[0][b] - nodes.position[0][a];
    const double ty = nodes.position[1][b] - nodes.position[1][a];
    const double length = std::hypot(tx, ty);
    measure_[f] = length;
    // (+ 0.0 makes an exact zero component +0, as an axis-aligned face's normal is written.)
    normal_[0][f] = length > 0.0 ? ty / length + 0.0 : 0.0;
    normal_[1][f] = length > 0.0 ? -tx / length + 0.0 : 0.0;
  }
}

}  // namespace rktsph
