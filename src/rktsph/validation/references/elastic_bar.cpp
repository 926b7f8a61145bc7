#include "rktsph/validation/references/elastic_bar.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace rktsph::references {

BarEnd BarEnd::free_end() {
  return stress([](double) { return 0.0; });
}

BarEnd BarEnd::fixed_end() {
  return velocity([](double) { return 0.0; });
}

BarEnd BarEnd::velocity(std::function<double(double)> velocity_of_time) {
  return BarEnd{Kind::Velocity, std::move(velocity_of_time)};
}

BarEnd BarEnd::stress(std::function<double(double)> stress_of_time) {
  return BarEnd{Kind::Stress, std::move(stress_of_time)};
}

ElasticBar::ElasticBar(double length, double young_modulus, double density, BarEnd left,
                       BarEnd right)
    : length_(length), left_(std::move(left)), right_(std::move(right)) {
  if (!(length > 0.0) || !(young_modulus > 0.0) || !(density > 0.0)) {
    throw std::invalid_argument("ElasticBar: length, Young's modulus and density must be > 0");
  }
  if (!left_.value || !right_.value) {
    throw std::invalid_argument("ElasticBar: each end needs a function of time");
  }
  wave_speed_ = std::sqrt(young_modulus / density);
  impedance_ = density * wave_speed_;
}

BarState ElasticBar::state(double x, double time) const {
  const double right_going = right_going_invariant(x, time);
  const double left_going = left_going_invariant(x, time);
  return BarState{(left_going - right_going) / (2.0 * impedance_),
                  0.5 * (right_going + left_going)};
}

double ElasticBar::right_going_invariant(double x, double time) const {
  const double departure = time - x / wave_speed_;
  return departure > 0.0 ? invariant_leaving(true, departure) : 0.0;
}

double ElasticBar::left_going_invariant(double x, double time) const {
  const double departure = time - (length_ - x) / wave_speed_;
  return departure > 0.0 ? invariant_leaving(false, departure) : 0.0;
}

double ElasticBar::invariant_leaving(bool left_end, double departure) const {
  // Every reflection is affine in the incoming invariant, R_out = sign·R_in + source(t):
  //   velocity end at x = 0: R⁺ = R⁻ − 2Z v_b;   at x = L: R⁻ = R⁺ + 2Z v_b;
  //   stress end (both):     R_out = 2σ_b − R_in.
  // Walking back one transit L/c per reflection and accumulating the sources with the product of
  // the signs gives the invariant without recursion; the chain ends when it reaches t ≤ 0.
  const double transit = length_ / wave_speed_;
  double invariant = 0.0;
  double sign = 1.0;
  double time = departure;
  bool at_left = left_end;
  while (time > 0.0) {
    const BarEnd& end = at_left ? left_ : right_;
    const double value = end.value(time);
    if (end.kind == BarEnd::Kind::Velocity) {
      const double outward_sign = at_left ? -1.0 : 1.0;
      invariant += sign * outward_sign * 2.0 * impedance_ * value;
    } else {
      invariant += sign * 2.0 * value;
      sign = -sign;
    }
    time -= transit;
    at_left = !at_left;
  }
  return invariant;
}

}  // namespace rktsph::references
