// Free-surface detection for a moving body of SPH nodes, after Marrone et al. (2010): a
// renormalisation-matrix pre-screen, an outward normal, and the "umbrella" scan region for the
// nodes the pre-screen cannot decide; then the smoothed normals of the detected surface nodes.
//
// The pre-screen uses the smallest eigenvalue of the renormalisation matrix
//   M_i = sum_j V_j (x_j - x_i) (x) grad_i W(x_i - x_j),
// divided by its value in the interior of a full square lattice of the caller's spacing at the
// same h, so that the thresholds do not depend on the kernel or on h/dx. Measured on a regular
// lattice (lambda_hat = lambda / lambda_lattice; the second row is one spacing inside a face):
//
//   kernel   h/dx  interior  second row  flat face  corner
//   cubic    1.0   1.000     1.000       0.500      0.337
//   cubic    1.2   1.000     0.942       0.500      0.295
//   cubic    1.3   1.000     0.891       0.500      0.271
//   cubic    1.5   1.000     0.814       0.500      0.235
//   quintic  1.0   1.000     0.925       0.500      0.283
//   quintic  1.2   1.000     0.826       0.500      0.244
//   quintic  1.3   1.000     0.781       0.500      0.229
//   quintic  1.5   1.000     0.709       0.500      0.207
//   gaussian 1.0   1.000     0.917       0.500      0.286
//   gaussian 1.3   1.000     0.785       0.500      0.231
//
// (A flat face is exactly 0.5: the face row contributes nothing to the normal-normal entry and
// the half plane gives half of it.) Measured on disordered blocks (tests): +-0.2 dx jitter, face
// nodes <= 0.71 and interior nodes >= 0.66; +-0.3 dx, face <= 0.78, interior >= 0.52; a block
// sheared by x += y, interior >= 0.64.
//
// Defaults: lambda_hat <= 0.15 is surface without a scan (below every corner above, which the scan
// then confirms, so only a node with very few neighbours, spray or a one-node-wide filament, skips
// the scan); lambda_hat > 0.85 is interior without a scan (above every face node measured, also at
// +-0.3 dx jitter, where Marrone's 0.75 would let some through unscanned). Between the two the
// node is a candidate and the scan region decides; a deep interior node (1.0 on a lattice)
// is not scanned, so the scans cost O(surface nodes). A scanned interior node is found interior:
// its umbrella holds the node in front of it.
//
// Scan region (Marrone et al. 2010), with its length s = support radius / 2 instead of h: s = h
// for the cubic spline (support 2h, as in the paper) and s = 1.5 h for the quintic spline and the
// truncated Gaussian (support 3h), so that the region stays inside the support whatever the kernel.
// With T = x_i + s n_i and tau = n_i turned by 90 degrees, node i is interior if a neighbour j has
// (|x_j - x_i| >= sqrt(2) s and |x_j - T| < s) or (|x_j - x_i| < sqrt(2) s and
// |n.(x_j - T)| + |tau.(x_j - T)| < s). The region tolerates a normal off by up to 45 degrees.
//
// Normals: Marrone's nu_i = -M_i^-1 sum_j V_j grad_i W_ij (the uncorrected sum where lambda_hat <
// 0.05, M being near singular), n_i = nu_i / |nu_i|, then two passes of an angle-limited smoothing
// over the surface nodes in the support (kernel-weighted mean of the neighbouring surface normals
// within 30 degrees of the node's own, so a 90-degree corner is not averaged into its faces). The
// refined normal of the interior indicator f (1 interior, 0 surface), g_i = sum_j V_j (f_j - f_i)
// grad_i W_ij, n_i = -g_i/|g_i|, and the mean of the two were measured worse on every test shape
// (the indicator sees the staircase of the second row: 15-17 degrees on a regular rectangle's face
// nodes next to a corner against 1-2); they remain options. Corners get the diagonal up to a few
// degrees on regular blocks. Measured errors and rates: the table in the tests' output
// (FreeSurfaceDetection.TableOfEveryShape).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "rktsph/core/point_cloud.hpp"
#include "rktsph/sph/kernel_type.hpp"
#include "rktsph/sph/neighbour_search.hpp"

namespace rktsph {

/// Which unit normal a detected surface node gets.
enum class FreeSurfaceNormal {
  Marrone,    ///< -M^-1 sum V grad W, normalised
  Indicator,  ///< -sum V (f_j - f_i) grad W of the interior indicator f, normalised
  Average,    ///< the normalised sum of the two unit normals above
};

struct FreeSurfaceOptions {
  KernelType kernel = KernelType::CubicSpline;
  double smoothing_length = 0.0;  ///< h [m], > 0
  double lattice_spacing = 0.0;   ///< dx of the initial lattice [m], > 0: scales lambda
  /// lambda_hat <= surface_threshold: surface without a scan.
  double surface_threshold = 0.15;
  /// lambda_hat > interior_threshold: interior without a scan.
  double interior_threshold = 0.85;
  FreeSurfaceNormal normal = FreeSurfaceNormal::Marrone;
  /// Passes of the surface smoothing of the normals: each replaces a surface node's normal by the
  /// kernel-weighted mean of the normals of the surface nodes within the support whose normal is
  /// within smoothing_angle_degrees of its own (so a corner is not averaged into its faces).
  int smoothing_passes = 2;
  double smoothing_angle_degrees = 30.0;
};

struct FreeSurface {
  std::vector<std::uint8_t> on_surface;  ///< 1: node on the free surface
  /// Outward unit normal of each surface node, components x, y, z; 0 for the other nodes.
  std::array<std::vector<double>, 3> normal;
  /// lambda_hat: the smallest eigenvalue of M_i over its full-lattice value (2D; all 0 in 1D,
  /// where only the ends are looked for).
  std::vector<double> lambda;
  std::size_t candidates = 0;  ///< nodes the pre-screen left to the scan region
  /// Scratch of the normal smoothing (kept for its capacity).
  std::array<std::vector<double>, 2> previous_normal;
};

/// Detects the free surface of `points`. `cells` must be a CellList of `points` itself (any cell
/// size). Nodes with excluded[i] != 0 (e.g. nodes whose velocity is fully prescribed) are never
/// surface nodes but still count as neighbours; an empty span excludes none. The buffers of
/// `out` are reused (no allocation when the size does not grow). Parallel over nodes.
/// 1D: the two end points are the surface, normals -x and +x. 3D: std::invalid_argument (not
/// implemented). Invalid options or mismatched sizes: std::invalid_argument.
void detect_free_surface(const PointCloud& points, const CellList& cells,
                         const FreeSurfaceOptions& options, std::span<const std::uint8_t> excluded,
                         FreeSurface& out);
/// As above with no excluded node.
void detect_free_surface(const PointCloud& points, const CellList& cells,
                         const FreeSurfaceOptions& options, FreeSurface& out);

/// lambda_min of M in the interior of a full square (2D) or uniform (1D) lattice of spacing
/// `lattice_spacing`, the value lambda is divided by.
double lattice_renormalisation_eigenvalue(KernelType kernel, int dimension, double smoothing_length,
                                          double lattice_spacing);

}  // namespace rktsph
