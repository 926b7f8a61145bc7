// The cells a case runs on, written as a Gmsh mesh file (docs/input-reference.md, `rktsph check
// --write-mesh`): to look at them in Gmsh or ParaView, to run another code on the same mesh (the
// finite elements of bench/peers/fe_triangles_bar_wave_2d.py), or to edit and read back through
// `geometry.mesh`. MSH 2.2, ASCII; the coordinates at round-trip precision.
#pragma once

#include <filesystem>
#include <string>

#include "rktsph/geometry/node_sets.hpp"

namespace rktsph {

/// The MSH 2.2 text of the node sets' cells (2D): the SPH nodes, every cell as a 3-node triangle
/// or a 4-node quadrilateral, counter-clockwise as in the complex, in the physical surface of its
/// material (tag = material index + 1, named by `material_names`). Read back by
/// `geometry.mesh`, a triangle mesh gives the same node sets to the bit. Throws
/// std::invalid_argument for node sets that are not 2D.
std::string gmsh_mesh_text(const NodeSets& nodes);

/// gmsh_mesh_text written to `path` whole or not at all (output/atomic_file.hpp).
void write_gmsh_mesh(const std::filesystem::path& path, const NodeSets& nodes);

}  // namespace rktsph
