#include "rktsph/validation/references/critical_state.hpp"

#include <cmath>
#include <numbers>

namespace rktsph::references {

double critical_state_ratio_compression(double friction_angle_deg) {
  const double sine = std::sin(friction_angle_deg * std::numbers::pi / 180.0);
  return 6.0 * sine / (3.0 - sine);
}

double isotropic_unloading_pressure(double initial_pressure, double volumetric_strain,
                                    double initial_void_ratio, double swelling_index) {
  return initial_pressure *
         std::exp(-(1.0 + initial_void_ratio) * volumetric_strain / swelling_index);
}

double undrained_failure_pressure(double initial_pressure, double overconsolidation_ratio,
                                  double compression_index, double swelling_index) {
  const double exponent = (compression_index - swelling_index) / compression_index;
  return initial_pressure * std::pow(0.5 * overconsolidation_ratio, exponent);
}

double drained_triaxial_failure_pressure(double initial_pressure, double critical_state_ratio) {
  return 3.0 * initial_pressure / (3.0 - critical_state_ratio);
}

}  // namespace rktsph::references
