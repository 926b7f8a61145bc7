// The normals of a lattice body's faces on its moving configuration (docs/theory.md §9.7): each
// facet keeps its identity (the node and the side of the lattice it faces), and its outward unit
// normal is the perpendicular of the perimeter through the node, from the current positions of the
// node's two neighbours along the face.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "rktsph/boundary/surface_set.hpp"
#include "rktsph/core/point_cloud.hpp"
#include "rktsph/geometry/node_sets.hpp"

namespace rktsph {

class PerimeterNormals {
 public:
  /// The facets of `surface`, a lattice surface of `reference` (lattice_surface): for each, the
  /// nodes before and after it along its face (the node itself where the face ends there).
  PerimeterNormals(const NodeSets& reference, const SurfaceSet& surface);

  /// Sets the normal of every facet of `surface` (the same facets) from the positions `nodes`.
  /// A 1D body keeps its normals -x and +x.
  void update(const PointCloud& nodes, SurfaceSet& surface) const;

 private:
  int dimension_ = 1;
  std::vector<std::array<std::int32_t, 2>> ends_;  // per facet: the nodes before and after it
  std::vector<double> orientation_;                // +-1: which perpendicular is outward
};

}  // namespace rktsph
