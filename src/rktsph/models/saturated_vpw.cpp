#include "rktsph/models/saturated_vpw.hpp"
#include "rktsph/core/parallel.hpp"

#include <algorithm>
#include <array>

namespace rktsph {

SaturatedVpw::SaturatedVpw(Kinematics kinematics, std::vector<std::unique_ptr<Material>> materials,
                           Loads loads, SourceIntegration integration, PoreFluid fluid)
    : DrySolid(kinematics, std::move(materials), loads, integration, true), fluid_(fluid) {}

double SaturatedVpw::divergence_bound(int field) const {
  if (field != pore_pressure_field()) return DrySolid::divergence_bound(field);
  // The undrained (Biot) modulus bounds the pressure of any physical volumetric strain.
  return 10.0 * (DrySolid::divergence_bound(dimension()) / 10.0 +
                 fluid_.biot_coefficient * fluid_.biot_coefficient / fluid_.storage);
}

void SaturatedVpw::flux_rate(std::span<const std::int32_t> material, const FieldArray& gradient,
                             FieldArray& rate) const {
  DrySolid::flux_rate(material, gradient, rate);  // reads and writes only the dry fields
  const auto n = static_cast<std::int64_t>(material.size());
  const int d = dimension();
  const int pw = pore_pressure_field();
  std::array<int, 3> pressure_gradient{};
  for (int a = 0; a < d; ++a)
    pressure_gradient[static_cast<std::size_t>(a)] = layout().gradient(pw, a);
  const double alpha = fluid_.biot_coefficient;
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
  for (std::int64_t i = 0; i < n; ++i) {
    const double density = this->material(material[i]).density();
    for (int a = 0; a < d; ++a)
      rate.field(layout().velocity(a))[i] -=
          alpha * gradient.field(pressure_gradient[static_cast<std::size_t>(a)])[i] /
          density;            // eq. 6.1
    rate.field(pw)[i] = 0.0;  // frozen in the pass; the projection advances it
  }
}

}  // namespace rktsph
