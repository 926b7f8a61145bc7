#include "rktsph/boundary/free_surface_detection.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>

#include "rktsph/core/parallel.hpp"
#include "rktsph/core/small_tensor.hpp"
#include "rktsph/sph/kernel.hpp"

namespace rktsph {
namespace {

/// Smallest eigenvalue of the symmetric part of the 2x2 matrix m (row-major, m[2*a + b]).
double smallest_symmetric_eigenvalue(const std::array<double, 4>& m) {
  const double a = m[0];
  const double c = m[3];
  const double b = 0.5 * (m[1] + m[2]);
  const double half_difference = 0.5 * (a - c);
  return 0.5 * (a + c) - std::sqrt(half_difference * half_difference + b * b);
}

/// Below this lambda_hat M is too close to singular to invert (a filament, a node with one or two
/// neighbours): the normal is then the uncorrected kernel-gradient sum.
constexpr double kIllConditioned = 0.05;

struct NodeSums {
  std::array<double, 4> matrix{0.0, 0.0, 0.0, 0.0};  // M_i, row-major
  Vec3 gradient_sum{0.0, 0.0, 0.0};                  // sum_j V_j grad_i W_ij
};

/// Unit vector along v, or the zero vector if v is (numerically) zero. `scale` is the magnitude
/// of a normal sum at a face, so that round-off in a symmetric sum is not taken for a direction.
Vec3 unit_or_zero(const Vec3& v, double scale) {
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(length > 1e-10 * scale)) return {0.0, 0.0, 0.0};
  return {v[0] / length, v[1] / length, v[2] / length};
}

/// Marrone's normal -M^-1 sum V grad W, or the uncorrected -sum V grad W where M is
/// ill-conditioned.
Vec3 corrected_normal(const NodeSums& sums, double lambda_hat, double scale) {
  const Vec3& s = sums.gradient_sum;
  if (lambda_hat < kIllConditioned) return unit_or_zero({-s[0], -s[1], 0.0}, scale);
  const std::array<double, 4>& m = sums.matrix;
  const double determinant = m[0] * m[3] - m[1] * m[2];
  const Vec3 nu{-(m[3] * s[0] - m[1] * s[1]) / determinant,
                -(-m[2] * s[0] + m[0] * s[1]) / determinant, 0.0};
  return unit_or_zero(nu, scale);
}

void check_inputs(const PointCloud& points, const CellList& cells,
                  const FreeSurfaceOptions& options, std::span<const std::uint8_t> excluded) {
  if (&cells.points() != &points)
    throw std::invalid_argument("detect_free_surface: the cell list is not of this point cloud");
  if (!(options.smoothing_length > 0.0) || !std::isfinite(options.smoothing_length))
    throw std::invalid_argument("detect_free_surface: the smoothing length must be positive");
  if (!(options.lattice_spacing > 0.0) || !std::isfinite(options.lattice_spacing))
    throw std::invalid_argument("detect_free_surface: the lattice spacing must be positive");
  if (!(options.surface_threshold <= options.interior_threshold))
    throw std::invalid_argument(
        "detect_free_surface: the surface threshold must not exceed the interior threshold");
  if (!excluded.empty() && excluded.size() != points.size())
    throw std::invalid_argument("detect_free_surface: the excluded mask has the wrong size");
}

void resize_output(std::size_t n, FreeSurface& out) {
  out.on_surface.assign(n, 0);
  for (auto& component : out.normal)
    component.assign(n, 0.0);
  out.lambda.assign(n, 0.0);
  out.candidates = 0;
}

/// 1D: the two end points of the cloud.
void detect_ends(const PointCloud& points, std::span<const std::uint8_t> excluded,
                 FreeSurface& out) {
  const std::vector<double>& x = points.position[0];
  std::size_t lowest = 0;
  std::size_t highest = 0;
  for (std::size_t i = 1; i < x.size(); ++i) {
    if (x[i] < x[lowest]) lowest = i;
    if (x[i] > x[highest]) highest = i;
  }
  const auto mark = [&](std::size_t i, double sign) {
    if (!excluded.empty() && excluded[i] != 0) return;
    out.on_surface[i] = 1;
    out.normal[0][i] = sign;
  };
  mark(highest, 1.0);
  mark(lowest, -1.0);  // a single node: its normal is -x
}

/// Pass 2 of the detection: the normal from the interior indicator.
void indicator_normals(const PointCloud& points, const CellList& cells,
                       const FreeSurfaceOptions& options, std::span<const std::uint8_t> excluded,
                       FreeSurface& out) {
  const Kernel kernel(options.kernel, points.dimension);
  const double h = options.smoothing_length;
  const double radius = kernel.support_radius(h);
  const double normal_scale = 1.0 / h;
  const auto count = static_cast<std::int64_t>(points.size());
  const auto is_excluded = [&](std::size_t i) { return !excluded.empty() && excluded[i] != 0; };

  // Pass 2: the normal from the interior indicator f (1 interior, 0 surface). Each node reads its
  // neighbours' flags and writes only its own normal. Excluded nodes count as interior where the
  // pre-screen says so and as surface otherwise (they are not scanned).
  const double interior_threshold = options.interior_threshold;
  const auto indicator = [&](std::size_t j) -> double {
    if (is_excluded(j)) return out.lambda[j] > interior_threshold ? 1.0 : 0.0;
    return out.on_surface[j] != 0 ? 0.0 : 1.0;
  };
#pragma omp parallel for schedule(static) if (count > kParallelThreshold)
  for (std::int64_t signed_i = 0; signed_i < count; ++signed_i) {
    const auto i = static_cast<std::size_t>(signed_i);
    if (out.on_surface[i] == 0) continue;
    Vec3 g{0.0, 0.0, 0.0};
    cells.for_each_within(points.point(i), radius, [&](std::int32_t j, const Vec3& offset, double) {
      const double f = indicator(static_cast<std::size_t>(j));
      if (f == 0.0) return;  // f_i = 0 on a surface node
      const double volume = points.volume[static_cast<std::size_t>(j)];
      const Vec3 gradient = kernel.gradient(offset, h);
      g[0] += volume * f * gradient[0];
      g[1] += volume * f * gradient[1];
    });
    const Vec3 refined = unit_or_zero({-g[0], -g[1], 0.0}, normal_scale);
    // No interior neighbour (a spray node, a filament): keep Marrone's normal.
    if (refined[0] == 0.0 && refined[1] == 0.0) continue;
    Vec3 result = refined;
    if (options.normal == FreeSurfaceNormal::Average) {
      const Vec3 sum{refined[0] + out.normal[0][i], refined[1] + out.normal[1][i], 0.0};
      const Vec3 average = unit_or_zero(sum, 1.0);
      if (average[0] != 0.0 || average[1] != 0.0) result = average;
    }
    out.normal[0][i] = result[0];
    out.normal[1][i] = result[1];
  }
}

/// A pass of the angle-limited smoothing of the surface normals.
void smooth_normals(const PointCloud& points, const CellList& cells,
                    const FreeSurfaceOptions& options, FreeSurface& out) {
  const Kernel kernel(options.kernel, points.dimension);
  const double h = options.smoothing_length;
  const double radius = kernel.support_radius(h);
  const double cosine = std::cos(options.smoothing_angle_degrees * std::numbers::pi / 180.0);
  const auto count = static_cast<std::int64_t>(points.size());
  out.previous_normal[0] = out.normal[0];
  out.previous_normal[1] = out.normal[1];
  const std::vector<double>& nx = out.previous_normal[0];
  const std::vector<double>& ny = out.previous_normal[1];
#pragma omp parallel for schedule(static) if (count > kParallelThreshold)
  for (std::int64_t signed_i = 0; signed_i < count; ++signed_i) {
    const auto i = static_cast<std::size_t>(signed_i);
    if (out.on_surface[i] == 0) continue;
    Vec3 sum{0.0, 0.0, 0.0};
    cells.for_each_within(points.point(i), radius,
                          [&](std::int32_t signed_j, const Vec3&, double distance_squared) {
                            const auto j = static_cast<std::size_t>(signed_j);
                            if (out.on_surface[j] == 0) return;
                            if (nx[i] * nx[j] + ny[i] * ny[j] < cosine) return;
                            const double w = kernel.value(std::sqrt(distance_squared), h);
                            sum[0] += w * nx[j];
                            sum[1] += w * ny[j];
                          });
    const Vec3 smoothed = unit_or_zero(sum, 1.0);
    if (smoothed[0] == 0.0 && smoothed[1] == 0.0) continue;
    out.normal[0][i] = smoothed[0];
    out.normal[1][i] = smoothed[1];
  }
}

}  // namespace

double lattice_renormalisation_eigenvalue(KernelType kernel_type, int dimension,
                                          double smoothing_length, double lattice_spacing) {
  if (dimension < 1 || dimension > 2)
    throw std::invalid_argument("lattice_renormalisation_eigenvalue: dimension 1 or 2 only");
  const Kernel kernel(kernel_type, dimension);
  const double radius = kernel.support_radius(smoothing_length);
  const auto reach = static_cast<int>(std::ceil(radius / lattice_spacing));
  const double volume = dimension == 1 ? lattice_spacing : lattice_spacing * lattice_spacing;
  // By the lattice's symmetry M is a multiple of the identity: its xx entry is the eigenvalue.
  double m_xx = 0.0;
  const int y_reach = dimension == 1 ? 0 : reach;
  for (int l = -y_reach; l <= y_reach; ++l) {
    for (int k = -reach; k <= reach; ++k) {
      const Vec3 offset{-k * lattice_spacing, -l * lattice_spacing, 0.0};  // x_i - x_j
      if (offset[0] * offset[0] + offset[1] * offset[1] >= radius * radius) continue;
      m_xx += volume * (-offset[0]) * kernel.gradient(offset, smoothing_length)[0];
    }
  }
  return m_xx;
}

void detect_free_surface(const PointCloud& points, const CellList& cells,
                         const FreeSurfaceOptions& options, FreeSurface& out) {
  detect_free_surface(points, cells, options, {}, out);
}

void detect_free_surface(const PointCloud& points, const CellList& cells,
                         const FreeSurfaceOptions& options, std::span<const std::uint8_t> excluded,
                         FreeSurface& out) {
  const int dimension = points.dimension;
  if (dimension == 3) throw std::invalid_argument("detect_free_surface: 3D is not implemented");
  if (dimension != 1 && dimension != 2)
    throw std::invalid_argument("detect_free_surface: dimension must be 1 or 2");
  check_inputs(points, cells, options, excluded);
  const std::size_t n = points.size();
  resize_output(n, out);
  if (dimension == 1) {
    detect_ends(points, excluded, out);
    return;
  }

  const Kernel kernel(options.kernel, dimension);
  const double h = options.smoothing_length;
  const double radius = kernel.support_radius(h);
  // The scan length: Marrone's h for a kernel of support 2h, so that the region (a disc of
  // radius s about x_i + s n) stays inside the support for any support factor.
  const double scan = 0.5 * radius;
  const double near_squared = 2.0 * scan * scan;
  const double inverse_reference = 1.0 / lattice_renormalisation_eigenvalue(
                                             options.kernel, dimension, h, options.lattice_spacing);
  // |sum V grad W| at a flat face is of order 1/h: the scale of a meaningful normal sum.
  const double normal_scale = 1.0 / h;
  const auto count = static_cast<std::int64_t>(n);
  const auto is_excluded = [&](std::size_t i) { return !excluded.empty() && excluded[i] != 0; };

  // Pass 1: M, lambda_hat, Marrone's normal; the pre-screen; the scan region for candidates.
  // out.on_surface holds 0 interior, 1 surface; the Marrone normal goes to out.normal for now.
  std::size_t candidates = 0;
#pragma omp parallel for schedule(static) reduction(+ : candidates) if (count > kParallelThreshold)
  for (std::int64_t signed_i = 0; signed_i < count; ++signed_i) {
    const auto i = static_cast<std::size_t>(signed_i);
    const Vec3 xi = points.point(i);
    NodeSums sums;
    cells.for_each_within(xi, radius, [&](std::int32_t j, const Vec3& offset, double) {
      const double volume = points.volume[static_cast<std::size_t>(j)];
      const Vec3 gradient = kernel.gradient(offset, h);
      // x_j - x_i = -offset.
      sums.matrix[0] -= volume * offset[0] * gradient[0];
      sums.matrix[1] -= volume * offset[0] * gradient[1];
      sums.matrix[2] -= volume * offset[1] * gradient[0];
      sums.matrix[3] -= volume * offset[1] * gradient[1];
      sums.gradient_sum[0] += volume * gradient[0];
      sums.gradient_sum[1] += volume * gradient[1];
    });
    const double lambda_hat = smallest_symmetric_eigenvalue(sums.matrix) * inverse_reference;
    out.lambda[i] = lambda_hat;
    if (is_excluded(i) || lambda_hat > options.interior_threshold) continue;
    const Vec3 normal = corrected_normal(sums, lambda_hat, normal_scale);
    bool surface = true;
    if (lambda_hat > options.surface_threshold) {
      ++candidates;
      // A candidate with no normal direction (a symmetric neighbourhood) has nothing to scan
      // towards: it lies inside the body.
      surface = normal[0] != 0.0 || normal[1] != 0.0;
      if (surface) {
        const double scan_squared = scan * scan;
        cells.for_each_within(xi, radius, [&](std::int32_t, const Vec3& offset, double d2) {
          if (!surface || d2 == 0.0) return;
          // x_j - T = -offset - s n.
          const double rx = -offset[0] - scan * normal[0];
          const double ry = -offset[1] - scan * normal[1];
          if (d2 >= near_squared) {
            if (rx * rx + ry * ry < scan_squared) surface = false;
          } else {
            const double along = rx * normal[0] + ry * normal[1];
            const double across = -rx * normal[1] + ry * normal[0];
            if (std::abs(along) + std::abs(across) < scan) surface = false;
          }
        });
      }
    }
    if (!surface) continue;
    out.on_surface[i] = 1;
    out.normal[0][i] = normal[0];
    out.normal[1][i] = normal[1];
  }
  out.candidates = candidates;
  if (options.normal != FreeSurfaceNormal::Marrone)
    indicator_normals(points, cells, options, excluded, out);
  for (int pass = 0; pass < options.smoothing_passes; ++pass)
    smooth_normals(points, cells, options, out);
}

}  // namespace rktsph
