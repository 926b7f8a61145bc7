#include "rktsph/validation/references/viscoplastic_bar.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace rktsph::references {
namespace {

void require(bool condition, const char* message) {
  if (!condition) throw std::invalid_argument(message);
}

}  // namespace

ViscoplasticBar::ViscoplasticBar(ViscoplasticBarParameters parameters)
    : parameters_(std::move(parameters)) {
  const ViscoplasticBarParameters& p = parameters_;
  require(p.length > 0.0 && p.young_modulus > 0.0 && p.density > 0.0,
          "ViscoplasticBar: length, Young's modulus and density must be > 0");
  require(p.initial_yield_stress > 0.0 && p.fluidity > 0.0 && p.exponent > 0.0,
          "ViscoplasticBar: initial yield stress, fluidity and exponent must be > 0");
  require(p.residual_yield_fraction > 0.0 && p.residual_yield_fraction <= 1.0,
          "ViscoplasticBar: residual_yield_fraction must be in (0, 1]");
  require(p.cells >= 2, "ViscoplasticBar: at least 2 cells");
  require(static_cast<bool>(p.right_velocity), "ViscoplasticBar: right_velocity is missing");
  const bool rollers = p.section == ViscoplasticBarParameters::Section::PlaneStressLateralRollers;
  require(!rollers || (p.poisson_ratio >= 0.0 && p.poisson_ratio < 0.5),
          "ViscoplasticBar: with lateral rollers the Poisson ratio must be in [0, 0.5)");
  require(!rollers || p.left_end == ViscoplasticBarParameters::LeftEnd::Fixed,
          "ViscoplasticBar: with lateral rollers the left end must be fixed");

  // The modulus of the long wave: E in uniaxial stress, M = E/(1 - nu^2) with rollers.
  const double modulus =
      rollers ? p.young_modulus / (1.0 - p.poisson_ratio * p.poisson_ratio) : p.young_modulus;
  wave_speed_ = std::sqrt(modulus / p.density);
  impedance_ = p.density * wave_speed_;
  grid_spacing_ = p.length / p.cells;
  time_step_ = grid_spacing_ / wave_speed_;
  source_weight_ = 0.5 * modulus * time_step_;
  lateral_weight_ = 0.5 * p.young_modulus * time_step_;
  residual_yield_ = p.residual_yield_fraction * p.initial_yield_stress;

  const std::size_t nodes = static_cast<std::size_t>(p.cells) + 1;
  stress_.assign(nodes, 0.0);
  velocity_.assign(nodes, 0.0);
  plastic_strain_.assign(nodes, 0.0);
  plastic_rate_.assign(nodes, 0.0);
  yield_.assign(nodes, p.initial_yield_stress);
  next_stress_.assign(nodes, 0.0);
  next_velocity_.assign(nodes, 0.0);
  next_rate_.assign(nodes, 0.0);
  if (rollers)
    for (auto* field : {&axial_rate_, &lateral_rate_, &equivalent_rate_, &lateral_offset_,
                        &next_axial_rate_, &next_lateral_rate_, &next_equivalent_rate_})
      field->assign(nodes, 0.0);
}

std::vector<double> ViscoplasticBar::lateral_stress() const {
  std::vector<double> lateral(stress_.size(), 0.0);
  if (!lateral_offset_.empty())
    for (std::size_t i = 0; i < lateral.size(); ++i)
      lateral[i] = parameters_.poisson_ratio * stress_[i] + lateral_offset_[i];
  return lateral;
}

double ViscoplasticBar::roller_plastic_rate(int node, double trial_stress) {
  // The new equivalent rate e = γφ ≥ 0 is bracketed and found by regula falsi (Illinois), as
  // plastic_rate finds its magnitude. For a given e, the new stress (σ_xx, σ_yy) solves (Newton on
  // two unknowns, analytic Jacobian)
  //   σ_xx = σ_trial − k_M e (n_xx + ν n_yy),   σ_yy − ν σ_xx = τ_known − k_E e n_yy,
  // with n = (3/2) s/q the Von Mises direction at the new stress, so ε̇_xx = e n_xx and
  // ε̇_yy = e n_yy. The outer residual g(e) = e − γ⟨q/Y(e) − 1⟩^N is negative at e = 0 (the trial
  // state flows) and positive once the flow has brought q below Y (or through zero, where the
  // inner problem has no solution: g = e there).
  const ViscoplasticBarParameters& p = parameters_;
  const auto i = static_cast<std::size_t>(node);
  const double nu = p.poisson_ratio, km = source_weight_, ke = lateral_weight_;
  const double tau_known = lateral_offset_[i] - ke * lateral_rate_[i];
  const double yield_slope = p.hardening_modulus * 0.5 * time_step_;
  const double scale = std::abs(trial_stress) + std::abs(tau_known) + yield_[i];

  struct State {
    bool exists = false;  // false: the flow has taken q through zero
    double xx = 0.0, yy = 0.0, q = 0.0, nxx = 0.0, nyy = 0.0;
  };
  const auto direction = [](State& s) {
    s.q = std::sqrt(std::max(0.0, s.xx * s.xx - s.xx * s.yy + s.yy * s.yy));
    if (s.q > 0.0) {
      s.nxx = (2.0 * s.xx - s.yy) / (2.0 * s.q);
      s.nyy = (2.0 * s.yy - s.xx) / (2.0 * s.q);
    }
  };
  State guess;
  guess.xx = trial_stress;
  guess.yy = nu * trial_stress + tau_known;
  direction(guess);
  const State trial = guess;
  const auto stress_at = [&](double e) {
    State s = guess.exists ? guess : trial;
    const auto residual = [&](const State& t, double& f1, double& f2) {
      f1 = t.xx - trial_stress + km * e * (t.nxx + nu * t.nyy);
      f2 = t.yy - nu * t.xx - tau_known + ke * e * t.nyy;
    };
    double f1 = 0.0, f2 = 0.0;
    residual(s, f1, f2);
    for (int iteration = 0; iteration < 100; ++iteration) {
      if (std::hypot(f1, f2) <= 1e-13 * scale) {
        s.exists = true;
        return s;
      }
      if (!(s.q > 1e-12 * scale)) break;
      // d n_xx/d s_xx = (1 − n_xx²)/q, d n_xx/d s_yy = d n_yy/d s_xx = −(1/2 + n_xx n_yy)/q,
      // d n_yy/d s_yy = (1 − n_yy²)/q.
      const double dxx = (1.0 - s.nxx * s.nxx) / s.q, dyy = (1.0 - s.nyy * s.nyy) / s.q;
      const double dxy = -(0.5 + s.nxx * s.nyy) / s.q;
      const double j11 = 1.0 + km * e * (dxx + nu * dxy), j12 = km * e * (dxy + nu * dyy);
      const double j21 = -nu + ke * e * dxy, j22 = 1.0 + ke * e * dyy;
      const double det = j11 * j22 - j12 * j21;
      if (!(std::abs(det) > 0.0)) break;
      const double step_xx = -(j22 * f1 - j12 * f2) / det;
      const double step_yy = -(j11 * f2 - j21 * f1) / det;
      bool decreased = false;
      for (double length = 1.0; length > 1e-12; length *= 0.5) {
        State next = s;
        next.xx = s.xx + length * step_xx;
        next.yy = s.yy + length * step_yy;
        direction(next);
        double g1 = 0.0, g2 = 0.0;
        residual(next, g1, g2);
        if (std::hypot(g1, g2) < std::hypot(f1, f2)) {
          s = next;
          f1 = g1;
          f2 = g2;
          decreased = true;
          break;
        }
      }
      if (!decreased) break;
    }
    return State{};  // no stress with q > 0 answers this rate
  };
  State at_root;
  const auto outer = [&](double e) {
    const State s = stress_at(e);
    if (!s.exists) return e;
    guess = s;
    at_root = s;
    const double yield =
        std::max(residual_yield_, yield_[i] + yield_slope * (equivalent_rate_[i] + e));
    const double overstress = s.q / yield - 1.0;
    return e - (overstress > 0.0 ? p.fluidity * std::pow(overstress, p.exponent) : 0.0);
  };

  double low = 0.0, g_low = outer(0.0);
  if (g_low >= 0.0) {  // no overstress at the trial state: elastic
    next_axial_rate_[i] = next_lateral_rate_[i] = next_equivalent_rate_[i] = 0.0;
    return 0.0;
  }
  double high = -g_low, g_high = outer(high);         // γφ of the trial state
  for (int doubling = 0; g_high < 0.0; ++doubling) {  // softening can raise φ as e grows
    if (doubling == 200) throw std::runtime_error("ViscoplasticBar: no bracket for a plastic rate");
    low = high;
    g_low = g_high;
    high *= 2.0;
    g_high = outer(high);
  }
  // Regula falsi with the Illinois halving, every third step a bisection (a steep g, N < 1 near
  // the yield surface, can stall the secant); every evaluation keeps a bracket [low, high].
  int side = 0;
  double e = high;
  for (int iteration = 0; iteration < 300 && high - low > 1e-14 * high; ++iteration) {
    e = (low * g_high - high * g_low) / (g_high - g_low);
    if (iteration % 3 == 2 || !(e > low && e < high)) e = 0.5 * (low + high);
    const double g = outer(e);
    if (g == 0.0) {
      low = high = e;
      break;
    }
    if (g < 0.0) {
      low = e;
      g_low = g;
      if (side == -1) g_high *= 0.5;
      side = -1;
    } else {
      high = e;
      g_high = g;
      if (side == 1) g_low *= 0.5;
      side = 1;
    }
  }
  e = 0.5 * (low + high);
  at_root = State{};
  const double g = outer(e);
  // Converged when the bracket has closed (with N < 1 g is steep at a root near the yield surface,
  // so a small |g| cannot be asked for) or g itself vanishes.
  const bool closed = high - low <= 1e-12 * high;
  if (!at_root.exists || !(closed || std::abs(g) <= 1e-12 * std::max(e, p.fluidity)))
    throw std::runtime_error("ViscoplasticBar: the plastic rates of a node did not converge");
  next_axial_rate_[i] = e * at_root.nxx;
  next_lateral_rate_[i] = e * at_root.nyy;
  next_equivalent_rate_[i] = e;
  return e * (at_root.nxx + nu * at_root.nyy);
}

double ViscoplasticBar::new_source_rate(int node, double trial_stress) {
  return lateral_offset_.empty() ? plastic_rate(node, trial_stress)
                                 : roller_plastic_rate(node, trial_stress);
}

double ViscoplasticBar::plastic_rate(int node, double trial_stress) const {
  // Unknown: the magnitude m of the new rate (its sign is that of the trial stress, because flow
  // only reduces |σ| = |σ_trial| − k m). Residual r(m) = m − γ φ(m), with φ the Perzyna
  // overstress function evaluated at the new stress and at the new (trapezoidal) yield stress.
  // r(0) ≤ 0 and r(|σ_trial|/k) > 0, so a root is bracketed; Newton steps that leave the bracket
  // are replaced by bisection.
  const ViscoplasticBarParameters& p = parameters_;
  const double k = source_weight_;
  const double magnitude = std::abs(trial_stress);
  const double old_rate = std::abs(plastic_rate_[node]);
  const double yield_slope = p.hardening_modulus * 0.5 * time_step_;
  const double old_yield = yield_[node];

  struct Evaluation {
    double residual;
    double derivative;
  };
  auto evaluate = [&](double m) {
    const double unclamped = old_yield + yield_slope * (old_rate + m);
    const double yield = std::max(residual_yield_, unclamped);
    const double yield_derivative = unclamped > residual_yield_ ? yield_slope : 0.0;
    const double stress = magnitude - k * m;
    const double overstress = stress / yield - 1.0;
    if (overstress <= 0.0) return Evaluation{m, 1.0};
    const double overstress_derivative = (-k * yield - stress * yield_derivative) / (yield * yield);
    const double flow = p.fluidity * std::pow(overstress, p.exponent);
    const double flow_derivative =
        p.fluidity * p.exponent * std::pow(overstress, p.exponent - 1.0) * overstress_derivative;
    return Evaluation{m - flow, 1.0 - flow_derivative};
  };

  const Evaluation at_zero = evaluate(0.0);
  if (at_zero.residual >= 0.0) return 0.0;

  double low = 0.0;
  double high = magnitude / k;
  // For H = 0 and N = 1 the residual is linear and this first guess is already the root.
  double m = std::min(high, -at_zero.residual / at_zero.derivative);
  for (int iteration = 0; iteration < 200; ++iteration) {
    const Evaluation e = evaluate(m);
    if (e.residual == 0.0) break;
    (e.residual > 0.0 ? high : low) = m;
    double next = e.derivative > 0.0 ? m - e.residual / e.derivative : 0.5 * (low + high);
    if (!(next > low && next < high)) next = 0.5 * (low + high);
    const bool converged =
        std::abs(next - m) <= 1e-15 * std::max(m, 1e-300) || high - low <= 1e-15 * high;
    m = next;
    if (converged) break;
  }
  return std::copysign(m, trial_stress);
}

void ViscoplasticBar::step() {
  const ViscoplasticBarParameters& p = parameters_;
  const int last = node_count() - 1;
  const double k = source_weight_;
  const double z = impedance_;
  const double new_time = static_cast<double>(steps_ + 1) * time_step_;

  // Left end: only the left-going invariant R⁻ = σ + Zv arrives, from node 1.
  {
    const double arriving = stress_[1] + z * velocity_[1] - k * plastic_rate_[1];
    if (p.left_end == ViscoplasticBarParameters::LeftEnd::Fixed) {
      const double rate = new_source_rate(0, arriving);
      next_rate_[0] = rate;
      next_stress_[0] = arriving - k * rate;
      next_velocity_[0] = 0.0;
    } else {
      // σ = 0 means no flow at a free end, so the source has no new-time part.
      next_rate_[0] = 0.0;
      next_stress_[0] = 0.0;
      next_velocity_[0] = arriving / z;
    }
  }
  // Interior: R⁺ from node i−1 and R⁻ from node i+1, each with half of its source known.
  for (int i = 1; i < last; ++i) {
    const double right_going = stress_[i - 1] - z * velocity_[i - 1] - k * plastic_rate_[i - 1];
    const double left_going = stress_[i + 1] + z * velocity_[i + 1] - k * plastic_rate_[i + 1];
    const double trial = 0.5 * (right_going + left_going);
    const double rate = new_source_rate(i, trial);
    next_rate_[i] = rate;
    next_stress_[i] = trial - k * rate;
    // The new-time source −k·rate enters both invariants equally and cancels in v.
    next_velocity_[i] = (left_going - right_going) / (2.0 * z);
  }
  // Right end: velocity imposed, only R⁺ arrives, from node last−1.
  {
    const double imposed = p.right_velocity(new_time);
    const double trial =
        stress_[last - 1] - z * velocity_[last - 1] - k * plastic_rate_[last - 1] + z * imposed;
    const double rate = new_source_rate(last, trial);
    next_rate_[last] = rate;
    next_stress_[last] = trial - k * rate;
    next_velocity_[last] = imposed;
  }

  const double half_step = 0.5 * time_step_;
  if (!lateral_offset_.empty()) {  // lateral rollers: ε_xx, Y from the equivalent rate, τ
    for (std::size_t i = 0; i < stress_.size(); ++i) {
      plastic_strain_[i] += half_step * (axial_rate_[i] + next_axial_rate_[i]);
      yield_[i] = std::max(residual_yield_,
                           yield_[i] + p.hardening_modulus * half_step *
                                           (equivalent_rate_[i] + next_equivalent_rate_[i]));
      lateral_offset_[i] -= lateral_weight_ * (lateral_rate_[i] + next_lateral_rate_[i]);
    }
    std::swap(axial_rate_, next_axial_rate_);
    std::swap(lateral_rate_, next_lateral_rate_);
    std::swap(equivalent_rate_, next_equivalent_rate_);
  }
  for (int i = 0; i <= last && lateral_offset_.empty(); ++i) {
    const double rate_sum = plastic_rate_[i] + next_rate_[i];
    const double rate_magnitude_sum = std::abs(plastic_rate_[i]) + std::abs(next_rate_[i]);
    plastic_strain_[i] += half_step * rate_sum;
    yield_[i] =
        std::max(residual_yield_, yield_[i] + p.hardening_modulus * half_step * rate_magnitude_sum);
  }
  std::swap(stress_, next_stress_);
  std::swap(velocity_, next_velocity_);
  std::swap(plastic_rate_, next_rate_);
  ++steps_;
}

void ViscoplasticBar::advance_to(double end_time) {
  while (time() + 0.5 * time_step_ < end_time)
    step();
}

ViscoplasticBarPoint ViscoplasticBar::at(double x) const {
  const double position = std::clamp(x / grid_spacing_, 0.0, static_cast<double>(node_count() - 1));
  const int left = std::min(static_cast<int>(position), node_count() - 2);
  const double weight = position - left;
  auto interpolate = [&](const std::vector<double>& field) {
    return (1.0 - weight) * field[left] + weight * field[left + 1];
  };
  return ViscoplasticBarPoint{interpolate(stress_), interpolate(velocity_),
                              interpolate(plastic_strain_)};
}

std::vector<ViscoplasticBarSample> viscoplastic_bar_history(
    const ViscoplasticBarParameters& parameters, double x, double end_time) {
  ViscoplasticBar bar(parameters);
  std::vector<ViscoplasticBarSample> history;
  history.reserve(static_cast<std::size_t>(std::max(0.0, end_time / bar.time_step())) + 2);
  history.push_back({bar.time(), bar.at(x)});
  while (bar.time() + 0.5 * bar.time_step() < end_time) {
    bar.step();
    history.push_back({bar.time(), bar.at(x)});
  }
  return history;
}

double viscoplastic_front_stress(double initial_front_stress, double initial_yield_stress,
                                 double young_modulus, double fluidity, double time) {
  // Behind a front into material at rest σ = ∓Zv, so both characteristic relations reduce to
  // dσ_f/dt = −(E/2) ε̇_vp(σ_f); with N = 1 this is linear in the overstress.
  const double magnitude = std::abs(initial_front_stress);
  if (magnitude <= initial_yield_stress) return initial_front_stress;
  const double decay = std::exp(-young_modulus * fluidity * time / (2.0 * initial_yield_stress));
  return std::copysign(initial_yield_stress + (magnitude - initial_yield_stress) * decay,
                       initial_front_stress);
}

double viscoplastic_decay_length(double young_modulus, double density, double initial_yield_stress,
                                 double fluidity) {
  const double wave_speed = std::sqrt(young_modulus / density);
  return 2.0 * wave_speed * initial_yield_stress / (young_modulus * fluidity);
}

}  // namespace rktsph::references
