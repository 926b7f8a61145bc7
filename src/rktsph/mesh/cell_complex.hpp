// The cells of a body (docs/theory.md §3.5): which nodes are each cell's corners, which cells meet
// at each node, each cell's kind, reference measure and material. Cell p carries stress point p.
// A lattice is one way to build a complex (geometry/node_sets.cpp); nothing else in the code
// knows how the cells were made.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "rktsph/core/point_cloud.hpp"
#include "rktsph/mesh/cell_kind.hpp"
#include "rktsph/mesh/cell_kinds/cell_corners.hpp"

namespace rktsph {

class CellComplex {
 public:
  CellComplex() = default;

  /// Starts an empty complex of dimension d over `node_count` nodes.
  CellComplex(int dimension, std::size_t node_count);

  /// Appends a cell; its corners in the kind's order (counter-clockwise in 2D).
  void add_cell(CellKind kind, std::span<const std::int32_t> corners, std::int32_t material);

  /// Computes the cells around each node and the reference measures from the node positions
  /// (the reference configuration), and moves to a new version. Call after the last add_cell.
  void finish(const PointCloud& nodes);

  int dimension() const { return dimension_; }
  std::size_t cell_count() const { return kind_.size(); }
  std::size_t node_count() const { return node_count_; }
  /// Changes whenever the cells change (a new complex, cells formed again).
  std::uint64_t version() const { return version_; }

  CellKind kind(std::size_t cell) const { return kind_[cell]; }
  std::span<const std::int32_t> corners(std::size_t cell) const {
    const auto start = static_cast<std::size_t>(corner_start_[cell]);
    return {corner_.data() + start, static_cast<std::size_t>(corner_start_[cell + 1]) - start};
  }
  /// The cells that have node n as a corner, in increasing order.
  std::span<const std::int32_t> cells_of(std::size_t node) const {
    const auto start = static_cast<std::size_t>(node_cell_start_[node]);
    return {node_cell_.data() + start,
            static_cast<std::size_t>(node_cell_start_[node + 1]) - start};
  }
  std::int32_t material(std::size_t cell) const { return material_[cell]; }
  std::span<const std::int32_t> materials() const { return material_; }
  /// Length (1D) or area (2D) of the cell in the reference configuration [m^d].
  double reference_measure(std::size_t cell) const { return reference_measure_[cell]; }

  /// The corner coordinates of a cell in the configuration `nodes`.
  CellCorners corner_positions(const PointCloud& nodes, std::size_t cell) const {
    return gather_corners(nodes, corners(cell));
  }

 private:
  int dimension_ = 1;
  std::size_t node_count_ = 0;
  std::uint64_t version_ = 0;
  std::vector<CellKind> kind_;
  std::vector<std::int32_t> corner_start_{0};  // corners of cell p: corner_[start[p], start[p+1])
  std::vector<std::int32_t> corner_;
  std::vector<std::int32_t> node_cell_start_;  // cells of node n: node_cell_[start[n], start[n+1])
  std::vector<std::int32_t> node_cell_;
  std::vector<std::int32_t> material_;
  std::vector<double> reference_measure_;
};

}  // namespace rktsph
