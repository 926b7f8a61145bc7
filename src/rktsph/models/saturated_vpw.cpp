#include "rktsph/models/saturated_vpw.hpp"
#include "rktsph/core/parallel.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace rktsph {

SaturatedVpw::SaturatedVpw(Kinematics kinematics, std::vector<std::unique_ptr<Material>> materials,
                           Loads loads, SourceIntegration integration, PoreFluid fluid)
    : DrySolid(kinematics, std::move(materials), loads, integration, true),
      fluid_(fluid),
      internal_names_with_table_(DrySolid::internal_names()) {
  if (!fluid_.water_table) return;
  set_body_force_weights(DrySolid::internal_count());
  internal_names_with_table_.emplace_back("gravity_weight");
  if (dimension() == 2) internal_names_with_table_.emplace_back("seepage_weight");
}

double SaturatedVpw::hydrostatic_pore_pressure(std::size_t node, double time) const {
  if (hydrostatic_at_full_gravity_.empty()) return 0.0;
  return loads().gravity_factor(time) * hydrostatic_at_full_gravity_[node];
}

std::array<double, 2> SaturatedVpw::body_force_weights(std::int32_t material, double x,
                                                       double y) const {
  // Below the table -alpha grad p_h = alpha rho_w (g_y y_w'(x), -g_y) per unit volume, so the
  // vertical weight is (rho - alpha rho_w)/rho (buoyancy) and the seepage weight
  // s = alpha rho_w y_w'/rho multiplies g_y along x; above it the soil weighs rho_above (eq. 6.8).
  const double density = this->material(material).density();
  const double alpha = fluid_.biot_coefficient, water = fluid_.fluid_density;
  const WaterTable& table = *fluid_.water_table;
  if (table.depth_below(x, y) > 0.0)
    return {(density - alpha * water) / density, alpha * water * table.slope(x) / density};
  return {table.density_above(density, fluid_.porosity, water) / density, 0.0};
}

void SaturatedVpw::place_water_table(const PointCloud& sph_nodes,
                                     std::span<const std::int32_t> node_material,
                                     std::span<const std::array<double, 2>> spans,
                                     FieldArray& internal) {
  if (!fluid_.water_table) return;
  const int d = dimension();
  const std::size_t n = node_material.size();
  const int weight = DrySolid::internal_count();
  // p_h = rho_w |g_y| (y_w - y)^+ (eq. 6.6); the factor of the gravity ramp is applied in time.
  const double gravity = std::abs(loads().gravity[static_cast<std::size_t>(d - 1)]);
  hydrostatic_at_full_gravity_.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = d == 2 ? sph_nodes.position[0][i] : 0.0;
    const double y = sph_nodes.position[static_cast<std::size_t>(d - 1)][i];
    hydrostatic_at_full_gravity_[i] =
        fluid_.fluid_density * gravity * fluid_.water_table->depth_below(x, y);
    // The weights are the mean over the soil the node stands for, so that the weight of every
    // lattice row is exact wherever the table cuts the rows (a node on the table inside the body
    // is half wet, half dry; one on the table at the top surface is wet).
    const double table = fluid_.water_table->height(x);
    const double low = spans[i][0], high = spans[i][1];
    const double wet_fraction =
        high > low ? std::clamp((table - low) / (high - low), 0.0, 1.0) : (y < table ? 1.0 : 0.0);
    const std::array<double, 2> wet = body_force_weights(node_material[i], x, table - 1.0);
    const std::array<double, 2> dry = body_force_weights(node_material[i], x, table + 1.0);
    for (int k = 0; k < (d == 2 ? 2 : 1); ++k)
      internal(weight + k, i) = wet_fraction * wet[static_cast<std::size_t>(k)] +
                                (1.0 - wet_fraction) * dry[static_cast<std::size_t>(k)];
  }
}

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
