#include "rktsph/boundary/surface_traction.hpp"

namespace rktsph {

namespace {
bool imposes(const TractionCondition& condition, int c) {
  return (condition.components >> c) & 1u;
}

/// sigma_ac = sign t_c: the lattice face's assignment, exact (no product with a 0 component).
void impose_on_axis(const TractionCondition& condition, const AxisNormal& n, int dimension,
                    StressTensor& sigma) {
  const auto a = static_cast<std::size_t>(n.axis);
  for (int c = 0; c < dimension; ++c) {
    if (!imposes(condition, c)) continue;
    const auto k = static_cast<std::size_t>(c);
    double value = n.sign * condition.traction[k];
    if (condition.biot_pore_pressure && k == a) value += *condition.biot_pore_pressure;
    sigma[a][k] = value;
    sigma[k][a] = value;
  }
}

/// Eq. 5.1a: with Delta = t - sigma·n on the imposed components (0 on the others),
/// sigma += Delta n^T + n Delta^T - (n·Delta) n n^T changes sigma·n by exactly Delta and leaves
/// u·sigma·w unchanged for tangents u, w: in the frame (n, tangents) it sets sigma_nn and sigma_nt
/// and keeps sigma_tt.
void impose_on_any_normal(const TractionCondition& condition, int dimension, StressTensor& sigma) {
  const Vec3& n = condition.normal;
  const auto d = static_cast<std::size_t>(dimension);
  Vec3 change{};
  for (std::size_t c = 0; c < d; ++c) {
    if (!imposes(condition, static_cast<int>(c))) continue;
    double sigma_n = 0.0;
    for (std::size_t b = 0; b < d; ++b)
      sigma_n += sigma[c][b] * n[b];
    double target = condition.traction[c];
    if (condition.biot_pore_pressure) target += *condition.biot_pore_pressure * n[c];
    change[c] = target - sigma_n;
  }
  double normal_change = 0.0;
  for (std::size_t c = 0; c < d; ++c)
    normal_change += n[c] * change[c];
  for (std::size_t a = 0; a < d; ++a)
    for (std::size_t c = 0; c < d; ++c)
      sigma[a][c] += change[a] * n[c] + n[a] * change[c] - normal_change * n[a] * n[c];
}
}  // namespace

std::optional<AxisNormal> as_axis_normal(const Vec3& n) {
  for (std::size_t a = 0; a < 3; ++a) {
    if (n[a] != 1.0 && n[a] != -1.0) continue;
    return AxisNormal{static_cast<int>(a), n[a]};
  }
  return std::nullopt;
}

void impose_traction(const TractionCondition& condition, int dimension, StressTensor& sigma) {
  if (const auto axis = as_axis_normal(condition.normal))
    impose_on_axis(condition, *axis, dimension, sigma);
  else
    impose_on_any_normal(condition, dimension, sigma);
}

}  // namespace rktsph
