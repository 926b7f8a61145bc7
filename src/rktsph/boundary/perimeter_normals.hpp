// The normals of a body's faces on its moving configuration (docs/theory.md §9.7): each facet
// keeps its identity (the node and the outline facets it gathers), and its outward unit normal is
// the perpendicular of the perimeter through the node, from the current positions of the node's
// two neighbours along the face (the other ends of its outline facets).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "rktsph/boundary/surface_set.hpp"
#include "rktsph/core/point_cloud.hpp"
#include "rktsph/mesh/outline.hpp"

namespace rktsph {

class PerimeterNormals {
 public:
  /// The facets of `surface`, made from `outline` (outline_surface) on the configuration
  /// `reference`: for each, the nodes before and after it along its face (the node itself where
  /// the face ends there).
  PerimeterNormals(const Outline& outline, const PointCloud& reference, const SurfaceSet& surface);

  /// Sets the normal of every facet of `surface` (the same facets) from the positions `nodes`.
  /// A 1D body keeps its normals -x and +x.
  void update(const PointCloud& nodes, SurfaceSet& surface) const;

 private:
  int dimension_ = 1;
  std::vector<std::array<std::int32_t, 2>> ends_;  // per facet: the nodes before and after it
  std::vector<double> orientation_;                // +-1: which perpendicular is outward
};

}  // namespace rktsph
