#include "rktsph/validation/references/strip_elastic.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rktsph::references {

StripStress flamant_strip_stress(double load, double half_width, double x, double z) {
  if (!(z > 0.0)) throw std::invalid_argument("flamant_strip_stress: depth must be > 0");
  const double delta = std::atan((x - half_width) / z);
  const double alpha = std::atan((x + half_width) / z) - delta;
  const double scale = load / std::numbers::pi;
  const double s = std::sin(alpha), c2 = std::cos(alpha + 2.0 * delta);
  return {scale * (alpha - s * c2), scale * (alpha + s * c2),
          scale * s * std::sin(alpha + 2.0 * delta)};
}

double flamant_centre_line_vertical_stress(double load, double half_width, double z) {
  if (!(z > 0.0)) throw std::invalid_argument("flamant: depth must be > 0");
  const double alpha = 2.0 * std::atan(half_width / z);
  return load / std::numbers::pi * (alpha + std::sin(alpha));
}

double flamant_centre_line_horizontal_stress(double load, double half_width, double z) {
  if (!(z > 0.0)) throw std::invalid_argument("flamant: depth must be > 0");
  const double alpha = 2.0 * std::atan(half_width / z);
  return load / std::numbers::pi * (alpha - std::sin(alpha));
}

namespace {

// g(s) = (a + b s) e^{-s} and its derivatives in s, order 0..3.
double decaying(double a, double b, double s, int order) {
  const double e = std::exp(-s);
  switch (order) {
    case 0:
      return (a + b * s) * e;
    case 1:
      return (b - a - b * s) * e;
    case 2:
      return (a - 2.0 * b + b * s) * e;
    default:
      return (3.0 * b - a - b * s) * e;
  }
}

// Gaussian elimination with partial pivoting of a 4 x 4 system.
std::array<double, 4> solve4(std::array<std::array<double, 5>, 4> m) {
  for (int c = 0; c < 4; ++c) {
    int pivot = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::abs(m[r][c]) > std::abs(m[pivot][c])) pivot = r;
    std::swap(m[c], m[pivot]);
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      const double f = m[r][c] / m[c][c];
      for (int k = c; k < 5; ++k)
        m[r][k] -= f * m[c][k];
    }
  }
  return {m[0][4] / m[0][0], m[1][4] / m[1][1], m[2][4] / m[2][2], m[3][4] / m[3][3]};
}

// The coefficients A, B, C, D of mode k (load amplitude p) for the layer of depth h:
// f(0) = p/k^2 (sigma_z = -k^2 f cos kx = -p cos kx at the surface), f'(0) = 0 (no shear),
// f'(H) = 0 (no shear on the base), f'''(H) = 0 (u_z = 0 on the base); f^(m)(z) / k^m =
// g^(m)(kz) + (-1)^m g_h^(m)(k(H - z)).
std::array<double, 4> layer_mode(double k, double p, double h) {
  const double kh = k * h;
  auto row = [](double s, double t, int order, double right) {
    const double sign = order % 2 == 0 ? 1.0 : -1.0;
    return std::array<double, 5>{decaying(1, 0, s, order), decaying(0, 1, s, order),
                                 sign * decaying(1, 0, t, order), sign * decaying(0, 1, t, order),
                                 right};
  };
  return solve4({row(0.0, kh, 0, p / (k * k)), row(0.0, kh, 1, 0.0), row(kh, 0.0, 1, 0.0),
                 row(kh, 0.0, 3, 0.0)});
}

void check_layer(double half_width, const SmoothLayer& layer, double x) {
  if (!(layer.width > 0.0 && layer.depth > 0.0 && half_width > 0.0 && half_width <= layer.width &&
        x >= 0.0 && x <= layer.width))
    throw std::invalid_argument("strip on a smooth layer: point or strip outside the box");
}

}  // namespace

std::vector<double> strip_on_smooth_layer_surface_settlement(double load, double half_width,
                                                             const SmoothLayer& layer,
                                                             double young_modulus,
                                                             const std::vector<double>& x,
                                                             long modes) {
  for (double point : x)
    check_layer(half_width, layer, point);
  const double nu = layer.poisson_ratio, pi = std::numbers::pi;
  const double oedometric = young_modulus * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double plane_modulus = young_modulus / (1.0 - nu * nu);
  std::vector<double> settlement(x.size(),
                                 load * half_width / layer.width * layer.depth / oedometric);
  for (long n = 1; n <= modes; ++n) {
    const double k = n * pi / layer.width;
    const double p = 2.0 * load / (n * pi) * std::sin(k * half_width);
    const auto [a, b, c, d] = layer_mode(k, p, layer.depth);
    const double f3 = k * k * k * (decaying(a, b, 0.0, 3) - decaying(c, d, k * layer.depth, 3));
    for (std::size_t i = 0; i < x.size(); ++i)
      settlement[i] += f3 / (plane_modulus * k * k) * std::cos(k * x[i]);
  }
  return settlement;
}

StripStress strip_on_smooth_layer_stress(double load, double half_width, const SmoothLayer& layer,
                                         double x, double z) {
  const double w = layer.width, h = layer.depth;
  check_layer(half_width, layer, x);
  if (!(z > 0.0 && z <= h))
    throw std::invalid_argument("strip_on_smooth_layer_stress: point outside the box");
  const double k0 = layer.poisson_ratio / (1.0 - layer.poisson_ratio);
  // The mean load: the oedometric state (tension-positive code below, sign flipped at the end).
  double sigma_z = -load * half_width / w, sigma_x = k0 * sigma_z;
  const double pi = std::numbers::pi;
  const long modes = static_cast<long>(std::ceil(37.0 * w / (pi * z))) + 1;
  for (long n = 1; n <= modes; ++n) {
    const double k = n * pi / w;
    const double p = 2.0 * load / (n * pi) * std::sin(k * half_width);
    const auto [a, b, c, d] = layer_mode(k, p, h);
    const double s = k * z, t = k * (h - z), cosine = std::cos(k * x);
    const double f = decaying(a, b, s, 0) + decaying(c, d, t, 0);
    const double f2 = k * k * (decaying(a, b, s, 2) + decaying(c, d, t, 2));
    sigma_z -= k * k * f * cosine;
    sigma_x += f2 * cosine;
  }
  return {-sigma_x, -sigma_z, 0.0};
}

}  // namespace rktsph::references
