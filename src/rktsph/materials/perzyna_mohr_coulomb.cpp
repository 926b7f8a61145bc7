#include "rktsph/materials/perzyna_mohr_coulomb.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "rktsph/materials/invariants.hpp"
#include "rktsph/materials/linear_elastic.hpp"
#include "rktsph/materials/perzyna_overstress.hpp"

namespace rktsph {

PerzynaMohrCoulomb::PerzynaMohrCoulomb(double density, ElasticConstants elastic,
                                       FrictionalParameters parameters)
    : Material(density, elastic), parameters_(parameters) {}

std::unique_ptr<Material> PerzynaMohrCoulomb::from_parameters(ParameterReader& reader) {
  const ElasticParameters elastic = read_elastic_parameters(reader);
  // F0 defaults to c0 cos(phi0), the shear strength of the planes at zero normal stress.
  const FrictionalParameters p =
      read_frictional_parameters(reader, [](const FrictionalParameters& s) {
        return s.cohesion * std::cos(radians(s.friction_angle));
      });
  return std::make_unique<PerzynaMohrCoulomb>(elastic.density, elastic.elastic, p);
}

std::vector<std::string> PerzynaMohrCoulomb::internal_names() const {
  return {"eps_vp", "cohesion", "friction_angle"};
}

void PerzynaMohrCoulomb::initial_internal(std::span<double> internal) const {
  initial_frictional_internal(parameters_, internal);
}

PerzynaMohrCoulomb::Planes PerzynaMohrCoulomb::planes(const SymmetricTensor& stress,
                                                      std::span<const double> internal) const {
  const FrictionalStrength strength = current_strength(parameters_, internal);
  Eigen::Matrix3d matrix;
  matrix << stress[0], stress[3], stress[5],  //
      stress[3], stress[1], stress[4],        //
      stress[5], stress[4], stress[2];
  // The iterative solver rather than computeDirect: its eigenvectors stay accurate when two
  // principal stresses nearly coincide (the corners), where the flow combines their projectors.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(matrix);
  Planes result;
  for (int k = 0; k < 3; ++k) {
    result.principal[k] = solver.eigenvalues()[k];
    const Eigen::Vector3d n = solver.eigenvectors().col(k);
    result.projector[k] = {n[0] * n[0], n[1] * n[1], n[2] * n[2],
                           n[0] * n[1], n[1] * n[2], n[2] * n[0]};
  }
  const double sin_phi = std::sin(strength.friction_angle);
  const double sin_psi = std::sin(strength.dilatancy_angle);
  const double shear_strength = strength.cohesion * std::cos(strength.friction_angle);
  int index = 0;
  // Eq. 1.16: F_ij for the six ordered pairs; the largest is the Mohr–Coulomb function.
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      if (i == j) continue;
      Plane& plane = result.plane[static_cast<std::size_t>(index++)];
      plane.normal = {0.0, 0.0, 0.0};
      plane.flow = {0.0, 0.0, 0.0};
      plane.normal[i] = 0.5 * (1.0 + sin_phi);
      plane.normal[j] = 0.5 * (-1.0 + sin_phi);
      plane.flow[i] = 0.5 * (1.0 + sin_psi);
      plane.flow[j] = 0.5 * (-1.0 + sin_psi);
      plane.value = plane.normal[i] * result.principal[i] + plane.normal[j] * result.principal[j] -
                    shear_strength;
    }
  // Rankine planes F_i = sigma_i - sigma_t, associated (eq. 1.17).
  for (int i = 0; i < 3; ++i) {
    Plane& plane = result.plane[static_cast<std::size_t>(index++)];
    plane.normal = {0.0, 0.0, 0.0};
    plane.normal[i] = 1.0;
    plane.flow = plane.normal;
    plane.value = result.principal[i] - strength.tension_limit;
  }
  return result;
}

double PerzynaMohrCoulomb::yield_function(const SymmetricTensor& stress,
                                          std::span<const double> internal) const {
  const Planes all = planes(stress, internal);
  double largest = -std::numeric_limits<double>::infinity();
  for (int a = 0; a < 6; ++a)
    largest = std::max(largest, all.plane[static_cast<std::size_t>(a)].value);
  return largest;
}

bool PerzynaMohrCoulomb::flows(const SymmetricTensor& stress,
                               std::span<const double> internal) const {
  const Planes all = planes(stress, internal);
  return std::any_of(all.plane.begin(), all.plane.end(),
                     [](const Plane& plane) { return plane.value > 0.0; });
}

void PerzynaMohrCoulomb::viscoplastic_rate(const SymmetricTensor& stress,
                                           std::span<const double> internal,
                                           SymmetricTensor& strain_rate,
                                           std::span<double> internal_rate) const {
  const Planes all = planes(stress, internal);
  // Koiter's rule with a Perzyna rate per plane (eq. 1.17): the principal components of the flow.
  std::array<double, 3> principal_rate = {0.0, 0.0, 0.0};
  for (const Plane& plane : all.plane) {
    const double rate =
        parameters_.fluidity *
        macaulay_power(plane.value / parameters_.reference_stress, parameters_.exponent);
    if (rate <= 0.0) continue;
    for (int k = 0; k < 3; ++k)
      principal_rate[static_cast<std::size_t>(k)] += rate * plane.flow[static_cast<std::size_t>(k)];
  }
  // Coaxial with the stress: sum_k rate_k P_k. Where two principal stresses coincide, their planes
  // have equal values and weights, so the sum holds their projectors' sum, which does not depend
  // on the eigenvectors the solver picked.
  strain_rate.fill(0.0);
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 6; ++i)
      strain_rate[i] += principal_rate[static_cast<std::size_t>(k)] *
                        all.projector[static_cast<std::size_t>(k)][static_cast<std::size_t>(i)];
  frictional_internal_rates(parameters_, internal, equivalent_strain_rate(strain_rate),
                            internal_rate);
}

double PerzynaMohrCoulomb::source_stiffness(const SymmetricTensor& stress,
                                            std::span<const double> internal) const {
  // The overstress of plane a relaxes as F_a_rate = -sum_b (n_a . D_principal . g_b) gamma Psi_b
  // with n_a . D . g_b = 2G n_a.g_b + lambda (sum n_a)(sum g_b) in principal components (coaxial
  // flow). The largest row sum of the Jacobian |d F_a_rate / d F_b| bounds its eigenvalues
  // (Gershgorin, eq. 1.18). Where nothing flows, the most loaded plane stands in for it, so that
  // the rate is that of the face the state would first meet.
  const Planes all = planes(stress, internal);
  const FrictionalStrength strength = current_strength(parameters_, internal);
  const double shear_modulus = elastic().shear_modulus();
  const double lame = elastic().lame_lambda();
  const double scale = parameters_.reference_stress;
  const double exponent = parameters_.exponent;
  std::array<bool, kPlaneCount> active{};
  int most_loaded = 0;
  bool any = false;
  for (int a = 0; a < kPlaneCount; ++a) {
    const auto index = static_cast<std::size_t>(a);
    active[index] = all.plane[index].value > 0.0;
    any = any || active[index];
    if (all.plane[index].value > all.plane[static_cast<std::size_t>(most_loaded)].value)
      most_loaded = a;
  }
  if (!any) active[static_cast<std::size_t>(most_loaded)] = true;
  const auto sum = [](const std::array<double, 3>& v) { return v[0] + v[1] + v[2]; };
  const auto dot = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };
  // Hardening raises each plane's strength per unit equivalent strain by cos(phi) H_c and by
  // |dF/dphi| H_phi; only hardening is added (an upper bound, as in perzyna_von_mises).
  const double cos_phi = std::cos(strength.friction_angle);
  const double sin_phi = std::sin(strength.friction_angle);
  // dF_ij/dphi = (sigma_i + sigma_j)/2 cos(phi) + c sin(phi), bounded by max|sigma_k| + c.
  const double friction_sensitivity =
      std::max(
          {std::abs(all.principal[0]), std::abs(all.principal[1]), std::abs(all.principal[2])}) +
      strength.cohesion * sin_phi;
  double largest = 0.0;
  for (int a = 0; a < kPlaneCount; ++a) {
    const auto ia = static_cast<std::size_t>(a);
    if (!active[ia]) continue;
    const Plane& row = all.plane[ia];
    double row_sum = 0.0;
    for (int b = 0; b < kPlaneCount; ++b) {
      const auto ib = static_cast<std::size_t>(b);
      if (!active[ib]) continue;
      const Plane& column = all.plane[ib];
      const double relative = std::max(column.value / scale, kOverstressFloor);
      const double slope = exponent == 1.0 ? 1.0 : exponent * std::pow(relative, exponent - 1.0);
      row_sum += std::abs(2.0 * shear_modulus * dot(row.normal, column.flow) +
                          lame * sum(row.normal) * sum(column.flow)) *
                 slope;
    }
    if (a < 6)
      row_sum += std::max(parameters_.cohesion_hardening_modulus, 0.0) * cos_phi +
                 std::max(parameters_.friction_hardening_modulus, 0.0) * radians(1.0) *
                     friction_sensitivity;
    largest = std::max(largest, row_sum);
  }
  return parameters_.fluidity * largest / scale;
}

}  // namespace rktsph
