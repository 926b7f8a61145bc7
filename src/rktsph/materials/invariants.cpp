#include "rktsph/materials/invariants.hpp"

#include <algorithm>
#include <cmath>

namespace rktsph {

namespace {
enum Component { kXX = 0, kYY = 1, kZZ = 2, kXY = 3, kYZ = 4, kZX = 5 };
}  // namespace

double trace(const SymmetricTensor& tensor) {
  return tensor[kXX] + tensor[kYY] + tensor[kZZ];
}

SymmetricTensor deviator(const SymmetricTensor& tensor) {
  const double mean = trace(tensor) / 3.0;
  SymmetricTensor result = tensor;
  for (int i = 0; i < 3; ++i)
    result[i] -= mean;
  return result;
}

double double_contraction(const SymmetricTensor& a, const SymmetricTensor& b) {
  return a[kXX] * b[kXX] + a[kYY] * b[kYY] + a[kZZ] * b[kZZ] +
         2.0 * (a[kXY] * b[kXY] + a[kYZ] * b[kYZ] + a[kZX] * b[kZX]);
}

SymmetricTensor square(const SymmetricTensor& t) {
  return {t[kXX] * t[kXX] + t[kXY] * t[kXY] + t[kZX] * t[kZX],
          t[kXY] * t[kXY] + t[kYY] * t[kYY] + t[kYZ] * t[kYZ],
          t[kZX] * t[kZX] + t[kYZ] * t[kYZ] + t[kZZ] * t[kZZ],
          t[kXX] * t[kXY] + t[kXY] * t[kYY] + t[kZX] * t[kYZ],
          t[kXY] * t[kZX] + t[kYY] * t[kYZ] + t[kYZ] * t[kZZ],
          t[kZX] * t[kXX] + t[kYZ] * t[kXY] + t[kZZ] * t[kZX]};
}

double determinant(const SymmetricTensor& t) {
  return t[kXX] * (t[kYY] * t[kZZ] - t[kYZ] * t[kYZ]) -
         t[kXY] * (t[kXY] * t[kZZ] - t[kYZ] * t[kZX]) +
         t[kZX] * (t[kXY] * t[kYZ] - t[kYY] * t[kZX]);
}

SymmetricTensor apply_elastic_stiffness(const ElasticConstants& elastic,
                                        const SymmetricTensor& strain) {
  const double volumetric = elastic.lame_lambda() * trace(strain);
  const double twice_shear_modulus = 2.0 * elastic.shear_modulus();
  SymmetricTensor stress;
  for (int i = 0; i < 6; ++i)
    stress[i] = twice_shear_modulus * strain[i];
  for (int i = 0; i < 3; ++i)
    stress[i] += volumetric;
  return stress;
}

double equivalent_strain_rate(const SymmetricTensor& strain_rate) {
  const SymmetricTensor deviatoric = deviator(strain_rate);
  return std::sqrt(2.0 / 3.0 * double_contraction(deviatoric, deviatoric));
}

double mean_pressure(const SymmetricTensor& stress) {
  return -trace(stress) / 3.0;
}

double von_mises_stress(const SymmetricTensor& stress) {
  // 1.5 x rounds as 3 (x/2) does (halving is exact), so this equals sqrt(3 J2) of
  // stress_invariants to the last bit.
  const SymmetricTensor s = deviator(stress);
  return std::sqrt(1.5 * double_contraction(s, s));
}

StressInvariants stress_invariants(const SymmetricTensor& stress) {
  StressInvariants result;
  result.i1 = trace(stress);
  result.pressure = -result.i1 / 3.0;
  result.deviator = deviator(stress);
  result.j2 = 0.5 * double_contraction(result.deviator, result.deviator);
  result.j3 = determinant(result.deviator);
  result.q = std::sqrt(3.0 * result.j2);
  double largest_component = 0.0;
  for (double component : stress)
    largest_component = std::max(largest_component, std::abs(component));
  result.lode_defined = std::sqrt(result.j2) > kLodeDefinedRatio * largest_component;
  if (result.lode_defined) {
    // Zienkiewicz–Pande sign (docs/theory.md eq. 1.6): J3 < 0 in triaxial compression gives +pi/6.
    const double sin_3theta =
        -1.5 * std::sqrt(3.0) * result.j3 / (result.j2 * std::sqrt(result.j2));
    result.sin_3theta = std::clamp(sin_3theta, -1.0, 1.0);
    result.lode_angle = std::asin(result.sin_3theta) / 3.0;
  }
  return result;
}

SymmetricTensor gradient_of_i1() {
  return {1.0, 1.0, 1.0, 0.0, 0.0, 0.0};
}

SymmetricTensor gradient_of_sqrt_j2(const StressInvariants& invariants) {
  SymmetricTensor gradient{};
  if (invariants.j2 <= 0.0) return gradient;
  const double scale = 0.5 / std::sqrt(invariants.j2);
  for (int i = 0; i < 6; ++i)
    gradient[i] = scale * invariants.deviator[i];
  return gradient;
}

SymmetricTensor gradient_of_j3(const StressInvariants& invariants) {
  SymmetricTensor gradient = square(invariants.deviator);
  for (int i = 0; i < 3; ++i)
    gradient[i] -= 2.0 / 3.0 * invariants.j2;
  return gradient;
}

SymmetricTensor flow_vector(const StressInvariants& invariants,
                            const FlowCoefficients& coefficients) {
  const SymmetricTensor m2 = gradient_of_sqrt_j2(invariants);
  SymmetricTensor flow{};
  for (int i = 0; i < 6; ++i)
    flow[i] = coefficients.c2 * m2[i];
  for (int i = 0; i < 3; ++i)
    flow[i] += coefficients.c1;
  if (coefficients.c3 != 0.0) {
    const SymmetricTensor m3 = gradient_of_j3(invariants);
    for (int i = 0; i < 6; ++i)
      flow[i] += coefficients.c3 * m3[i];
  }
  return flow;
}

}  // namespace rktsph
