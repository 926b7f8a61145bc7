#include "rktsph/physics/kinematics/elastic_stiffness.hpp"

namespace rktsph {

StiffnessMatrix elastic_stiffness(const ElasticConstants& elastic) {
  const double lambda = elastic.lame_lambda(), shear = elastic.shear_modulus();
  StiffnessMatrix stiffness(StiffnessMatrix::kMax);
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b)
      stiffness(a, b) = lambda;
    stiffness(a, a) = lambda + 2.0 * shear;
    stiffness(3 + a, 3 + a) = shear;
  }
  return stiffness;
}

StiffnessMatrix condensed_stiffness(const StiffnessMatrix& full, std::span<const int> kept,
                                    std::span<const int> stress_free) {
  // Eliminating a stress-free component f: sigma_f = 0 gives gamma_f = -sum_b D_fb gamma_b / D_ff,
  // so D_ab -> D_ab - D_af D_fb / D_ff on the others.
  StiffnessMatrix reduced = full;
  for (const int f : stress_free)
    for (int a = 0; a < full.size(); ++a)
      for (int b = 0; b < full.size(); ++b)
        if (a != f && b != f) reduced(a, b) -= reduced(a, f) * reduced(f, b) / reduced(f, f);
  StiffnessMatrix result(static_cast<int>(kept.size()));
  for (std::size_t r = 0; r < kept.size(); ++r)
    for (std::size_t c = 0; c < kept.size(); ++c)
      result(static_cast<int>(r), static_cast<int>(c)) = reduced(kept[r], kept[c]);
  return result;
}

StiffnessMatrix compliance(const StiffnessMatrix& stiffness) {
  const int n = stiffness.size();
  StiffnessMatrix a = stiffness;
  StiffnessMatrix inverse(n);
  for (int r = 0; r < n; ++r)
    inverse(r, r) = 1.0;
  for (int p = 0; p < n; ++p) {
    const double pivot = a(p, p);
    for (int c = 0; c < n; ++c) {
      a(p, c) /= pivot;
      inverse(p, c) /= pivot;
    }
    for (int r = 0; r < n; ++r) {
      if (r == p) continue;
      const double factor = a(r, p);
      for (int c = 0; c < n; ++c) {
        a(r, c) -= factor * a(p, c);
        inverse(r, c) -= factor * inverse(p, c);
      }
    }
  }
  return inverse;
}

}  // namespace rktsph
