// The surface set: a body's faces from the outline of its cells (on a lattice, the directions with
// no neighbour node), rebuilt into the same buffers, and the boundary conditions acting on a
// surface whose normals are not lattice axes.
#include "rktsph/boundary/surface_set.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../support/lattices.hpp"
#include "rktsph/boundary/boundary_conditions.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::surface_set_test {
namespace {

TEST(SurfaceSet, LatticeFacesAreTheMissingNeighbours) {
  const NodeSets nodes = test::rectangle_lattice(2.0, 1.0, 1.0);  // 3 x 2 nodes, all on the surface
  std::vector<std::uint8_t> mirror_axes(nodes.sph_nodes.size(), 0);
  SurfaceSet surface;
  outline_surface(nodes.cells, nodes.outline, nodes.sph_nodes, mirror_axes, surface);
  ASSERT_EQ(surface.size(), 6u);
  EXPECT_EQ(surface.facet_count(), 2u * 4u + 2u * 2u - 2u);  // 4 corners x 2, 2 edge middles x 1
  const std::int32_t corner = test::lattice_node(nodes, 0, 0);
  const auto k = static_cast<std::size_t>(
      std::find(surface.node.begin(), surface.node.end(), corner) - surface.node.begin());
  ASSERT_EQ(surface.facets_end(k) - surface.facets_begin(k), 2);
  EXPECT_EQ(surface.facet_normal(surface.facets_begin(k)), (Vec3{-1.0, 0.0, 0.0}));
  EXPECT_EQ(surface.facet_normal(surface.facets_begin(k) + 1), (Vec3{0.0, -1.0, 0.0}));

  // A mirror plane y = 0 closes the bottom faces.
  for (std::int32_t i = 0; i < 3; ++i)
    mirror_axes[static_cast<std::size_t>(test::lattice_node(nodes, i, 0))] = 0b10;
  outline_surface(nodes.cells, nodes.outline, nodes.sph_nodes, mirror_axes, surface);
  EXPECT_EQ(surface.facet_count(), 10u - 3u);
}

// The faces of a lattice body by the rule the lattice suggests: the directions +-e_a with no
// neighbour node and no mirror plane, in the order -x, +x, -y, +y, as node -> normals. Written
// here from positions, independently of the outline.
std::vector<std::pair<std::int32_t, std::vector<Vec3>>> missing_neighbours(
    const NodeSets& nodes, const std::vector<std::uint8_t>& mirror_axes) {
  const PointCloud& x = nodes.sph_nodes;
  const double dx = nodes.spacing;
  auto node_near = [&](double px, double py) {
    for (std::size_t j = 0; j < x.size(); ++j)
      if (std::abs(x.position[0][j] - px) < 1e-9 && std::abs(x.position[1][j] - py) < 1e-9)
        return true;
    return false;
  };
  std::vector<std::pair<std::int32_t, std::vector<Vec3>>> faces;
  for (std::size_t i = 0; i < x.size(); ++i) {
    std::vector<Vec3> normals;
    for (int a = 0; a < 2; ++a) {
      if ((mirror_axes[i] >> a) & 1u) continue;
      for (const double sign : {-1.0, 1.0}) {
        const double px = x.position[0][i] + (a == 0 ? sign * dx : 0.0);
        const double py = x.position[1][i] + (a == 1 ? sign * dx : 0.0);
        if (node_near(px, py)) continue;
        Vec3 n{};
        n[static_cast<std::size_t>(a)] = sign;
        normals.push_back(n);
      }
    }
    if (!normals.empty()) faces.emplace_back(static_cast<std::int32_t>(i), normals);
  }
  return faces;
}

TEST(SurfaceSet, OnLatticeBodiesTheOutlineFacesAreTheMissingNeighbours) {
  // A rectangle, an L (re-entrant corner), a 45-degree staircase and a notched polygon, with and
  // without a mirror plane on the left face.
  const std::vector<std::vector<Vec3>> outlines = {
      {{0, 0, 0}, {3, 0, 0}, {3, 2, 0}, {0, 2, 0}},
      {{0, 0, 0}, {3, 0, 0}, {3, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}},
      {{0, 0, 0}, {4, 0, 0}, {4, 1, 0}, {1, 4, 0}, {0, 4, 0}},
      {{0, 0, 0},
       {4, 0, 0},
       {4, 3, 0},
       {2.5, 3, 0},
       {2.5, 1.5, 0},
       {1.5, 1.5, 0},
       {1.5, 3, 0},
       {0, 3, 0}}};
  for (const auto& vertices : outlines)
    for (const bool mirror : {false, true}) {
      GeometrySpec geometry;
      geometry.spacing = 0.5;
      ShapeSpec shape;
      shape.kind = ShapeSpec::Kind::Polygon;
      shape.vertices = vertices;
      shape.material = "soil";
      geometry.shapes = {shape};
      const NodeSets nodes = build_node_sets(geometry, 2, {"soil"});
      std::vector<std::uint8_t> mirror_axes(nodes.sph_nodes.size(), 0);
      if (mirror)
        for (std::size_t i = 0; i < mirror_axes.size(); ++i)
          if (nodes.sph_nodes.position[0][i] == 0.0) mirror_axes[i] = 0b01;
      SurfaceSet surface;
      outline_surface(nodes.cells, nodes.outline, nodes.sph_nodes, mirror_axes, surface);
      const auto expected = missing_neighbours(nodes, mirror_axes);
      ASSERT_EQ(surface.size(), expected.size()) << vertices.size() << " vertices, " << mirror;
      for (std::size_t k = 0; k < surface.size(); ++k) {
        EXPECT_EQ(surface.node[k], expected[k].first);
        ASSERT_EQ(surface.facets_end(k) - surface.facets_begin(k),
                  static_cast<std::int32_t>(expected[k].second.size()));
        for (std::int32_t f = surface.facets_begin(k); f < surface.facets_end(k); ++f) {
          EXPECT_EQ(surface.facet_normal(f),
                    expected[k].second[static_cast<std::size_t>(f - surface.facets_begin(k))]);
          // Each facet gathers the node's one or two outline facets along that face.
          EXPECT_GE(surface.pieces(f).size(), 1u);
          EXPECT_LE(surface.pieces(f).size(), 2u);
        }
      }
    }
}

TEST(SurfaceSet, RebuildingWithTheSameSizeDoesNotAllocate) {
  const NodeSets nodes = test::rectangle_lattice(4.0, 3.0, 1.0);
  const std::vector<std::uint8_t> mirror_axes(nodes.sph_nodes.size(), 0);
  SurfaceSet surface;
  outline_surface(nodes.cells, nodes.outline, nodes.sph_nodes, mirror_axes, surface);
  const double* normals = surface.normal[0].data();
  const std::int32_t* ids = surface.node.data();
  outline_surface(nodes.cells, nodes.outline, nodes.sph_nodes, mirror_axes, surface);
  EXPECT_EQ(surface.normal[0].data(), normals);
  EXPECT_EQ(surface.node.data(), ids);
}

TEST(SurfaceSet, OppositeFacetsAreOneProjection) {
  SurfaceSet surface;
  surface.clear();
  surface.add_node(7);
  surface.add_facet({-1.0, 0.0, 0.0});
  surface.add_facet({1.0, 0.0, 0.0});
  surface.add_facet({0.0, 1.0, 0.0});
  const SurfaceNormals normals = surface.projected_normals(0);
  ASSERT_EQ(normals.count, 2);
  EXPECT_EQ(normals.normal[0], (Vec3{-1.0, 0.0, 0.0}));
  EXPECT_EQ(normals.normal[1], (Vec3{0.0, 1.0, 0.0}));
  surface.projected[2] = 0;
  EXPECT_EQ(surface.projected_normals(0).count, 1);
}

const char* kBlock = R"(
name: block
dimension: 2
geometry:
  spacing: 1.0
  shapes: [{rectangle: {min: [0, 0], max: [4, 3]}, material: soil}]
materials:
  soil: {model: linear_elastic, density: 2000.0, young_modulus: 1.0e7, poisson_ratio: 0.3}
boundary_conditions:
  - {group: xmin, fixed: true}
time: {end: 0.01}
)";

TEST(SurfaceSet, ConditionsOnATiltedSurfaceMakeItTractionFree) {
  Simulation simulation(read_case_text(kBlock, "block.yaml"));
  BoundaryConditions conditions(simulation.description().boundary_conditions, simulation.nodes(),
                                simulation.groups(), simulation.model());
  const std::int32_t free_node = test::lattice_node(simulation.nodes(), 4, 1);
  const std::int32_t fixed_node = test::lattice_node(simulation.nodes(), 0, 1);
  const double c30 = std::cos(std::numbers::pi / 6.0), s30 = std::sin(std::numbers::pi / 6.0);
  SurfaceSet tilted;
  tilted.clear();
  tilted.add_node(fixed_node);
  tilted.add_facet({-1.0, 0.0, 0.0});
  tilted.add_node(free_node);
  tilted.add_facet({c30, s30, 0.0});
  conditions.replace_surface(tilted);
  // The fixed face's stress is a reaction; the tilted facet is free and projected.
  EXPECT_EQ(conditions.surface().reactions[0], 0b11);
  EXPECT_EQ(conditions.surface().projected[0], 0);
  EXPECT_EQ(conditions.surface().reactions[1], 0);
  EXPECT_EQ(conditions.surface().projected[1], 1);

  const PhysicsModel& model = simulation.model();
  FieldArray fields(model.field_count(), simulation.nodes().sph_nodes.size());
  const auto i = static_cast<std::size_t>(free_node);
  const int xx = model.stress_field(0, 0), yy = model.stress_field(1, 1),
            xy = model.stress_field(0, 1), zz = model.stress_field(2, 2);
  fields(xx, i) = 3.0e4;
  fields(yy, i) = -2.0e4;
  fields(xy, i) = 1.0e4;
  fields(zz, i) = 5.0e3;
  const double tangential =  // t·sigma·t with t = (-sin 30, cos 30)
      s30 * s30 * 3.0e4 - 2.0 * s30 * c30 * 1.0e4 + c30 * c30 * -2.0e4;
  conditions.apply(0.0, fields);
  EXPECT_NEAR(fields(xx, i) * c30 + fields(xy, i) * s30, 0.0, 1e-11);
  EXPECT_NEAR(fields(xy, i) * c30 + fields(yy, i) * s30, 0.0, 1e-11);
  EXPECT_NEAR(
      s30 * s30 * fields(xx, i) - 2.0 * s30 * c30 * fields(xy, i) + c30 * c30 * fields(yy, i),
      tangential, 1e-11 * 3.0e4);
  EXPECT_EQ(fields(zz, i), 5.0e3);
  // The stress the hourglass stiffness must treat as imposed follows the surface.
  const auto pairs = conditions.constrained_stress();
  EXPECT_EQ(std::count(pairs.begin(), pairs.end(), std::pair<std::int32_t, int>{free_node, xy}), 1);
}

}  // namespace
}  // namespace rktsph::surface_set_test
