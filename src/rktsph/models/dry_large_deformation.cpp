#include "rktsph/models/dry_large_deformation.hpp"

#include <cstdint>

#include "rktsph/core/parallel.hpp"
#include "rktsph/physics/kinematics/objective_rate.hpp"

namespace rktsph {

DryLargeDeformation::DryLargeDeformation(Kinematics kinematics,
                                         std::vector<std::unique_ptr<Material>> materials,
                                         Loads loads, SourceIntegration integration)
    : DrySolid(kinematics, std::move(materials), std::move(loads), integration) {}

void DryLargeDeformation::rotate_stress(const FieldArray& gradient,
                                        std::span<const int> velocity_gradient, double interval,
                                        std::size_t count, FieldArray& values) const {
  // A bar has no spin; in the plane only W_xy is non-zero, and sigma_zz (plane strain) is
  // unchanged by an in-plane rotation (docs/theory.md eq. 9.2).
  if (dimension() != 2) return;
  const double* dvx_dy = gradient.field(velocity_gradient[1]);
  const double* dvy_dx = gradient.field(velocity_gradient[2]);
  double* xx = values.field(stress_field(0, 0));
  double* yy = values.field(stress_field(1, 1));
  double* xy = values.field(stress_field(0, 1));
  const auto n = static_cast<std::int64_t>(count);
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
  for (std::int64_t i = 0; i < n; ++i) {
    const PlaneRotation q = hughes_winget_rotation(0.5 * (dvx_dy[i] - dvy_dx[i]), interval);
    rotate_plane_stress(q, xx[i], yy[i], xy[i]);
  }
}

}  // namespace rktsph
