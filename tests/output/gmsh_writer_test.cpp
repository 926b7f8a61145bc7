// The cells a case runs on as a Gmsh mesh file (output/gmsh_writer.hpp): the project's triangles
// read back through geometry.mesh to the same node sets, to the bit; a lattice as quadrilaterals.
#include "rktsph/output/gmsh_writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>

#include "../support/same_node_sets.hpp"
#include "../support/shapes.hpp"
#include "../support/shell.hpp"
#include "rktsph/geometry/triangle_mesher.hpp"
#include "rktsph/geometry/triangle_node_sets.hpp"

namespace rktsph::gmsh_writer_test {
namespace {

namespace fs = std::filesystem;

TEST(GmshWriter, TrianglesReadBackToTheSameNodeSetsToTheBit) {
  const std::vector<std::string> names = {"rock", "soil"};
  GeometrySpec shapes;
  shapes.spacing = 0.7;
  shapes.cells = CellLayout::Triangles;
  shapes.shapes = test::two_material_slope();
  const NodeSets own = build_triangle_node_sets(shapes, names);
  const fs::path file = test::scratch_file("rktsph_gmsh_writer", "slope.msh");
  write_gmsh_mesh(file, own);
  GeometrySpec mesh;
  mesh.mesh = file.string();
  test::expect_same_node_sets(build_mesh_node_sets(mesh, names), own);
}

TEST(GmshWriter, ALatticeIsWrittenAsQuadrilaterals) {
  // 4 x 2 squares of 0.5 m: 15 nodes, 8 quadrilaterals, counter-clockwise from the lower left.
  GeometrySpec box;
  box.spacing = 0.5;
  box.shapes = {test::rectangle(0.0, 0.0, 2.0, 1.0, "soil")};
  const NodeSets lattice = build_node_sets(box, 2, {"soil"});
  const std::string text = gmsh_mesh_text(lattice);
  EXPECT_NE(text.find("$PhysicalNames\n1\n2 1 \"soil\"\n$EndPhysicalNames"), std::string::npos)
      << text;
  EXPECT_NE(text.find("$Nodes\n15\n"), std::string::npos) << text;
  EXPECT_NE(text.find("$Elements\n8\n"), std::string::npos) << text;
  std::istringstream elements(text.substr(text.find("$Elements\n8\n") + 12));
  for (std::size_t p = 0; p < 8; ++p) {
    int number = 0, type = 0, tags = 0, physical = 0, entity = 0;
    elements >> number >> type >> tags >> physical >> entity;
    EXPECT_EQ(type, 3) << "element " << number;
    const CellCorners c = lattice.cells.corner_positions(lattice.sph_nodes, p);
    double doubled_area = 0.0;  // shoelace over the written corner order
    std::array<int, 4> corner{};
    for (int& k : corner)
      elements >> k;
    for (std::size_t k = 0; k < 4; ++k) {
      const auto i = static_cast<std::size_t>(corner[k] - 1);
      const auto j = static_cast<std::size_t>(corner[(k + 1) % 4] - 1);
      doubled_area += lattice.sph_nodes.position[0][i] * lattice.sph_nodes.position[1][j] -
                      lattice.sph_nodes.position[0][j] * lattice.sph_nodes.position[1][i];
    }
    EXPECT_NEAR(doubled_area, 2.0 * 0.25, 1e-12) << "element " << number;
    EXPECT_EQ(c.count, 4);
  }
}

TEST(GmshWriter, RefusesNodeSetsThatAreNot2D) {
  GeometrySpec bar;
  bar.spacing = 0.5;
  bar.shapes = {test::segment(0.0, 2.0, "soil")};
  EXPECT_THROW(gmsh_mesh_text(build_node_sets(bar, 1, {"soil"})), std::invalid_argument);
}

}  // namespace
}  // namespace rktsph::gmsh_writer_test
