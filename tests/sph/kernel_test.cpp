#include "rktsph/sph/kernel.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace rktsph::kernel_test {
namespace {

constexpr double kPi = std::numbers::pi;

const std::array<KernelType, 3> kAllTypes = {KernelType::CubicSpline, KernelType::QuinticSpline,
                                             KernelType::Gaussian};

/// Composite 5-point Gauss-Legendre rule on [lower, upper] with `panels` equal panels. It is exact
/// for polynomials up to degree 9 on each panel, so with panel ends on the spline breakpoints the
/// radial moments of the splines are integrated exactly (up to round-off).
double integrate(const std::function<double(double)>& integrand, double lower, double upper,
                 int panels) {
  const std::array<double, 5> node = {0.0, -0.5384693101056831, 0.5384693101056831,
                                      -0.9061798459386640, 0.9061798459386640};
  const std::array<double, 5> weight = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                        0.2369268850561891, 0.2369268850561891};
  const double width = (upper - lower) / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double centre = lower + (p + 0.5) * width;
    for (int k = 0; k < 5; ++k)
      sum += weight[k] * integrand(centre + 0.5 * width * node[k]);
  }
  return 0.5 * width * sum;
}

/// Integral of W over R^d for a radial kernel: the d-dimensional measure of a shell of radius r
/// is 2 (1D, both sides), 2 pi r (2D), 4 pi r^2 (3D).
double total_mass(const Kernel& kernel, double smoothing_length) {
  const double support = kernel.support_radius(smoothing_length);
  // One panel per 0.01 h: breakpoints (multiples of h) are panel ends; the Gaussian's quadrature
  // error at this resolution is far below 1e-12.
  const int panels = static_cast<int>(std::lround(kernel.support_factor() * 100));
  const int dimension = kernel.dimension();
  return integrate(
      [&](double r) {
        const double shell = dimension == 1   ? 2.0
                             : dimension == 2 ? 2.0 * kPi * r
                                              : 4.0 * kPi * r * r;
        return shell * kernel.value(r, smoothing_length);
      },
      0.0, support, panels);
}

TEST(Kernel, IntegratesToOneInEveryDimension) {
  for (KernelType type : kAllTypes) {
    for (int dimension = 1; dimension <= 3; ++dimension) {
      for (double smoothing_length : {1.0, 0.037}) {
        const Kernel kernel(type, dimension);
        EXPECT_NEAR(total_mass(kernel, smoothing_length), 1.0, 1e-8)
            << kernel_type_name(type) << " " << dimension << "D h=" << smoothing_length;
      }
    }
  }
}

TEST(Kernel, TwoDimensionalCartesianQuadratureAgreesWithRadialNormalisation) {
  // Independent of the radial reduction: a tensor-product Gauss rule (240 x 240 panels) over the
  // square [-R, R]^2. The square panels cut the circles where the kernel is not smooth:
  // - splines: only a jump in a high derivative (cubic: the third at q = 1, 2), so the error is
  //   tiny and 1e-9 is a loose bound;
  // - Gaussian: W itself jumps by e^{-9}/(pi h^2) at q = 3. The cut panels cover an area of about
  //   2 pi R * width, which bounds the error by ~2e-5 for h = 0.5 (cancellation makes it smaller).
  for (KernelType type : kAllTypes) {
    const Kernel kernel(type, 2);
    const double smoothing_length = 0.5;
    const double support = kernel.support_radius(smoothing_length);
    const int panels = 240;
    const double mass = integrate(
        [&](double y) {
          return integrate(
              [&](double x) { return kernel.value(std::hypot(x, y), smoothing_length); }, -support,
              support, panels);
        },
        -support, support, panels);
    const double tolerance = type == KernelType::Gaussian ? 2e-5 : 1e-9;
    EXPECT_NEAR(mass, 1.0, tolerance) << kernel_type_name(type);
  }
}

TEST(Kernel, CentralValuesMatchHandDerivedConstants) {
  const double h = 0.5;
  // Cubic: f(0) = 1, so W(0) = alpha_d.
  EXPECT_NEAR(Kernel(KernelType::CubicSpline, 1).value(0.0, h), 2.0 / (3.0 * h), 1e-14);
  EXPECT_NEAR(Kernel(KernelType::CubicSpline, 2).value(0.0, h), 10.0 / (7.0 * kPi * h * h), 1e-14);
  EXPECT_NEAR(Kernel(KernelType::CubicSpline, 3).value(0.0, h), 1.0 / (kPi * h * h * h), 1e-14);
  // Cubic at q = 1.5: f = 0.25 * 0.5^3 = 1/32.
  EXPECT_NEAR(Kernel(KernelType::CubicSpline, 2).value(1.5 * h, h),
              10.0 / (7.0 * kPi * h * h) / 32.0, 1e-15);
  // Quintic: f(0) = 3^5 - 6 * 2^5 + 15 = 66.
  EXPECT_NEAR(Kernel(KernelType::QuinticSpline, 1).value(0.0, h), 66.0 / (120.0 * h), 1e-13);
  // 3D quintic: 4 pi times the integral of q^2 f(q) is 4 pi (3^8 - 6 * 2^8 + 15) / 168 = 120 pi.
  EXPECT_NEAR(Kernel(KernelType::QuinticSpline, 3).value(0.0, h), 66.0 / (120.0 * kPi * h * h * h),
              1e-12);
  // Quintic at q = 2.5: f = 0.5^5.
  EXPECT_NEAR(Kernel(KernelType::QuinticSpline, 2).value(2.5 * h, h),
              7.0 / (478.0 * kPi * h * h) / 32.0, 1e-15);
  // Gaussian in 2D: 1/(pi h^2) divided by the mass kept inside q < 3, which is 1 - e^{-9}.
  EXPECT_NEAR(Kernel(KernelType::Gaussian, 2).value(h, h),
              std::exp(-1.0) / (kPi * h * h) / (1.0 - std::exp(-9.0)), 1e-14);
}

TEST(Kernel, DerivativeMatchesCentralDifferences) {
  const double h = 0.8;
  const double step = 1e-5 * h;
  for (KernelType type : kAllTypes) {
    for (int dimension = 1; dimension <= 3; ++dimension) {
      const Kernel kernel(type, dimension);
      const double scale = kernel.value(0.0, h) / h;  // size of dW/dr
      // q = 0.013, 0.113, ... avoids the breakpoints and the truncation by more than the step.
      for (double q = 0.013; q < kernel.support_factor() - 0.01; q += 0.1) {
        const double r = q * h;
        const double difference =
            (kernel.value(r + step, h) - kernel.value(r - step, h)) / (2.0 * step);
        // Central-difference truncation ~ step^2 |W'''| / 6 ~ 1e-10 scale; round-off
        // ~ 1e-16 W / step ~ 1e-11 scale.
        EXPECT_NEAR(kernel.derivative(r, h), difference, 1e-8 * scale)
            << kernel_type_name(type) << " " << dimension << "D q=" << q;
      }
    }
  }
}

TEST(Kernel, DerivativeIsNeverPositiveAndVanishesAtOrigin) {
  for (KernelType type : kAllTypes) {
    const Kernel kernel(type, 2);
    EXPECT_EQ(kernel.derivative(0.0, 1.0), 0.0) << kernel_type_name(type);
    for (double q = 0.0; q < 3.5; q += 0.01) {
      EXPECT_LE(kernel.derivative(q, 1.0), 0.0) << kernel_type_name(type) << " q=" << q;
    }
  }
}

TEST(Kernel, ValueAndDerivativeAreContinuousAtBreakpoints) {
  const double h = 1.0;
  const double epsilon = 1e-9;
  struct Case {
    KernelType type;
    std::vector<double> breakpoints;
  };
  // The cubic spline is C2 and the quintic C4, so both W and dW/dr must be continuous at every
  // breakpoint, including the edge of the support (where both reach 0).
  const std::vector<Case> cases = {{KernelType::CubicSpline, {1.0, 2.0}},
                                   {KernelType::QuinticSpline, {1.0, 2.0, 3.0}}};
  for (const Case& c : cases) {
    for (int dimension = 1; dimension <= 3; ++dimension) {
      const Kernel kernel(c.type, dimension);
      const double scale = kernel.value(0.0, h);
      for (double q : c.breakpoints) {
        // A jump would be O(scale); continuity leaves O(epsilon * scale).
        EXPECT_NEAR(kernel.value(q - epsilon, h), kernel.value(q + epsilon, h), 1e-7 * scale);
        EXPECT_NEAR(kernel.derivative(q - epsilon, h), kernel.derivative(q + epsilon, h),
                    1e-7 * scale);
      }
    }
  }
  // At the end of the support the splines vanish to high order.
  EXPECT_NEAR(Kernel(KernelType::CubicSpline, 1).value(2.0 - 1e-3, h), 2.0 / 3.0 * 0.25e-9, 1e-20);
}

TEST(Kernel, ZeroAtAndBeyondSupport) {
  for (KernelType type : kAllTypes) {
    for (int dimension = 1; dimension <= 3; ++dimension) {
      const Kernel kernel(type, dimension);
      for (double h : {0.3, 1.0, 7.0}) {
        const double support = kernel.support_radius(h);
        for (double r : {support, support * (1.0 + 1e-12), 1.5 * support, 1e6 * support}) {
          EXPECT_EQ(kernel.value(r, h), 0.0) << kernel_type_name(type) << " r=" << r;
          EXPECT_EQ(kernel.derivative(r, h), 0.0) << kernel_type_name(type) << " r=" << r;
        }
        EXPECT_GT(kernel.value(support * (1.0 - 1e-3), h), 0.0);
      }
    }
  }
}

TEST(Kernel, SupportFactors) {
  EXPECT_EQ(Kernel(KernelType::CubicSpline, 1).support_factor(), 2.0);
  EXPECT_EQ(Kernel(KernelType::QuinticSpline, 2).support_factor(), 3.0);
  EXPECT_EQ(Kernel(KernelType::Gaussian, 3).support_factor(), 3.0);
  EXPECT_DOUBLE_EQ(Kernel(KernelType::CubicSpline, 2).support_radius(0.75), 1.5);
}

std::array<double, 3> cross(const std::array<double, 3>& u, const std::array<double, 3>& v) {
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

TEST(Kernel, GradientIsOddAntiparallelToOffsetWithMagnitudeOfDerivative) {
  const double h = 0.6;
  const std::vector<std::array<double, 3>> offsets = {
      {0.3, 0.0, 0.0}, {0.2, -0.5, 0.0}, {-0.1, 0.4, 0.7}, {0.01, 0.02, -0.03}, {1.0, 1.0, 1.0}};
  for (KernelType type : kAllTypes) {
    const Kernel kernel(type, 3);
    for (const auto& offset : offsets) {
      const auto gradient = kernel.gradient(offset, h);
      const auto mirrored = kernel.gradient({-offset[0], -offset[1], -offset[2]}, h);
      const double distance =
          std::sqrt(offset[0] * offset[0] + offset[1] * offset[1] + offset[2] * offset[2]);
      const double slope = kernel.derivative(distance, h);
      for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(mirrored[a], -gradient[a]);
        // dW/dr <= 0, so grad W = (dW/dr) e_r points back along -offset.
        EXPECT_NEAR(gradient[a], slope * offset[a] / distance, 1e-14 * std::abs(slope) + 1e-300);
      }
      const auto normal = cross(gradient, offset);
      for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(normal[a], 0.0, 1e-14 * std::abs(slope));
    }
  }
}

TEST(Kernel, GradientMatchesFiniteDifferencesOfValueIn2D) {
  const Kernel kernel(KernelType::QuinticSpline, 2);
  const double h = 1.1;
  const double step = 1e-6;
  const std::array<double, 3> offset{0.7, -1.3, 0.0};
  const auto gradient = kernel.gradient(offset, h);
  for (int a = 0; a < 2; ++a) {
    auto plus = offset;
    auto minus = offset;
    plus[a] += step;
    minus[a] -= step;
    const double difference = (kernel.value(std::hypot(plus[0], plus[1]), h) -
                               kernel.value(std::hypot(minus[0], minus[1]), h)) /
                              (2.0 * step);
    EXPECT_NEAR(gradient[a], difference, 1e-8);
  }
}

TEST(Kernel, GradientIgnoresComponentsBeyondDimensionAndVanishesAtOrigin) {
  for (KernelType type : kAllTypes) {
    const Kernel planar(type, 2);
    const auto with_z = planar.gradient({0.3, 0.4, 9.0}, 1.0);
    const auto without_z = planar.gradient({0.3, 0.4, 0.0}, 1.0);
    EXPECT_EQ(with_z, without_z);
    EXPECT_EQ(with_z[2], 0.0);
    // |offset| = 0.5, so the gradient is dW/dr(0.5) times the unit vector (0.6, 0.8).
    EXPECT_NEAR(with_z[0], 0.6 * planar.derivative(0.5, 1.0), 1e-15);

    const Kernel line(type, 1);
    const auto along_line = line.gradient({-0.5, 3.0, 3.0}, 1.0);
    EXPECT_NEAR(along_line[0], -line.derivative(0.5, 1.0), 1e-15);
    EXPECT_EQ(along_line[1], 0.0);

    const std::array<double, 3> zero{0.0, 0.0, 0.0};
    EXPECT_EQ(Kernel(type, 3).gradient(zero, 1.0), zero);
    EXPECT_EQ(planar.gradient({0.0, 0.0, 5.0}, 1.0), zero);
  }
}

TEST(Kernel, NamesRoundTripAndUnknownNamesAreRejected) {
  for (KernelType type : kAllTypes)
    EXPECT_EQ(kernel_type_from_name(kernel_type_name(type)), type);
  EXPECT_EQ(kernel_type_from_name("cubic_spline"), KernelType::CubicSpline);
  EXPECT_EQ(kernel_type_from_name("quintic_spline"), KernelType::QuinticSpline);
  EXPECT_EQ(kernel_type_from_name("gaussian"), KernelType::Gaussian);
  EXPECT_THROW(kernel_type_from_name("cubic"), std::invalid_argument);
  EXPECT_THROW(kernel_type_from_name(""), std::invalid_argument);
  EXPECT_THROW(kernel_type_from_name("Gaussian"), std::invalid_argument);
}

TEST(Kernel, RejectsUnsupportedDimension) {
  EXPECT_THROW(Kernel(KernelType::CubicSpline, 0), std::invalid_argument);
  EXPECT_THROW(Kernel(KernelType::Gaussian, 4), std::invalid_argument);
  const Kernel kernel(KernelType::QuinticSpline, 3);
  EXPECT_EQ(kernel.type(), KernelType::QuinticSpline);
  EXPECT_EQ(kernel.dimension(), 3);
}

}  // namespace
}  // namespace rktsph::kernel_test
