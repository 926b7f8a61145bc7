// Bishop's simplified method of slices with a phreatic line, and the critical-circle search
// (slope_limit_equilibrium.hpp gives the sources).
//
// Slice equations (Bishop 1955; Duncan & Wright 2005, ch. 6). The slip mass between entry and exit
// is cut into slices of equal width b. For slice i:
//   W_i = ∫ over the slice of ∫ γ(y) dy from the arc up to the ground (γ_sat below the table,
//         γ above it), by two-point Gauss quadrature on each piece between the vertices of the
//         ground and of the table;
//   U_i = ∫ u dx over the slice, u = γ_w max(0, y_w(x) − y_arc(x)): hydrostatic below the
//         phreatic line in the vertical, the usual convention of finite-element codes;
//   sin α_i = ±(x_c − x_mid)/R at the slice's mid-width, the sign chosen so that Σ W sin α > 0:
//         α > 0 where the base descends in the direction of sliding (under the crest), α < 0
//         where it rises (towards the toe).
// Vertical force equilibrium of each slice with the interslice shear neglected, and moment
// equilibrium of the whole mass about the centre, give
//   F = Σ [c' b + (W − U) tan φ'] / m_α  /  Σ W sin α,   m_α = cos α + sin α tan φ' / F,
// solved by fixed-point iteration. Where W − U < 0 (pore pressure exceeding the overburden, which
// a table below the ground only permits on steep bases) the effective normal force is set to
// zero, not negative: that base carries cohesion only. Circles where some m_α < 0.2 at the
// solution are rejected (NaN): the normal force there is unreliable and Bishop's F is known to be
// spuriously low or high; 0.2 is the threshold usually attributed to Whitman & Bailey (1967).
// Ponded water (a table above the ground) would need its weight and thrust on the slope face and
// is not supported: the profile is rejected.
#include "rktsph/validation/references/slope_limit_equilibrium.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace rktsph::references {
namespace slope_le_detail {

using Point = std::array<double, 2>;

constexpr double kSlopeDegree = std::numbers::pi / 180.0;
constexpr double kSlopeNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kSlopeInfinity = std::numeric_limits<double>::infinity();
/// Smallest admissible m_α at the solution.
constexpr double kSlopeMinimumMAlpha = 0.2;

/// Height of a polyline at x; constant beyond its ends (a single vertex is a level line).
double polyline_height(const std::vector<Point>& line, double x) {
  if (x <= line.front()[0]) return line.front()[1];
  if (x >= line.back()[0]) return line.back()[1];
  const auto upper = std::upper_bound(line.begin(), line.end(), x,
                                      [](double value, const Point& p) { return value < p[0]; });
  const Point& a = *(upper - 1);
  const Point& b = *upper;
  return a[1] + (b[1] - a[1]) * (x - a[0]) / (b[0] - a[0]);
}

void check_polyline(const std::vector<Point>& line, std::size_t min_points,
                    const std::string& name) {
  if (line.size() < min_points) {
    throw std::invalid_argument("slope profile: " + name + " needs at least " +
                                std::to_string(min_points) + " vertices");
  }
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (!std::isfinite(line[i][0]) || !std::isfinite(line[i][1])) {
      throw std::invalid_argument("slope profile: " + name + " has a non-finite vertex");
    }
    if (i > 0 && !(line[i][0] > line[i - 1][0])) {
      throw std::invalid_argument("slope profile: " + name + " x must increase strictly");
    }
  }
}

void validate_profile(const SlopeProfile& p) {
  check_polyline(p.ground, 2, "ground");
  if (!std::isfinite(p.base)) throw std::invalid_argument("slope profile: base must be finite");
  for (const Point& v : p.ground) {
    if (v[1] < p.base) throw std::invalid_argument("slope profile: ground below the base");
  }
  if (!(p.unit_weight_above > 0.0) || !std::isfinite(p.unit_weight_above)) {
    throw std::invalid_argument("slope profile: unit_weight_above must be positive");
  }
  if (!(p.cohesion >= 0.0) || !std::isfinite(p.cohesion)) {
    throw std::invalid_argument("slope profile: cohesion must be >= 0");
  }
  if (!(p.friction_angle >= 0.0 && p.friction_angle < 90.0)) {
    throw std::invalid_argument("slope profile: friction angle must lie in [0, 90) degrees");
  }
  if (p.water_table.empty()) return;
  check_polyline(p.water_table, 1, "water table");
  if (!(p.unit_weight_below > 0.0) || !std::isfinite(p.unit_weight_below)) {
    throw std::invalid_argument("slope profile: unit_weight_below must be positive");
  }
  if (!(p.water_unit_weight >= 0.0) || !std::isfinite(p.water_unit_weight)) {
    throw std::invalid_argument("slope profile: water_unit_weight must be >= 0");
  }
  // Both lines are piecewise linear and level beyond their ends, so table − ground is largest at
  // one of their vertices.
  auto check_at = [&](double x) {
    const double ground = polyline_height(p.ground, x);
    if (polyline_height(p.water_table, x) > ground + 1e-9 * (1.0 + std::abs(ground))) {
      throw std::invalid_argument(
          "slope profile: the water table stands above the ground (ponded water is not "
          "supported)");
    }
  };
  for (const Point& v : p.ground)
    check_at(v[0]);
  for (const Point& v : p.water_table)
    check_at(v[0]);
}

/// The x interval where the lower arc of the circle lies below the ground.
struct SlipInterval {
  bool valid = false;
  double entry = 0.0;
  double exit = 0.0;
};

/// Ground minus lower arc: positive inside the slip mass. On each linear piece of the ground it is
/// concave (a line plus a concave root), so its positive part there is one interval whose ends
/// are roots of a quadratic; those intervals, merged over the pieces, must form exactly one arc
/// that ends strictly inside [x_c − R, x_c + R] (ground below the centre at the circle's sides).
SlipInterval slip_interval(const std::vector<Point>& ground, double xc, double yc, double r) {
  const double left = xc - r;
  const double right = xc + r;
  const double tiny = 1e-12 * (r + std::abs(xc));
  auto gap = [&](double x) {
    const double dx = x - xc;
    return polyline_height(ground, x) - (yc - std::sqrt(std::max(0.0, r * r - dx * dx)));
  };
  // Pieces: level before the first vertex, the segments, level after the last vertex.
  std::vector<double> cuts{left};
  for (const Point& v : ground) {
    if (v[0] > left && v[0] < right) cuts.push_back(v[0]);
  }
  cuts.push_back(right);
  std::vector<std::array<double, 2>> positive;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double p = cuts[k];
    const double q = cuts[k + 1];
    if (!(q > p)) continue;
    const double mid = 0.5 * (p + q);
    const double slope = (polyline_height(ground, q) - polyline_height(ground, p)) / (q - p);
    const double at_centre = polyline_height(ground, mid) + slope * (xc - mid);
    // With u = x − x_c and h = y_c − (line at x_c): R² − u² = (h − s u)², h − s u >= 0.
    const double h = yc - at_centre;
    const double a = 1.0 + slope * slope;
    const double disc = a * r * r - h * h;
    std::vector<double> points{p};
    if (disc >= 0.0) {
      const double root = std::sqrt(disc);
      for (const double u : {(h * slope - root) / a, (h * slope + root) / a}) {
        const double x = xc + u;
        if (h - slope * u >= 0.0 && x > p && x < q) points.push_back(x);
      }
    }
    points.push_back(q);
    std::sort(points.begin(), points.end());
    for (std::size_t j = 0; j + 1 < points.size(); ++j) {
      const double lo = points[j];
      const double hi = points[j + 1];
      if (hi - lo <= tiny || gap(0.5 * (lo + hi)) <= 0.0) continue;
      if (!positive.empty() && lo <= positive.back()[1] + tiny) {
        positive.back()[1] = hi;
      } else {
        positive.push_back({lo, hi});
      }
    }
  }
  SlipInterval result;
  if (positive.size() != 1) return result;
  if (positive[0][0] <= left + tiny || positive[0][1] >= right - tiny) return result;
  result.valid = true;
  result.entry = positive[0][0];
  result.exit = positive[0][1];
  return result;
}

struct CircleEvaluation {
  double factor = kSlopeNaN;
  double entry = kSlopeNaN;
  double exit = kSlopeNaN;
  double depth = 0.0;  ///< greatest vertical thickness of the slip mass (at quadrature points)
};

/// Bishop's simplified F of one circle, with the slip mass's extent and depth.
CircleEvaluation evaluate_circle(const SlopeProfile& p, double xc, double yc, double r,
                                 int slices) {
  CircleEvaluation out;
  const SlipInterval arc = slip_interval(p.ground, xc, yc, r);
  if (!arc.valid) return out;
  out.entry = arc.entry;
  out.exit = arc.exit;
  // The arc is lowest either at x_c or, when x_c is outside the mass, at an end on the ground
  // (which is not below the base).
  if (xc > arc.entry && xc < arc.exit && yc - r < p.base - 1e-9 * (1.0 + std::abs(p.base))) {
    return out;
  }

  const bool wet = !p.water_table.empty();
  std::vector<double> kinks;
  for (const Point& v : p.ground) {
    if (v[0] > arc.entry && v[0] < arc.exit) kinks.push_back(v[0]);
  }
  if (wet) {
    for (const Point& v : p.water_table) {
      if (v[0] > arc.entry && v[0] < arc.exit) kinks.push_back(v[0]);
    }
  }
  std::sort(kinks.begin(), kinks.end());

  // Weight per unit width and pore pressure at x; updates the depth.
  auto column = [&](double x, double& weight, double& pore) {
    const double dx = x - xc;
    const double y_arc = yc - std::sqrt(std::max(0.0, r * r - dx * dx));
    const double y_ground = polyline_height(p.ground, x);
    weight = 0.0;
    pore = 0.0;
    if (y_ground <= y_arc) return;
    out.depth = std::max(out.depth, y_ground - y_arc);
    if (!wet) {
      weight = p.unit_weight_above * (y_ground - y_arc);
      return;
    }
    const double y_water = polyline_height(p.water_table, x);
    const double wet_top = std::clamp(y_water, y_arc, y_ground);
    weight = p.unit_weight_below * (wet_top - y_arc) + p.unit_weight_above * (y_ground - wet_top);
    pore = p.water_unit_weight * std::max(0.0, y_water - y_arc);
  };

  const double width = (arc.exit - arc.entry) / slices;
  std::vector<double> weights(slices);
  std::vector<double> pores(slices);
  std::vector<double> sines(slices);
  std::size_t next_kink = 0;
  double moment = 0.0;
  double total_weight = 0.0;
  for (int i = 0; i < slices; ++i) {
    const double a = arc.entry + width * i;
    const double b = i + 1 == slices ? arc.exit : arc.entry + width * (i + 1);
    double lo = a;
    double slice_weight = 0.0;
    double slice_pore = 0.0;
    while (lo < b) {
      double hi = b;
      if (next_kink < kinks.size() && kinks[next_kink] < b) hi = kinks[next_kink++];
      const double mid = 0.5 * (lo + hi);
      const double half = 0.5 * (hi - lo);
      const double offset = half / std::numbers::sqrt3;  // two-point Gauss-Legendre abscissae
      for (const double x : {mid - offset, mid + offset}) {
        double w = 0.0;
        double u = 0.0;
        column(x, w, u);
        slice_weight += half * w;
        slice_pore += half * u;
      }
      lo = hi;
    }
    weights[i] = slice_weight;
    pores[i] = slice_pore;
    sines[i] = std::clamp((xc - 0.5 * (a + b)) / r, -1.0, 1.0);
    moment += slice_weight * sines[i];
    total_weight += slice_weight;
  }
  if (!(std::abs(moment) > 1e-12 * total_weight)) return out;
  const double sense = moment > 0.0 ? 1.0 : -1.0;
  const double driving = std::abs(moment);

  const double tan_phi = std::tan(p.friction_angle * kSlopeDegree);
  std::vector<double> resisting(slices);
  double lowest_factor = 0.0;  // below it some m_α with α < 0 would fall under the threshold
  for (int i = 0; i < slices; ++i) {
    sines[i] *= sense;
    const double cosine = std::sqrt(std::max(0.0, 1.0 - sines[i] * sines[i]));
    resisting[i] = p.cohesion * width + std::max(0.0, weights[i] - pores[i]) * tan_phi;
    if (sines[i] < 0.0 && tan_phi > 0.0) {
      if (cosine <= kSlopeMinimumMAlpha) return out;
      lowest_factor = std::max(lowest_factor, -sines[i] * tan_phi / (cosine - kSlopeMinimumMAlpha));
    }
  }
  auto m_alpha = [&](int i, double factor) {
    const double cosine = std::sqrt(std::max(0.0, 1.0 - sines[i] * sines[i]));
    return cosine + sines[i] * tan_phi / factor;
  };
  auto update = [&](double factor) {
    double sum = 0.0;
    for (int i = 0; i < slices; ++i)
      sum += resisting[i] / m_alpha(i, factor);
    return sum / driving;
  };

  // The iterate is kept above lowest_factor so that every m_α stays positive; a solution at or
  // below it has some m_α <= 0.2 and is rejected.
  double factor = std::max(1.0, 1.01 * lowest_factor);
  bool converged = false;
  for (int iteration = 0; iteration < 500; ++iteration) {
    double next = update(factor);
    if (!(next > 0.0)) {
      // No resistance at all (c' = 0 and no effective normal force anywhere).
      out.factor = 0.0;
      return out;
    }
    if (lowest_factor > 0.0) next = std::max(next, lowest_factor * (1.0 + 1e-9));
    const bool small_step = std::abs(next - factor) <= 1e-12 * next;
    factor = next;
    if (small_step) {
      converged = true;
      break;
    }
  }
  if (!converged) return out;
  for (int i = 0; i < slices; ++i) {
    if (m_alpha(i, factor) < kSlopeMinimumMAlpha) return out;
  }
  out.factor = factor;
  return out;
}

using Simplex3 = std::array<std::array<double, 3>, 4>;

/// Nelder & Mead (1965) downhill simplex in three variables, standard coefficients (reflection 1,
/// expansion 2, contraction 1/2, shrink 1/2). Infeasible points have value +inf, which the
/// comparisons handle. Stops when the simplex is smaller than `size` or after `max_evaluations`.
template <class Objective>
std::array<double, 3> nelder_mead_3(Objective&& objective, const std::array<double, 3>& start,
                                    double step, double size, int max_evaluations, double& best) {
  Simplex3 vertex;
  std::array<double, 4> value;
  for (int k = 0; k < 4; ++k) {
    vertex[k] = start;
    if (k > 0) vertex[k][k - 1] += step;
    value[k] = objective(vertex[k]);
  }
  int evaluations = 4;
  auto point = [](const std::array<double, 3>& from, const std::array<double, 3>& towards,
                  double t) {
    std::array<double, 3> result;
    for (int d = 0; d < 3; ++d)
      result[d] = from[d] + t * (towards[d] - from[d]);
    return result;
  };
  while (evaluations < max_evaluations) {
    std::array<int, 4> order{0, 1, 2, 3};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return value[a] < value[b]; });
    Simplex3 sorted_vertex;
    std::array<double, 4> sorted_value;
    for (int k = 0; k < 4; ++k) {
      sorted_vertex[k] = vertex[order[k]];
      sorted_value[k] = value[order[k]];
    }
    vertex = sorted_vertex;
    value = sorted_value;
    double extent = 0.0;
    for (int k = 1; k < 4; ++k) {
      for (int d = 0; d < 3; ++d)
        extent = std::max(extent, std::abs(vertex[k][d] - vertex[0][d]));
    }
    if (extent < size) break;
    std::array<double, 3> centroid{0.0, 0.0, 0.0};
    for (int k = 0; k < 3; ++k) {
      for (int d = 0; d < 3; ++d)
        centroid[d] += vertex[k][d] / 3.0;
    }
    const std::array<double, 3> reflected = point(centroid, vertex[3], -1.0);
    const double f_reflected = objective(reflected);
    ++evaluations;
    if (f_reflected < value[0]) {
      const std::array<double, 3> expanded = point(centroid, vertex[3], -2.0);
      const double f_expanded = objective(expanded);
      ++evaluations;
      if (f_expanded < f_reflected) {
        vertex[3] = expanded;
        value[3] = f_expanded;
      } else {
        vertex[3] = reflected;
        value[3] = f_reflected;
      }
      continue;
    }
    if (f_reflected < value[2]) {
      vertex[3] = reflected;
      value[3] = f_reflected;
      continue;
    }
    const bool outside = f_reflected < value[3];
    const std::array<double, 3> contracted =
        outside ? point(centroid, reflected, 0.5) : point(centroid, vertex[3], 0.5);
    const double f_contracted = objective(contracted);
    ++evaluations;
    if (f_contracted < (outside ? f_reflected : value[3])) {
      vertex[3] = contracted;
      value[3] = f_contracted;
      continue;
    }
    for (int k = 1; k < 4; ++k) {
      vertex[k] = point(vertex[0], vertex[k], 0.5);
      value[k] = objective(vertex[k]);
      ++evaluations;
    }
  }
  int best_index = 0;
  for (int k = 1; k < 4; ++k) {
    if (value[k] < value[best_index]) best_index = k;
  }
  best = value[best_index];
  return vertex[best_index];
}

}  // namespace slope_le_detail

double bishop_factor(const SlopeProfile& profile, double centre_x, double centre_y, double radius,
                     int slices) {
  slope_le_detail::validate_profile(profile);
  if (!(radius > 0.0) || !std::isfinite(radius) || !std::isfinite(centre_x) ||
      !std::isfinite(centre_y)) {
    throw std::invalid_argument("bishop_factor: the circle must be finite with radius > 0");
  }
  if (slices < 1) throw std::invalid_argument("bishop_factor: slices must be >= 1");
  return slope_le_detail::evaluate_circle(profile, centre_x, centre_y, radius, slices).factor;
}

SlipCircle critical_bishop_circle(const SlopeProfile& profile) {
  using slope_le_detail::evaluate_circle;
  using slope_le_detail::kSlopeInfinity;
  slope_le_detail::validate_profile(profile);
  const auto& ground = profile.ground;

  // Extent of the sloping part of the ground and the slope height.
  double y_min = ground.front()[1];
  double y_max = ground.front()[1];
  double x_first = kSlopeInfinity;
  double x_last = -kSlopeInfinity;
  for (std::size_t i = 0; i < ground.size(); ++i) {
    y_min = std::min(y_min, ground[i][1]);
    y_max = std::max(y_max, ground[i][1]);
    if (i > 0 && ground[i][1] != ground[i - 1][1]) {
      x_first = std::min(x_first, ground[i - 1][0]);
      x_last = std::max(x_last, ground[i][0]);
    }
  }
  if (!(y_max > y_min)) throw std::invalid_argument("critical_bishop_circle: the ground is level");
  const double height = y_max - y_min;
  const double scale = std::max(height, x_last - x_first);
  const double min_depth = kMinimumSlipDepthFraction * height;

  // Objective over (x_c, y_c, R). A radius reaching below the base is cut back to the circle
  // tangent to it: the arc can only pass below the base at its lowest point (x_c, y_c − R), since
  // its ends lie on the ground, so the cut-back circle is the nearest admissible one. This turns
  // the base constraint into a flat region the simplex can slide along.
  auto objective = [&](const std::array<double, 3>& v, int slices) {
    const double r = std::min(v[2], v[1] - profile.base);
    if (!(r > 0.0)) return kSlopeInfinity;
    const auto e = evaluate_circle(profile, v[0], v[1], r, slices);
    if (!std::isfinite(e.factor) || e.depth < min_depth) return kSlopeInfinity;
    return e.factor;
  };

  // Coarse search (60 slices, F within ~1e-3): centres on a 21 x 21 grid over the box from half
  // the scale before the sloping part to half the scale after it, and from the toe level to two
  // scales above the crest (where the critical centres of the usual slopes lie: Bishop &
  // Morgenstern 1960 and Duncan & Wright 2005 place them above the face, higher for flatter
  // slopes); for each centre 12 circles whose lowest points are spaced evenly from the base up to
  // just below the crest, i.e. from the deepest admissible circle to shallow ones.
  struct Candidate {
    std::array<double, 3> v;
    double factor;
  };
  std::vector<Candidate> candidates;
  constexpr int kCentres = 21;
  constexpr int kDepths = 12;
  for (int i = 0; i < kCentres; ++i) {
    const double xc = x_first - 0.5 * scale + (x_last - x_first + scale) * i / (kCentres - 1);
    for (int j = 0; j < kCentres; ++j) {
      const double yc = y_min + (height + 2.0 * scale) * j / (kCentres - 1);
      for (int k = 0; k < kDepths; ++k) {
        const double lowest = profile.base + (y_max - profile.base) * k / kDepths;
        const std::array<double, 3> v{xc, yc, yc - lowest};
        const double f = objective(v, 60);
        if (std::isfinite(f)) candidates.push_back({v, f});
      }
    }
  }
  if (candidates.empty()) {
    throw std::invalid_argument("critical_bishop_circle: no admissible circle found");
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.factor < b.factor; });

  // Refinement: Nelder-Mead with the full slice count from the best four mutually distinct grid
  // circles (distinct: more than a tenth of the scale apart), each restarted once from its result
  // since a collapsed simplex can stall on the slightly rough surface F(x_c, y_c, R).
  auto fine = [&](const std::array<double, 3>& v) { return objective(v, kBishopDefaultSlices); };
  std::vector<std::array<double, 3>> starts;
  for (const Candidate& c : candidates) {
    bool distinct = true;
    for (const auto& s : starts) {
      const double d = std::hypot(c.v[0] - s[0], c.v[1] - s[1], c.v[2] - s[2]);
      if (d < 0.1 * scale) distinct = false;
    }
    if (distinct) starts.push_back(c.v);
    if (starts.size() == 4) break;
  }
  std::array<double, 3> best_v = candidates.front().v;
  double best_f = fine(best_v);
  for (const auto& s : starts) {
    double f = kSlopeInfinity;
    auto v = slope_le_detail::nelder_mead_3(fine, s, 0.05 * scale, 1e-6 * scale, 600, f);
    v = slope_le_detail::nelder_mead_3(fine, v, 0.01 * scale, 1e-7 * scale, 400, f);
    if (f < best_f) {
      best_f = f;
      best_v = v;
    }
  }

  const double r = std::min(best_v[2], best_v[1] - profile.base);
  const auto e = evaluate_circle(profile, best_v[0], best_v[1], r, kBishopDefaultSlices);
  SlipCircle circle;
  circle.centre_x = best_v[0];
  circle.centre_y = best_v[1];
  circle.radius = r;
  circle.entry_x = e.entry;
  circle.exit_x = e.exit;
  circle.factor = e.factor;
  return circle;
}

}  // namespace rktsph::references
