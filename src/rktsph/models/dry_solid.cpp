#include "rktsph/models/dry_solid.hpp"
#include "rktsph/core/axes.hpp"
#include "rktsph/core/parallel.hpp"

#include <algorithm>
#include <cmath>

namespace rktsph {

namespace {
constexpr int kMaxStress = 4;
constexpr int kMaxInternal = 8;

struct StressComponent {
  int i, j;
};

std::vector<StressComponent> carried_stress(Kinematics kinematics) {
  switch (kinematics) {
    case Kinematics::Bar1D:
      return {{0, 0}};
    case Kinematics::PlaneStrain:
      return {{0, 0}, {1, 1}, {0, 1}, {2, 2}};
    case Kinematics::PlaneStress:
      return {{0, 0}, {1, 1}, {0, 1}};
  }
  return {};
}

// Index of a symmetric tensor component in SymmetricTensor order (xx, yy, zz, xy, yz, zx).
int tensor_slot(int i, int j) {
  if (i == j) return i;
  const int lo = std::min(i, j), hi = std::max(i, j);
  if (lo == 0 && hi == 1) return 3;
  if (lo == 1 && hi == 2) return 4;
  return 5;
}
}  // namespace

Vec3 Loads::body_force(double t) const {
  const double factor = gravity_factor(t);
  return {gravity[0] * factor, gravity[1] * factor, gravity[2] * factor};
}

double Loads::damping_at(double t) const {
  return (t >= damping_start && t < damping_end) ? damping : 0.0;
}

DrySolid::DrySolid(Kinematics kinematics, std::vector<std::unique_ptr<Material>> materials,
                   Loads loads, SourceIntegration integration)
    : kinematics_(kinematics),
      materials_(std::move(materials)),
      loads_(loads),
      integration_(integration) {
  const int d = dimension();
  for (int a = 0; a < d; ++a) {
    names_.push_back(std::string("velocity_") + axis_letter(a));
    parities_.push_back(vector_parity(a));
  }
  for (const StressComponent& c : carried_stress(kinematics_)) {
    stress_slot_[names_.size() - static_cast<std::size_t>(d)] = tensor_slot(c.i, c.j);
    names_.push_back(std::string("stress_") + axis_letter(c.i) + axis_letter(c.j));
    parities_.push_back(tensor_parity(c.i, c.j));
  }
  stress_count_ = static_cast<int>(names_.size()) - d;
  for (const auto& material : materials_)
    if (material->internal_count() > internal_count_) {
      internal_count_ = material->internal_count();
      internal_names_ = material->internal_names();
    }
}

int DrySolid::stress_field(int i, int j) const {
  const int slot = tensor_slot(i, j);
  for (int c = 0; c < stress_count_; ++c)
    if (stress_slot_[c] == slot) return dimension() + c;
  return -1;
}

double DrySolid::wave_speed(std::int32_t material) const {
  const Material& m = *materials_[static_cast<std::size_t>(material)];
  const ElasticConstants& e = m.elastic();
  const double modulus = kinematics_ == Kinematics::Bar1D         ? e.young_modulus
                         : kinematics_ == Kinematics::PlaneStrain ? e.constrained_modulus()
                                                                  : e.plane_stress_modulus();
  return std::sqrt(modulus / m.density());
}

double DrySolid::max_wave_speed() const {
  double speed = 0.0;
  for (std::size_t k = 0; k < materials_.size(); ++k)
    speed = std::max(speed, wave_speed(static_cast<std::int32_t>(k)));
  return speed;
}

std::array<double, 3> DrySolid::in_plane_moduli(std::int32_t material) const {
  const ElasticConstants& e = materials_[static_cast<std::size_t>(material)]->elastic();
  if (kinematics_ == Kinematics::PlaneStress)
    return {e.plane_stress_modulus(), e.poisson_ratio * e.plane_stress_modulus(),
            e.shear_modulus()};
  return {e.constrained_modulus(), e.lame_lambda(), e.shear_modulus()};
}

double DrySolid::divergence_bound(int field) const {
  // |v| = 10 c_p or |sigma| = 10 M means a strain of about 10 (docs/theory.md §2.5).
  if (field < dimension()) return 10.0 * max_wave_speed();
  double modulus = 0.0;
  for (const auto& material : materials_)
    modulus = std::max(modulus, material->elastic().constrained_modulus());
  return 10.0 * modulus;
}

void DrySolid::flux_rate(std::span<const std::int32_t> material, const FieldArray& gradient,
                         FieldArray& rate) const {
  const auto n = static_cast<std::int64_t>(material.size());
  const int d = dimension();
  // Gradient of field f along axis c is gradient field f * d + c (docs/theory.md §2.2).
  auto grad = [&](int f, int c, std::int64_t i) { return gradient.field(f * d + c)[i]; };
  switch (kinematics_) {
    case Kinematics::Bar1D:
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
      for (std::int64_t i = 0; i < n; ++i) {
        const Material& m = *materials_[material[i]];
        rate.field(0)[i] = grad(1, 0, i) / m.density();
        rate.field(1)[i] = m.elastic().young_modulus * grad(0, 0, i);
      }
      break;
    case Kinematics::PlaneStrain:
    case Kinematics::PlaneStress: {
      const bool plane_strain = kinematics_ == Kinematics::PlaneStrain;
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
      for (std::int64_t i = 0; i < n; ++i) {
        const Material& m = *materials_[material[i]];
        const ElasticConstants& e = m.elastic();
        const double strain_xx = grad(0, 0, i), strain_yy = grad(1, 1, i);
        const double strain_xy = 0.5 * (grad(0, 1, i) + grad(1, 0, i));
        rate.field(0)[i] = (grad(2, 0, i) + grad(4, 1, i)) / m.density();
        rate.field(1)[i] = (grad(4, 0, i) + grad(3, 1, i)) / m.density();
        const double shear = e.shear_modulus();
        if (plane_strain) {
          const double lambda = e.lame_lambda();
          rate.field(2)[i] = (lambda + 2.0 * shear) * strain_xx + lambda * strain_yy;
          rate.field(3)[i] = lambda * strain_xx + (lambda + 2.0 * shear) * strain_yy;
          rate.field(4)[i] = 2.0 * shear * strain_xy;
          rate.field(5)[i] = lambda * (strain_xx + strain_yy);
        } else {
          const double modulus = e.plane_stress_modulus(), nu = e.poisson_ratio;
          rate.field(2)[i] = modulus * (strain_xx + nu * strain_yy);
          rate.field(3)[i] = modulus * (nu * strain_xx + strain_yy);
          rate.field(4)[i] = 2.0 * shear * strain_xy;
        }
      }
      break;
    }
  }
}

void DrySolid::advance_velocity(double rate_v[3], double time, double interval, double v[3]) const {
  // v' = R_v + b(t) - xi(t) v, classical RK4 with sub-steps when xi * interval is large.
  const int d = dimension();
  const double stiffness = loads_.damping_at(time);
  const int substeps =
      std::clamp(static_cast<int>(std::ceil(interval * stiffness / integration_.substep_factor)), 1,
                 integration_.max_substeps);
  const double delta = interval / substeps;
  for (int s = 0; s < substeps; ++s) {
    const double t0 = time + s * delta;
    const Vec3 b0 = loads_.body_force(t0), b1 = loads_.body_force(t0 + 0.5 * delta),
               b2 = loads_.body_force(t0 + delta);
    const double x0 = loads_.damping_at(t0), x1 = loads_.damping_at(t0 + 0.5 * delta),
                 x2 = loads_.damping_at(t0 + delta);
    for (int a = 0; a < d; ++a) {
      const double r = integration_.frozen_flux ? rate_v[a] : 0.0;
      const double k1 = r + b0[a] - x0 * v[a];
      const double k2 = r + b1[a] - x1 * (v[a] + 0.5 * delta * k1);
      const double k3 = r + b1[a] - x1 * (v[a] + 0.5 * delta * k2);
      const double k4 = r + b2[a] - x2 * (v[a] + delta * k3);
      v[a] += delta / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
  }
  if (!integration_.frozen_flux)
    for (int a = 0; a < d; ++a)
      v[a] += interval * rate_v[a];
}

void DrySolid::stress_source(const Material& material, const double* sigma, const double* kappa,
                             double* sigma_rate, double* kappa_rate) const {
  SymmetricTensor stress{};
  for (int c = 0; c < stress_count_; ++c)
    stress[stress_slot_[c]] = sigma[c];
  SymmetricTensor strain_rate{};
  const int nk = material.internal_count();
  material.viscoplastic_rate(stress, std::span<const double>(kappa, nk), strain_rate,
                             std::span<double>(kappa_rate, nk));
  const ElasticConstants& e = material.elastic();
  const double shear = e.shear_modulus();
  switch (kinematics_) {
    case Kinematics::Bar1D:
      sigma_rate[0] = -e.young_modulus * strain_rate[0];
      break;
    case Kinematics::PlaneStrain: {
      const double lambda = e.lame_lambda();
      const double trace = strain_rate[0] + strain_rate[1] + strain_rate[2];
      sigma_rate[0] = -(lambda * trace + 2.0 * shear * strain_rate[0]);
      sigma_rate[1] = -(lambda * trace + 2.0 * shear * strain_rate[1]);
      sigma_rate[2] = -2.0 * shear * strain_rate[3];
      sigma_rate[3] = -(lambda * trace + 2.0 * shear * strain_rate[2]);
      break;
    }
    case Kinematics::PlaneStress: {
      const double modulus = e.plane_stress_modulus(), nu = e.poisson_ratio;
      sigma_rate[0] = -modulus * (strain_rate[0] + nu * strain_rate[1]);
      sigma_rate[1] = -modulus * (nu * strain_rate[0] + strain_rate[1]);
      sigma_rate[2] = -2.0 * shear * strain_rate[3];
      break;
    }
  }
}

void DrySolid::advance_stress(const Material& material, const double* rate_sigma, double time,
                              double interval, double* sigma, double* kappa) const {
  (void)time;  // the stress source is autonomous; kept for models with time-dependent sources
  const int ns = stress_count_;
  if (material.is_elastic()) {
    for (int k = 0; k < ns; ++k)
      sigma[k] += interval * rate_sigma[k];
    return;
  }
  // (sigma, kappa)' = R_sigma - D^e : eps_dot^vp, kappa_dot: RK4 with sub-steps sized by the
  // relaxation rate of the source (docs/theory.md §2.1, sub-step rule).
  const int nk = material.internal_count();
  SymmetricTensor stress{};
  for (int c = 0; c < ns; ++c)
    stress[stress_slot_[c]] = sigma[c];
  // Both ends of the straight path sigma + t R inside the (convex) elastic domain: no flow at all
  // within the step, so the update is exactly elastic.
  SymmetricTensor predictor{};
  for (int c = 0; c < ns; ++c)
    predictor[stress_slot_[c]] = sigma[c] + interval * rate_sigma[c];
  const std::span<const double> kappa_view(kappa, static_cast<std::size_t>(nk));
  if (integration_.frozen_flux && !material.flows(stress, kappa_view) &&
      !material.flows(predictor, kappa_view)) {
    for (int c = 0; c < ns; ++c)
      sigma[c] += interval * rate_sigma[c];
    return;
  }
  // The source may switch on within the step (an elastic state pushed beyond the yield surface by
  // the flux): size the sub-steps by the larger stiffness of the start and of the elastic
  // predictor.
  const double stiffness = std::max(material.source_stiffness(stress, kappa_view),
                                    material.source_stiffness(predictor, kappa_view));
  const int substeps =
      std::clamp(static_cast<int>(std::ceil(interval * stiffness / integration_.substep_factor)), 1,
                 integration_.max_substeps);
  const double delta = interval / substeps;
  const int n = ns + nk;
  double y[kMaxStress + kMaxInternal], stage[kMaxStress + kMaxInternal];
  double k[4][kMaxStress + kMaxInternal];
  const bool frozen = integration_.frozen_flux;
  auto evaluate = [&](const double* state, double* slope) {
    stress_source(material, state, state + ns, slope, slope + ns);
    if (frozen)
      for (int c = 0; c < ns; ++c)
        slope[c] += rate_sigma[c];
  };
  std::copy(sigma, sigma + ns, y);
  std::copy(kappa, kappa + nk, y + ns);
  for (int s = 0; s < substeps; ++s) {
    evaluate(y, k[0]);
    for (int c = 0; c < n; ++c)
      stage[c] = y[c] + 0.5 * delta * k[0][c];
    evaluate(stage, k[1]);
    for (int c = 0; c < n; ++c)
      stage[c] = y[c] + 0.5 * delta * k[1][c];
    evaluate(stage, k[2]);
    for (int c = 0; c < n; ++c)
      stage[c] = y[c] + delta * k[2][c];
    evaluate(stage, k[3]);
    for (int c = 0; c < n; ++c)
      y[c] += delta / 6.0 * (k[0][c] + 2.0 * k[1][c] + 2.0 * k[2][c] + k[3][c]);
  }
  if (!frozen)
    for (int c = 0; c < ns; ++c)
      y[c] += interval * rate_sigma[c];
  std::copy(y, y + ns, sigma);
  std::copy(y + ns, y + n, kappa);
}

void DrySolid::advance(std::span<const std::int32_t> material, const FieldArray& rate, double time,
                       double interval, FieldArray& values, FieldArray& internal,
                       AdvancedFields part) const {
  const auto n = static_cast<std::int64_t>(material.size());
  const int d = dimension();
  const int ns = stress_count_;
  const int nk = internal_count_;
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
  for (std::int64_t i = 0; i < n; ++i) {
    const Material& m = *materials_[material[i]];
    if (part != AdvancedFields::Others) {
      double v[3] = {}, rate_v[3] = {};
      for (int a = 0; a < d; ++a) {
        v[a] = values.field(a)[i];
        rate_v[a] = rate.field(a)[i];
      }
      advance_velocity(rate_v, time, interval, v);
      for (int a = 0; a < d; ++a)
        values.field(a)[i] = v[a];
    }
    if (part == AdvancedFields::Velocity) continue;

    double sigma[kMaxStress], rate_sigma[kMaxStress], kappa[kMaxInternal] = {};
    for (int c = 0; c < ns; ++c) {
      sigma[c] = values.field(d + c)[i];
      rate_sigma[c] = rate.field(d + c)[i];
    }
    for (int c = 0; c < nk; ++c)
      kappa[c] = internal.field(c)[i];
    advance_stress(m, rate_sigma, time, interval, sigma, kappa);
    for (int c = 0; c < ns; ++c)
      values.field(d + c)[i] = sigma[c];
    for (int c = 0; c < nk; ++c)
      internal.field(c)[i] = kappa[c];
  }
}

void DrySolid::project_traction_free_increment(std::int32_t material, const SurfaceNormals& normals,
                                               std::span<const double> start, FieldArray& values,
                                               std::size_t i) const {
  // Lattice faces only, for now: the normals are coordinate axes.
  std::uint8_t normal_axes = 0;
  for (int r = 0; r < normals.count; ++r)
    for (int a = 0; a < 3; ++a)
      if (normals.normal[static_cast<std::size_t>(r)][static_cast<std::size_t>(a)] != 0.0)
        normal_axes |= static_cast<std::uint8_t>(1u << a);
  // Normal strain corrections delta_eps_n (n in the constrained set N) solve
  //   sum_m D_nm delta_eps_m = -(sigma_nn - sigma_nn^start),  n, m in N,
  // and every carried normal stress then moves by sum_m D_km delta_eps_m (docs/theory.md §5.1).
  const ElasticConstants& e = materials_[material]->elastic();
  const int d = dimension();
  int axes[2], count = 0;
  for (int a = 0; a < d; ++a)
    if (normal_axes & (1u << a)) axes[count++] = a;
  if (count == 0) return;
  auto normal_index = [&](int a) { return stress_field(a, a); };
  auto stiffness = [&](int k, int m) {  // D_km between normal components k and m
    switch (kinematics_) {
      case Kinematics::Bar1D:
        return e.young_modulus;
      case Kinematics::PlaneStrain:
        return e.lame_lambda() + (k == m ? 2.0 * e.shear_modulus() : 0.0);
      case Kinematics::PlaneStress:
        return e.plane_stress_modulus() * (k == m ? 1.0 : e.poisson_ratio);
    }
    return 0.0;
  };
  double residual[2], correction[2];
  for (int r = 0; r < count; ++r) {
    const int f = normal_index(axes[r]);
    residual[r] = -(values(f, i) - start[static_cast<std::size_t>(f)]);
  }
  if (count == 1) {
    correction[0] = residual[0] / stiffness(axes[0], axes[0]);
  } else {
    const double a = stiffness(axes[0], axes[0]), b = stiffness(axes[0], axes[1]),
                 c = stiffness(axes[1], axes[0]), dd = stiffness(axes[1], axes[1]);
    const double det = a * dd - b * c;
    correction[0] = (dd * residual[0] - b * residual[1]) / det;
    correction[1] = (a * residual[1] - c * residual[0]) / det;
  }
  const int normal_components = kinematics_ == Kinematics::PlaneStrain ? 3 : d;
  for (int k = 0; k < normal_components; ++k) {
    const int f = normal_index(k);
    for (int r = 0; r < count; ++r)
      values(f, i) += stiffness(k, axes[r]) * correction[r];
  }
}

void DrySolid::add_artificial_viscosity(std::span<const std::int32_t> material,
                                        const FieldArray& gradient, double alpha_dx,
                                        FieldArray& values) const {
  const auto n = static_cast<std::int64_t>(material.size());
  const int d = dimension();
  const int xx = stress_field(0, 0), yy = stress_field(1, 1), xy = stress_field(0, 1);
  const double c = max_wave_speed();
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
  for (std::int64_t i = 0; i < n; ++i) {
    // q = alpha rho c_p dx eps_dot (docs/theory.md §2.7); c_p of the stiffest material keeps the
    // coefficient uniform across material interfaces.
    const double viscosity = alpha_dx * materials_[material[i]]->density() * c;
    values.field(xx)[i] += viscosity * gradient.field(0)[i];
    if (d >= 2) {
      values.field(yy)[i] += viscosity * gradient.field(1 * d + 1)[i];
      values.field(xy)[i] +=
          viscosity * 0.5 * (gradient.field(0 * d + 1)[i] + gradient.field(1 * d + 0)[i]);
    }
  }
}

void DrySolid::flowing(std::span<const std::int32_t> material, const FieldArray& values,
                       const FieldArray& internal, std::span<std::uint8_t> flowing) const {
  for (std::size_t i = 0; i < material.size(); ++i) {
    const Material& m = *materials_[static_cast<std::size_t>(material[i])];
    if (m.is_elastic()) {
      flowing[i] = 0;
      continue;
    }
    double kappa[kMaxInternal] = {};
    for (int c = 0; c < m.internal_count(); ++c)
      kappa[c] = internal(c, i);
    flowing[i] =
        m.flows(stress_tensor(values, i),
                std::span<const double>(kappa, static_cast<std::size_t>(m.internal_count())))
            ? 1
            : 0;
  }
}

void DrySolid::initial_internal(std::int32_t material, FieldArray& internal, std::size_t i) const {
  const Material& m = *materials_[material];
  double kappa[kMaxInternal] = {};
  m.initial_internal(std::span<double>(kappa, static_cast<std::size_t>(m.internal_count())));
  for (int c = 0; c < internal_count_; ++c)
    internal(c, i) = kappa[c];
}

}  // namespace rktsph
