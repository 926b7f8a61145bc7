#include "rktsph/stabilisation/strain_hourglass_stiffness.hpp"

#include <algorithm>
#include <numeric>

#include "rktsph/core/parallel.hpp"
#include "rktsph/physics/physics_model.hpp"

namespace rktsph {

namespace {
// The order of the 2D strain components held per point.
constexpr int kStrainXX = 0, kStrainYY = 1, kStrainXY = 2;
}  // namespace

StrainHourglassStiffness::StrainHourglassStiffness(
    const PhysicsModel& model, const WeightTable& to_points, std::span<const double> point_volume,
    std::span<const std::uint8_t> mirror_axes,
    std::span<const std::pair<std::int32_t, int>> constrained,
    std::span<const std::int32_t> node_material, const NodeSets& nodes, double epsilon,
    StrainControl form) {
  if (model.dimension() != 2 || !(epsilon > 0.0)) return;
  epsilon_ = epsilon;
  form_ = form;
  displacement_parity_ = {vector_parity(0), vector_parity(1)};
  strain_parity_ = {tensor_parity(0, 0), tensor_parity(1, 1), tensor_parity(0, 1)};
  stress_field_ = {model.stress_field(0, 0), model.stress_field(1, 1), model.stress_field(0, 1)};
  const std::size_t points = to_points.rows();
  gradient_ = FieldArray(4, points);
  strain_ = FieldArray(3, points);
  point_strain_ = FieldArray(3, points);
  // Only the four velocity-gradient slots are ever written (add_stress); the others stay zero.
  model_gradient_ = FieldArray(model.field_count() * 2, points);
  rate_ = FieldArray(model.field_count(), points);
  if (form == StrainControl::Patch) {
    patch_fit_ =
        PatchFit(nodes.cells, nodes.sph_nodes, nodes.stress_points, mirror_axes, strain_parity_);
    return;
  }
  const std::size_t node_count = mirror_axes.size();
  std::vector<std::int32_t> targets(node_count);
  std::iota(targets.begin(), targets.end(), 0);
  const std::vector<std::int32_t> no_own_value(node_count, -1);
  node_average_ = build_adjoint_operator(to_points, point_volume, targets, no_own_value);
  for (std::size_t n = 0; n < node_count; ++n)
    if (mirror_axes[n] != 0) {
      mirror_nodes_.push_back(static_cast<std::int32_t>(n));
      mirror_bits_.push_back(mirror_axes[n]);
    }
  std::vector<std::int32_t> slot(node_count, -1);
  for (const auto& [node, field] : constrained) {
    const auto k = std::find(stress_field_.begin(), stress_field_.end(), field);
    if (k == stress_field_.end()) continue;  // sigma_zz: no in-plane strain of its own
    if (slot[static_cast<std::size_t>(node)] < 0) {
      slot[static_cast<std::size_t>(node)] = static_cast<std::int32_t>(constrained_.size());
      ConstrainedNode rule;
      rule.node = node;
      rule.moduli = model.in_plane_moduli(node_material[static_cast<std::size_t>(node)]);
      constrained_.push_back(rule);
    }
    constrained_[static_cast<std::size_t>(slot[static_cast<std::size_t>(node)])]
        .imposed[static_cast<std::size_t>(k - stress_field_.begin())] = true;
  }
  node_strain_ = FieldArray(3, node_count);
}

void StrainHourglassStiffness::set_reference(const FieldArray& fields) {
  for (ConstrainedNode& rule : constrained_)
    for (int k = 0; k < 3; ++k)
      rule.reference[static_cast<std::size_t>(k)] =
          fields(stress_field_[static_cast<std::size_t>(k)], static_cast<std::size_t>(rule.node));
}

void StrainHourglassStiffness::apply_face_rule(const ConstrainedNode& rule,
                                               const FieldArray* fields, bool transpose) {
  // Eq. 3.8: the strain the nodal stress received where sigma_ij is imposed is the one that gives
  // the imposed increment, sigma_aa = M' e_aa + lambda' e_bb, sigma_xy = 2G e_xy. Strains
  // (transpose = false) get that affine map; stresses (transpose = true) the transpose of its
  // linear part, in the pairing tau : r = tau_xx r_xx + tau_yy r_yy + 2 tau_xy r_xy.
  const auto n = static_cast<std::size_t>(rule.node);
  const double modulus = rule.moduli[0], lambda = rule.moduli[1], shear = rule.moduli[2];
  double* xx = node_strain_.field(kStrainXX);
  double* yy = node_strain_.field(kStrainYY);
  double* xy = node_strain_.field(kStrainXY);
  auto increment = [&](int k) {
    return (*fields)(stress_field_[static_cast<std::size_t>(k)], n) -
           rule.reference[static_cast<std::size_t>(k)];
  };
  double* normal[2] = {xx, yy};
  const bool fix_xx = rule.imposed[kStrainXX], fix_yy = rule.imposed[kStrainYY];
  if (rule.imposed[kStrainXY]) xy[n] = transpose ? 0.0 : increment(kStrainXY) / (2.0 * shear);
  if (fix_xx && fix_yy) {
    if (transpose) {
      xx[n] = yy[n] = 0.0;
    } else {
      const double det = modulus * modulus - lambda * lambda;
      const double sxx = increment(kStrainXX), syy = increment(kStrainYY);
      xx[n] = (modulus * sxx - lambda * syy) / det;
      yy[n] = (modulus * syy - lambda * sxx) / det;
    }
  } else if (fix_xx || fix_yy) {
    const int a = fix_xx ? kStrainXX : kStrainYY;  // the imposed normal component
    double* imposed = normal[a];
    double* free = normal[1 - a];
    if (transpose) {
      free[n] -= lambda / modulus * imposed[n];
      imposed[n] = 0.0;
    } else {
      imposed[n] = (increment(a) - lambda * free[n]) / modulus;
    }
  }
}

void StrainHourglassStiffness::average_to_nodes(const FieldArray& x) {
  std::fill(node_strain_.data().begin(), node_strain_.data().end(), 0.0);
  add_adjoint_interpolation(node_average_, x, strain_parity_, every_, node_strain_);
  for (std::size_t k = 0; k < mirror_nodes_.size(); ++k)  // odd across the plane: zero there
    for (std::size_t f = 0; f < 3; ++f)
      if ((strain_parity_[f] & mirror_bits_[k]) != 0)
        node_strain_.field(static_cast<int>(f))[mirror_nodes_[k]] = 0.0;
}

void StrainHourglassStiffness::remove_received_stress(const WeightTable& to_points, FieldArray& x) {
  average_to_nodes(x);
  for (const ConstrainedNode& rule : constrained_)
    apply_face_rule(rule, nullptr, true);
  apply_operator(to_points, node_strain_, strain_parity_, &point_strain_, nullptr);
  std::vector<double>& values = x.data();
  const std::vector<double>& received = point_strain_.data();
  const auto count = static_cast<std::int64_t>(values.size());
#pragma omp parallel for schedule(static) if (count > kParallelThreshold)
  for (std::int64_t k = 0; k < count; ++k)
    values[static_cast<std::size_t>(k)] -= received[static_cast<std::size_t>(k)];
}

void StrainHourglassStiffness::symmetric_part(const FieldArray& gradient,
                                              const std::array<int, 4>& slot) {
  // slot: the xx, xy, yx, yy entries of the gradient.
  const std::size_t points = strain_.point_count();
  for (std::size_t i = 0; i < points; ++i) {
    strain_(kStrainXX, i) = gradient(slot[0], i);
    strain_(kStrainYY, i) = gradient(slot[3], i);
    strain_(kStrainXY, i) = 0.5 * (gradient(slot[1], i) + gradient(slot[2], i));
  }
}

void StrainHourglassStiffness::subtract_interpolated_node_strain(const WeightTable& to_points) {
  apply_operator(to_points, node_strain_, strain_parity_, &point_strain_, nullptr);
  for (std::size_t k = 0; k < strain_.data().size(); ++k)
    strain_.data()[k] -= point_strain_.data()[k];
}

void StrainHourglassStiffness::elastic_stress_of_strain(const PhysicsModel& model,
                                                        std::span<const std::int32_t> material) {
  // tau = epsilon D : r, the model's stress rate for the "velocity gradient" epsilon r.
  const int vx = model.velocity_field(0), vy = model.velocity_field(1);
  const std::size_t points = strain_.point_count();
  for (std::size_t i = 0; i < points; ++i) {
    model_gradient_(vx * 2 + 0, i) = epsilon_ * strain_(kStrainXX, i);
    model_gradient_(vy * 2 + 1, i) = epsilon_ * strain_(kStrainYY, i);
    model_gradient_(vx * 2 + 1, i) = epsilon_ * strain_(kStrainXY, i);
    model_gradient_(vy * 2 + 0, i) = epsilon_ * strain_(kStrainXY, i);
  }
  model.flux_rate(material, model_gradient_, rate_);
  for (int k = 0; k < 3; ++k)
    std::copy_n(rate_.field(stress_field_[static_cast<std::size_t>(k)]), points, strain_.field(k));
}

void StrainHourglassStiffness::add_to(FieldArray& point_values) const {
  const std::size_t points = strain_.point_count();
  for (int k = 0; k < 3; ++k) {
    const double* tau = strain_.field(k);
    double* value = point_values.field(stress_field_[static_cast<std::size_t>(k)]);
    for (std::size_t p = 0; p < points; ++p)
      value[p] += tau[p];
  }
}

void StrainHourglassStiffness::add_stress(const PhysicsModel& model, const WeightTable& to_points,
                                          std::span<const std::int32_t> point_material,
                                          const FieldArray& displacement, const FieldArray& strain,
                                          const FieldArray& point_gradient, double dt,
                                          const FieldArray& fields, std::span<const double> factor,
                                          FieldArray& point_values) {
  if (!active()) return;
  if (form_ == StrainControl::Patch) {
    add_patch_stress(model, to_points, point_material, displacement, factor, point_values);
    return;
  }
  const int vx = model.velocity_field(0), vy = model.velocity_field(1);
  // e^{n+1/2} = e^n + dt/2 A(G v^n): the strain the nodal stress has received, half a step on.
  symmetric_part(point_gradient, {vx * 2, vx * 2 + 1, vy * 2, vy * 2 + 1});
  average_to_nodes(strain_);
  const std::vector<double>& integral = strain.data();
  std::vector<double>& received = node_strain_.data();
  for (std::size_t k = 0; k < received.size(); ++k)
    received[k] = integral[k] + 0.5 * dt * received[k];
  for (const ConstrainedNode& rule : constrained_)
    apply_face_rule(rule, &fields, false);
  // r = G u^{n+1/2} - I P(e^{n+1/2}) (eq. 3.5).
  apply_operator(to_points, displacement, displacement_parity_, nullptr, &gradient_);
  symmetric_part(gradient_, {0, 1, 2, 3});
  subtract_interpolated_node_strain(to_points);
  elastic_stress_of_strain(model, point_material);
  remove_received_stress(to_points, strain_);  // eq. 3.6
  add_to(point_values);
}

void StrainHourglassStiffness::add_patch_stress(const PhysicsModel& model,
                                                const WeightTable& to_points,
                                                std::span<const std::int32_t> point_material,
                                                const FieldArray& displacement,
                                                std::span<const double> factor,
                                                FieldArray& point_values) {
  // Eq. 3.12: r = the residual of G u's patch fits (eq. 3.13); tau = beta D : r is the gradient
  // of the patch energy as it stands, since a fit's residual is orthogonal to what it fits.
  apply_operator(to_points, displacement, displacement_parity_, nullptr, &gradient_);
  symmetric_part(gradient_, {0, 1, 2, 3});
  patch_fit_.residual(strain_, point_strain_);
  std::swap(strain_, point_strain_);
  elastic_stress_of_strain(model, point_material);
  // Eq. 3.14: each cell's share follows the flow around it, so that the control does not hold a
  // mechanism (a factor per stress point on tau, as eq. 3.9 scales the lattice's cells).
  for (std::size_t p = 0; p < factor.size(); ++p)
    for (int k = 0; k < 3; ++k)
      strain_(k, p) *= factor[p];
  add_to(point_values);
}

void StrainHourglassStiffness::integrate_strain(const PhysicsModel& model,
                                                const FieldArray& node_gradient, double dt,
                                                FieldArray& strain) const {
  if (!needs_received_strain()) return;
  const int vx = model.velocity_field(0), vy = model.velocity_field(1);
  const std::size_t nodes = strain.point_count();
  for (std::size_t i = 0; i < nodes; ++i) {
    strain(kStrainXX, i) += dt * node_gradient(vx * 2, i);
    strain(kStrainYY, i) += dt * node_gradient(vy * 2 + 1, i);
    strain(kStrainXY, i) += 0.5 * dt * (node_gradient(vx * 2 + 1, i) + node_gradient(vy * 2, i));
  }
}

}  // namespace rktsph
