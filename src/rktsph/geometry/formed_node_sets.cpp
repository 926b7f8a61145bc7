#include "rktsph/geometry/formed_node_sets.hpp"

#include "rktsph/mesh/cell_geometry.hpp"

namespace rktsph {

FormedNodeSets form_node_sets(const NodeSets& start, const PointCloud& current,
                              std::span<const double> spacing, double alpha,
                              std::span<const std::vector<Vec3>> solids) {
  DelaunayCells delaunay = delaunay_cells(current, spacing, start.node_material, alpha,
                                          /*every_node_in_a_cell=*/true, solids);
  FormedNodeSets formed;
  formed.count = delaunay.count;
  NodeSets& nodes = formed.nodes;
  nodes.dimension = start.dimension;
  nodes.spacing = start.spacing;
  nodes.layout = CellLayout::Triangles;
  nodes.sph_nodes = current;
  nodes.sph_nodes.volume = start.sph_nodes.volume;  // mass over reference density (eq. 9.11)
  nodes.node_material = start.node_material;
  nodes.material_names = start.material_names;
  nodes.mesh_groups = start.mesh_groups;
  nodes.cells = std::move(delaunay.cells);
  nodes.outline = Outline(nodes.cells, current);

  const std::size_t nv = nodes.cells.cell_count();
  nodes.stress_points.dimension = current.dimension;
  nodes.stress_points.resize(nv);
  for (std::size_t p = 0; p < nv; ++p) {
    const auto corners = nodes.cells.corners(p);
    const auto centroid =
        cell_centroid(nodes.cells.kind(p), nodes.cells.corner_positions(current, p));
    for (int a = 0; a < current.dimension; ++a)
      nodes.stress_points.position[static_cast<std::size_t>(a)][p] =
          centroid[static_cast<std::size_t>(a)];
    double reference_over_current = 0.0;  // the corners' mean V_0 / V (eq. 9.12)
    for (const std::int32_t node : corners) {
      const auto i = static_cast<std::size_t>(node);
      reference_over_current += start.sph_nodes.volume[i] / current.volume[i];
    }
    reference_over_current /= static_cast<double>(corners.size());
    nodes.stress_points.volume[p] = nodes.cells.reference_measure(p) * reference_over_current;
  }
  return formed;
}

}  // namespace rktsph
