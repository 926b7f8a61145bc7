// The outward unit normals of a surface node: one on a face, up to one per axis at an edge or a
// corner of a lattice body (mutually orthogonal there), one from the free-surface detection of a
// moving body. The traction-free projection (docs/theory.md §5.1) takes them in this form.
#pragma once

#include <array>
#include <cassert>

namespace rktsph {

struct SurfaceNormals {
  static constexpr int kMax = 3;
  std::array<std::array<double, 3>, kMax> normal{};  ///< unit vectors, components x, y, z
  int count = 0;

  void add(const std::array<double, 3>& unit_normal) {
    assert(count < kMax);
    normal[static_cast<std::size_t>(count++)] = unit_normal;
  }
  /// The normal of a lattice face: +-1 along `axis`.
  void add_axis(int axis, double sign = 1.0) {
    std::array<double, 3> n{};
    n[static_cast<std::size_t>(axis)] = sign;
    add(n);
  }
};

}  // namespace rktsph
