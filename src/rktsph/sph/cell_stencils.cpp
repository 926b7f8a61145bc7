#include "rktsph/sph/cell_stencils.hpp"

#include <algorithm>
#include <cmath>

namespace rktsph {

namespace {

/// The planes of `mirrors` through x, as a bit set over their indices.
unsigned planes_through(const std::array<double, 3>& x, std::span<const MirrorPlane> mirrors,
                        double tolerance) {
  unsigned through = 0;
  for (std::size_t m = 0; m < mirrors.size(); ++m)
    if (std::abs(x[mirrors[m].axis] - mirrors[m].coordinate) <= tolerance) through |= 1u << m;
  return through;
}

/// Appends, for every non-empty subset of the planes `through`, the images of the stencil's first
/// `count` sources across that subset's planes; a source lying on one of them has no image there
/// (it would coincide with the source).
void add_images(std::span<const MirrorPlane> mirrors, unsigned through, double tolerance,
                std::size_t count, std::vector<StencilSource>& stencil) {
  for (unsigned subset = 1; subset <= through; ++subset) {
    if ((subset & through) != subset) continue;
    for (std::size_t k = 0; k < count; ++k) {
      StencilSource image = stencil[k];
      bool on_a_plane = false;
      for (std::size_t m = 0; m < mirrors.size(); ++m) {
        if (!(subset & (1u << m))) continue;
        const int axis = mirrors[m].axis;
        const double offset = image.position[axis] - mirrors[m].coordinate;
        on_a_plane =
            on_a_plane || std::abs(stencil[k].position[axis] - mirrors[m].coordinate) <= tolerance;
        image.position[axis] = mirrors[m].coordinate - offset;
        image.reflection = static_cast<std::uint8_t>(image.reflection ^ (1u << axis));
      }
      if (!on_a_plane) stencil.push_back(image);
    }
  }
}

}  // namespace

double cell_stencil_smoothing_length(const std::array<double, 3>& target,
                                     std::span<const StencilSource> stencil, int dimension,
                                     double h_over_dx, CellStencilKind kind) {
  double farthest = 0.0;
  for (const StencilSource& s : stencil) {
    double squared = 0.0;
    for (int a = 0; a < dimension; ++a)
      squared += (s.position[a] - target[a]) * (s.position[a] - target[a]);
    farthest = std::max(farthest, squared);
  }
  const double on_lattice = kind == CellStencilKind::CellNeighbours
                                ? std::sqrt(static_cast<double>(dimension))
                                : 0.5 * std::sqrt(static_cast<double>(dimension));
  return h_over_dx * std::sqrt(farthest) / on_lattice;
}

void gather_cell_corners(const CellComplex& cells, const PointCloud& nodes, std::size_t cell,
                         std::vector<StencilSource>& stencil) {
  stencil.clear();
  for (std::int32_t corner : cells.corners(cell)) {
    const auto j = static_cast<std::size_t>(corner);
    stencil.push_back(StencilSource{corner, 0, nodes.point(j), nodes.volume[j]});
  }
}

void gather_cell_centroids(const CellComplex& cells, const PointCloud& nodes,
                           const PointCloud& points, std::size_t node,
                           std::span<const MirrorPlane> mirrors, double tolerance,
                           std::vector<StencilSource>& stencil) {
  stencil.clear();
  for (std::int32_t cell : cells.cells_of(node)) {
    const auto p = static_cast<std::size_t>(cell);
    stencil.push_back(StencilSource{cell, 0, points.point(p), points.volume[p]});
  }
  add_images(mirrors, planes_through(nodes.point(node), mirrors, tolerance), tolerance,
             stencil.size(), stencil);
}

void gather_cell_neighbours(const CellComplex& cells, const PointCloud& nodes, std::size_t node,
                            std::span<const MirrorPlane> mirrors, double tolerance,
                            std::vector<StencilSource>& stencil) {
  stencil.clear();
  for (std::int32_t cell : cells.cells_of(node))
    for (std::int32_t corner : cells.corners(static_cast<std::size_t>(cell)))
      if (static_cast<std::size_t>(corner) != node)
        stencil.push_back(StencilSource{corner, 0, {}, 0.0});
  std::sort(stencil.begin(), stencil.end(),
            [](const StencilSource& a, const StencilSource& b) { return a.column < b.column; });
  stencil.erase(std::unique(stencil.begin(), stencil.end(),
                            [](const StencilSource& a, const StencilSource& b) {
                              return a.column == b.column;
                            }),
                stencil.end());
  for (StencilSource& s : stencil) {
    const auto j = static_cast<std::size_t>(s.column);
    s.position = nodes.point(j);
    s.volume = nodes.volume[j];
  }
  add_images(mirrors, planes_through(nodes.point(node), mirrors, tolerance), tolerance,
             stencil.size(), stencil);
}

void cell_smoothing_lengths(const CellComplex& cells, const PointCloud& nodes,
                            const PointCloud& points, double h_over_dx,
                            std::vector<double>& node_smoothing_length,
                            std::vector<double>& point_smoothing_length) {
  const int d = nodes.dimension;
  std::vector<StencilSource> stencil;
  point_smoothing_length.resize(points.size());
  for (std::size_t p = 0; p < points.size(); ++p) {
    gather_cell_corners(cells, nodes, p, stencil);
    point_smoothing_length[p] = cell_stencil_smoothing_length(
        points.point(p), stencil, d, h_over_dx, CellStencilKind::CellCorners);
  }
  node_smoothing_length.resize(nodes.size());
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    gather_cell_centroids(cells, nodes, points, n, {}, 0.0, stencil);
    node_smoothing_length[n] = cell_stencil_smoothing_length(nodes.point(n), stencil, d, h_over_dx,
                                                             CellStencilKind::CellCentroids);
  }
}

}  // namespace rktsph
