// A set of points in structure-of-arrays form: one array per coordinate, one for volumes.
// Both node sets of the method (SPH nodes and stress points) are PointClouds.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace rktsph {

constexpr int kMaxDimension = 3;

struct PointCloud {
  int dimension = 1;
  /// position[a][i]: coordinate a (0 = x, 1 = y, 2 = z) of point i [m]; only a < dimension used.
  std::array<std::vector<double>, kMaxDimension> position;
  /// Volume of each point [m^dimension] (length in 1D, area in 2D, per unit thickness).
  std::vector<double> volume;

  std::size_t size() const { return volume.size(); }

  void resize(std::size_t n) {
    for (auto& coordinate : position)
      coordinate.resize(n, 0.0);
    volume.resize(n, 0.0);
  }

  /// Appends a point; coordinates beyond `dimension` are ignored.
  void push_back(const std::array<double, kMaxDimension>& x, double point_volume) {
    for (int a = 0; a < kMaxDimension; ++a)
      position[a].push_back(a < dimension ? x[a] : 0.0);
    volume.push_back(point_volume);
  }

  std::array<double, kMaxDimension> point(std::size_t i) const {
    return {position[0][i], position[1][i], position[2][i]};
  }
};

/// Point i and its position for messages: "x = 1.5 m" in 1D, "(x, y) = (1.5, 2) m" in 2D.
std::string describe_point(const PointCloud& points, std::size_t i);

}  // namespace rktsph
