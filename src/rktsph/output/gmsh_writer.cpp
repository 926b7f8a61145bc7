#include "rktsph/output/gmsh_writer.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "rktsph/output/atomic_file.hpp"

namespace rktsph {

namespace {

// Gmsh's element types: 2 the 3-node triangle, 3 the 4-node quadrilateral.
int gmsh_element_type(CellKind kind) {
  switch (kind) {
    case CellKind::Triangle:
      return 2;
    case CellKind::Quadrilateral:
      return 3;
    case CellKind::Segment:
      break;
  }
  throw std::invalid_argument("gmsh_mesh_text: a segment cell has no 2D element");
}

}  // namespace

std::string gmsh_mesh_text(const NodeSets& nodes) {
  if (nodes.dimension != 2)
    throw std::invalid_argument(
        fmt::format("gmsh_mesh_text: the node sets are {}D; a mesh file is 2D", nodes.dimension));
  std::string text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n";
  text += fmt::format("{}\n", nodes.material_names.size());
  for (std::size_t m = 0; m < nodes.material_names.size(); ++m)
    text += fmt::format("2 {} \"{}\"\n", m + 1, nodes.material_names[m]);
  text += "$EndPhysicalNames\n$Nodes\n";
  const std::size_t n = nodes.sph_nodes.size();
  text += fmt::format("{}\n", n);
  for (std::size_t i = 0; i < n; ++i)
    text += fmt::format("{} {:.17g} {:.17g} 0\n", i + 1, nodes.sph_nodes.position[0][i],
                        nodes.sph_nodes.position[1][i]);
  const CellComplex& cells = nodes.cells;
  text += fmt::format("$EndNodes\n$Elements\n{}\n", cells.cell_count());
  for (std::size_t p = 0; p < cells.cell_count(); ++p) {
    // Two tags: the physical surface (the material) and the elementary entity (the same).
    const int material = cells.material(p) + 1;
    text +=
        fmt::format("{} {} 2 {} {}", p + 1, gmsh_element_type(cells.kind(p)), material, material);
    for (const std::int32_t corner : cells.corners(p))
      text += fmt::format(" {}", corner + 1);
    text += '\n';
  }
  return text + "$EndElements\n";
}

void write_gmsh_mesh(const std::filesystem::path& path, const NodeSets& nodes) {
  write_file_atomically(path, gmsh_mesh_text(nodes));
}

}  // namespace rktsph
