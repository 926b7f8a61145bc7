// The outline of a cell complex (docs/theory.md §3.5): the cell faces that belong to one cell
// only, i.e. the body's boundary as its cells draw it. Each facet knows its nodes and, on a given
// configuration, its outward unit normal and its measure; each node knows the facets it is on.
// Boundary classification, the traction-free projection, imposed tractions and the energy
// budget read it; nothing else draws the body's boundary.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "rktsph/core/point_cloud.hpp"
#include "rktsph/mesh/cell_complex.hpp"

namespace rktsph {

class Outline {
 public:
  Outline() = default;
  /// The boundary facets of `cells`, with normals and measures on the configuration `nodes`.
  Outline(const CellComplex& cells, const PointCloud& nodes);

  /// Recomputes every facet's normal and measure on the configuration `nodes`.
  void update(const PointCloud& nodes);

  int dimension() const { return dimension_; }
  std::size_t facet_count() const { return first_.size(); }
  /// The facet's first node; in 2D its nodes run from first to second with the body on the left.
  std::int32_t first_node(std::size_t facet) const { return first_[facet]; }
  /// 2D: the facet's second node. 1D: the other node of the facet's cell (the side the body is).
  std::int32_t second_node(std::size_t facet) const { return second_[facet]; }
  /// Outward unit normal [-] and length (2D) or 1 (1D) [m^(d-1)] on the last configuration.
  std::array<double, 3> normal(std::size_t facet) const {
    return {normal_[0][facet], normal_[1][facet], 0.0};
  }
  double measure(std::size_t facet) const { return measure_[facet]; }
  /// The facets that node n lies on, in increasing order.
  std::span<const std::int32_t> facets_at(std::size_t node) const {
    const auto start = static_cast<std::size_t>(node_start_[node]);
    return {node_facet_.data() + start, static_cast<std::size_t>(node_start_[node + 1]) - start};
  }
  /// True if `node` is one of the facet's nodes.
  bool has_node(std::size_t facet, std::int32_t node) const {
    return first_[facet] == node || (dimension_ >= 2 && second_[facet] == node);
  }
  /// The facet's node other than `node` (2D), or `node` itself in 1D.
  std::int32_t other_node(std::size_t facet, std::int32_t node) const {
    if (dimension_ < 2) return node;
    return first_[facet] == node ? second_[facet] : first_[facet];
  }

 private:
  int dimension_ = 1;
  std::vector<std::int32_t> first_, second_;
  std::array<std::vector<double>, 2> normal_;
  std::vector<double> measure_;
  std::vector<std::int32_t> node_start_{0};
  std::vector<std::int32_t> node_facet_;
};

}  // namespace rktsph
