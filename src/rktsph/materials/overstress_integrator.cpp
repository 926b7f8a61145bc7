#include "rktsph/materials/overstress_integrator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace rktsph {

namespace {
constexpr int kMaxStress = CarriedStress::kMax;

/// The inverse of the count x count leading block of `matrix` (row stride kMaxStress), by
/// Gauss-Jordan elimination with partial pivoting; D is symmetric positive definite.
CondensedStiffness inverse(const CondensedStiffness& matrix, int count) {
  double a[kMaxStress][2 * kMaxStress] = {};
  for (int r = 0; r < count; ++r) {
    for (int c = 0; c < count; ++c)
      a[r][c] = matrix[static_cast<std::size_t>(r * kMaxStress + c)];
    a[r][count + r] = 1.0;
  }
  for (int column = 0; column < count; ++column) {
    int pivot = column;
    for (int r = column + 1; r < count; ++r)
      if (std::abs(a[r][column]) > std::abs(a[pivot][column])) pivot = r;
    for (int c = 0; c < 2 * count; ++c)
      std::swap(a[column][c], a[pivot][c]);
    const double diagonal = a[column][column];
    for (int c = 0; c < 2 * count; ++c)
      a[column][c] /= diagonal;
    for (int r = 0; r < count; ++r) {
      if (r == column) continue;
      const double factor = a[r][column];
      for (int c = 0; c < 2 * count; ++c)
        a[r][c] -= factor * a[column][c];
    }
  }
  CondensedStiffness result{};
  for (int r = 0; r < count; ++r)
    for (int c = 0; c < count; ++c)
      result[static_cast<std::size_t>(r * kMaxStress + c)] = a[r][count + c];
  return result;
}

/// sum_c matrix(r, c) x[c] for each row r < count.
void multiply(const CondensedStiffness& matrix, int count, const double* x, double* result) {
  for (int r = 0; r < count; ++r) {
    const double* row = matrix.data() + static_cast<std::size_t>(r) * kMaxStress;
    double sum = row[0] * x[0];
    for (int c = 1; c < count; ++c)
      sum += row[c] * x[c];
    result[r] = sum;
  }
}
}  // namespace

OverstressIntegrator::OverstressIntegrator(const Material& material, const CarriedStress& carried,
                                           const CondensedStiffness& stiffness,
                                           SourceIntegration integration,
                                           StiffnessCondenser condense)
    : material_(material),
      carried_(carried),
      stiffness_(stiffness),
      integration_(integration),
      condense_(std::move(condense)) {
  if (material.stress_dependent_elasticity()) {
    if (!condense_)
      throw std::invalid_argument(
          "OverstressIntegrator: a material with stress-dependent elasticity needs a condenser");
    compliance_ = inverse(stiffness_, carried_.count);
  }
}

SymmetricTensor OverstressIntegrator::full_stress(const double* sigma) const {
  SymmetricTensor stress{};
  for (int c = 0; c < carried_.count; ++c)
    stress[static_cast<std::size_t>(carried_.slot[static_cast<std::size_t>(c)])] = sigma[c];
  return stress;
}

void OverstressIntegrator::integrate_stress_dependent(const double* rate_sigma, double interval,
                                                      double* sigma, double* kappa) const {
  const int ns = carried_.count;
  const int nk = material_.internal_count();
  double strain_rate[kMaxStress];
  multiply(compliance_, ns, rate_sigma, strain_rate);
  const std::span<const double> kappa_view(kappa, static_cast<std::size_t>(nk));
  double predictor[kMaxStress];
  for (int c = 0; c < ns; ++c)
    predictor[c] = sigma[c] + interval * rate_sigma[c];
  const SymmetricTensor stress = full_stress(sigma);
  // Sub-steps: the relaxation rate of the source (eq. 2.7), and the relative rate at which the
  // elastic stiffness itself changes, |sigma'| / |sigma| (K ~ p: that is the rate of K / K).
  double rate_norm = 0.0, stress_norm = 0.0;
  for (int c = 0; c < ns; ++c) {
    rate_norm += rate_sigma[c] * rate_sigma[c];
    stress_norm += sigma[c] * sigma[c];
  }
  const double elastic_rate = stress_norm > 0.0 ? std::sqrt(rate_norm / stress_norm) : 0.0;
  const double relaxation_rate =
      std::max({material_.source_stiffness(stress, kappa_view),
                material_.source_stiffness(full_stress(predictor), kappa_view), elastic_rate});
  const int substeps = substep_count(interval, relaxation_rate, integration_.substep_factor,
                                     integration_.max_substeps);
  const int n = ns + nk;
  double y[kMaxStress + kMaxInternal], stage[kMaxStress + kMaxInternal];
  double k[4][kMaxStress + kMaxInternal];
  double* const slopes[4] = {k[0], k[1], k[2], k[3]};
  // eq. 1.10c: sigma' = D(sigma) : (eps_dot - eps_dot^vp); eps_dot is frozen over the interval as
  // R_sigma is in integrate() (docs/theory.md §2.8).
  auto evaluate = [&](double, const double* state, double* slope) {
    const SymmetricTensor current = full_stress(state);
    SymmetricTensor plastic_rate{};
    material_.viscoplastic_rate(current, std::span<const double>(state + ns, nk), plastic_rate,
                                std::span<double>(slope + ns, nk));
    double elastic_strain_rate[kMaxStress];
    for (int c = 0; c < ns; ++c) {
      const auto i = static_cast<std::size_t>(c);
      elastic_strain_rate[c] =
          strain_rate[c] -
          carried_.shear_factor[i] * plastic_rate[static_cast<std::size_t>(carried_.slot[i])];
    }
    multiply(condense_(material_.elastic_at(current)), ns, elastic_strain_rate, slope);
  };
  std::copy(sigma, sigma + ns, y);
  std::copy(kappa, kappa + nk, y + ns);
  rk4_substeps(evaluate, 0.0, interval, substeps, n, y, stage, slopes);
  std::copy(y, y + ns, sigma);
  std::copy(y + ns, y + n, kappa);
}

void OverstressIntegrator::source(const double* sigma, const double* kappa, double* sigma_rate,
                                  double* kappa_rate) const {
  const int ns = carried_.count;
  SymmetricTensor stress{};
  for (int c = 0; c < ns; ++c)
    stress[static_cast<std::size_t>(carried_.slot[static_cast<std::size_t>(c)])] = sigma[c];
  SymmetricTensor strain_rate{};
  const int nk = material_.internal_count();
  material_.viscoplastic_rate(stress, std::span<const double>(kappa, nk), strain_rate,
                              std::span<double>(kappa_rate, nk));
  // The strains of the stress-free components are condensed into the stiffness, so only the
  // carried components of eps_dot^vp enter (engineering shear, docs/theory.md §1.6).
  double plastic[kMaxStress];
  for (int c = 0; c < ns; ++c) {
    const auto k = static_cast<std::size_t>(c);
    plastic[c] = carried_.shear_factor[k] * strain_rate[static_cast<std::size_t>(carried_.slot[k])];
  }
  // -D plastic, each row summed in component order.
  for (int r = 0; r < ns; ++r) {
    const double* row = stiffness_.data() + static_cast<std::size_t>(r) * kMaxStress;
    double sum = row[0] * plastic[0];
    for (int c = 1; c < ns; ++c)
      sum += row[c] * plastic[c];
    sigma_rate[r] = -sum;
  }
}

void OverstressIntegrator::cut_tension(double* sigma) const {
  const double limit = material_.tension_cutoff();
  if (!std::isfinite(limit)) return;
  // p = tr(sigma)/3 over the full tensor; the stress-free normal components are zero.
  double trace = 0.0;
  int normals = 0;
  const int ns = carried_.count;
  for (int c = 0; c < ns; ++c)
    if (carried_.slot[static_cast<std::size_t>(c)] < 3) {
      trace += sigma[c];
      ++normals;
    }
  const double excess = trace / 3.0 - limit;
  if (!(excess > 0.0) || normals == 0) return;
  // Shifting the carried normal components alike lowers p by exactly the excess (eq. 1.7).
  const double shift = 3.0 * excess / normals;
  for (int c = 0; c < ns; ++c)
    if (carried_.slot[static_cast<std::size_t>(c)] < 3) sigma[c] -= shift;
}

void OverstressIntegrator::integrate(const double* rate_sigma, double interval, double* sigma,
                                     double* kappa) const {
  if (material_.stress_dependent_elasticity())
    return integrate_stress_dependent(rate_sigma, interval, sigma, kappa);
  const int ns = carried_.count;
  if (material_.is_elastic()) {
    for (int k = 0; k < ns; ++k)
      sigma[k] += interval * rate_sigma[k];
    return;
  }
  // (sigma, kappa)' = R_sigma - D^e : eps_dot^vp, kappa_dot: RK4 with sub-steps sized by the
  // relaxation rate of the source (docs/theory.md §2.1, sub-step rule).
  const int nk = material_.internal_count();
  SymmetricTensor stress{}, predictor{};
  for (int c = 0; c < ns; ++c) {
    const auto slot = static_cast<std::size_t>(carried_.slot[static_cast<std::size_t>(c)]);
    stress[slot] = sigma[c];
    predictor[slot] = sigma[c] + interval * rate_sigma[c];
  }
  // Both ends of the straight path sigma + t R inside the (convex) elastic domain: no flow at all
  // within the step, so the update is exactly elastic.
  const std::span<const double> kappa_view(kappa, static_cast<std::size_t>(nk));
  if (integration_.frozen_flux && !material_.flows(stress, kappa_view) &&
      !material_.flows(predictor, kappa_view)) {
    for (int c = 0; c < ns; ++c)
      sigma[c] += interval * rate_sigma[c];
    return;
  }
  // The source may switch on within the step (an elastic state pushed beyond the yield surface by
  // the flux): size the sub-steps by the larger stiffness of the start and of the elastic
  // predictor.
  const double relaxation_rate = std::max(material_.source_stiffness(stress, kappa_view),
                                          material_.source_stiffness(predictor, kappa_view));
  const int substeps = substep_count(interval, relaxation_rate, integration_.substep_factor,
                                     integration_.max_substeps);
  const int n = ns + nk;
  double y[kMaxStress + kMaxInternal], stage[kMaxStress + kMaxInternal];
  double k[4][kMaxStress + kMaxInternal];
  double* const slopes[4] = {k[0], k[1], k[2], k[3]};
  const bool frozen = integration_.frozen_flux;
  // The source is autonomous: the stage times of rk4_substeps are not needed.
  auto evaluate = [&](double, const double* state, double* slope) {
    source(state, state + ns, slope, slope + ns);
    if (frozen)
      for (int c = 0; c < ns; ++c)
        slope[c] += rate_sigma[c];
  };
  std::copy(sigma, sigma + ns, y);
  std::copy(kappa, kappa + nk, y + ns);
  rk4_substeps(evaluate, 0.0, interval, substeps, n, y, stage, slopes);
  if (!frozen)
    for (int c = 0; c < ns; ++c)
      y[c] += interval * rate_sigma[c];
  std::copy(y, y + ns, sigma);
  std::copy(y + ns, y + n, kappa);
}

}  // namespace rktsph
