#include "rktsph/mesh/cell_complex.hpp"

#include <atomic>
#include <stdexcept>

#include "rktsph/mesh/cell_geometry.hpp"

namespace rktsph {

namespace {

// Versions are unique across complexes, so a table built for one complex is never taken for
// another's.
std::uint64_t next_version() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

}  // namespace

CellComplex::CellComplex(int dimension, std::size_t node_count)
    : dimension_(dimension), node_count_(node_count) {}

void CellComplex::add_cell(CellKind kind, std::span<const std::int32_t> corners,
                           std::int32_t material) {
  if (static_cast<int>(corners.size()) != corner_count(kind) || cell_dimension(kind) != dimension_)
    throw std::logic_error("CellComplex::add_cell: corners do not fit the kind or dimension");
  for (const std::int32_t node : corners)
    if (node < 0 || static_cast<std::size_t>(node) >= node_count_)
      throw std::logic_error("CellComplex::add_cell: a corner is not a node of the complex");
  kind_.push_back(kind);
  corner_.insert(corner_.end(), corners.begin(), corners.end());
  corner_start_.push_back(static_cast<std::int32_t>(corner_.size()));
  material_.push_back(material);
}

void CellComplex::finish(const PointCloud& nodes) {
  if (nodes.size() != node_count_)
    throw std::logic_error("CellComplex::finish: positions of another number of nodes");
  // Node -> cells by a counting sort, so each node's cells come in increasing order.
  node_cell_start_.assign(node_count_ + 1, 0);
  for (const std::int32_t node : corner_)
    ++node_cell_start_[static_cast<std::size_t>(node) + 1];
  for (std::size_t n = 0; n < node_count_; ++n)
    node_cell_start_[n + 1] += node_cell_start_[n];
  node_cell_.assign(corner_.size(), 0);
  std::vector<std::int32_t> next(node_cell_start_.begin(), node_cell_start_.end() - 1);
  for (std::size_t p = 0; p < cell_count(); ++p)
    for (const std::int32_t node : corners(p))
      node_cell_[static_cast<std::size_t>(next[static_cast<std::size_t>(node)]++)] =
          static_cast<std::int32_t>(p);
  reference_measure_.resize(cell_count());
  for (std::size_t p = 0; p < cell_count(); ++p)
    reference_measure_[p] = cell_measure(kind_[p], corner_positions(nodes, p));
  version_ = next_version();
}

}  // namespace rktsph
