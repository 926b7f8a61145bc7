// The typed, validated description of one case, as read from a case file (YAML).
//
// Everything here is in SI units: m, s, kg, Pa, m/s. Stress is positive in tension; pore pressure
// positive in compression. Every item keeps the SourceLocation of the key it came from so that
// later stages (geometry, materials, boundary conditions) can report errors at the right line.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rktsph/core/error.hpp"
#include "rktsph/core/small_tensor.hpp"
#include "rktsph/core/step_choices.hpp"
#include "rktsph/core/time_function.hpp"
#include "rktsph/linear_algebra/preconditioner.hpp"
#include "rktsph/sph/kernel_type.hpp"

namespace rktsph {

/// "dry_solid" (V1), "dry_large_deformation" (V2), "saturated_vpw" (V3)
enum class ModelKind { DrySolid, DryLargeDeformation, SaturatedVpw };
enum class PlaneKind { Strain, Stress };  // 2D only; 1D is always the uniaxial bar

/// A scalar parameter with the place it was written, for material blocks whose keys are
/// validated by the material itself (each material knows its own parameters).
struct Parameter {
  double value = 0.0;
  SourceLocation where;
};

/// Parameters of a block, by key. `where` is the location of the block itself.
struct ParameterBlock {
  std::string path;  ///< dotted key path of the block, e.g. "materials.soil"
  SourceLocation where;
  std::map<std::string, Parameter> values;
  /// Non-numeric entries (e.g. "model: perzyna_von_mises"), by key.
  std::map<std::string, std::pair<std::string, SourceLocation>> words;
};

struct ShapeSpec {
  enum class Kind { Segment, Rectangle, Polygon };
  Kind kind = Kind::Segment;
  /// Segment: {from, to} in x. Rectangle: {min, max}. Polygon: vertices in order (either sense).
  std::vector<Vec3> vertices;
  std::string material;  ///< name of an entry of `materials`
  SourceLocation where;
};

/// How the shapes are cut into cells (docs/theory.md §3.1 and §3.6).
enum class CellLayout {
  Lattice,    ///< a square lattice of spacing dx; shape vertices on lattice points
  Triangles,  ///< a constrained Delaunay triangle mesh, edges at most dx; 2D only
};

/// Which cells a large-deformation model integrates over as its nodes move (docs/theory.md
/// §9.17): those of the start, moved with the nodes, or cells formed again from the nodes.
enum class CellPolicy {
  Moving,    ///< the cells of the start, their corners moved with the nodes (§9.1)
  Reformed,  ///< Delaunay cells of the current nodes, formed again when one distorts (§9.17)
};

struct GeometrySpec {
  /// Lattice spacing dx, or the triangles' longest edge [m], > 0; with `mesh`, the mesh's longest
  /// edge, set when the mesh is read (0 until then).
  double spacing = 0.0;
  CellLayout cells = CellLayout::Lattice;
  /// Shapes fill one common lattice (or mesh); where shapes overlap, the later shape's material
  /// wins (so a small shape after a large one makes a weak zone). Empty with `mesh`.
  std::vector<ShapeSpec> shapes;
  /// A Gmsh mesh file instead of shapes (docs/theory.md §3.8): its path, relative paths resolved
  /// against the case file's folder; empty with shapes.
  std::string mesh;
  SourceLocation mesh_where;  ///< of the `mesh` key
  SourceLocation where;
};

struct GroupSpec {
  enum class Kind { Edge, Box, Polygon, Point, Physical, All };
  std::string name;
  Kind kind = Kind::All;
  std::string edge;   ///< Edge: "xmin", "xmax", "ymin" or "ymax" of the body's bounding box
  Vec3 min{}, max{};  ///< Box (inclusive, with a tolerance of 1e-6 dx)
  std::vector<Vec3> vertices;  ///< Polygon (boundary included)
  Vec3 point{};                ///< Point: the node nearest to it
  std::string physical;        ///< Physical: a physical group's name in the mesh file
  SourceLocation where;
};

struct BoundaryConditionSpec {
  enum class Kind {
    Velocity,      ///< imposed velocity components (those given), others free
    Fixed,         ///< v = 0 (rough rigid wall)
    Roller,        ///< v_n = 0, sigma_nt = 0 (smooth wall, = symmetry plane), mirror images
    Traction,      ///< imposed traction components on the face (those given), others zero
    PorePressure,  ///< drained face: prescribed excess pore pressure (saturated model only)
    Rotation,      ///< both velocity components of a rigid rotation about `centre` (2D only)
    RigidWall,     ///< contact with a fixed plane: no penetration; rough (no slip) or smooth
    RigidBody,     ///< contact with a rigid polygon at an imposed velocity or load (2D)
  };
  Kind kind = Kind::Velocity;
  std::string group;
  std::array<std::optional<TimeFunction>, 3> velocity;  ///< Velocity: per component [m/s]
  std::array<std::optional<TimeFunction>, 3> traction;  ///< Traction: per component [Pa]
  std::optional<TimeFunction> pore_pressure;            ///< PorePressure [Pa]
  int axis = 0;        ///< Roller: axis of the normal (0 = x, 1 = y)
  bool mirror = true;  ///< Roller: fold mirror images into the operators (docs/theory.md §4.5)
  double angular_velocity = 0.0;   ///< Rotation: omega [rad/s], counter-clockwise positive, != 0
  Vec3 centre{};                   ///< Rotation: the fixed point [m]
  Vec3 wall_point{};               ///< RigidWall: a point of the plane [m]
  Vec3 wall_normal{};              ///< RigidWall: its normal, pointing into the body (any length)
  bool wall_rough = true;          ///< RigidWall, RigidBody: no slip while in contact (else free)
  std::string body_name;           ///< RigidBody: its name in probes.csv and summary.json
  std::vector<Vec3> body_polygon;  ///< RigidBody: its outline at t = 0 [m] (simple, 3+ vertices)
  std::array<std::optional<TimeFunction>, 3> body_velocity;  ///< RigidBody: per axis [m/s]
  /// RigidBody: the force on it besides the soil's, per axis not in body_velocity [N/m]
  std::array<std::optional<TimeFunction>, 3> body_load;
  std::optional<double> body_mass;      ///< RigidBody with a load: its mass [kg/m]
  std::optional<double> body_friction;  ///< RigidBody: Coulomb coefficient (replaces `surface`)
  SourceLocation where;
};

struct GravitySpec {
  Vec3 acceleration{};                                ///< [m/s^2], e.g. (0, -9.81)
  TimeFunction factor = TimeFunction::constant(1.0);  ///< dimensionless ramp (docs/theory.md §1.2)
  SourceLocation where;
};

struct DampingSpec {
  double coefficient = 0.0;  ///< xi [1/s], momentum source -xi v
  double start = 0.0;        ///< [s]
  double end = 1e300;        ///< [s], exclusive
  SourceLocation where;
};

/// An initial rigid rotation, omega e_z x (X - centre), added to the initial velocity (2D).
struct InitialRotationSpec {
  double rate = 0.0;  ///< omega [rad/s], counter-clockwise positive
  Vec3 centre{};      ///< [m]
  SourceLocation where;
};

/// The first bending mode of a cantilever along x clamped at x = root, as an initial transverse
/// velocity v_y(x) (2D).
struct BendingModeSpec {
  double root = 0.0;          ///< x of the clamped root [m]
  double length = 0.0;        ///< L [m], > 0
  double tip_velocity = 0.0;  ///< v_y at x = root + L [m/s]
  SourceLocation where;
};

struct InitialConditionsSpec {
  Vec3 velocity{};                          ///< uniform initial velocity [m/s]
  std::optional<double> geostatic_surface;  ///< y of the free surface [m] for geostatic stress
  std::optional<double> k0;                 ///< sigma_h / sigma_v; default nu/(1-nu)
  /// Uniform stress [Pa] added to every node, by component ("xx", "yy", "xy", "zz"); each keeps
  /// its line, since whether the model carries it is known only once the model is built.
  std::map<std::string, Parameter> stress;
  std::optional<InitialRotationSpec> angular_velocity;
  std::optional<BendingModeSpec> bending_mode;
  SourceLocation where;
};

/// The case file's word for each preconditioner (`pore_fluid.preconditioner`), in documented order;
/// summary.json reports the same words.
inline const std::vector<std::pair<std::string, PressurePreconditioner>>& preconditioner_words() {
  static const std::vector<std::pair<std::string, PressurePreconditioner>> words = {
      {"multigrid", PressurePreconditioner::Multigrid},
      {"jacobi", PressurePreconditioner::Jacobi},
      {"incomplete_cholesky", PressurePreconditioner::IncompleteCholesky}};
  return words;
}

/// A phreatic surface of the saturated model (docs/theory.md §6.8): a level, or a polyline of
/// the surface's height y_w(x), held constant beyond its end vertices. Below it the pore water is
/// hydrostatic, above it the soil is drained and weighs `density_above`.
struct WaterTableSpec {
  std::optional<double> level;                  ///< y_w of a horizontal table [m]
  std::vector<std::array<double, 2>> polyline;  ///< (x, y_w) vertices, x increasing (2D) [m]
  /// Mass density of the soil above the table [kg/m^3]; unset: rho - n rho_w of each material.
  std::optional<double> density_above;
  SourceLocation where;
};

/// Pore water and the pressure solve of the saturated v-pw model (docs/theory.md §6).
struct PoreFluidSpec {
  double bulk_modulus = 2.2e9;          ///< K_w [Pa]
  double density = 1000.0;              ///< rho_w [kg/m^3]
  double porosity = 0.3;                ///< n [-]
  double hydraulic_conductivity = 0.0;  ///< Darcy k [m/s]; k_bar = k / (rho_w g)
  double gravity = 9.81;                ///< g [m/s^2] of the conversion k -> k_bar
  double biot_coefficient = 1.0;        ///< alpha
  double projection_beta = 1.0;         ///< incremental projection (1) or not (0)
  PressurePreconditioner preconditioner = PressurePreconditioner::Multigrid;
  double solver_tolerance = 1e-8;             ///< relative residual of the conjugate gradient
  long solver_max_iterations = 0;             ///< 0: twice the number of nodes
  double laplacian_scale = 0.0;               ///< 0: computed so that L(|x|^2) = 2d in the interior
  double checkerboard_stabilisation = 0.0;    ///< theta of the p_w checkerboard term (theory §6.6)
  std::optional<WaterTableSpec> water_table;  ///< none: fully saturated, p_w the excess only
  SourceLocation where;
};

/// epsilon of the cells' hourglass stiffness when the case does not set it (docs/theory.md §3.4):
/// in cells of elastic materials, and of viscoplastic ones, where it must not resist a shear band.
inline constexpr double kDefaultHourglassStiffness = 1.0;
inline constexpr double kDefaultViscoplasticHourglassStiffness = 0.05;
/// beta of the patch strain stiffness (docs/theory.md eq. 3.12) on triangle meshes when the case
/// does not set it; 0 on a lattice, whose quadrilaterals the cells' hourglass stiffness controls.
inline constexpr double kDefaultTrianglePatchStiffness = 0.03;

struct NumericsSpec {
  KernelType kernel = KernelType::CubicSpline;
  double h_over_dx = 0.75;          ///< docs/theory.md §4.1
  int interpolation_order = 0;      ///< 0 = Shepard, 1 = (d+1) system
  double courant = 0.5;             ///< C in dt = C dx / c_p
  std::optional<double> time_step;  ///< fixed dt [s] overriding the Courant rule
  bool frozen_flux_source = true;   ///< docs/theory.md §2.8; false = additive
  double rk_substep_factor = 0.5;   ///< m = ceil(tau * lambda_src / factor), docs/theory.md §2.1
  int rk_max_substeps = 1000;
  bool hourglass_filter = true;  ///< docs/theory.md §3.3, default on in 2D, ignored in 1D
  double hourglass_kappa = 0.1;
  double hourglass_h_over_dx = 1.3;
  double neighbour_search_distance = 0.1;  ///< over dx, moving configurations (theory §9.5)
  std::optional<HourglassFields> hourglass_fields;  ///< unset: from the stencil width
  /// unset: MeanVelocity in 2D, HalfStep in 1D (docs/theory.md §2.2)
  std::optional<StressUpdate> stress_update;
  /// epsilon of the cells' hourglass stiffness (docs/theory.md eqs. 3.3, 3.9); unset:
  /// kDefaultHourglassStiffness with the mean-velocity update in 2D, else 0 (off)
  std::optional<double> hourglass_stiffness;
  /// psi of eq. 3.9: the fraction of the stiffness that acts in cells in viscoplastic flow
  double hourglass_plastic_fraction = 0.0;
  /// epsilon_s of the strain hourglass stiffness (theory eq. 3.5), at most (1 - C^2)/C^2; 0 = off
  double strain_hourglass_stiffness = 0.0;
  /// beta of the patch strain stiffness (theory eq. 3.12); unset: kDefaultTrianglePatchStiffness
  /// on triangles, 0 (off) on a lattice
  std::optional<double> patch_stiffness;
  double artificial_viscosity = 0.0;  ///< alpha of docs/theory.md §2.7, 0 = off
  /// numerics.cells (docs/theory.md §9.17): the cells of a moving configuration.
  CellPolicy cell_policy = CellPolicy::Moving;
  double reform_alpha = 1.0;         ///< alpha of eq. 3.15 when cells are formed again
  double reform_corner_ratio = 0.5;  ///< a cell's corner Jacobian over its formation one below
  double spread_below = 0.0;         ///< crowded nodes spread before a forming (eq. 9.16); 0: never
                                     ///< which the cells are formed again
  SourceLocation where;
};

struct TimeSpec {
  double end = 0.0;  ///< [s], > 0
  long max_steps = 100000000;
  /// Ends the run once the largest speed stays at or below this fraction of its peak for one
  /// P-wave transit of the body (docs/theory.md §2.6); unset: the run goes to `end`.
  std::optional<double> stop_when_at_rest;
  SourceLocation where;
};

struct OutputSpec {
  double interval = 0.0;        ///< field (VTU) output every `interval` s; 0 = first and last only
  double probe_interval = 0.0;  ///< probes every `probe_interval` s; 0 = every step
  double checkpoint_interval = 0.0;  ///< checkpoint.bin every `checkpoint_interval` s; 0 = none
  std::vector<std::string> fields;   ///< empty = all fields of the model
  SourceLocation where;
};

struct ProbeSpec {
  enum class Reduction { Mean, Min, Max, MaxAbs };
  std::string name;
  std::string group;
  std::vector<std::string> fields;  ///< e.g. "velocity_x", "stress_xx", "pore_pressure"
  Reduction reduction = Reduction::Mean;
  SourceLocation where;
  std::string path;                         ///< "probes.<index>", for error messages
  std::vector<SourceLocation> field_where;  ///< of each field (its line, or its --set argument)
};

struct CaseDescription {
  std::string name;
  std::string description;
  std::string file;  ///< path of the case file it was read from
  ModelKind model = ModelKind::DrySolid;
  int dimension = 1;
  PlaneKind plane = PlaneKind::Strain;
  GeometrySpec geometry;
  std::map<std::string, ParameterBlock> materials;
  std::vector<GroupSpec> groups;
  std::vector<BoundaryConditionSpec> boundary_conditions;
  std::optional<GravitySpec> gravity;
  std::optional<DampingSpec> damping;
  std::optional<PoreFluidSpec> pore_fluid;  ///< required for the saturated model
  InitialConditionsSpec initial;
  NumericsSpec numerics;
  TimeSpec time;
  OutputSpec output;
  std::vector<ProbeSpec> probes;
};

}  // namespace rktsph
