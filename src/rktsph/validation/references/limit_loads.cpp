#include "rktsph/validation/references/limit_loads.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rktsph/validation/references/elastic_moduli.hpp"

namespace rktsph::references {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

}  // namespace

double von_mises_plane_strain_cohesion(double yield_stress) {
  return yield_stress / std::numbers::sqrt3;
}

double taylor_critical_height(double cohesion, double unit_weight) {
  return kTaylorVerticalCutStabilityNumber * cohesion / unit_weight;
}

double culmann_critical_height(double cohesion, double unit_weight) {
  return kCulmannVerticalCutStabilityNumber * cohesion / unit_weight;
}

double footing_on_cut_limit_pressure(double cohesion) {
  return 2.0 * cohesion;
}

double footing_on_cut_wedge_pressure(double cohesion, double unit_weight, double footing_width,
                                     double wedge_angle_deg) {
  // The wedge (top width B) slides at speed V down a plane of length B/cos θ: the dissipation
  // c·V·B/cos θ, divided by the vertical speed V sin θ and by B, gives 2c/sin 2θ; the wedge
  // weight γB² tan θ/2 moves down with it and does work for the load.
  const double angle = wedge_angle_deg * kDegree;
  return 2.0 * cohesion / std::sin(2.0 * angle) -
         0.5 * unit_weight * footing_width * std::tan(angle);
}

double footing_on_cut_45_degree_wedge(double cohesion, double unit_weight, double footing_width) {
  return footing_on_cut_wedge_pressure(cohesion, unit_weight, footing_width, 45.0);
}

WedgeBound footing_on_cut_optimal_wedge(double cohesion, double unit_weight, double footing_width,
                                        double cut_height) {
  // −γB tanθ/2 can make the bound fall again towards 90°, so it is not known to be unimodal on
  // the whole interval: a uniform scan finds the best sample, and a golden-section search refines
  // it between that sample's neighbours.
  const double upper = std::atan(cut_height / footing_width) / kDegree;
  auto pressure = [&](double angle) {
    return footing_on_cut_wedge_pressure(cohesion, unit_weight, footing_width, angle);
  };
  constexpr int kSamples = 1000;
  int best = 1;
  for (int i = 2; i <= kSamples; ++i) {
    if (pressure(upper * i / kSamples) < pressure(upper * best / kSamples)) best = i;
  }
  double low = upper * (best - 1) / kSamples;
  double high = upper * std::min(best + 1, kSamples) / kSamples;
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  double left = high - ratio * (high - low);
  double right = low + ratio * (high - low);
  double left_value = pressure(left);
  double right_value = pressure(right);
  for (int iteration = 0; iteration < 200 && high - low > 1e-10; ++iteration) {
    if (left_value <= right_value) {
      high = right;
      right = left;
      right_value = left_value;
      left = high - ratio * (high - low);
      left_value = pressure(left);
    } else {
      low = left;
      left = right;
      left_value = right_value;
      right = low + ratio * (high - low);
      right_value = pressure(right);
    }
  }
  const double angle = 0.5 * (low + high);
  return WedgeBound{pressure(angle), angle};
}

double prandtl_bearing_capacity(double cohesion, double surcharge) {
  return (2.0 + std::numbers::pi) * cohesion + surcharge;
}

double thin_layer_bearing_factor_upper_bound(double footing_width, double layer_depth) {
  return 2.0 + 2.0 * std::numbers::sqrt2 + footing_width / (2.0 * layer_depth) +
         layer_depth / footing_width;
}

double j2_plane_strain_band_angle_deg() {
  return 45.0;
}

double j2_first_yield_band_angle_deg(double poisson_ratio) {
  // Deviator of (σ_x, σ_y, σ_z) = (0, −1, −ν): the scale S cancels in N.
  const double mean = -(1.0 + poisson_ratio) / 3.0;
  const double s_x = -mean;
  const double s_y = -1.0 - mean;
  const double s_z = -poisson_ratio - mean;
  const double j2 = 0.5 * (s_x * s_x + s_y * s_y + s_z * s_z);
  const double lode = s_z / std::sqrt(j2);
  const double argument = lode * (1.0 - 2.0 * poisson_ratio) / std::sqrt(4.0 - 3.0 * lode * lode);
  return 45.0 + 0.5 * std::asin(argument) / kDegree;
}

double plane_strain_first_yield_stress(double yield_stress, double poisson_ratio) {
  return yield_stress / std::sqrt(1.0 - poisson_ratio + poisson_ratio * poisson_ratio);
}

double coulomb_band_angle_deg(double friction_angle_deg) {
  return 45.0 - 0.5 * friction_angle_deg;
}

double roscoe_band_angle_deg(double dilatancy_angle_deg) {
  return 45.0 - 0.5 * dilatancy_angle_deg;
}

double arthur_band_angle_deg(double friction_angle_deg, double dilatancy_angle_deg) {
  return 45.0 - 0.25 * (friction_angle_deg + dilatancy_angle_deg);
}

double strip_subtended_angle(double half_width, double x, double z) {
  if (z <= 0.0) {
    const double distance = std::abs(x);
    if (distance < half_width) return std::numbers::pi;
    return distance == half_width ? 0.5 * std::numbers::pi : 0.0;
  }
  return std::atan((x + half_width) / z) - std::atan((x - half_width) / z);
}

double strip_undrained_pore_pressure(double load, double half_width, double x, double z) {
  // Incompressible undrained response: ν_u = 1/2, so σ_y = (σ_x + σ_z)/2 and p0 equals the mean
  // total stress (σ_x + σ_y + σ_z)/3 = (σ_x + σ_z)/2 = qα/π.
  return load * strip_subtended_angle(half_width, x, z) / std::numbers::pi;
}

double strip_centre_line_pore_pressure(double load, double half_width, double z) {
  return 2.0 * load / std::numbers::pi * std::atan(half_width / z);
}

double strip_undrained_compressibility_factor(double young_modulus, double poisson_ratio,
                                              double porosity, double fluid_bulk_modulus) {
  const double drained_bulk = bulk_modulus(young_modulus, poisson_ratio);
  const double shear = shear_modulus(young_modulus, poisson_ratio);
  const double biot = fluid_bulk_modulus / porosity;
  const double skempton = biot / (biot + drained_bulk);
  const double undrained_bulk = drained_bulk + biot;
  const double undrained_poisson =
      (3.0 * undrained_bulk - 2.0 * shear) / (2.0 * (3.0 * undrained_bulk + shear));
  return skempton * (1.0 + undrained_poisson) * 2.0 / 3.0;
}

double frictional_vertical_cut_stability_number(double friction_angle_deg) {
  const double phi = friction_angle_deg * std::numbers::pi / 180.0;
  return kTaylorVerticalCutStabilityNumber * std::tan(std::numbers::pi / 4.0 + phi / 2.0);
}

double vertical_cut_upper_bound_factor(double height, double unit_weight, double cohesion,
                                       double friction_angle_deg) {
  const double tan_phi = std::tan(friction_angle_deg * std::numbers::pi / 180.0);
  // gamma H F / c grows with F and the bound falls with it: one root, bracketed by [1e-3, 1e3].
  const auto excess = [&](double factor) {
    const double reduced = std::atan(tan_phi / factor) * 180.0 / std::numbers::pi;
    return unit_weight * height * factor / cohesion -
           frictional_vertical_cut_stability_number(reduced);
  };
  double low = 1e-3, high = 1e3;
  for (int k = 0; k < 200; ++k) {
    const double middle = std::sqrt(low * high);
    (excess(middle) < 0.0 ? low : high) = middle;
  }
  return std::sqrt(low * high);
}

}  // namespace rktsph::references
