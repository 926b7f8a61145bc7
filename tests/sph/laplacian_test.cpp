// The Morris SPH Laplacian of the pore-pressure equation (docs/theory.md §6.3,
// §7.2): consistency scale, exactness on quadratics, second-order accuracy in the interior, and
// the symmetry and sign structure of Ltilde = diag(V_eff) L with mirror planes (half volumes).
#include "rktsph/sph/laplacian.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <numbers>

#include "../support/lattices.hpp"
#include "rktsph/geometry/node_sets.hpp"

namespace rktsph::laplacian_test {
namespace {

using test::bar_lattice;
using test::rectangle_lattice;

OperatorOptions options_for(int dimension, double smoothing_length,
                            std::vector<MirrorPlane> mirrors = {}) {
  OperatorOptions options;
  options.kernel = Kernel(KernelType::CubicSpline, dimension);
  options.smoothing_length = smoothing_length;
  options.mirrors = std::move(mirrors);
  return options;
}

LaplacianMatrix laplacian_on(const NodeSets& nodes, const OperatorOptions& options) {
  const CellList cells(nodes.sph_nodes, options.kernel.support_radius(options.smoothing_length));
  return build_laplacian(nodes.sph_nodes, cells, options, nodes.spacing, 0.0);
}

// (L f)_I = (Ltilde f)_I / V_eff,I. Ltilde is assembled with the sign of the Morris sum, so for a
// convex f it is positive: (Ltilde f)_I = V_eff,I sum_J c V_J F_IJ (f_I - f_J) with F_IJ < 0.
Eigen::VectorXd apply_laplacian(const LaplacianMatrix& laplacian, const PointCloud& points,
                                const std::function<double(const std::array<double, 3>&)>& field) {
  Eigen::VectorXd values(static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    values[static_cast<Eigen::Index>(i)] = field(points.point(i));
  Eigen::VectorXd result = laplacian.weighted * values;
  for (std::size_t i = 0; i < points.size(); ++i)
    result[static_cast<Eigen::Index>(i)] /= laplacian.effective_volume[i];
  return result;
}

// True if every lattice point of the (symmetric) stencil of x exists, real or mirrored: x is at
// least `reach` (the farthest lattice offset inside the support; dx for 2h = 1.5 dx) from every
// face of the box [0, extent] that is not a mirror plane.
bool has_full_stencil(const std::array<double, 3>& x, const std::array<double, 3>& extent,
                      int dimension, double reach, bool mirrored_low_faces) {
  for (int a = 0; a < dimension; ++a) {
    if (!mirrored_low_faces && x[a] < reach - 1e-9) return false;
    if (x[a] > extent[a] - reach + 1e-9) return false;
  }
  return true;
}

// The cubic spline of Monaghan in 1D, written out here independently of sph/kernel: with
// q = r/h and sigma = 2/(3h), W = sigma (2 - q)^3 / 4 for 1 <= q < 2, so
// dW/dr = -3 sigma (2 - q)^2 / (4h).
double cubic_spline_derivative_1d_outer(double r, double h) {
  const double q = r / h;
  const double sigma = 2.0 / (3.0 * h);
  return -3.0 * sigma * (2.0 - q) * (2.0 - q) / (4.0 * h);
}

TEST(LaplacianScale, MatchesHandDerivedValueIn1D) {
  // At h = 0.75 dx the support 2h = 1.5 dx holds only the neighbours at +-dx, so the Morris sum
  // of |x - x_I|^2 is 2 dx * (-2 dx W'(dx) / (dx^2 + eta^2)) * dx^2 and c = 2 / that.
  const double dx = 0.25, h = 0.75 * dx, eta = 0.1 * h;
  const double pair = -2.0 * dx * cubic_spline_derivative_1d_outer(dx, h) / (dx * dx + eta * eta);
  const double expected = 2.0 / (2.0 * dx * pair * dx * dx);
  const Kernel kernel(KernelType::CubicSpline, 1);
  EXPECT_NEAR(laplacian_consistency_scale(kernel, h, dx, 1), expected, 1e-12 * expected);
  // Independent numbers of the Python prototype (docs/theory.md §7.2, S1), quoted to 4 decimals.
  EXPECT_NEAR(laplacian_consistency_scale(kernel, h, dx, 1), 1.2727, 1e-4);
}

TEST(LaplacianScale, MatchesPrototypeIn2D) {
  // docs/theory.md §7.2, S1: L(|x|^2) = 2.978 without the scale at h = 0.75 dx
  // (factor 1.343, 1.3434 to four decimals), and 3.923 at h = 1.2 dx (factor 1.020). Quoted to 3-4
  // digits.
  const Kernel kernel(KernelType::CubicSpline, 2);
  const double dx = 0.5;
  EXPECT_NEAR(laplacian_consistency_scale(kernel, 0.75 * dx, dx, 2), 4.0 / 2.978, 2e-4);
  EXPECT_NEAR(laplacian_consistency_scale(kernel, 0.75 * dx, dx, 2), 1.3434, 1e-4);
  EXPECT_NEAR(laplacian_consistency_scale(kernel, 1.2 * dx, dx, 2), 4.0 / 3.923, 2e-4);
}

TEST(Laplacian, QuadraticIsExactInTheInterior1D) {
  // L(x^2) = 2 wherever the stencil is complete; a linear part must add nothing. Round-off:
  // a few terms of size f/dx^2 ~ 1e3 against 2: 1e-9 absolute is generous.
  const double dx = 0.25, length = 5.0;
  const NodeSets nodes = bar_lattice(length, dx);
  const OperatorOptions options = options_for(1, 0.75 * dx);
  const LaplacianMatrix laplacian = laplacian_on(nodes, options);
  const Eigen::VectorXd result = apply_laplacian(
      laplacian, nodes.sph_nodes, [](const auto& x) { return x[0] * x[0] - 3.0 * x[0] + 1.0; });
  int checked = 0;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    if (!has_full_stencil(nodes.sph_nodes.point(i), {length, 0, 0}, 1, dx, false)) continue;
    EXPECT_NEAR(result[static_cast<Eigen::Index>(i)], 2.0, 1e-9) << "node " << i;
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(nodes.sph_nodes.size()) - 2);
}

TEST(Laplacian, QuadraticIsExactInTheInterior2D) {
  // Laplacian of 3x^2 - xy + 2y^2 + x - y is 6 + 4 = 10; the mixed term cancels on the symmetric
  // stencil, so the interior value is exact up to round-off (values ~ 1e2 / dx^2 ~ 1e3).
  const double dx = 0.25;
  const NodeSets nodes = rectangle_lattice(3.0, 2.0, dx);
  const OperatorOptions options = options_for(2, 0.75 * dx);
  const LaplacianMatrix laplacian = laplacian_on(nodes, options);
  const Eigen::VectorXd result = apply_laplacian(laplacian, nodes.sph_nodes, [](const auto& x) {
    return 3.0 * x[0] * x[0] - x[0] * x[1] + 2.0 * x[1] * x[1] + x[0] - x[1];
  });
  int checked = 0;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    if (!has_full_stencil(nodes.sph_nodes.point(i), {3.0, 2.0, 0}, 2, dx, false)) continue;
    EXPECT_NEAR(result[static_cast<Eigen::Index>(i)], 10.0, 1e-8) << "node " << i;
    ++checked;
  }
  EXPECT_EQ(checked, (13 - 2) * (9 - 2));
}

TEST(Laplacian, EqualsTheThreePointStencilIn1D) {
  // At h = 0.75 dx each node sees only x +- dx, so the scaled Morris operator must be exactly the
  // finite-difference (f_{I+1} - 2 f_I + f_{I-1}) / dx^2; for sin(kx) that is
  // -sin(kx) (2 - 2 cos(k dx)) / dx^2, a closed form with the O(dx^2) truncation error built in.
  const double dx = 0.1, length = 4.0, wave_number = 1.3;
  const NodeSets nodes = bar_lattice(length, dx);
  const LaplacianMatrix laplacian = laplacian_on(nodes, options_for(1, 0.75 * dx));
  const Eigen::VectorXd result = apply_laplacian(
      laplacian, nodes.sph_nodes, [&](const auto& x) { return std::sin(wave_number * x[0]); });
  const double symbol = (2.0 - 2.0 * std::cos(wave_number * dx)) / (dx * dx);
  for (std::size_t i = 1; i + 1 < nodes.sph_nodes.size(); ++i) {
    const double x = nodes.sph_nodes.position[0][i];
    EXPECT_NEAR(result[static_cast<Eigen::Index>(i)], -symbol * std::sin(wave_number * x), 1e-9);
  }
}

// Max interior error of L against the exact Laplacian of a smooth, non-polynomial field.
double interior_error(int dimension, double dx) {
  const double extent = 2.0;
  const NodeSets nodes =
      dimension == 1 ? bar_lattice(extent, dx) : rectangle_lattice(extent, extent, dx);
  const LaplacianMatrix laplacian = laplacian_on(nodes, options_for(dimension, 0.75 * dx));
  const double kx = 1.1, ky = 0.7;
  auto field = [&](const std::array<double, 3>& x) {
    return std::sin(kx * x[0]) * (dimension == 2 ? std::cos(ky * x[1]) : 1.0);
  };
  const double exact_factor = -(kx * kx + (dimension == 2 ? ky * ky : 0.0));
  const Eigen::VectorXd result = apply_laplacian(laplacian, nodes.sph_nodes, field);
  double error = 0.0;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    const auto x = nodes.sph_nodes.point(i);
    // The same physical interior at every resolution: 0.5 m from each face.
    bool inside = true;
    for (int a = 0; a < dimension; ++a)
      inside = inside && x[a] >= 0.5 - 1e-9 && x[a] <= extent - 0.5 + 1e-9;
    if (!inside) continue;
    error =
        std::max(error, std::abs(result[static_cast<Eigen::Index>(i)] - exact_factor * field(x)));
  }
  return error;
}

TEST(Laplacian, IsSecondOrderAccurateInTheInterior) {
  // Halving dx must divide the interior error by 4 (order 2): the leading truncation term is
  // dx^2 times fourth derivatives, the next one dx^4, which at k dx <= 0.14 moves the ratio by
  // < 1 %; the window [3.6, 4.4] (order 1.85 .. 2.14) leaves room for that and nothing else.
  for (int dimension : {1, 2}) {
    const double coarse = interior_error(dimension, 0.125);
    const double fine = interior_error(dimension, 0.0625);
    EXPECT_GT(coarse, 0.0);
    EXPECT_GT(coarse / fine, 3.6) << "dimension " << dimension;
    EXPECT_LT(coarse / fine, 4.4) << "dimension " << dimension;
    // And the error is small in absolute terms: dx^2/12 |f''''| ~ 1e-3 at dx = 0.125.
    EXPECT_LT(coarse, 5e-3) << "dimension " << dimension;
  }
}

TEST(Laplacian, MirrorPlanesHalveVolumesAndKeepTheMatrixSymmetric) {
  // Mirrors at x = 0 and y = 0 (a corner): the node on one plane stands for both halves of the
  // mirrored domain (V/2), the corner node for four quarters (V/4) (docs/theory.md §7.2, S2).
  const double dx = 0.25;
  const NodeSets nodes = rectangle_lattice(1.5, 2.0, dx);
  const OperatorOptions options = options_for(2, 0.75 * dx, {{0, 0.0}, {1, 0.0}});
  const LaplacianMatrix laplacian = laplacian_on(nodes, options);
  const std::size_t n = nodes.sph_nodes.size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto x = nodes.sph_nodes.point(i);
    const double full = dx * dx;
    const double expected = full * (x[0] == 0.0 ? 0.5 : 1.0) * (x[1] == 0.0 ? 0.5 : 1.0);
    EXPECT_DOUBLE_EQ(laplacian.effective_volume[i], expected) << "node " << i;
  }
  const Eigen::MatrixXd dense = Eigen::MatrixXd(laplacian.weighted);
  const double size = dense.cwiseAbs().maxCoeff();
  EXPECT_LE((dense - dense.transpose()).cwiseAbs().maxCoeff(), 1e-13 * size);
  for (Eigen::Index i = 0; i < dense.rows(); ++i) {
    EXPECT_NEAR(dense.row(i).sum(), 0.0, 1e-13 * size) << "row " << i;  // constants in the kernel
    for (Eigen::Index j = 0; j < dense.cols(); ++j)
      if (i != j) {
        EXPECT_GE(dense(i, j), 0.0);  // an M-matrix pattern: -Ltilde is diagonally dominant
      }
  }
  // Negative semi-definite with exactly one zero mode (the constant): the lattice is connected.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> spectrum(-dense);
  const Eigen::VectorXd eigenvalues = spectrum.eigenvalues();
  EXPECT_NEAR(eigenvalues[0], 0.0, 1e-12 * size);
  EXPECT_GT(eigenvalues[1], 1e-6 * size);

  // An even quadratic about the mirror planes, x^2 + y^2, is exact (4) at every node whose real
  // plus image stencil is complete: all but the far faces x = 1.5 and y = 2, including the nodes
  // on the planes.
  const Eigen::VectorXd result = apply_laplacian(
      laplacian, nodes.sph_nodes, [](const auto& x) { return x[0] * x[0] + x[1] * x[1]; });
  int checked = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!has_full_stencil(nodes.sph_nodes.point(i), {1.5, 2.0, 0}, 2, dx, true)) continue;
    EXPECT_NEAR(result[static_cast<Eigen::Index>(i)], 4.0, 1e-9) << "node " << i;
    ++checked;
  }
  EXPECT_EQ(checked, 6 * 8);
}

}  // namespace
}  // namespace rktsph::laplacian_test

namespace rktsph::laplacian_test {
namespace {

TEST(Laplacian, CheckerboardRateIsTheEigenvalueOnTheLattice) {
  // The checkerboard (-1)^(i+j) is an eigenvector of L on complete stencils with eigenvalue
  // -laplacian_checkerboard_rate (it sets the p_w checkerboard stabilisation, theory §6.6). At
  // h = 0.75 dx only the four axis neighbours (opposite sign) count: rate = 8 c dx^2 |F(dx)|,
  // F(r) = 2 r W'(r)/(r^2 + eta^2): 7.68/dx^2 (the 5-point stencil has 8/dx^2).
  const double dx = 0.25;
  const NodeSets nodes = rectangle_lattice(3.0, 2.0, dx);
  const OperatorOptions options = options_for(2, 0.75 * dx);
  const LaplacianMatrix laplacian = laplacian_on(nodes, options);
  const double rate =
      laplacian_checkerboard_rate(options.kernel, 0.75 * dx, dx, 2, laplacian.scale);
  const double h = 0.75 * dx, eta = 0.1 * h;
  const double factor = 2.0 * dx * options.kernel.derivative(dx, h) / (dx * dx + eta * eta);
  EXPECT_NEAR(rate, 8.0 * laplacian.scale * dx * dx * std::abs(factor), 1e-12 * rate);
  EXPECT_NEAR(rate * dx * dx, 7.679, 1e-3);  // measured; the 5-point stencil has 8
  const Eigen::VectorXd result = apply_laplacian(laplacian, nodes.sph_nodes, [dx](const auto& x) {
    return (std::lround(x[0] / dx) + std::lround(x[1] / dx)) % 2 == 0 ? 1.0 : -1.0;
  });
  int checked = 0;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    const auto x = nodes.sph_nodes.point(i);
    if (!has_full_stencil(x, {3.0, 2.0, 0}, 2, dx, false)) continue;
    const double sign = (std::lround(x[0] / dx) + std::lround(x[1] / dx)) % 2 == 0 ? 1.0 : -1.0;
    EXPECT_NEAR(result[static_cast<Eigen::Index>(i)], -rate * sign, 1e-10 * rate) << "node " << i;
    ++checked;
  }
  EXPECT_EQ(checked, (13 - 2) * (9 - 2));
}

}  // namespace
}  // namespace rktsph::laplacian_test
