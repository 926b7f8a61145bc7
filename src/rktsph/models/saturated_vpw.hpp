// V3 "saturated soil", v-pw form (docs/theory.md §6): the dry solid on the effective stress plus
// the pore pressure p_w (positive in compression), which the RK-TSPH pass carries frozen:
//   rho dv/dt = div sigma' - alpha grad p_w + rho b - rho xi v        (6.1)
// p_w itself is advanced by the pressure projection (models/pressure_projection.hpp).
// With a water table (docs/theory.md §6.8) the carried p_w is the excess over the hydrostatic
// pressure p_h, whose gradient enters (6.1) in closed form as a weight on the body force.
#pragma once

#include <optional>

#include "rktsph/models/dry_solid.hpp"
#include "rktsph/physics/water_table.hpp"

namespace rktsph {

/// Pore-water constants of the mixture (docs/theory.md §6.1).
struct PoreFluid {
  double biot_coefficient = 1.0;          ///< alpha
  double storage = 0.0;                   ///< 1/Q = n/K_w [1/Pa] (incompressible grains)
  double permeability = 0.0;              ///< k_bar = k / (rho_w g) [m^3 s/kg]
  double fluid_density = 1000.0;          ///< rho_w
  double porosity = 0.3;                  ///< n, for the density of the soil above a water table
  std::optional<WaterTable> water_table;  ///< none: fully saturated, p_w the excess only
};

class SaturatedVpw final : public DrySolid {
 public:
  SaturatedVpw(Kinematics kinematics, std::vector<std::unique_ptr<Material>> materials, Loads loads,
               SourceIntegration integration, PoreFluid fluid);

  double biot_coefficient() const override { return fluid_.biot_coefficient; }
  double divergence_bound(int field) const override;

  void flux_rate(std::span<const std::int32_t> material, const FieldArray& gradient,
                 FieldArray& rate) const override;

  const PoreFluid& fluid() const { return fluid_; }

  // The water table (docs/theory.md §6.8). Its internal variables follow the materials': the
  // body-force weights w (vertical) and, in 2D, s (seepage along x) of eq. 6.8.
  int internal_count() const override {
    return static_cast<int>(internal_names_with_table_.size());
  }
  const std::vector<std::string>& internal_names() const override {
    return internal_names_with_table_;
  }
  double hydrostatic_pore_pressure(std::size_t node, double time) const override;
  /// Places the SPH nodes against the water table: p_h of each (eq. 6.6, at full gravity) and
  /// its body-force weights (eq. 6.8), the mean over the node's vertical span [low, high] (the
  /// heights of the soil it stands for), in `internal`. Nothing without a water table.
  void place_water_table(const PointCloud& sph_nodes, std::span<const std::int32_t> node_material,
                         std::span<const std::array<double, 2>> spans, FieldArray& internal);
  /// The soil's weights at (x, y) of material m: {w, s} of eq. 6.8.
  std::array<double, 2> body_force_weights(std::int32_t material, double x, double y) const;
  const WaterTable* water_table() const override {
    return fluid_.water_table ? &*fluid_.water_table : nullptr;
  }

 private:
  PoreFluid fluid_;
  std::vector<std::string> internal_names_with_table_;
  std::vector<double> hydrostatic_at_full_gravity_;  // p_h of each SPH node at factor 1 [Pa]
};

}  // namespace rktsph
