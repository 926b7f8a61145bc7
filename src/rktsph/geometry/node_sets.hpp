// Geometry to nodes: the SPH nodes on a square lattice of spacing dx (boundary nodes included) and
// the stress points at the cell centres (2D) or mid-points (1D), docs/theory.md §3.1. The triangle
// builder (triangle_mesher.hpp, §3.6) fills the same NodeSets without the lattice's fields.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "rktsph/case/case_description.hpp"
#include "rktsph/core/point_cloud.hpp"
#include "rktsph/geometry/shapes.hpp"
#include "rktsph/mesh/cell_complex.hpp"
#include "rktsph/mesh/outline.hpp"

namespace rktsph {

struct NodeSets {
  int dimension = 1;
  double spacing = 0.0;  ///< dx [m]; for triangles, the longest edge allowed
  /// How the cells were made. Nothing downstream reads a lattice index: the lattice builder keeps
  /// its indices to itself, and everything else works on the cells and the positions.
  CellLayout layout = CellLayout::Lattice;

  PointCloud sph_nodes;
  PointCloud stress_points;
  std::vector<std::int32_t> node_material;  ///< index into `material_names`
  /// The cells: cell p carries stress point p; its material is the one covering its centre.
  CellComplex cells;
  /// The boundary facets of the cells, with normals on the reference configuration.
  Outline outline;
  std::vector<std::string> material_names;
  /// The physical groups of a mesh file by name (docs/theory.md §3.8), their nodes sorted; empty
  /// for shapes.
  std::map<std::string, std::vector<std::int32_t>> mesh_groups;

  /// True for the lattice builder's node sets: nodes on a square lattice of spacing dx.
  bool on_lattice() const { return layout == CellLayout::Lattice; }
};

/// The size of a lattice before it is built, in double so that no count can overflow: the nodes
/// and stress points of every shape (Pick's theorem: area/dx^d plus half the boundary; overlaps
/// counted twice, so an upper bound) and the lattice points of the shapes' bounding box, which
/// the node lookup spans.
struct NodeEstimate {
  double sph_nodes = 0.0;
  double stress_points = 0.0;
  double lattice_points = 0.0;
  double largest_shape_nodes = 0.0;
  std::size_t largest_shape = 0;  ///< index into geometry.shapes
};
/// For geometry.cells = triangles, the counts of a mesh of equilateral triangles of the edge that
/// gives a refined mesh's count (about 2/3 of the spacing), and no lattice points (no lookup).
NodeEstimate estimate_node_sets(const GeometrySpec& geometry, int dimension);

/// Fills the shapes of `geometry` with nodes. Every shape vertex must be a lattice point so that
/// the physical boundary carries nodes (InputError at the shape otherwise).
NodeSets build_node_sets(const GeometrySpec& geometry, int dimension,
                         const std::vector<std::string>& material_names);

/// The box around the body: the shapes' vertices, or a mesh file's nodes, in the first
/// `dimension` axes (the others stay as initialised).
struct Box {
  Vec3 min{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), 0.0};
  Vec3 max{std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest(), 0.0};
};
Box bounding_box(const GeometrySpec& geometry, int dimension);

/// Node groups by name: the built-in ones (all, xmin, xmax, ymin, ymax) and those of the case.
/// A group that selects no node is an InputError at its definition.
std::map<std::string, std::vector<std::int32_t>> select_groups(
    const NodeSets& nodes, const std::vector<GroupSpec>& groups);

/// The smallest cell quality (cell_quality: the smallest corner's sine) a built complex may have:
/// sin 1°. The triangle mesher guarantees about 20.7° except at sharper input corners; a cell
/// below this is a sliver whose corner Jacobians, and so its stress point's gradients, are
/// nearly singular (docs/theory.md §3.6).
inline constexpr double kMinimumCellQuality = 0.0174524064372835;

/// Refuses a complex with a cell of non-positive measure (degenerate or inverted) or of quality
/// below kMinimumCellQuality: InputError at the shape covering the cell's centroid (at the
/// geometry section if none does).
void check_cells(const NodeSets& nodes, const GeometrySpec& geometry);

}  // namespace rktsph
