#include "rktsph/physics/configuration_motion.hpp"

#include <algorithm>
#include <stdexcept>

#include "rktsph/mesh/cell_geometry.hpp"

namespace rktsph {

namespace {
// The squared distance from a cell's centroid to its farthest corner: its stencil's reach (§4.8).
double squared_reach(const CellCorners& corners, const std::array<double, 3>& centroid) {
  double farthest = 0.0;
  for (int k = 0; k < corners.count; ++k) {
    const auto c = static_cast<std::size_t>(k);
    const double dx = corners.x[c] - centroid[0], dy = corners.y[c] - centroid[1];
    farthest = std::max(farthest, dx * dx + dy * dy);
  }
  return farthest;
}
}  // namespace

ConfigurationMotion::ConfigurationMotion(const NodeSets& reference, const CellFormation* formation)
    : reference_(reference),
      origin_(formation ? *formation->origin : reference.sph_nodes),
      formed_(formation != nullptr),
      base_node_volume_(formation ? formation->node_volume : reference.sph_nodes.volume) {
  const CellComplex& cells = reference.cells;
  if (reference.dimension > 2) throw std::invalid_argument("ConfigurationMotion: 1D and 2D only");
  const std::size_t nv = cells.cell_count();
  const std::size_t ns = reference.sph_nodes.size();
  reference_corner_jacobian_.resize(nv);
  if (formed_) {
    reference_reach_.resize(nv);
    for (std::size_t p = 0; p < nv; ++p) {
      const CellCorners corners = cells.corner_positions(reference.sph_nodes, p);
      reference_reach_[p] = squared_reach(corners, cell_centroid(cells.kind(p), corners));
    }
  }
  for (std::size_t p = 0; p < nv; ++p)
    cell_corner_jacobians(cells.kind(p), cells.corner_positions(reference.sph_nodes, p),
                          reference_corner_jacobian_[p]);
  cell_area_.resize(nv);
  for (std::size_t p = 0; p < nv; ++p)
    cell_area_[p] = cells.reference_measure(p);
  reference_node_cell_area_.assign(ns, 0.0);
  for (std::size_t i = 0; i < ns; ++i)
    for (const std::int32_t p : cells.cells_of(i))
      reference_node_cell_area_[i] += cells.reference_measure(static_cast<std::size_t>(p));
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
      nodes.position[axis][i] = origin_.position[axis][i] + u[i];
  }
  const CellComplex& cells = reference_.cells;
  quality_ = CellQuality{};
  for (std::size_t p = 0; p < nv; ++p) {
    const CellKind kind = cells.kind(p);
    const CellCorners corners = cells.corner_positions(nodes, p);
    const auto centroid = cell_centroid(kind, corners);
    for (int a = 0; a < d; ++a)
      points.position[static_cast<std::size_t>(a)][p] = centroid[static_cast<std::size_t>(a)];
    cell_area_[p] = cell_measure(kind, corners);
    const double ratio = cell_area_[p] / cells.reference_measure(p);
    points.volume[p] = formed_ ? cell_area_[p] : reference_.stress_points.volume[p] * ratio;
    if (ratio < quality_.smallest_volume_ratio || quality_.smallest_cell < 0) {
      quality_.smallest_volume_ratio = ratio;
      quality_.smallest_cell = static_cast<std::int32_t>(p);
    }
    double smallest_corner = ratio, largest_corner = ratio;  // 1D: the cell's length ratio
    if (d == 2) {
      std::array<double, kMaxCellCorners> jacobian{};
      cell_corner_jacobians(kind, corners, jacobian);
      for (std::size_t k = 0; k < static_cast<std::size_t>(corners.count); ++k) {
        const double corner = jacobian[k] / reference_corner_jacobian_[p][k];
        smallest_corner = std::min(smallest_corner, corner);
        largest_corner = std::max(largest_corner, corner);
      }
    }
    quality_.largest_corner_ratio = std::max(quality_.largest_corner_ratio, largest_corner);
    if (formed_) {
      quality_.largest_reach_ratio = std::max(
          quality_.largest_reach_ratio, squared_reach(corners, centroid) / reference_reach_[p]);
      const double width = cell_width(kind, corners);
      if (quality_.narrowest_width == 0.0 || width < quality_.narrowest_width)
        quality_.narrowest_width = width;
    }
    quality_.smallest_corner_ratio = std::min(quality_.smallest_corner_ratio, smallest_corner);
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
    for (const std::int32_t p : cells.cells_of(i))
      area += cell_area_[static_cast<std::size_t>(p)];
    node_volume_ratio_[i] =
        reference_node_cell_area_[i] > 0.0 ? area / reference_node_cell_area_[i] : 1.0;
    // Formed cells: the node's volume at forming times the area ratio of its cells since, so that
    // its density stays continuous across a forming (eq. 9.11).
    nodes.volume[i] = base_node_volume_[i] * node_volume_ratio_[i];
  }
}

}  // namespace rktsph
