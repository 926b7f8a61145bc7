// Node sets of a triangle mesh (docs/theory.md §3.6, §3.8), whoever made the triangles: the
// project's mesher of the shapes (triangle_mesher.hpp) or a Gmsh file (`geometry.mesh`). The nodes
// are the corners, the stress points the centroids with the triangles' areas, and each node's
// volume a third of the area of each of its triangles.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "rktsph/case/case_description.hpp"
#include "rktsph/geometry/node_sets.hpp"

namespace rktsph {

struct MeshTriangle {
  std::array<std::int32_t, 3> corners;  ///< counter-clockwise
  std::int32_t material;                ///< index into the material names
};

/// The node sets of `triangles` on `points`, which must be numbered by (y, x). Each triangle's
/// corners are rotated to start at the lowest-numbered one and the triangles sorted by corners,
/// so that the result does not depend on the order they came in. A node of material -1 takes its
/// first triangle's. The cells are not checked here (check_cells, or the mesh reader's checks).
NodeSets triangle_node_sets(const std::vector<Vec3>& points,
                            std::vector<std::int32_t> node_material,
                            std::vector<MeshTriangle> triangles, double spacing,
                            const std::vector<std::string>& material_names);

/// The node sets of the Gmsh mesh `geometry.mesh` (docs/theory.md §3.8): each triangle's material
/// is its physical surface's name (a mesh without physical surfaces takes the case's only
/// material), its spacing the mesh's longest edge. Refused, at the line of the file: a triangle
/// of no area or of a corner sharper than 1°, an edge of more than two triangles, two nodes at one
/// position (surfaces meshed apart), a physical surface that names no material.
NodeSets build_mesh_node_sets(const GeometrySpec& geometry,
                              const std::vector<std::string>& material_names);

/// The SPH nodes and triangles a mesh file holds, for the size estimate before a run.
struct MeshFileSize {
  std::size_t nodes = 0, triangles = 0;
};
MeshFileSize mesh_file_size(const GeometrySpec& geometry);

}  // namespace rktsph
