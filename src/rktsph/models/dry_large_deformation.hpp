// V2 "dry solid, large deformation": the dry solid of V1 (docs/theory.md §1.2) on the moving
// configuration, updated Lagrangian (docs/theory.md §9):
//   rho dv/dt = div sigma + rho b - rho xi v          (rho = rho_0 V_0 / V, the current density)
//   dsigma/dt = D^e : (sym grad v - eps_dot^vp) + W sigma - sigma W   (Jaumann, W = skw grad v)
// with every derivative on the current configuration. The flux rate and sources are V1's; the
// step adds the corotational terms as an incremental rotation (rotate_stress) and the motion.
#pragma once

#include "rktsph/models/dry_solid.hpp"

namespace rktsph {

class DryLargeDeformation final : public DrySolid {
 public:
  DryLargeDeformation(Kinematics kinematics, std::vector<std::unique_ptr<Material>> materials,
                      Loads loads, SourceIntegration integration);

  bool objective_stress_rate() const override { return true; }
  void rotate_stress(const FieldArray& gradient, std::span<const int> velocity_gradient,
                     double interval, std::size_t count, FieldArray& values) const override;
};

}  // namespace rktsph
