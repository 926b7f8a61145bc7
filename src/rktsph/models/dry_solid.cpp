#include "rktsph/models/dry_solid.hpp"
#include "rktsph/core/axes.hpp"
#include "rktsph/core/parallel.hpp"

#include <algorithm>
#include <cmath>

namespace rktsph {

namespace {

// Classical RK4 over the sub-steps of dv/dt = r + b(t) − ξ(t) v (the velocity part of the source,
// docs/theory.md §2.8): `body(loads, k)` gives b at the sub-step's start (k = 0), middle (1) and
// end (2), so that advance_velocities and its water-table form (eq. 6.8) share one integrator.
template <class Loads, class Body>
double integrate_velocity(double v, double r, const std::vector<Loads>& loads, int substeps,
                          double delta, const Body& body) {
  for (int s = 0; s < substeps; ++s) {
    const Loads& l = loads[static_cast<std::size_t>(s)];
    const double b0 = body(l, 0), b1 = body(l, 1), b2 = body(l, 2);
    const double k1 = r + b0 - l.damping[0] * v;
    const double k2 = r + b1 - l.damping[1] * (v + 0.5 * delta * k1);
    const double k3 = r + b1 - l.damping[1] * (v + 0.5 * delta * k2);
    const double k4 = r + b2 - l.damping[2] * (v + delta * k3);
    v += delta / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return v;
}
constexpr int kMaxInternal = OverstressIntegrator::kMaxInternal;
constexpr int kMaxNormals = SurfaceNormals::kMax;

// Solves the count x count system a x = b (count <= 3) by Cramer's rule.
void solve_small(const double a[kMaxNormals][kMaxNormals], const double* b, int count, double* x) {
  if (count == 1) {
    x[0] = b[0] / a[0][0];
  } else if (count == 2) {
    const double det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    x[0] = (a[1][1] * b[0] - a[0][1] * b[1]) / det;
    x[1] = (a[0][0] * b[1] - a[1][0] * b[0]) / det;
  } else {
    auto det3 = [](const double m[3][3]) {
      return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
             m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
             m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    };
    const double det = det3(a);
    for (int k = 0; k < 3; ++k) {
      double replaced[3][3];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          replaced[r][c] = c == k ? b[r] : a[r][c];
      x[k] = det3(replaced) / det;
    }
  }
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
    : DrySolid(kinematics, std::move(materials), loads, integration, false) {}

DrySolid::DrySolid(Kinematics kinematics, std::vector<std::unique_ptr<Material>> materials,
                   Loads loads, SourceIntegration integration, bool pore_pressure)
    : kinematics_(kinematics),
      layout_(kinematic_assumption(kinematics), pore_pressure),
      materials_(std::move(materials)),
      loads_(loads),
      integration_(integration) {
  const KinematicAssumption& assumption = layout_.kinematics();
  for (const auto& material : materials_) {
    stiffness_.push_back(assumption.stiffness(material->elastic()));
    compliance_.push_back(compliance(stiffness_.back()));
    if (material->internal_count() > internal_count_) {
      internal_count_ = material->internal_count();
      internal_names_ = material->internal_names();
    }
  }
  const int d = dimension();
  carried_.count = layout_.stress_count();
  for (int c = 0; c < layout_.stress_count(); ++c) {
    const auto k = static_cast<std::size_t>(c);
    const TensorComponent component = assumption.stress_component(c);
    carried_.slot[k] = assumption.stress_slot(c);
    carried_.shear_factor[k] = component.i == component.j ? 1.0 : 2.0;
    const StrainRateTerms terms = assumption.strain_rate_terms(c);
    strain_rate_gradients_[k].count = terms.count;
    for (int t = 0; t < terms.count; ++t) {
      const VelocityGradientTerm term = terms.term[static_cast<std::size_t>(t)];
      strain_rate_gradients_[k].field[static_cast<std::size_t>(t)] =
          layout_.gradient(layout_.velocity(term.velocity), term.axis);
    }
  }
  // R_v = (1/rho) sum_b d sigma_ab / dx_b (docs/theory.md eq. 1.4): every in-plane stress is
  // carried.
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b)
      divergence_gradients_[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] =
          layout_.gradient(layout_.stress(a, b), b);
  // The integrators take D as a plain table: StiffnessMatrix belongs to physics/, above
  // materials/.
  const auto as_table = [](const StiffnessMatrix& matrix) {
    CondensedStiffness table{};
    for (int r = 0; r < matrix.size(); ++r)
      for (int c = 0; c < matrix.size(); ++c)
        table[static_cast<std::size_t>(r * CarriedStress::kMax + c)] = matrix(r, c);
    return table;
  };
  // The tangent D of a material whose elasticity depends on the stress, condensed like
  // stiffness_ (the assumption is a static object, so the condenser outlives any copy).
  const StiffnessCondenser condense = [&assumption, as_table](const ElasticConstants& elastic) {
    return as_table(assumption.stiffness(elastic));
  };
  integrators_.reserve(materials_.size());
  for (std::size_t m = 0; m < materials_.size(); ++m)
    integrators_.emplace_back(*materials_[m], carried_, as_table(stiffness_[m]), integration_,
                              condense);
}

double DrySolid::wave_speed(std::int32_t material) const {
  // The P-wave modulus of the kinematics: D_xx,xx (E, lambda + 2G or E').
  const int xx = layout_.kinematics().carried_index(0, 0);
  return std::sqrt(stiffness(material)(xx, xx) / density(material));
}

double DrySolid::max_wave_speed() const {
  double speed = 0.0;
  for (std::size_t k = 0; k < materials_.size(); ++k)
    speed = std::max(speed, wave_speed(static_cast<std::int32_t>(k)));
  return speed;
}

std::array<double, 3> DrySolid::in_plane_moduli(std::int32_t material) const {
  const KinematicAssumption& assumption = layout_.kinematics();
  const StiffnessMatrix& d = stiffness(material);
  const int xx = assumption.carried_index(0, 0), yy = assumption.carried_index(1, 1),
            xy = assumption.carried_index(0, 1);
  return {d(xx, xx), yy < 0 ? 0.0 : d(xx, yy), xy < 0 ? 0.0 : d(xy, xy)};
}

double DrySolid::divergence_bound(int field) const {
  // |v| = 10 c_p or |sigma| = 10 M means a strain of about 10 (docs/theory.md §2.5).
  if (field < dimension()) return 10.0 * max_wave_speed();
  double modulus = 0.0;
  for (const auto& material : materials_)
    modulus = std::max(modulus, elastic_stiffness(material->elastic())(0, 0));
  return 10.0 * modulus;
}

double DrySolid::elastic_energy_density(std::int32_t material, const FieldArray& values,
                                        std::size_t i) const {
  const int count = layout_.stress_count();
  double sigma[kMaxStress], gamma[kMaxStress];
  for (int c = 0; c < count; ++c)
    sigma[c] = values(layout_.stress_component(c), i);
  compliance_[static_cast<std::size_t>(material)].multiply(sigma, gamma);
  double energy = 0.0;
  for (int c = 0; c < count; ++c)
    energy += 0.5 * sigma[c] * gamma[c];
  return energy;
}

void DrySolid::strain_rate(const FieldArray& gradient, std::int64_t i, double* strain_rate) const {
  for (int c = 0; c < layout_.stress_count(); ++c) {
    const StrainRateGradients& terms = strain_rate_gradients_[static_cast<std::size_t>(c)];
    double rate = terms.count > 0 ? gradient.field(terms.field[0])[i] : 0.0;
    if (terms.count > 1) rate += gradient.field(terms.field[1])[i];
    strain_rate[c] = rate;
  }
}

template <int Dimension, int StressCount>
void DrySolid::flux_rate_fixed(std::span<const std::int32_t> material, const FieldArray& gradient,
                               FieldArray& rate) const {
  // The same sums, in the same order, as the general loop below (docs/theory.md §1.6).
  const auto n = static_cast<std::int64_t>(material.size());
  const double* divergence[Dimension][Dimension];
  double* velocity_rate[Dimension];
  for (int a = 0; a < Dimension; ++a) {
    velocity_rate[a] = rate.field(layout_.velocity(a));
    for (int b = 0; b < Dimension; ++b)
      divergence[a][b] = gradient.field(
          divergence_gradients_[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)]);
  }
  const double* strain_terms[StressCount][2] = {};
  int strain_term_count[StressCount];
  double* stress_rate[StressCount];
  for (int c = 0; c < StressCount; ++c) {
    const StrainRateGradients& terms = strain_rate_gradients_[static_cast<std::size_t>(c)];
    strain_term_count[c] = terms.count;
    for (int t = 0; t < terms.count; ++t)
      strain_terms[c][t] = gradient.field(terms.field[static_cast<std::size_t>(t)]);
    stress_rate[c] = rate.field(layout_.stress_component(c));
  }
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
  for (std::int64_t i = 0; i < n; ++i) {
    const auto m = static_cast<std::size_t>(material[i]);
    const double density = materials_[m]->density();
    for (int a = 0; a < Dimension; ++a) {
      double sum = divergence[a][0][i];
      for (int b = 1; b < Dimension; ++b)
        sum += divergence[a][b][i];
      velocity_rate[a][i] = sum / density;
    }
    double strain[StressCount];
    for (int c = 0; c < StressCount; ++c) {
      double value = strain_term_count[c] > 0 ? strain_terms[c][0][i] : 0.0;
      if (strain_term_count[c] > 1) value += strain_terms[c][1][i];
      strain[c] = value;
    }
    const StiffnessMatrix& stiffness = stiffness_[m];
    for (int r = 0; r < StressCount; ++r) {
      double sum = stiffness(r, 0) * strain[0];
      for (int c = 1; c < StressCount; ++c)
        sum += stiffness(r, c) * strain[c];
      stress_rate[r][i] = sum;
    }
  }
}

void DrySolid::flux_rate(std::span<const std::int32_t> material, const FieldArray& gradient,
                         FieldArray& rate) const {
  const int d = dimension(), ns = layout_.stress_count();
  if (d == 2 && ns == 4) return flux_rate_fixed<2, 4>(material, gradient, rate);  // plane strain
  if (d == 2 && ns == 3) return flux_rate_fixed<2, 3>(material, gradient, rate);  // plane stress
  if (d == 1 && ns == 1) return flux_rate_fixed<1, 1>(material, gradient, rate);  // 1D bar
  const auto n = static_cast<std::int64_t>(material.size());
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
  for (std::int64_t i = 0; i < n; ++i) {
    const double density = materials_[static_cast<std::size_t>(material[i])]->density();
    for (int a = 0; a < d; ++a) {
      const auto& divergence_terms = divergence_gradients_[static_cast<std::size_t>(a)];
      double divergence = gradient.field(divergence_terms[0])[i];
      for (int b = 1; b < d; ++b)
        divergence += gradient.field(divergence_terms[static_cast<std::size_t>(b)])[i];
      rate.field(layout_.velocity(a))[i] = divergence / density;
    }
    double strain[kMaxStress], stress_rate[kMaxStress];
    strain_rate(gradient, i, strain);
    stiffness_[static_cast<std::size_t>(material[i])].multiply(strain, stress_rate);
    for (int c = 0; c < ns; ++c)
      rate.field(layout_.stress_component(c))[i] = stress_rate[c];
  }
}

void DrySolid::advance_velocities(std::int64_t n, const FieldArray& rate, double time,
                                  double interval, FieldArray& values,
                                  const FieldArray& internal) const {
  // v' = R_v + b(t) - xi(t) v, classical RK4 with sub-steps when xi * interval is large. The loads
  // are the same for every node: evaluated once per sub-step before the node loop, which then
  // does each node's sub-steps in one pass (the arithmetic of a node-by-node evaluation).
  // Points [0, n) of the arrays.
  const int d = dimension();
  const double stiffness = loads_.damping_at(time);
  const int substeps =
      substep_count(interval, stiffness, integration_.substep_factor, integration_.max_substeps);
  const double delta = interval / substeps;
  const bool frozen = integration_.frozen_flux;
  std::vector<SubstepLoads>& loads = substep_loads_;
  if (loads.size() < static_cast<std::size_t>(substeps))
    loads.resize(static_cast<std::size_t>(substeps));
  for (int s = 0; s < substeps; ++s) {
    const double t0 = time + s * delta;
    loads[static_cast<std::size_t>(s)] = {
        {loads_.body_force(t0), loads_.body_force(t0 + 0.5 * delta), loads_.body_force(t0 + delta)},
        {loads_.damping_at(t0), loads_.damping_at(t0 + 0.5 * delta),
         loads_.damping_at(t0 + delta)}};
  }
  if (body_force_weight_ >= 0) {
    advance_weighted_velocities(n, rate, delta, substeps, interval, values, internal);
    return;
  }
  for (int a = 0; a < d; ++a) {
    const auto axis = static_cast<std::size_t>(a);
    double* velocity = values.field(layout_.velocity(a));
    const double* rate_v = rate.field(layout_.velocity(a));
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
    for (std::int64_t i = 0; i < n; ++i) {
      double v = integrate_velocity(velocity[i], frozen ? rate_v[i] : 0.0, loads, substeps, delta,
                                    [axis](const auto& l, int k) { return l.body[k][axis]; });
      if (!frozen) v += interval * rate_v[i];
      velocity[i] = v;
    }
  }
}

void DrySolid::advance_weighted_velocities(std::int64_t n, const FieldArray& rate, double delta,
                                           int substeps, double interval, FieldArray& values,
                                           const FieldArray& internal) const {
  // advance_velocities with the body force of each point scaled by its weights (eq. 6.8): the
  // vertical component by w, and in 2D s times it added along x (a sloping water table's seepage
  // force). The loads of the sub-steps are those advance_velocities evaluated.
  const int d = dimension();
  const auto vertical = static_cast<std::size_t>(d - 1);
  const double* weight = internal.field(body_force_weight_);
  const double* seepage = d == 2 ? internal.field(body_force_weight_ + 1) : nullptr;
  const bool frozen = integration_.frozen_flux;
  const std::vector<SubstepLoads>& loads = substep_loads_;
  for (int a = 0; a < d; ++a) {
    const auto axis = static_cast<std::size_t>(a);
    double* velocity = values.field(layout_.velocity(a));
    const double* rate_v = rate.field(layout_.velocity(a));
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
    for (std::int64_t i = 0; i < n; ++i) {
      // body_a = scale b_a + cross b_y
      const double scale = axis == vertical ? weight[i] : 1.0;
      const double cross = axis == vertical ? 0.0 : seepage[i];
      double v = integrate_velocity(velocity[i], frozen ? rate_v[i] : 0.0, loads, substeps, delta,
                                    [=](const auto& l, int k) {
                                      return scale * l.body[k][axis] + cross * l.body[k][vertical];
                                    });
      if (!frozen) v += interval * rate_v[i];
      velocity[i] = v;
    }
  }
}

void DrySolid::advance(std::span<const std::int32_t> material, const FieldArray& rate, double time,
                       double interval, FieldArray& values, FieldArray& internal,
                       AdvancedFields part) const {
  const auto n = static_cast<std::int64_t>(material.size());
  const int ns = layout_.stress_count();
  const int nk = internal_count_;
  if (part != AdvancedFields::Others) advance_velocities(n, rate, time, interval, values, internal);
  if (part == AdvancedFields::Velocity) return;
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
  for (std::int64_t i = 0; i < n; ++i) {
    const auto material_index = static_cast<std::size_t>(material[i]);

    double sigma[kMaxStress], rate_sigma[kMaxStress], kappa[kMaxInternal] = {};
    for (int c = 0; c < ns; ++c) {
      sigma[c] = values.field(layout_.stress_component(c))[i];
      rate_sigma[c] = rate.field(layout_.stress_component(c))[i];
    }
    for (int c = 0; c < nk; ++c)
      kappa[c] = internal.field(c)[i];
    integrators_[material_index].advance(rate_sigma, interval, sigma, kappa);
    for (int c = 0; c < ns; ++c)
      values.field(layout_.stress_component(c))[i] = sigma[c];
    for (int c = 0; c < nk; ++c)
      internal.field(c)[i] = kappa[c];
  }
}

void DrySolid::normal_strain(const std::array<double, 3>& normal, double* strain) const {
  // n (x) n with engineering shear strains: n_i n_j on the diagonal, 2 n_i n_j off it, so that
  // n . sigma . n is the plain dot product of this strain with the carried stresses.
  for (int c = 0; c < layout_.stress_count(); ++c) {
    const TensorComponent component = layout_.kinematics().stress_component(c);
    strain[c] = carried_.shear_factor[static_cast<std::size_t>(c)] *
                normal[static_cast<std::size_t>(component.i)] *
                normal[static_cast<std::size_t>(component.j)];
  }
}

void DrySolid::project_traction_free_increment(std::int32_t material, const SurfaceNormals& normals,
                                               std::span<const double> start, FieldArray& values,
                                               std::size_t i) const {
  // A normal strain c_r n_r (x) n_r along each unit normal n_r, with c solving
  //   sum_m (n_r (x) n_r : D : n_m (x) n_m) c_m = -n_r . (sigma - sigma_start) . n_r,
  // keeps every normal traction n_r . sigma . n_r at its start value; every carried stress then
  // moves by D : (sum_m c_m n_m (x) n_m) (docs/theory.md eq. 5.1).
  const int count = normals.count;
  if (count == 0) return;
  const int ns = layout_.stress_count();
  double strain[kMaxNormals][kMaxStress], stress[kMaxNormals][kMaxStress];
  for (int r = 0; r < count; ++r) {
    normal_strain(normals.normal[static_cast<std::size_t>(r)], strain[r]);
    stiffness(material).multiply(strain[r], stress[r]);
  }
  auto dot = [ns](const double* a, const double* b) {
    double sum = 0.0;
    for (int c = 0; c < ns; ++c)
      sum += a[c] * b[c];
    return sum;
  };
  double increment[kMaxStress];
  for (int c = 0; c < ns; ++c) {
    const int f = layout_.stress_component(c);
    increment[c] = values(f, i) - start[static_cast<std::size_t>(f)];
  }
  double system[kMaxNormals][kMaxNormals], residual[kMaxNormals], correction[kMaxNormals];
  for (int r = 0; r < count; ++r) {
    residual[r] = -dot(strain[r], increment);
    for (int m = 0; m < count; ++m)
      system[r][m] = dot(strain[r], stress[m]);
  }
  solve_small(system, residual, count, correction);
  for (int c = 0; c < ns; ++c)
    for (int m = 0; m < count; ++m)
      values(layout_.stress_component(c), i) += stress[m][c] * correction[m];
}

void DrySolid::add_artificial_viscosity(std::span<const std::int32_t> material,
                                        const FieldArray& gradient, double alpha_dx,
                                        FieldArray& values) const {
  const auto n = static_cast<std::int64_t>(material.size());
  const int ns = layout_.stress_count();
  const double c = max_wave_speed();
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
  for (std::int64_t i = 0; i < n; ++i) {
    // q = alpha rho c_p dx eps_dot (docs/theory.md §2.7) on every carried component (tensor
    // strain rate, eps = gamma / 2 off the diagonal); c_p of the stiffest material keeps the
    // coefficient uniform across material interfaces.
    const double viscosity =
        alpha_dx * materials_[static_cast<std::size_t>(material[i])]->density() * c;
    double strain[kMaxStress];
    strain_rate(gradient, i, strain);
    for (int k = 0; k < ns; ++k)
      values.field(layout_.stress_component(k))[i] +=
          viscosity * (strain[k] / carried_.shear_factor[static_cast<std::size_t>(k)]);
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
    const std::span<const double> state(kappa, static_cast<std::size_t>(m.internal_count()));
    flowing[i] = m.flows(stress_tensor(values, i), state) ? 1 : m.has_flowed(state) ? 2 : 0;
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
