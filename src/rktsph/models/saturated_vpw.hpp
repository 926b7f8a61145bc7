// V3 "saturated soil", v-pw form (docs/theory.md §6): the dry solid on the effective stress plus
// the pore pressure p_w (positive in compression), which the RK-TSPH pass carries frozen:
//   rho dv/dt = div sigma' - alpha grad p_w + rho b - rho xi v        (6.1)
// p_w itself is advanced by the pressure projection (models/pressure_projection.hpp).
#pragma once

#include "rktsph/models/dry_solid.hpp"

namespace rktsph {

/// Pore-water constants of the mixture (docs/theory.md §6.1).
struct PoreFluid {
  double biot_coefficient = 1.0;  ///< alpha
  double storage = 0.0;           ///< 1/Q = n/K_w [1/Pa] (incompressible grains)
  double permeability = 0.0;      ///< k_bar = k / (rho_w g) [m^3 s/kg]
  double fluid_density = 1000.0;  ///< rho_w
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

 private:
  PoreFluid fluid_;
};

}  // namespace rktsph
