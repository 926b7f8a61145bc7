// Fixed-radius neighbour search with cell-linked lists (docs/theory.md §4.6)
// and compressed-row neighbour tables for the SPH operators.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "rktsph/core/point_cloud.hpp"

namespace rktsph {

/// Compressed-row neighbour table: row i lists the source indices j with |x_i - x_j| < radius,
/// in ascending j.
struct NeighbourTable {
  std::vector<std::int64_t> row_start;  // size rows + 1
  std::vector<std::int32_t> neighbour;  // size row_start.back()

  std::size_t rows() const { return row_start.empty() ? 0 : row_start.size() - 1; }
  std::size_t count(std::size_t i) const {
    return static_cast<std::size_t>(row_start[i + 1] - row_start[i]);
  }
  std::span<const std::int32_t> row(std::size_t i) const {
    return {neighbour.data() + row_start[i], count(i)};
  }
  std::size_t total() const {
    return row_start.empty() ? 0 : static_cast<std::size_t>(row_start.back());
  }
};

/// Bins a point cloud into square/cubic cells over its bounding box with a counting sort (one
/// `cell_start` array and the point indices sorted by cell; no per-cell containers). The cloud is
/// referenced, not copied, and must outlive the CellList; positions are copied in cell order so
/// that a scan reads memory contiguously.
class CellList {
 public:
  /// `cell_size` must be positive and finite, the coordinates finite, and the cloud smaller than
  /// 2^31 points (std::invalid_argument otherwise). If the bounding box would need more than
  /// about max(8 N, 4096) cells (a few far-away points), the cells are made larger: results are
  /// unchanged, only the scan gets coarser. cell_size() reports the size actually used.
  CellList(const PointCloud& points, double cell_size);
  /// An empty list, to be filled by rebuild().
  CellList() = default;
  /// Bins `points` again (as the constructor does), reusing the list's buffers: a moving
  /// configuration rebuilds its lists every step without allocating once they have grown.
  void rebuild(const PointCloud& points, double cell_size);

  /// Calls visit(std::int32_t j, const std::array<double, 3>& offset, double distance_squared)
  /// for every point j with |query - x_j| < radius, where offset = query - x_j (components
  /// beyond the dimension are 0). Any radius works: the scanned cell range covers
  /// [query - radius, query + radius], clamped to the grid, so queries outside the bounding box
  /// are fine. Points are visited in cell order, not in index order.
  template <class Visitor>
  void for_each_within(const std::array<double, 3>& query, double radius, Visitor&& visit) const {
    if (sorted_index_.empty() || !(radius > 0.0)) return;
    switch (dimension_) {
      case 1:
        scan<1>(query, radius, visit);
        break;
      case 2:
        scan<2>(query, radius, visit);
        break;
      default:
        scan<3>(query, radius, visit);
        break;
    }
  }

  const PointCloud& points() const { return *points_; }
  int dimension() const { return dimension_; }
  double cell_size() const { return cell_size_; }
  /// Number of cells along each axis (1 along axes beyond the dimension, 0 for an empty cloud).
  const std::array<std::int64_t, 3>& cell_counts() const { return cell_count_; }

 private:
  /// Inclusive range of cell indices along `axis` that can hold points within `radius` of
  /// `coordinate`; false if it misses the grid.
  bool cell_range(int axis, double coordinate, double radius, std::int64_t& lower,
                  std::int64_t& upper) const {
    const double relative = (coordinate - origin_[axis]) * inverse_cell_size_;
    const double reach = radius * inverse_cell_size_;
    // Widen by a few thousand ulps so that rounding in the subtraction never drops a point that
    // lies on a cell face at exactly the radius.
    const double slack = 1e-12 * (std::abs(relative) + reach) + 1e-12;
    const double lowest = std::floor(relative - reach - slack);
    const double highest = std::floor(relative + reach + slack);
    const double last = static_cast<double>(cell_count_[axis] - 1);
    if (!(highest >= 0.0) || !(lowest <= last)) return false;
    lower = lowest < 0.0 ? 0 : static_cast<std::int64_t>(lowest);
    upper = highest > last ? cell_count_[axis] - 1 : static_cast<std::int64_t>(highest);
    return true;
  }

  template <int Dimension, class Visitor>
  void scan(const std::array<double, 3>& query, double radius, Visitor& visit) const {
    std::array<std::int64_t, 3> lower{0, 0, 0};
    std::array<std::int64_t, 3> upper{0, 0, 0};
    for (int a = 0; a < Dimension; ++a) {
      if (!cell_range(a, query[a], radius, lower[a], upper[a])) return;
    }
    const double radius_squared = radius * radius;
    std::array<double, 3> offset{0.0, 0.0, 0.0};
    for (std::int64_t z = lower[2]; z <= upper[2]; ++z) {
      for (std::int64_t y = lower[1]; y <= upper[1]; ++y) {
        // Cells lower[0]..upper[0] of one row are consecutive in the linear numbering, so their
        // points form one contiguous block of the sorted arrays.
        const std::int64_t row_base = (z * cell_count_[1] + y) * cell_count_[0];
        const std::int32_t begin = cell_start_[row_base + lower[0]];
        const std::int32_t end = cell_start_[row_base + upper[0] + 1];
        for (std::int32_t k = begin; k < end; ++k) {
          double distance_squared = 0.0;
          for (int a = 0; a < Dimension; ++a) {
            offset[a] = query[a] - sorted_position_[a][k];
            distance_squared += offset[a] * offset[a];
          }
          if (distance_squared < radius_squared) visit(sorted_index_[k], offset, distance_squared);
        }
      }
    }
  }

  const PointCloud* points_ = nullptr;
  int dimension_ = 1;
  double cell_size_ = 1.0;
  double inverse_cell_size_ = 0.0;
  std::array<double, 3> origin_{0.0, 0.0, 0.0};
  std::array<std::int64_t, 3> cell_count_{0, 0, 0};
  /// Points of cell c are sorted_index_[cell_start_[c] .. cell_start_[c + 1]).
  std::vector<std::int32_t> cell_start_;
  /// Point indices in cell order (ascending within a cell).
  std::vector<std::int32_t> sorted_index_;
  std::vector<std::int64_t> cell_of_point_;  // scratch of rebuild()
  std::vector<std::int32_t> cursor_;
  /// Coordinates in the same order as sorted_index_.
  std::array<std::vector<double>, 3> sorted_position_;
};

/// Neighbours in `sources` of each point of `targets` within `radius` (strictly closer). If
/// `same_set` is true (targets and sources are the same cloud) a point is not its own neighbour.
/// Built in parallel with OpenMP (count pass, prefix sum, fill pass); each row is sorted, so the
/// table does not depend on the number of threads. The dimensions must agree, and with same_set
/// the sizes too (std::invalid_argument). A radius <= 0 gives empty rows.
NeighbourTable find_neighbours(const PointCloud& targets, const PointCloud& sources, double radius,
                               bool same_set);
NeighbourTable find_neighbours(const PointCloud& targets, const CellList& sources, double radius,
                               bool same_set);

}  // namespace rktsph
