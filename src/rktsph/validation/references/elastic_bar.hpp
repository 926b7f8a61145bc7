// Exact solution of the 1D linear elastic bar by characteristics (docs/theory.md
// §8.2).
//
//   ρ v_t = σ_x,  σ_t = E v_x  on 0 ≤ x ≤ L,  v = σ = 0 at t = 0,  tension positive.
//
// With c = √(E/ρ) and Z = ρc, R⁺ = σ − Zv is constant along dx/dt = +c and R⁻ = σ + Zv along
// dx/dt = −c. Any point is solved by following both invariants back through the boundary
// reflections until they leave the initial (zero) state, so the answer is exact for any load
// history, including steps.
#pragma once

#include <functional>

namespace rktsph::references {

/// One end of the bar: either its velocity or its (tension-positive) stress is prescribed as a
/// function of time. The function is only called for t > 0.
struct BarEnd {
  enum class Kind { Velocity, Stress };
  Kind kind = Kind::Stress;
  std::function<double(double)> value;  ///< [m/s] or [Pa] against time [s]

  static BarEnd free_end();   ///< σ = 0
  static BarEnd fixed_end();  ///< v = 0
  static BarEnd velocity(std::function<double(double)> velocity_of_time);
  static BarEnd stress(std::function<double(double)> stress_of_time);
};

struct BarState {
  double velocity = 0.0;  ///< [m/s]
  double stress = 0.0;    ///< [Pa], tension positive
};

class ElasticBar {
 public:
  /// Throws std::invalid_argument for a non-positive length, modulus or density, or an end
  /// without a function.
  ElasticBar(double length, double young_modulus, double density, BarEnd left, BarEnd right);

  double length() const { return length_; }
  double wave_speed() const { return wave_speed_; }  ///< c = √(E/ρ)
  double impedance() const { return impedance_; }    ///< Z = ρc

  /// State at 0 ≤ x ≤ L, t ≥ 0. Exactly on a front the state ahead of it is returned.
  BarState state(double x, double time) const;
  double velocity(double x, double time) const { return state(x, time).velocity; }
  double stress(double x, double time) const { return state(x, time).stress; }

 private:
  /// R⁺ = σ − Zv arriving at (x, t) from the left.
  double right_going_invariant(double x, double time) const;
  /// R⁻ = σ + Zv arriving at (x, t) from the right.
  double left_going_invariant(double x, double time) const;
  /// Follows an invariant that left end `left_end` at `departure`, back to the initial state.
  double invariant_leaving(bool left_end, double departure) const;

  double length_;
  double wave_speed_;
  double impedance_;
  BarEnd left_;
  BarEnd right_;
};

}  // namespace rktsph::references
