#include "rktsph/physics/configuration_motion.hpp"

#include <algorithm>
#include <stdexcept>

namespace rktsph {

namespace {

// Corner k of a cell as offsets from its lower corner: counter-clockwise in 2D.
constexpr std::array<std::array<int, 2>, 4> kCornerOffset{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};

double cross(double ax, double ay, double bx, double by) {
  return ax * by - ay * bx;
}

// The corner Jacobians of a quadrilateral: the cross product of the two edges leaving each corner
// (counter-clockwise order), positive for a convex, unfolded cell.
std::array<double, 4> corner_jacobians(const PointCloud& nodes,
                                       const std::array<std::int32_t, 4>& corner) {
  std::array<double, 4> jacobian{};
  for (std::size_t k = 0; k < 4; ++k) {
    const auto at = static_cast<std::size_t>(corner[k]);
    const auto next = static_cast<std::size_t>(corner[(k + 1) % 4]);
    const auto previous = static_cast<std::size_t>(corner[(k + 3) % 4]);
    jacobian[k] = cross(nodes.position[0][next] - nodes.position[0][at],
                        nodes.position[1][next] - nodes.position[1][at],
                        nodes.position[0][previous] - nodes.position[0][at],
                        nodes.position[1][previous] - nodes.position[1][at]);
  }
  return jacobian;
}

// Signed area of the cell: half the cross product of its diagonals (2D); its length (1D).
double cell_area(const PointCloud& nodes, const std::array<std::int32_t, 4>& corner,
                 int dimension) {
  const auto c0 = static_cast<std::size_t>(corner[0]);
  const auto c1 = static_cast<std::size_t>(corner[1]);
  if (dimension == 1) return nodes.position[0][c1] - nodes.position[0][c0];
  const auto c2 = static_cast<std::size_t>(corner[2]);
  const auto c3 = static_cast<std::size_t>(corner[3]);
  return 0.5 * cross(nodes.position[0][c2] - nodes.position[0][c0],
                     nodes.position[1][c2] - nodes.position[1][c0],
                     nodes.position[0][c3] - nodes.position[0][c1],
                     nodes.position[1][c3] - nodes.position[1][c1]);
}

}  // namespace

ConfigurationMotion::ConfigurationMotion(const NodeSets& reference) : reference_(reference) {
  const int d = reference.dimension;
  if (d > 2) throw std::invalid_argument("ConfigurationMotion: 1D and 2D lattices only");
  const std::size_t nv = reference.stress_points.size();
  const std::size_t ns = reference.sph_nodes.size();
  const int corner_count = 1 << d;
  corners_.assign(nv, {-1, -1, -1, -1});
  std::vector<std::int32_t> count(ns + 1, 0);
  for (std::size_t p = 0; p < nv; ++p)
    for (int k = 0; k < corner_count; ++k) {
      LatticeIndex index = reference.stress_point_index[p];
      for (int a = 0; a < d; ++a)
        index[static_cast<std::size_t>(a)] += kCornerOffset[static_cast<std::size_t>(k)][a];
      const std::int32_t node = reference.node_at(index);
      if (node < 0) throw std::logic_error("ConfigurationMotion: a cell without a corner node");
      corners_[p][static_cast<std::size_t>(k)] = node;
      ++count[static_cast<std::size_t>(node) + 1];
    }
  node_cell_start_.assign(ns + 1, 0);
  for (std::size_t i = 0; i < ns; ++i)
    node_cell_start_[i + 1] = node_cell_start_[i] + count[i + 1];
  node_cell_.assign(static_cast<std::size_t>(node_cell_start_[ns]), 0);
  std::vector<std::int32_t> next(node_cell_start_.begin(), node_cell_start_.end() - 1);
  for (std::size_t p = 0; p < nv; ++p)
    for (int k = 0; k < corner_count; ++k)
      node_cell_[static_cast<std::size_t>(next[static_cast<std::size_t>(corners_[p][k])]++)] =
          static_cast<std::int32_t>(p);
  reference_cell_area_.resize(nv);
  reference_corner_jacobian_.resize(nv);
  for (std::size_t p = 0; p < nv; ++p) {
    reference_cell_area_[p] = cell_area(reference.sph_nodes, corners_[p], d);
    if (d == 2) reference_corner_jacobian_[p] = corner_jacobians(reference.sph_nodes, corners_[p]);
  }
  cell_area_ = reference_cell_area_;
  reference_node_cell_area_.assign(ns, 0.0);
  for (std::size_t i = 0; i < ns; ++i)
    for (auto k = node_cell_start_[i]; k < node_cell_start_[i + 1]; ++k)
      reference_node_cell_area_[i] +=
          reference_cell_area_[static_cast<std::size_t>(node_cell_[static_cast<std::size_t>(k)])];
  node_volume_ratio_.assign(ns, 1.0);
}

void ConfigurationMotion::move(const FieldArray& displacement, Configuration& configuration) {
  const int d = reference_.dimension;
  const std::size_t ns = reference_.sph_nodes.size();
  const std::size_t nv = reference_.stress_points.size();
  PointCloud& nodes = configuration.sph_nodes;
  PointCloud& points = configuration.stress_points;
  for (int a = 0; a < d; ++a) {
    const auto axis = static_cast<std::size_t>(a);
    const double* u = displacement.field(a);
    for (std::size_t i = 0; i < ns; ++i)
      nodes.position[axis][i] = reference_.sph_nodes.position[axis][i] + u[i];
  }
  const int corner_count = 1 << d;
  quality_ = CellQuality{};
  for (std::size_t p = 0; p < nv; ++p) {
    const auto& corner = corners_[p];
    for (int a = 0; a < d; ++a) {
      const auto axis = static_cast<std::size_t>(a);
      double sum = 0.0;
      for (int k = 0; k < corner_count; ++k)
        sum += nodes.position[axis][static_cast<std::size_t>(corner[static_cast<std::size_t>(k)])];
      points.position[axis][p] = sum / corner_count;
    }
    cell_area_[p] = cell_area(nodes, corner, d);
    const double ratio = cell_area_[p] / reference_cell_area_[p];
    points.volume[p] = reference_.stress_points.volume[p] * ratio;
    if (ratio < quality_.smallest_volume_ratio || quality_.smallest_cell < 0) {
      quality_.smallest_volume_ratio = ratio;
      quality_.smallest_cell = static_cast<std::int32_t>(p);
    }
    double smallest_corner = ratio;  // 1D: the cell's length ratio
    if (d == 2) {
      const auto jacobian = corner_jacobians(nodes, corner);
      for (std::size_t k = 0; k < 4; ++k)
        smallest_corner = std::min(smallest_corner, jacobian[k] / reference_corner_jacobian_[p][k]);
    }
    if (ratio <= 0.0) {
      if (quality_.inverted_cells++ == 0)
        quality_.first_inverted_cell = static_cast<std::int32_t>(p);
    } else if (smallest_corner <= 0.0) {
      ++quality_.concave_cells;
    } else if (smallest_corner < kDistortedCornerRatio) {
      ++quality_.distorted_cells;
    }
  }
  for (std::size_t i = 0; i < ns; ++i) {
    double area = 0.0;
    for (auto k = node_cell_start_[i]; k < node_cell_start_[i + 1]; ++k)
      area += cell_area_[static_cast<std::size_t>(node_cell_[static_cast<std::size_t>(k)])];
    node_volume_ratio_[i] =
        reference_node_cell_area_[i] > 0.0 ? area / reference_node_cell_area_[i] : 1.0;
    nodes.volume[i] = reference_.sph_nodes.volume[i] * node_volume_ratio_[i];
  }
}

}  // namespace rktsph
