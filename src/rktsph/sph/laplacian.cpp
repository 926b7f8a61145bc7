#include "rktsph/sph/laplacian.hpp"

#include <cmath>

namespace rktsph {

namespace {

// The Morris pair factor 2 (x_I - x_J).grad_I W / (r^2 + eta^2) = 2 r W'(r) / (r^2 + eta^2) < 0.
double pair_factor(const Kernel& kernel, double r, double h) {
  const double eta = 0.1 * h;
  return 2.0 * r * kernel.derivative(r, h) / (r * r + eta * eta);
}

// Sum over the full lattice stencil of a node, I excluded, of V_J pair_factor(r_IJ) times
// weight(lattice offset, r_IJ).
template <typename Weight>
double lattice_stencil_sum(const Kernel& kernel, double smoothing_length, double spacing,
                           int dimension, Weight weight) {
  const double support = kernel.support_radius(smoothing_length);
  const int reach = static_cast<int>(std::ceil(support / spacing));
  const int reach_y = dimension >= 2 ? reach : 0, reach_z = dimension >= 3 ? reach : 0;
  const double volume = std::pow(spacing, dimension);
  double sum = 0.0;
  for (int i = -reach; i <= reach; ++i)
    for (int j = -reach_y; j <= reach_y; ++j)
      for (int k = -reach_z; k <= reach_z; ++k) {
        if (i == 0 && j == 0 && k == 0) continue;
        const double r = spacing * std::sqrt(static_cast<double>(i * i + j * j + k * k));
        if (r >= support) continue;
        sum += volume * pair_factor(kernel, r, smoothing_length) * weight(i + j + k, r);
      }
  return sum;
}

}  // namespace

double laplacian_consistency_scale(const Kernel& kernel, double smoothing_length, double spacing,
                                   int dimension) {
  // L(|x - x_I|^2) at I = -sum_J V_J pair_factor r_IJ^2 over the full lattice stencil; exact 2d.
  const double sum = -lattice_stencil_sum(kernel, smoothing_length, spacing, dimension,
                                          [](int, double r) { return r * r; });
  return 2.0 * dimension / sum;
}

double laplacian_checkerboard_rate(const Kernel& kernel, double smoothing_length, double spacing,
                                   int dimension, double scale) {
  // -L c / c on the checkerboard c = (-1)^(i+j+k): sum_J V_J pair_factor (c_J - c_I) / c_I.
  const double sum =
      -lattice_stencil_sum(kernel, smoothing_length, spacing, dimension, [](int offset, double) {
        return offset % 2 == 0 ? 0.0 : 2.0;  // 1 - (-1)^offset
      });
  return scale * sum;
}

LaplacianMatrix build_laplacian(const PointCloud& points, const CellList& cells,
                                const OperatorOptions& options, double spacing, double scale) {
  const int d = points.dimension;
  const double h = options.smoothing_length;
  const std::size_t n = points.size();
  LaplacianMatrix result;
  result.scale = scale > 0.0 ? scale : laplacian_consistency_scale(options.kernel, h, spacing, d);
  result.effective_volume.resize(n);
  const double on_plane = 1e-8 * h;
  for (std::size_t i = 0; i < n; ++i) {
    double volume = points.volume[i];
    for (const MirrorPlane& plane : options.mirrors)
      if (std::abs(points.position[plane.axis][i] - plane.coordinate) <= on_plane) volume *= 0.5;
    result.effective_volume[i] = volume;
  }

  std::vector<Eigen::Triplet<double>> entries;
  std::vector<StencilSource> stencil;
  for (std::size_t i = 0; i < n; ++i) {
    const auto x = points.point(i);
    gather_stencil(x, cells, options, static_cast<std::int32_t>(i), stencil);
    double diagonal = 0.0;
    for (const StencilSource& s : stencil) {
      double r2 = 0.0;
      for (int a = 0; a < d; ++a)
        r2 += std::pow(x[a] - s.position[a], 2);
      // Row I of Ltilde: V_eff,I * c * V_J * pair_factor * (p_I - p_J).
      const double weight = result.effective_volume[i] * result.scale * s.volume *
                            pair_factor(options.kernel, std::sqrt(r2), h);
      diagonal += weight;
      entries.emplace_back(static_cast<int>(i), s.column, -weight);
    }
    entries.emplace_back(static_cast<int>(i), static_cast<int>(i), diagonal);
  }
  result.weighted.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  result.weighted.setFromTriplets(entries.begin(), entries.end());  // sums duplicate (images)
  return result;
}

}  // namespace rktsph
