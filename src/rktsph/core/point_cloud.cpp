#include "rktsph/core/point_cloud.hpp"

#include <fmt/format.h>

namespace rktsph {

std::string describe_point(const PointCloud& points, std::size_t i) {
  if (points.dimension == 1) return fmt::format("x = {:.6g} m", points.position[0][i]);
  return fmt::format("(x, y) = ({:.6g}, {:.6g}) m", points.position[0][i], points.position[1][i]);
}

}  // namespace rktsph
