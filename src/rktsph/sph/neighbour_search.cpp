#include "rktsph/sph/neighbour_search.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace rktsph {

namespace {

/// Grids larger than this many cells per point are coarsened (a few far-away points or a tiny
/// cell size would otherwise allocate a huge, almost empty cell_start array).
constexpr double kMaxCellsPerPoint = 8.0;
constexpr double kMinCellBudget = 4096.0;

struct BoundingBox {
  std::array<double, 3> lower{0.0, 0.0, 0.0};
  std::array<double, 3> upper{0.0, 0.0, 0.0};
};

BoundingBox bounding_box(const PointCloud& points) {
  BoundingBox box;
  for (int a = 0; a < points.dimension; ++a) {
    const auto& coordinate = points.position[a];
    // A NaN would make min/max meaningless; an infinity would make the grid infinite.
    for (double x : coordinate) {
      if (!std::isfinite(x)) {
        throw std::invalid_argument("CellList: non-finite coordinate in point cloud");
      }
    }
    const auto [lowest, highest] = std::minmax_element(coordinate.begin(), coordinate.end());
    box.lower[a] = *lowest;
    box.upper[a] = *highest;
  }
  return box;
}

/// Cells per axis covering the box with cells of `cell_size`; the number of cells along an axis
/// is floor(extent / cell_size) + 1 so that the largest coordinate falls in the last cell.
std::array<double, 3> cells_per_axis(const BoundingBox& box, int dimension, double cell_size) {
  std::array<double, 3> count{1.0, 1.0, 1.0};
  for (int a = 0; a < dimension; ++a) {
    count[a] = std::floor((box.upper[a] - box.lower[a]) / cell_size) + 1.0;
  }
  return count;
}

double product(const std::array<double, 3>& values) {
  return values[0] * values[1] * values[2];
}

/// Grows the cell size until the grid fits the budget; returns the size to use.
double affordable_cell_size(const BoundingBox& box, int dimension, double cell_size,
                            std::size_t point_count) {
  const double budget =
      std::max(kMinCellBudget, kMaxCellsPerPoint * static_cast<double>(point_count));
  double cells = product(cells_per_axis(box, dimension, cell_size));
  while (cells > budget) {
    // Scaling by (cells / budget)^(1/d) would land just under the budget for a large box; the
    // extra 1% and the loop take care of the "+1" cells and of small boxes.
    cell_size *= 1.01 * std::pow(cells / budget, 1.0 / dimension);
    cells = product(cells_per_axis(box, dimension, cell_size));
  }
  return cell_size;
}

void check_compatible(const PointCloud& targets, const PointCloud& sources, bool same_set) {
  if (targets.dimension != sources.dimension) {
    throw std::invalid_argument("find_neighbours: targets are " +
                                std::to_string(targets.dimension) + "D but sources are " +
                                std::to_string(sources.dimension) + "D");
  }
  if (same_set && targets.size() != sources.size()) {
    throw std::invalid_argument("find_neighbours: same_set with clouds of different sizes");
  }
}

/// Count pass of find_neighbours: row_start[i + 1] = number of neighbours of target i.
void count_neighbours(const PointCloud& targets, const CellList& sources, double radius,
                      bool same_set, std::vector<std::int64_t>& row_start) {
  const std::int64_t rows = static_cast<std::int64_t>(targets.size());
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::int64_t i = 0; i < rows; ++i) {
    std::int64_t count = 0;
    const auto self = static_cast<std::int32_t>(i);
    sources.for_each_within(targets.point(static_cast<std::size_t>(i)), radius,
                            [&](std::int32_t j, const std::array<double, 3>&, double) {
                              if (!same_set || j != self) ++count;
                            });
    row_start[i + 1] = count;
  }
}

/// Fill pass of find_neighbours: writes each row into its slot and sorts it.
void fill_neighbours(const PointCloud& targets, const CellList& sources, double radius,
                     bool same_set, NeighbourTable& table) {
  const std::int64_t rows = static_cast<std::int64_t>(targets.size());
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::int64_t i = 0; i < rows; ++i) {
    std::int32_t* const row_begin = table.neighbour.data() + table.row_start[i];
    std::int32_t* cursor = row_begin;
    const auto self = static_cast<std::int32_t>(i);
    sources.for_each_within(targets.point(static_cast<std::size_t>(i)), radius,
                            [&](std::int32_t j, const std::array<double, 3>&, double) {
                              if (!same_set || j != self) *cursor++ = j;
                            });
    // Cells are visited in grid order, not index order; sorting makes rows canonical.
    std::sort(row_begin, cursor);
  }
}

}  // namespace

CellList::CellList(const PointCloud& points, double cell_size) {
  rebuild(points, cell_size);
}

void CellList::rebuild(const PointCloud& points, double cell_size) {
  points_ = &points;
  dimension_ = points.dimension;
  cell_size_ = cell_size;
  inverse_cell_size_ = 0.0;
  if (dimension_ < 1 || dimension_ > 3) {
    throw std::invalid_argument("CellList: dimension must be 1, 2 or 3, got " +
                                std::to_string(dimension_));
  }
  if (!(cell_size > 0.0) || !std::isfinite(cell_size)) {
    throw std::invalid_argument("CellList: cell size must be positive and finite, got " +
                                std::to_string(cell_size));
  }
  const std::size_t point_count = points.size();
  if (point_count > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    throw std::invalid_argument("CellList: more than 2^31 - 1 points");
  }
  cell_start_.assign(1, 0);
  if (point_count == 0) {
    sorted_index_.clear();
    cell_count_ = {0, 0, 0};
    return;
  }

  const BoundingBox box = bounding_box(points);
  cell_size_ = affordable_cell_size(box, dimension_, cell_size, point_count);
  inverse_cell_size_ = 1.0 / cell_size_;
  origin_ = box.lower;
  const std::array<double, 3> count = cells_per_axis(box, dimension_, cell_size_);
  for (int a = 0; a < 3; ++a)
    cell_count_[a] = static_cast<std::int64_t>(count[a]);
  const std::int64_t cell_total = cell_count_[0] * cell_count_[1] * cell_count_[2];

  // Cell of each point; clamped because (x - origin) / size may round up to the count.
  const auto points_signed = static_cast<std::int64_t>(point_count);
  cell_of_point_.resize(point_count);
  std::int64_t* cell_of_point = cell_of_point_.data();
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < points_signed; ++i) {
    std::int64_t linear = 0;
    for (int a = dimension_ - 1; a >= 0; --a) {
      const double relative = (points.position[a][i] - origin_[a]) * inverse_cell_size_;
      const auto cell =
          std::clamp(static_cast<std::int64_t>(relative), std::int64_t{0}, cell_count_[a] - 1);
      linear = linear * cell_count_[a] + cell;
    }
    cell_of_point[i] = linear;
  }

  // Counting sort, stable, so indices stay ascending within a cell.
  cell_start_.assign(static_cast<std::size_t>(cell_total) + 1, 0);
  for (std::int64_t cell : cell_of_point_)
    ++cell_start_[cell + 1];
  for (std::int64_t c = 0; c < cell_total; ++c)
    cell_start_[c + 1] += cell_start_[c];
  cursor_.assign(cell_start_.begin(), cell_start_.end() - 1);
  sorted_index_.resize(point_count);
  for (std::int64_t i = 0; i < points_signed; ++i) {
    sorted_index_[cursor_[cell_of_point[i]]++] = static_cast<std::int32_t>(i);
  }
  for (int a = 0; a < dimension_; ++a) {
    sorted_position_[a].resize(point_count);
    for (std::size_t k = 0; k < point_count; ++k) {
      sorted_position_[a][k] = points.position[a][sorted_index_[k]];
    }
  }
}

NeighbourTable find_neighbours(const PointCloud& targets, const PointCloud& sources, double radius,
                               bool same_set) {
  check_compatible(targets, sources, same_set);
  if (!(radius > 0.0)) {
    NeighbourTable empty;
    empty.row_start.assign(targets.size() + 1, 0);
    return empty;
  }
  const CellList cells(sources, radius);
  return find_neighbours(targets, cells, radius, same_set);
}

NeighbourTable find_neighbours(const PointCloud& targets, const CellList& sources, double radius,
                               bool same_set) {
  check_compatible(targets, sources.points(), same_set);
  NeighbourTable table;
  table.row_start.assign(targets.size() + 1, 0);
  count_neighbours(targets, sources, radius, same_set, table.row_start);
  for (std::size_t i = 0; i < targets.size(); ++i)
    table.row_start[i + 1] += table.row_start[i];
  table.neighbour.resize(static_cast<std::size_t>(table.row_start.back()));
  fill_neighbours(targets, sources, radius, same_set, table);
  return table;
}

}  // namespace rktsph
