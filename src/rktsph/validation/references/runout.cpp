#include "rktsph/validation/references/runout.hpp"

#include <cmath>
#include <stdexcept>

namespace rktsph::references {
namespace {

void require_material(double cohesion, double unit_weight) {
  if (!(cohesion > 0.0) || !(unit_weight > 0.0))
    throw std::invalid_argument("run-out bound: cohesion and unit weight must be > 0");
}

}  // namespace

double nye_height(double distance_behind_front, double cohesion, double unit_weight) {
  require_material(cohesion, unit_weight);
  if (!(distance_behind_front >= 0.0))
    throw std::invalid_argument("nye_height: the distance behind the front must be >= 0");
  return std::sqrt(2.0 * cohesion * distance_behind_front / unit_weight);
}

double nye_minimum_runout(double area, double cohesion, double unit_weight) {
  require_material(cohesion, unit_weight);
  if (!(area > 0.0)) throw std::invalid_argument("nye_minimum_runout: the area must be > 0");
  return std::pow(1.5 * area, 2.0 / 3.0) * std::cbrt(unit_weight / (2.0 * cohesion));
}

double ritter_front(double time, double initial_front, double height, double gravity) {
  if (!(time >= 0.0) || !(height >= 0.0) || !(gravity >= 0.0))
    throw std::invalid_argument("ritter_front: time, height and gravity must be >= 0");
  return initial_front + 2.0 * time * std::sqrt(gravity * height);
}

}  // namespace rktsph::references
