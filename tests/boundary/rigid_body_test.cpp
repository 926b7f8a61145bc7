// The `rigid_body` boundary condition (docs/input-reference.md, "boundary_conditions";
// docs/theory.md §9.18): a rigid polygon moving at an imposed velocity or under a load; the
// distance of a point to it, the contact rules (smooth, rough, Coulomb) relative to its velocity,
// the facets pressed against it carrying its reaction, its force against the oedometric stiffness
// of a column it compresses, a loaded body's equation of motion (eq. 9.17) free and on the column,
// a restart with it, and its input errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "../support/case_text.hpp"
#include "../support/elastic_block.hpp"
#include "rktsph/boundary/rigid_body.hpp"
#include "rktsph/core/checkpoint.hpp"
#include "rktsph/core/error.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::rigid_body_test {
namespace {

const std::vector<Vec3> kSquare = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};

TEST(RigidBody, DistanceToAPolygonIsItsDepthInsideAndTheNormalOfItsNearestFacet) {
  // Inside, 0.25 from the bottom edge: depth 0.25, outward normal (0, -1).
  PolygonDistance inside = polygon_distance(kSquare, 1.0, 0.25);
  EXPECT_DOUBLE_EQ(inside.depth, 0.25);
  EXPECT_DOUBLE_EQ(inside.normal[0], 0.0);
  EXPECT_DOUBLE_EQ(inside.normal[1], -1.0);
  // Outside beside the right edge: depth -0.5, normal (1, 0); either orientation.
  const std::vector<Vec3> clockwise(kSquare.rbegin(), kSquare.rend());
  for (const auto& polygon : {kSquare, clockwise}) {
    const PolygonDistance beside = polygon_distance(polygon, 2.5, 1.0);
    EXPECT_DOUBLE_EQ(beside.depth, -0.5);
    EXPECT_DOUBLE_EQ(beside.normal[0], 1.0);
    EXPECT_DOUBLE_EQ(beside.normal[1], 0.0);
  }
  // Off a corner: distance to the corner, normal from the corner to the point.
  const PolygonDistance corner = polygon_distance(kSquare, 2.3, -0.4);
  EXPECT_NEAR(corner.depth, -0.5, 1e-15);
  EXPECT_NEAR(corner.normal[0], 0.6, 1e-15);
  EXPECT_NEAR(corner.normal[1], -0.8, 1e-15);
}

/// A body over the square moving at (0, -1) m/s: one node under its bottom edge.
RigidBody body_at_rest_on(ContactSurface surface) {
  std::array<std::optional<TimeFunction>, 3> velocity;
  velocity[1] = TimeFunction::constant(-1.0);
  return RigidBody("plate", kSquare, BodyDrive{velocity, {}, 0.0}, surface, {0});
}

/// Node 0 at (x, y) at `time`, with velocity v and normal stress `sigma_nn`, after the body's
/// contact rule.
Vec3 contact_velocity(const RigidBody& prototype, double x, double y, double time, Vec3 v,
                      double sigma_nn = 0.0) {
  RigidBody body = prototype;
  PointCloud nodes;
  nodes.dimension = 2;
  nodes.push_back(Vec3{x, y, 0.0}, 1.0);
  body.find_contacts(nodes, time, 1e-9);
  FieldArray fields(2, 1);
  fields(0, 0) = v[0];
  fields(1, 0) = v[1];
  const int velocity_field[2] = {0, 1};
  body.impose(time, velocity_field, fields, {},
              [sigma_nn](std::size_t, const Vec3&) { return sigma_nn; });
  return {fields(0, 0), fields(1, 0), 0.0};
}

TEST(RigidBody, AMovingBodyHoldsTheNodesItReachesByTheirVelocityRelativeToIt) {
  // At t = 0.5 s the body's bottom edge is at y = -0.5: a node at y = -0.5 touches it, one at
  // y = -0.6 does not.
  const RigidBody smooth = body_at_rest_on({false, std::nullopt});
  const RigidBody rough = body_at_rest_on({true, std::nullopt});
  const RigidBody coulomb = body_at_rest_on({true, 0.5});
  EXPECT_DOUBLE_EQ(smooth.displacement(0.5)[1], -0.5);
  // Approaching the body (relative normal speed -0.5 - (-1)... v_y = -0.5 is slower than the body
  // moving down at -1, so the body runs into it): normal relative speed held at 0.
  const Vec3 v{0.4, -0.5, 0.0};
  Vec3 out = contact_velocity(smooth, 1.0, -0.5, 0.5, v);
  EXPECT_DOUBLE_EQ(out[0], 0.4);  // slides freely
  EXPECT_DOUBLE_EQ(out[1], -1.0);
  out = contact_velocity(rough, 1.0, -0.5, 0.5, v);
  EXPECT_DOUBLE_EQ(out[0], 0.0);  // moves with the body
  EXPECT_DOUBLE_EQ(out[1], -1.0);
  // Coulomb, mu = 0.5: the normal correction 0.5 m/s holds at most 0.25 m/s of the 0.4 of slip.
  out = contact_velocity(coulomb, 1.0, -0.5, 0.5, v);
  EXPECT_NEAR(out[0], 0.15, 1e-15);
  EXPECT_DOUBLE_EQ(out[1], -1.0);
  // Leaving the body (moving down faster than it): untouched by a smooth body.
  out = contact_velocity(smooth, 1.0, -0.5, 0.5, {0.4, -1.5, 0.0});
  EXPECT_DOUBLE_EQ(out[0], 0.4);
  EXPECT_DOUBLE_EQ(out[1], -1.5);
  // Pressed against the body (compressive normal stress), it is held on it instead.
  out = contact_velocity(smooth, 1.0, -0.5, 0.5, {0.4, -1.5, 0.0}, -1.0);
  EXPECT_DOUBLE_EQ(out[0], 0.4);
  EXPECT_DOUBLE_EQ(out[1], -1.0);
  // A node below the body, beyond the contact tolerance, is not in contact.
  out = contact_velocity(rough, 1.0, -0.6, 0.5, v);
  EXPECT_DOUBLE_EQ(out[0], 0.4);
  EXPECT_DOUBLE_EQ(out[1], -0.5);
  // A node beside the body, past its edge, is not either: it slid off.
  out = contact_velocity(rough, 2.2, -0.5, 0.5, v);
  EXPECT_DOUBLE_EQ(out[1], -0.5);
}

std::string column(const std::string& body) {
  test::ElasticBlock block;
  block.spacing = 0.25;
  block.shapes = test::ElasticBlock::rectangle(1.0, 2.0);
  block.conditions = {"{group: xmin, roller: x}", "{group: xmax, roller: x}",
                      "{group: ymin, roller: y}", "{group: all, rigid_body: " + body + "}"};
  block.loads = "{damping: {coefficient: 40}}";
  std::string text = "model: dry_large_deformation\n" + block.text();
  const std::string end = "time: {end: 1.0}";
  text.replace(text.find(end), end.size(), "time: {end: 2.0}");
  return text;
}

TEST(RigidBody, APlatePressedIntoAColumnFeelsItsOedometricStiffness) {
  // A smooth plate over the 1 m x 2 m column's top moves down 2 mm over 0.5 s and stops: at rest
  // the column is compressed by eps = 1e-3 in the oedometer (rollers), so the plate carries
  // M eps W with M = E (1 - nu) / ((1 + nu)(1 - 2 nu)) = 13.46 MPa: 13.46 kN per m.
  Simulation simulation(read_case_text(
      column("{name: plate, polygon: [[-1, 2], [2, 2], [2, 3], [-1, 3]], surface: smooth, "
             "velocity: {y: {function: table, points: [[0, 0], [0.05, -0.004444444444444444], "
             "[0.45, -0.004444444444444444], [0.5, 0], [2, 0]]}}}"),
      "column.yaml"));
  ASSERT_EQ(simulation.run(), RunStatus::Completed) << simulation.message();
  const BoundaryConditions& conditions = simulation.boundary_conditions();
  ASSERT_EQ(conditions.rigid_bodies().size(), 1u);
  EXPECT_NEAR(conditions.rigid_bodies()[0].displacement(2.0)[1], -0.002, 1e-12);
  // The force is the traction of the top row over the plate's width (measured when the last
  // step applied its conditions, a part in 1e6 before the state's last update at rest).
  const int syy = simulation.model().stress_field(1, 1);
  double top_row = 0.0;
  for (std::size_t i = 0; i < simulation.nodes().sph_nodes.size(); ++i)
    if (simulation.nodes().sph_nodes.position[1][i] == 2.0)
      top_row += simulation.state().fields(syy, i) *
                 (simulation.nodes().sph_nodes.position[0][i] *
                              (1.0 - simulation.nodes().sph_nodes.position[0][i]) ==
                          0.0
                      ? 0.125
                      : 0.25);
  const double force = conditions.rigid_body_force(0)[1];
  EXPECT_NEAR(force, -top_row, 1e-5 * std::abs(top_row));
  EXPECT_NEAR(conditions.rigid_body_force(0)[0], 0.0, 1e-6 * std::abs(top_row));
  // Against the oedometer: the lattice's static state alternates row to row by +-0.6 % here
  // (the strain modes of nodal stress storage, docs/theory.md §3.4, family ii), so the top row
  // lies within 1.5 % of M eps; a force not taken from the contact (zero, or the impulses of the
  // constraint, 2.2 times it on the strip footing) is far outside.
  const double modulus = 1.0e7 * 0.7 / (1.3 * 0.4);
  const double expected = modulus * 0.002 / 2.0 * 1.0;
  EXPECT_NEAR(force, expected, 0.015 * expected);
}

TEST(RigidBody, TheLoadedWidthEndsAtTheBodysCorner) {
  // A plate ending at x = 0.6 m over the column's top row (nodes every 0.25 m): the nodes at 0,
  // 0.25 and 0.5 m touch it, and the last one's share runs on to the corner, 0.1 m beyond it
  // (eq. 9.15): the force is their traction over 0.125, 0.25 and 0.225 m, 0.6 m in all.
  std::string text = column(
      "{name: plate, polygon: [[-1, 2], [0.6, 2], [0.6, 3], [-1, 3]], surface: smooth, "
      "velocity: {y: {function: table, points: [[0, 0], [0.05, -0.04], [0.1, 0], [2, 0]]}}}");
  text.replace(text.find("time: {end: 2.0}"), 16, "time: {end: 1.0}");  // at rest by then
  Simulation simulation(read_case_text(text, "column.yaml"));
  ASSERT_EQ(simulation.run(), RunStatus::Completed) << simulation.message();
  const auto& position = simulation.nodes().sph_nodes.position;  // at the start
  const FieldArray& u = simulation.state().displacement;
  const int syy = simulation.model().stress_field(1, 1);
  double expected = 0.0;
  for (std::size_t i = 0; i < simulation.nodes().sph_nodes.size(); ++i) {
    if (position[1][i] != 2.0 || position[0][i] > 0.6) continue;
    const double x = position[0][i];
    // Half the way to each neighbour on the plate, and from the last one on to the corner.
    const double share = x == 0.0   ? 0.125 + 0.5 * u(0, i + 1) - 0.5 * u(0, i)
                         : x == 0.5 ? 0.125 + 0.5 * (u(0, i) - u(0, i - 1)) + 0.1 - u(0, i)
                                    : 0.25 + 0.5 * (u(0, i + 1) - u(0, i - 1));
    expected -= simulation.state().fields(syy, i) * share;
  }
  ASSERT_GT(expected, 0.0);
  EXPECT_NEAR(simulation.boundary_conditions().rigid_body_force(0)[1], expected, 1e-4 * expected);
}

TEST(RigidBody, SurfaceAndFrictionTogetherAreRefusedAtTheirLine) {
  try {
    read_case_text(column("{name: plate, polygon: [[0, 2], [1, 2], [1, 3]], surface: smooth, "
                          "friction: 0.3}"),
                   "column.yaml");
    FAIL() << "surface and friction were both accepted";
  } catch (const InputError& error) {
    const std::string text = error.what();
    EXPECT_NE(text.find("friction"), std::string::npos) << text;
    EXPECT_NE(text.find("column.yaml:"), std::string::npos) << text;
  }
}

TEST(RigidBody, TheSmallDeformationModelRefusesIt) {
  std::string text = column("{name: plate, polygon: [[0, 2], [1, 2], [1, 3]]}");
  text.replace(text.find("model: dry_large_deformation"), 28, "model: dry_solid");
  try {
    read_case_text(text, "column.yaml");
    FAIL() << "a rigid body was accepted by the small-deformation model";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("dry_large_deformation"), std::string::npos)
        << error.what();
  }
}

TEST(RigidBody, ALoadedBodyMovesByItsEquationOfMotion) {
  // No soil in reach: M dV/dt = P + M g (eq. 9.17) with P = -1000 N/m, M = 10 kg/m, g = -9.81
  // m/s2, a = -109.81 m/s2 from rest; x imposed at 0.5 m/s. The velocity is linear over each
  // step and the displacement its trapezoidal integral, exact for a constant force, at the ends
  // of the steps and in between.
  BodyDrive drive;
  drive.velocity[0] = TimeFunction::constant(0.5);
  drive.load[1] = TimeFunction::constant(-1000.0);
  drive.mass = 10.0;
  RigidBody body("block", kSquare, drive, {true, std::nullopt}, {});
  ASSERT_TRUE(body.loaded());
  const double a = -1000.0 / 10.0 - 9.81, dt = 0.01;
  for (int step = 0; step < 100; ++step) {
    const double t = step * dt;
    body.begin_step(t, dt, Vec3{}, Vec3{0.0, -9.81, 0.0}, {});
    if (step == 50) {
      EXPECT_NEAR(body.velocity(t + 0.3 * dt)[1], a * (t + 0.3 * dt), 1e-11);
      EXPECT_NEAR(body.displacement(t + 0.3 * dt)[1], 0.5 * a * std::pow(t + 0.3 * dt, 2), 1e-11);
    }
    body.end_step();
  }
  EXPECT_NEAR(body.velocity(1.0)[1], a, 1e-11);
  EXPECT_NEAR(body.displacement(1.0)[1], 0.5 * a, 1e-11);
  EXPECT_DOUBLE_EQ(body.velocity(1.0)[0], 0.5);
  EXPECT_DOUBLE_EQ(body.displacement(1.0)[0], 0.5);
  // The soil's force enters as any other: an upward 1098.1 N/m holds it still.
  body.begin_step(1.0, dt, Vec3{0.0, 1098.1, 0.0}, Vec3{0.0, -9.81, 0.0}, {});
  EXPECT_NEAR(body.velocity(1.0 + dt)[1], a, 1e-11);
}

// The column's plate under a load: P = 13 461.5 N/m, the force that compresses the column by
// eps = 1e-3 (M eps W with M = 13.46 MPa, W = 1 m), ramped in over 0.5 s and held.
std::string loaded_column(const std::string& mass) {
  return column(
      "{name: plate, polygon: [[-1, 2], [2, 2], [2, 3], [-1, 3]], surface: smooth, mass: " + mass +
      ", load: {y: {function: table, points: [[0, 0], [0.5, -13461.538461538461], "
      "[2, -13461.538461538461]]}}}");
}

TEST(RigidBody, ALoadedPlateSettlesByTheOedometricComplianceOfTheColumn) {
  // At rest the plate has settled P H / (M W) = 2 mm and the soil carries the load. The
  // lattice's static state alternates row to row by +-0.6 % (as above), hence 1.5 %. A plate of
  // 1 kg/m, far lighter than the row of soil under it (250 kg/m), is as stable as a heavy one:
  // the nodes its contact holds ride with it (eq. 9.17). Without them (measured) the 1 kg/m
  // plate fell through the column in its first steps, and one of 100 kg/m grew an oscillation
  // that ended at 5.9 times the settlement.
  for (const std::string mass : {"1", "10000"}) {
    std::string text = loaded_column(mass);
    text.replace(text.find("time: {end: 2.0}"), 16, "time: {end: 3.0}");
    Simulation simulation(read_case_text(text, "column.yaml"));
    // No node ends a step inside the plate by more than the contact tolerance, 0.02 dx (§9.18).
    double deepest = 0.0;
    while (simulation.state().step < simulation.total_steps()) {
      simulation.take_step();
      deepest = std::max(deepest, simulation.boundary_conditions().deepest_penetration());
    }
    EXPECT_LE(deepest, 0.02 * 0.25) << mass;
    const BoundaryConditions& conditions = simulation.boundary_conditions();
    const RigidBody& plate = conditions.rigid_bodies()[0];
    EXPECT_NEAR(plate.displacement(3.0)[1], -0.002, 0.015 * 0.002) << mass;
    // At rest: below 1 % of its speed during the ramp (the heavy plate's oscillation on the
    // column decays through the soil's damping only: 1.4e-5 m/s at 3 s).
    EXPECT_NEAR(plate.velocity(3.0)[1], 0.0, 0.01 * 0.004) << mass;
    EXPECT_NEAR(conditions.rigid_body_force(0)[1], 13461.538461538461, 1e-3 * 13461.5) << mass;
    // The soil under it follows it: the top row's settlement is the plate's.
    const FieldArray& u = simulation.state().displacement;
    for (std::size_t i = 0; i < simulation.nodes().sph_nodes.size(); ++i) {
      if (simulation.nodes().sph_nodes.position[1][i] != 2.0) continue;
      EXPECT_NEAR(u(1, i), plate.displacement(3.0)[1], 1e-3 * 0.002) << mass << " node " << i;
    }
  }
}

std::uint64_t bits_of(double value) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

TEST(RigidBody, ARestartWithALoadedBodyContinuesToTheBit) {
  // Checkpointed mid-ramp, with the cells formed again from the nodes: the body's motion and the
  // soil's force it moves by are carried through the formings and the checkpoint.
  std::string text = loaded_column("100");
  text.replace(text.find("numerics: {}"), 12,
               "numerics: {cells: {policy: reformed, reform_below: 1.0}}");
  const CaseDescription description = read_case_text(text, "column.yaml");
  Simulation original(description);
  for (int s = 0; s < 60; ++s)
    original.take_step();
  ASSERT_GT(original.assembly().cell_forming().formings, 1);
  const std::string bytes = encode_checkpoint(1, {{"simulation", &original}});
  Simulation restored(description);
  restore_checkpoint_parts(decode_checkpoint(bytes, "memory", 1), {{"simulation", &restored}});
  for (int s = 0; s < 60; ++s) {
    original.take_step();
    restored.take_step();
  }
  const double t = original.state().time;
  const RigidBody& a = original.boundary_conditions().rigid_bodies()[0];
  const RigidBody& b = restored.boundary_conditions().rigid_bodies()[0];
  EXPECT_LT(a.displacement(t)[1], -1e-5);  // it has moved
  EXPECT_EQ(bits_of(a.displacement(t)[1]), bits_of(b.displacement(t)[1]));
  EXPECT_EQ(bits_of(a.velocity(t)[1]), bits_of(b.velocity(t)[1]));
  const std::vector<double>& u = original.state().displacement.data();
  const std::vector<double>& v = restored.state().displacement.data();
  ASSERT_EQ(u.size(), v.size());
  for (std::size_t k = 0; k < u.size(); ++k)
    ASSERT_EQ(bits_of(u[k]), bits_of(v[k])) << k;
}

/// The input error reading `body` raises, or "" if it was accepted.
std::string body_error(const std::string& body) {
  try {
    read_case_text(column(body), "column.yaml");
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(RigidBody, ALoadWithoutMassOrOnAnImposedAxisAndAMassWithoutLoadAreRefused) {
  const std::string polygon = "name: plate, polygon: [[0, 2], [1, 2], [1, 3]]";
  std::string error = body_error("{" + polygon + ", load: {y: -1000}}");
  EXPECT_NE(error.find("column.yaml:"), std::string::npos) << error;
  EXPECT_NE(error.find("mass"), std::string::npos) << error;
  error = body_error("{" + polygon + ", mass: 10}");
  EXPECT_NE(error.find("column.yaml:"), std::string::npos) << error;
  EXPECT_NE(error.find("load"), std::string::npos) << error;
  error = body_error("{" + polygon + ", mass: 10, load: {y: -1000}, velocity: {y: -0.1}}");
  EXPECT_NE(error.find("column.yaml:"), std::string::npos) << error;
  EXPECT_NE(error.find("both imposed and loaded"), std::string::npos) << error;
  error = body_error("{" + polygon + ", mass: 0, load: {y: -1000}}");
  EXPECT_NE(error.find("mass"), std::string::npos) << error;
  EXPECT_EQ(body_error("{" + polygon + ", mass: 10, load: {y: -1000}, velocity: {x: 0}}"), "");
}

}  // namespace
}  // namespace rktsph::rigid_body_test
