// Triangle meshes read from Gmsh files (docs/theory.md §3.8, `geometry.mesh`): both MSH formats,
// materials from physical surfaces, clockwise triangles turned, the node sets equal to the bit to
// those of the project's own mesher when its mesh is written out and read back, every refusal at
// its line of the file, the case keys, and a two-layer column meshed by Gmsh itself, loaded by
// gravity to rest against the closed-form geostatic stress.
#include "rktsph/geometry/gmsh_mesh.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "../support/same_node_sets.hpp"
#include "../support/shapes.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/geometry/triangle_mesher.hpp"
#include "rktsph/geometry/triangle_node_sets.hpp"
#include "rktsph/mesh/cell_geometry.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::gmsh_mesh_test {
namespace {

namespace fs = std::filesystem;

/// A scratch folder of this test, emptied first.
fs::path scratch(const std::string& name) {
  const fs::path folder = fs::temp_directory_path() / ("rktsph-gmsh-test-" + name);
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

fs::path write(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
  return file;
}

GeometrySpec mesh_geometry(const fs::path& file) {
  GeometrySpec geometry;
  geometry.cells = CellLayout::Triangles;
  geometry.mesh = file.string();
  geometry.mesh_where = SourceLocation{"case.yaml", 4, 9};
  return geometry;
}

// The unit square of two triangles, the second written clockwise, with a line and a point element
// that are left out. MSH 2.2: element tag, type, number of tags, tags (physical first), nodes.
const char* kSquare22 = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
1 2 "base"
2 1 "soil"
$EndPhysicalNames
$Nodes
4
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
$EndNodes
$Elements
4
1 15 2 0 1 1
2 1 2 2 1 1 2
3 2 2 1 1 1 2 3
4 2 2 1 1 1 4 3
$EndElements
)";

// The same square in MSH 4.1: the elements name their entity (the bottom curve, the surface),
// whose physical tags are in $Entities.
const char* kSquare41 = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
1 2 "base"
2 1 "soil"
$EndPhysicalNames
$Entities
0 1 1 0
1 0 0 0 1 0 0 1 2 0
1 0 0 0 1 1 0 1 1 0
$EndEntities
$Nodes
1 4 1 4
2 1 0 4
1
2
3
4
0 0 0
1 0 0
1 1 0
0 1 0
$EndNodes
$Elements
2 3 2 5
1 1 1 1
5 1 2
2 1 2 2
3 1 2 3
4 1 4 3
$EndElements
)";

void expect_square(const NodeSets& nodes) {
  ASSERT_EQ(nodes.sph_nodes.size(), 4u);
  ASSERT_EQ(nodes.cells.cell_count(), 2u);
  EXPECT_EQ(nodes.layout, CellLayout::Triangles);
  EXPECT_DOUBLE_EQ(nodes.spacing, std::sqrt(2.0));  // the longest edge, a diagonal
  double area = 0.0;
  for (std::size_t p = 0; p < nodes.cells.cell_count(); ++p) {
    const double measure =
        cell_measure(CellKind::Triangle, nodes.cells.corner_positions(nodes.sph_nodes, p));
    EXPECT_DOUBLE_EQ(measure, 0.5) << "cell " << p << " counter-clockwise";
    area += nodes.sph_nodes.volume[2 * p] + nodes.sph_nodes.volume[2 * p + 1];
  }
  EXPECT_DOUBLE_EQ(area, 1.0);  // lumped node volumes add up to the area
  // Numbered by (y, x).
  EXPECT_EQ(nodes.sph_nodes.position[1][0], 0.0);
  EXPECT_EQ(nodes.sph_nodes.position[0][1], 1.0);
  EXPECT_EQ(nodes.sph_nodes.position[0][2], 0.0);
  EXPECT_EQ(nodes.sph_nodes.position[1][3], 1.0);
}

TEST(GmshMesh, ReadsBothFormatsTurnsClockwiseTrianglesAndLeavesOutPointsAndLines) {
  const fs::path folder = scratch("formats");
  for (const char* text : {kSquare22, kSquare41}) {
    const fs::path file = write(folder / "square.msh", text);
    const GmshMesh mesh = read_gmsh_mesh(file, {});
    ASSERT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(mesh.triangles[0].physical, "soil");
    EXPECT_EQ(mesh.triangles[1].element, 4);
    EXPECT_EQ(mesh.points.size(), 4u);
    // The material named by the physical surface, and the other material unused.
    const NodeSets nodes = build_mesh_node_sets(mesh_geometry(file), {"clay", "soil"});
    expect_square(nodes);
    for (std::size_t p = 0; p < 2; ++p)
      EXPECT_EQ(nodes.cells.material(p), 1);
    // The physical groups: the bottom line's two nodes, the surface's four.
    EXPECT_EQ(nodes.mesh_groups.at("base"), (std::vector<std::int32_t>{0, 1}));
    EXPECT_EQ(nodes.mesh_groups.at("soil"), (std::vector<std::int32_t>{0, 1, 2, 3}));
  }
}

TEST(GmshMesh, WithoutPhysicalSurfacesTheCasesOnlyMaterialIsTaken) {
  std::string text = kSquare22;
  for (const char* tags : {"3 2 2 1 1", "4 2 2 1 1"})
    text.replace(text.find(tags), std::string(tags).size(), std::string(tags).substr(0, 4) + "0");
  const fs::path file = write(scratch("no-physical") / "square.msh", text);
  expect_square(build_mesh_node_sets(mesh_geometry(file), {"clay"}));
  try {
    build_mesh_node_sets(mesh_geometry(file), {"clay", "sand"});
    FAIL() << "two materials and no physical surface were accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("in no physical surface"), std::string::npos)
        << error.what();
    EXPECT_EQ(error.location().line, 20);
  }
}

// The project's own mesh of a slope, written as a Gmsh file at round-trip precision and read
// back: the same node sets, to the bit.
TEST(GmshMesh, TheMeshersOwnTrianglesReadBackToTheBit) {
  GeometrySpec shapes;
  shapes.spacing = 0.7;
  shapes.cells = CellLayout::Triangles;
  shapes.shapes = test::two_material_slope();
  const std::vector<std::string> names = {"rock", "soil"};
  const NodeSets own = build_triangle_node_sets(shapes, names);
  std::string text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n";
  text += "2 1 \"rock\"\n2 2 \"soil\"\n$EndPhysicalNames\n$Nodes\n";
  // Tags in reverse order and the corners rotated, so that only the reader's own ordering can
  // give the same numbering.
  const std::size_t n = own.sph_nodes.size();
  text += fmt::format("{}\n", n);
  for (std::size_t i = 0; i < n; ++i)
    text += fmt::format("{} {:.17g} {:.17g} 0\n", n - i, own.sph_nodes.position[0][i],
                        own.sph_nodes.position[1][i]);
  text += fmt::format("$EndNodes\n$Elements\n{}\n", own.cells.cell_count());
  for (std::size_t p = 0; p < own.cells.cell_count(); ++p) {
    const auto c = own.cells.corners(p);
    text += fmt::format("{} 2 2 {} 7 {} {} {}\n", p + 1, own.cells.material(p) + 1,
                        n - static_cast<std::size_t>(c[1]), n - static_cast<std::size_t>(c[2]),
                        n - static_cast<std::size_t>(c[0]));
  }
  text += "$EndElements\n";
  const fs::path file = write(scratch("round-trip") / "slope.msh", text);
  const NodeSets read = build_mesh_node_sets(mesh_geometry(file), names);
  test::expect_same_node_sets(read, own);
  EXPECT_EQ(read.outline.facet_count(), own.outline.facet_count());
  EXPECT_LE(read.spacing, shapes.spacing);  // the longest edge, at most the one asked for
}

struct Refusal {
  std::string name, from, to;  // replace `from` by `to` in kSquare22
  int line;                    // expected line of the error in the file (0: none)
  std::string says;            // expected in the message
};

TEST(GmshMesh, MistakesAreRefusedAtTheirLineOfTheFile) {
  const std::vector<Refusal> refusals = {
      {"binary", "2.2 0 8", "2.2 1 8", 2, "binary"},
      {"version", "2.2 0 8", "3.0 0 8", 2, "MSH version 3.0"},
      {"quadrangle", "4 2 2 1 1 1 4 3", "4 3 2 1 1 1 2 3 4", 21, "4-node quadrangle"},
      {"second order", "4 2 2 1 1 1 4 3", "4 9 2 1 1 1 2 3 4 1 2 3", 21, "second-order"},
      {"missing node", "4 2 2 1 1 1 4 3", "4 2 2 1 1 1 4 9", 21, "which $Nodes does not define"},
      {"off the plane", "3 1 1 0", "3 1 1 0.5", 20, "off the plane z = 0"},
      {"bad number", "2 1 0 0", "2 1,5 0 0", 12, "not a finite number"},
      {"degenerate", "4 0 1 0", "4 2 2 0", 21, "has no area"},
      {"unknown material", "2 1 \"soil\"", "2 1 \"silt\"", 20, "'silt', which names no material"},
      {"coincident nodes", "4 0 1 0", "4 1 1 0", 0, "lie at the same position"},
      {"triangle twice", "4\n1 15", "5\n5 2 2 1 1 1 2 3\n1 15", 22, "shares an edge with two"},
      {"no elements",
       "$Elements\n4\n1 15 2 0 1 1\n2 1 2 2 1 1 2\n3 2 2 1 1 1 2 3\n4 2 2 1 1 1 4 3\n"
       "$EndElements\n",
       "", 0, "no $Elements section"},
      {"truncated", "$EndElements\n", "", 21, "the file ends"},
  };
  const fs::path folder = scratch("refusals");
  for (const Refusal& refusal : refusals) {
    std::string text = kSquare22;
    const std::size_t at = text.find(refusal.from);
    ASSERT_NE(at, std::string::npos) << refusal.name;
    text.replace(at, refusal.from.size(), refusal.to);
    const fs::path file = write(folder / "mesh.msh", text);
    try {
      build_mesh_node_sets(mesh_geometry(file), {"clay", "soil"});
      ADD_FAILURE() << refusal.name << ": accepted";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(refusal.says), std::string::npos)
          << refusal.name << ": " << error.what();
      EXPECT_EQ(error.location().file, file.string()) << refusal.name;
      if (refusal.line > 0) {
        EXPECT_EQ(error.location().line, refusal.line) << refusal.name;
      }
      EXPECT_EQ(error.key(), "geometry.mesh") << refusal.name;
    }
  }
}

TEST(GmshMesh, AMissingFileOrAFolderIsNamedAtTheCaseKey) {
  const fs::path folder = scratch("missing");
  for (const auto& [path, says] : {std::pair{folder / "absent.msh", "no file of this name"},
                                   std::pair{folder, "not a regular file"},
                                   std::pair{fs::path("/dev/zero"), "not a regular file"}}) {
    try {
      build_mesh_node_sets(mesh_geometry(path), {"soil"});
      ADD_FAILURE() << path << ": accepted";
    } catch (const InputError& error) {
      EXPECT_EQ(error.location().file, "case.yaml");
      EXPECT_EQ(error.location().line, 4);
      EXPECT_NE(std::string(error.what()).find(says), std::string::npos) << error.what();
    }
  }
}

std::string mesh_case(const std::string& geometry) {
  return "name: m\ndimension: 2\ngeometry:\n" + geometry +
         "materials:\n  soil: {model: linear_elastic, density: 2000, young_modulus: 1.0e8, "
         "poisson_ratio: 0.3}\ntime: {end: 0.01}\n";
}

TEST(GmshMesh, TheCaseNamesTheMeshRelativeToItsFolderAndWritesItBackResolved) {
  const fs::path folder = scratch("case");
  write(folder / "square.msh", kSquare41);
  const std::string text = mesh_case("  mesh: square.msh\n");
  const CaseDescription description =
      read_case_text(text, (folder / "sub" / ".." / "case.yaml").string());
  EXPECT_EQ(fs::path(description.geometry.mesh), (folder / "square.msh").lexically_normal());
  EXPECT_EQ(description.geometry.cells, CellLayout::Triangles);
  const std::string written = write_case_yaml(description);
  EXPECT_NE(written.find(fs::absolute(folder / "square.msh").string()), std::string::npos)
      << written;
  EXPECT_EQ(written.find("spacing"), std::string::npos) << written;
  EXPECT_EQ(written.find("shapes"), std::string::npos) << written;
  // Read back from elsewhere, the written case names the same file.
  const CaseDescription again = read_case_text(written, "/elsewhere/case.yaml");
  EXPECT_EQ(again.geometry.mesh, fs::absolute(folder / "square.msh").string());
  Simulation simulation(description);
  EXPECT_EQ(simulation.nodes().sph_nodes.size(), 4u);
  EXPECT_DOUBLE_EQ(simulation.nodes().spacing, std::sqrt(2.0));
}

TEST(GmshMesh, TheCaseRefusesASpacingShapesALatticeOrOneDimensionWithAMesh) {
  const std::vector<std::pair<std::string, std::string>> refusals = {
      {mesh_case("  mesh: square.msh\n  spacing: 0.5\n"), "brings its own spacing"},
      {mesh_case("  mesh: square.msh\n  cells: lattice\n"), "a mesh file holds triangles"},
      {mesh_case("  mesh: square.msh\n  shapes: [{rectangle: {min: [0, 0], max: [1, 1]}, "
                 "material: soil}]\n"),
       "'mesh' and 'shapes' are both given"},
      {mesh_case("  spacing: 0.5\n"), "exactly one of 'shapes' or 'mesh'"},
      {mesh_case("  mesh: ''\n"), "path is empty"},
  };
  for (const auto& [text, says] : refusals) {
    try {
      read_case_text(text, "case.yaml");
      ADD_FAILURE() << says << ": accepted";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(says), std::string::npos) << error.what();
    }
  }
  std::string one_dimensional = mesh_case("  mesh: square.msh\n");
  one_dimensional.replace(one_dimensional.find("dimension: 2"), 12, "dimension: 1");
  EXPECT_THROW(read_case_text(one_dimensional, "case.yaml"), InputError);
}

TEST(GmshMesh, GroupsSelectThePhysicalGroupsOfTheFileByName) {
  const fs::path folder = scratch("groups");
  write(folder / "square.msh", kSquare41);
  const auto select = [&](const std::string& groups) {
    const CaseDescription description =
        read_case_text(mesh_case("  mesh: square.msh\n") + groups, (folder / "c.yaml").string());
    const Simulation simulation(description);
    return simulation.groups();
  };
  const auto groups = select("groups:\n  bottom: {physical: base}\n  body: {physical: soil}\n");
  EXPECT_EQ(groups.at("bottom"), (std::vector<std::int32_t>{0, 1}));
  EXPECT_EQ(groups.at("body").size(), 4u);
  try {
    select("groups:\n  top: {physical: crest}\n");
    ADD_FAILURE() << "an unknown physical group was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("one of 'base', 'soil'"), std::string::npos)
        << error.what();
  }
  // Without a mesh file a physical group means nothing.
  EXPECT_THROW(read_case_text("name: m\ndimension: 2\ngeometry:\n  spacing: 0.5\n  shapes: "
                              "[{rectangle: {min: [0, 0], max: [1, 1]}, material: soil}]\n"
                              "materials:\n  soil: {model: linear_elastic, density: 2000, "
                              "young_modulus: 1.0e8, poisson_ratio: 0.3}\ngroups:\n  b: "
                              "{physical: base}\ntime: {end: 0.01}\n",
                              "case.yaml"),
               InputError);
}

// A two-layer column meshed by Gmsh (tests/data/meshes/two-layer-column.geo): sand (1700 kg/m3,
// nu = 0.25) 2.5 m over clay (1900 kg/m3, nu = 0.3), rollers at the sides, a rough base, gravity
// ramped in and damped to rest; the base is the file's physical curve "base". Each layer is in
// uniaxial strain: sigma_v is the weight above, sigma_h = K0 sigma_v with K0 = nu / (1 - nu) of the
// layer. Tolerances as triangles-slope-elastic's (2 % on sigma_v, 3 % on K0) away from the
// interface: a node within one spacing of it averages the strains of both layers (its stiffness
// jumps there), so there the check is vertical equilibrium instead, the interface row's resultant
// against the sand's weight.
TEST(GmshMeshSlow, TwoLayerColumnMeshedByGmshComesToRestUnderItsGeostaticStress) {
  const fs::path mesh = fs::path(RKTSPH_TEST_DATA_DIR) / "meshes" / "two-layer-column.msh";
  const std::string text = fmt::format(R"(name: column
dimension: 2
plane: strain
geometry:
  mesh: {}
materials:
  clay: {{model: linear_elastic, density: 1900.0, young_modulus: 3.0e7, poisson_ratio: 0.3}}
  sand: {{model: linear_elastic, density: 1700.0, young_modulus: 5.0e7, poisson_ratio: 0.25}}
groups:
  base: {{physical: base}}
boundary_conditions:
  - {{group: xmin, roller: x}}
  - {{group: xmax, roller: x}}
  - {{group: base, fixed: true}}
loads:
  gravity: {{acceleration: [0, -9.81], factor: {{function: ramp, value: 1, duration: 0.3}}}}
  damping: {{coefficient: 30}}
time: {{end: 1.5}}
output: {{interval: 0}}
)",
                                       mesh.string());
  Simulation simulation(read_case_text(text, "column.yaml"));
  ASSERT_EQ(simulation.run(), RunStatus::Completed) << simulation.message();
  const NodeSets& nodes = simulation.nodes();
  const FieldArray& fields = simulation.state().fields;
  const int xx = simulation.model().stress_field(0, 0), yy = simulation.model().stress_field(1, 1);
  const int vx = simulation.model().velocity_field(0), vy = simulation.model().velocity_field(1);
  constexpr double g = 9.81, top = 4.0, interface = 1.5;
  const auto weight_above = [&](double y) {
    return y >= interface ? 1700.0 * g * (top - y)
                          : 1700.0 * g * (top - interface) + 1900.0 * g * (interface - y);
  };
  double stress_error = 0.0, k0_error = 0.0, speed = 0.0;
  std::vector<std::pair<double, double>> interface_row;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    const double x = nodes.sph_nodes.position[0][i], y = nodes.sph_nodes.position[1][i];
    speed = std::max({speed, std::abs(fields(vx, i)), std::abs(fields(vy, i))});
    if (std::abs(y - interface) < 1e-9) interface_row.emplace_back(x, fields(yy, i));
    if (top - y < 0.5 || std::abs(y - interface) <= nodes.spacing) continue;
    stress_error = std::max(stress_error, std::abs(-fields(yy, i) / weight_above(y) - 1.0));
    const double nu = y > interface ? 0.25 : 0.3;
    k0_error = std::max(k0_error, std::abs(fields(xx, i) / fields(yy, i) / (nu / (1.0 - nu)) - 1));
  }
  EXPECT_LE(stress_error, 0.02);
  EXPECT_LE(k0_error, 0.03);
  EXPECT_LE(speed, 1e-6);  // m/s; the settlement is about 1 mm
  std::sort(interface_row.begin(), interface_row.end());
  ASSERT_GE(interface_row.size(), 3u);
  double resultant = 0.0;
  for (std::size_t k = 0; k + 1 < interface_row.size(); ++k)
    resultant += 0.5 * (interface_row[k + 1].first - interface_row[k].first) *
                 (interface_row[k].second + interface_row[k + 1].second);
  EXPECT_NEAR(-resultant / 2.0, weight_above(interface), 0.02 * weight_above(interface));
  // Each triangle carries the material of its physical surface.
  for (std::size_t p = 0; p < nodes.cells.cell_count(); ++p)
    EXPECT_EQ(nodes.material_names[static_cast<std::size_t>(nodes.cells.material(p))],
              nodes.stress_points.position[1][p] < interface ? "clay" : "sand");
}

}  // namespace
}  // namespace rktsph::gmsh_mesh_test
