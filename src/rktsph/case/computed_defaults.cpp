#include "rktsph/case/computed_defaults.hpp"

#include <cmath>

#include "rktsph/sph/kernel.hpp"
#include "rktsph/sph/laplacian.hpp"

namespace rktsph {

StressUpdate default_stress_update(int dimension) {
  return dimension >= 2 ? StressUpdate::MeanVelocity : StressUpdate::HalfStep;
}

bool has_wide_stencils(const NumericsSpec& numerics, int dimension) {
  const Kernel kernel(numerics.kernel, dimension);
  const double nearest_other_node = std::sqrt(2.25 + 0.25 * (dimension - 1));  // in spacings
  return kernel.support_radius(numerics.h_over_dx) > nearest_other_node;
}

HourglassFields default_hourglass_fields(const NumericsSpec& numerics, int dimension) {
  return has_wide_stencils(numerics, dimension) ? HourglassFields::All : HourglassFields::Velocity;
}

double default_laplacian_scale(const CaseDescription& description) {
  // On triangles the pressure solve takes the cells' P1 Laplacian, consistent as it is (docs/
  // theory.md eq. 6.6): a factor other than 1 would make L(|x|^2) differ from 2d.
  if (description.geometry.cells == CellLayout::Triangles && description.dimension >= 2) return 1.0;
  // The arguments the pressure projection gives build_laplacian (time/rk_taylor_step.cpp,
  // step_operator_options), so that the value is the same to the last bit.
  const double spacing = description.geometry.spacing;
  const Kernel kernel(description.numerics.kernel, description.dimension);
  return laplacian_consistency_scale(kernel, description.numerics.h_over_dx * spacing, spacing,
                                     description.dimension);
}

}  // namespace rktsph
