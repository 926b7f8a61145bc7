// A triangle mesh written by Gmsh (docs/theory.md §3.8, docs/input-reference.md `geometry.mesh`):
// the MSH formats 2.2 and 4.1 in ASCII, their 3-node triangles and the physical surfaces that
// name each triangle's material. Points and lines are left out; any other element (quadrilaterals,
// second-order triangles, 3D cells) and a binary file are input errors at their line.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "rktsph/core/error.hpp"

namespace rktsph {

struct GmshMesh {
  struct Triangle {
    std::array<std::int32_t, 3> corners{};  ///< indices into `points`, as the file orders them
    std::string physical;  ///< its physical surface's name, or its tag as text; "" if none
    long element = 0;      ///< the element's tag in the file
    int line = 0;          ///< the line of the file that defines it
  };
  std::filesystem::path file;
  /// The nodes of the triangles (nodes that no triangle uses are left out), in file order.
  std::vector<std::array<double, 2>> points;
  std::vector<long> node_tags;  ///< the file's tag of each point
  std::vector<Triangle> triangles;
  /// The nodes (indices into `points`) of each physical group, of any dimension, by name (its tag
  /// as text if it has none): a physical point's node, a physical curve's line nodes, a physical
  /// surface's triangle corners; sorted, each once. Nodes of no triangle are left out.
  std::map<std::string, std::vector<std::int32_t>> physical_nodes;
};

/// Reads `file`. `where` is the case-file key that names it: a file that cannot be opened is an
/// InputError there; a mistake inside the file is an InputError at its line of the file.
GmshMesh read_gmsh_mesh(const std::filesystem::path& file, const SourceLocation& where);

}  // namespace rktsph
