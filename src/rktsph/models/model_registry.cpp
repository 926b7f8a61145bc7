#include "rktsph/models/model_registry.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "rktsph/models/dry_large_deformation.hpp"
#include "rktsph/models/dry_solid.hpp"
#include "rktsph/models/pressure_projection.hpp"
#include "rktsph/models/saturated_vpw.hpp"

namespace rktsph {

namespace {

Kinematics kinematics_of(const CaseDescription& description) {
  if (description.dimension == 1) return Kinematics::Bar1D;
  return description.plane == PlaneKind::Strain ? Kinematics::PlaneStrain : Kinematics::PlaneStress;
}

Loads loads_of(const CaseDescription& description) {
  Loads loads;
  if (description.gravity) {
    loads.gravity = description.gravity->acceleration;
    loads.gravity_factor = description.gravity->factor;
  }
  if (description.damping) {
    loads.damping = description.damping->coefficient;
    loads.damping_start = description.damping->start;
    loads.damping_end = description.damping->end;
  }
  return loads;
}

SourceIntegration integration_of(const NumericsSpec& numerics) {
  return {numerics.rk_substep_factor, numerics.rk_max_substeps, numerics.frozen_flux_source};
}

std::unique_ptr<PhysicsModel> create_dry_solid(const CaseDescription& description,
                                               std::vector<std::unique_ptr<Material>> materials) {
  return std::make_unique<DrySolid>(kinematics_of(description), std::move(materials),
                                    loads_of(description), integration_of(description.numerics));
}

std::unique_ptr<PhysicsModel> create_dry_large_deformation(
    const CaseDescription& description, std::vector<std::unique_ptr<Material>> materials) {
  return std::make_unique<DryLargeDeformation>(kinematics_of(description), std::move(materials),
                                               loads_of(description),
                                               integration_of(description.numerics));
}

// A water table is a level surface of the hydrostatic pore pressure under gravity along -y (-x
// in 1D), the vertical axis of its heights (docs/theory.md §6.8).
void check_water_table_gravity(const CaseDescription& description) {
  const int d = description.dimension;
  const WaterTableSpec& table = *description.pore_fluid->water_table;
  const Vec3 g = description.gravity ? description.gravity->acceleration : Vec3{};
  bool vertical = g[static_cast<std::size_t>(d - 1)] < 0.0;
  for (int a = 0; a < d - 1; ++a)
    vertical = vertical && g[static_cast<std::size_t>(a)] == 0.0;
  if (!vertical)
    throw InputError(
        table.where, "pore_fluid.water_table",
        description.gravity ? fmt::format("gravity ({}, {})", g[0], g[1]) : "no gravity",
        "a water table needs gravity along the vertical axis, downward",
        d == 2 ? "loads.gravity.acceleration: [0, -g]" : "loads.gravity.acceleration: -g");
}

std::unique_ptr<PhysicsModel> create_saturated_vpw(
    const CaseDescription& description, std::vector<std::unique_ptr<Material>> materials) {
  const PoreFluidSpec& fluid = *description.pore_fluid;
  // 1/Q = n/K_w (incompressible grains), k_bar = k/(rho_w g) (docs/theory.md §6.1).
  PoreFluid pore{fluid.biot_coefficient,
                 fluid.porosity / fluid.bulk_modulus,
                 fluid.hydraulic_conductivity / (fluid.density * fluid.gravity),
                 fluid.density,
                 fluid.porosity,
                 std::nullopt};
  if (const auto& table = fluid.water_table) {
    check_water_table_gravity(description);
    pore.water_table = table->level ? WaterTable::level(*table->level, table->density_above)
                                    : WaterTable::polyline(table->polyline, table->density_above);
  }
  return std::make_unique<SaturatedVpw>(kinematics_of(description), std::move(materials),
                                        loads_of(description), integration_of(description.numerics),
                                        pore);
}

std::unique_ptr<StepProjection> create_pressure_projection(
    const PhysicsModel& model, const NodeSets& nodes, const OperatorOptions& options,
    const BoundaryConditions& conditions, const CaseDescription& description, double dt) {
  const PoreFluidSpec& fluid = *description.pore_fluid;
  const PressureSolveOptions solve{fluid.projection_beta,       fluid.solver_tolerance,
                                   fluid.solver_max_iterations, fluid.preconditioner,
                                   fluid.laplacian_scale,       fluid.checkerboard_stabilisation};
  return std::make_unique<PressureProjection>(static_cast<const SaturatedVpw&>(model), nodes,
                                              options, conditions, solve, dt);
}

}  // namespace

const std::vector<RegisteredModel>& registered_models() {
  static const std::vector<RegisteredModel> models = {
      {ModelKind::DrySolid, OperatorPolicy::ReferenceConfiguration, create_dry_solid, nullptr},
      {ModelKind::DryLargeDeformation, OperatorPolicy::CurrentConfiguration,
       create_dry_large_deformation, nullptr},
      {ModelKind::SaturatedVpw, OperatorPolicy::ReferenceConfiguration, create_saturated_vpw,
       create_pressure_projection},
  };
  return models;
}

const RegisteredModel& registered_model(ModelKind kind) {
  for (const RegisteredModel& model : registered_models())
    if (model.kind == kind) return model;
  throw std::logic_error("registered_model: a ModelKind without an entry");
}

}  // namespace rktsph
