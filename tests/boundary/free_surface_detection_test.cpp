// Free-surface detection on shapes whose surface is known: regular, moved, notched, sheared and
// jittered lattice blocks, and discs. Each shape carries its reference perimeter and outward
// normals; the tests print the false-positive / false-negative counts and the normal angle errors
// (the table of the theory text) and assert the bounds the method must keep.
#include "rktsph/boundary/free_surface_detection.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "rktsph/sph/kernel.hpp"

namespace rktsph::free_surface_detection_test {
namespace {

using Vector = std::array<double, 3>;

/// A point set with its reference surface.
struct Shape {
  PointCloud cloud;
  std::vector<std::uint8_t> surface;     ///< 1: on the reference perimeter
  std::vector<std::uint8_t> second_row;  ///< 1: interior node next to a perimeter node
  std::vector<std::uint8_t> corner;      ///< 1: convex corner (two missing lattice neighbours)
  std::vector<Vector> normal;            ///< reference outward unit normal of perimeter nodes
  std::function<Vector(const Vector&)> reference_normal_at;  ///< if set, for any node (disc)
};

Vector unit(const Vector& v) {
  const double length = std::hypot(v[0], v[1]);
  return {v[0] / length, v[1] / length, 0.0};
}

/// The lattice nodes (i, j) with keep(i, j), mapped to space by `map` (which also gets the
/// node's index, for jitter). Topology (perimeter, normals, second row) is that of the lattice;
/// `normal_map` takes a lattice normal to the mapped shape's normal direction.
Shape lattice_shape(int nx, int ny, double dx, const std::function<bool(int, int)>& keep,
                    const std::function<Vector(double, double, std::size_t)>& map,
                    const std::function<Vector(const Vector&)>& normal_map) {
  Shape shape;
  shape.cloud.dimension = 2;
  std::vector<std::int64_t> index(static_cast<std::size_t>(nx * ny), -1);
  const auto at = [&](int i, int j) -> std::int64_t {
    if (i < 0 || j < 0 || i >= nx || j >= ny) return -1;
    return index[static_cast<std::size_t>(j * nx + i)];
  };
  std::vector<std::pair<int, int>> lattice;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      if (!keep(i, j)) continue;
      index[static_cast<std::size_t>(j * nx + i)] = static_cast<std::int64_t>(lattice.size());
      shape.cloud.push_back(map(i * dx, j * dx, lattice.size()), dx * dx);
      lattice.emplace_back(i, j);
    }
  }
  const std::size_t n = lattice.size();
  shape.surface.assign(n, 0);
  shape.second_row.assign(n, 0);
  shape.corner.assign(n, 0);
  shape.normal.assign(n, {0.0, 0.0, 0.0});
  constexpr int kSteps[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
  for (std::size_t k = 0; k < n; ++k) {
    const auto [i, j] = lattice[k];
    Vector missing{0.0, 0.0, 0.0};
    int missing_count = 0;
    for (const auto& step : kSteps) {
      if (at(i + step[0], j + step[1]) >= 0) continue;
      missing[0] += step[0];
      missing[1] += step[1];
      ++missing_count;
    }
    if (missing_count == 0) continue;
    shape.surface[k] = 1;
    shape.corner[k] = missing_count >= 2 ? 1 : 0;
    shape.normal[k] = unit(normal_map(missing));
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (shape.surface[k] != 0) continue;
    const auto [i, j] = lattice[k];
    for (int dj = -1; dj <= 1; ++dj) {
      for (int di = -1; di <= 1; ++di) {
        const std::int64_t m = at(i + di, j + dj);
        if (m >= 0 && shape.surface[static_cast<std::size_t>(m)] != 0) shape.second_row[k] = 1;
      }
    }
  }
  return shape;
}

Vector identity_map(double x, double y, std::size_t) {
  return {x, y, 0.0};
}
Vector identity_normal(const Vector& n) {
  return n;
}
bool keep_all(int, int) {
  return true;
}

Shape rectangle(int nx, int ny, double dx) {
  return lattice_shape(nx, ny, dx, keep_all, identity_map, identity_normal);
}

Vector rotated(const Vector& v, double angle) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  return {c * v[0] - s * v[1], s * v[0] + c * v[1], 0.0};
}

/// Lattice nodes inside radius R of the lattice point (c, c); perimeter: a 4-neighbour outside.
Shape lattice_disc(double radius_in_dx, double dx) {
  const int half = static_cast<int>(std::ceil(radius_in_dx)) + 1;
  const int size = 2 * half + 1;
  const auto inside = [=](int i, int j) { return std::hypot(i - half, j - half) < radius_in_dx; };
  Shape shape = lattice_shape(size, size, dx, inside, identity_map, identity_normal);
  const double centre = half * dx;
  shape.reference_normal_at = [centre](const Vector& x) {
    return unit({x[0] - centre, x[1] - centre, 0.0});
  };
  return shape;
}

/// Rings of spacing dx about the origin, ring k with round(2 pi k) nodes; the outer ring is the
/// surface.
Shape polar_disc(int rings, double dx) {
  Shape shape;
  shape.cloud.dimension = 2;
  shape.cloud.push_back({0.0, 0.0, 0.0}, std::numbers::pi * 0.25 * dx * dx);
  for (int k = 1; k <= rings; ++k) {
    const int count = static_cast<int>(std::lround(2.0 * std::numbers::pi * k));
    const double r = k * dx;
    for (int m = 0; m < count; ++m) {
      const double angle = 2.0 * std::numbers::pi * m / count;
      shape.cloud.push_back({r * std::cos(angle), r * std::sin(angle), 0.0},
                            2.0 * std::numbers::pi * r * dx / count);
    }
  }
  const std::size_t n = shape.cloud.size();
  shape.surface.assign(n, 0);
  shape.second_row.assign(n, 0);
  shape.corner.assign(n, 0);
  shape.normal.assign(n, {0.0, 0.0, 0.0});
  for (std::size_t i = 0; i < n; ++i) {
    const double r = std::hypot(shape.cloud.position[0][i], shape.cloud.position[1][i]);
    if (r > (rings - 0.5) * dx) {
      shape.surface[i] = 1;
      shape.normal[i] = unit(shape.cloud.point(i));
    } else if (r > (rings - 1.5) * dx) {
      shape.second_row[i] = 1;
    }
  }
  shape.reference_normal_at = [](const Vector& x) { return unit(x); };
  return shape;
}

struct Score {
  std::size_t surface = 0;              ///< reference perimeter nodes
  std::size_t interior = 0;             ///< reference interior nodes
  std::size_t missed = 0;               ///< false negatives
  std::size_t false_positive = 0;       ///< interior nodes flagged
  std::size_t false_beyond_second = 0;  ///< of which not in the second row
  std::size_t candidates = 0;
  double max_angle = 0.0;  ///< degrees, over the nodes scored
  double mean_angle = 0.0;
  double max_face_angle = 0.0;         ///< degrees, corners left out
  double max_surface_lambda = 0.0;     ///< largest lambda_hat of a reference perimeter node
  double min_interior_lambda = 1e300;  ///< smallest lambda_hat of a reference interior node
};

double angle_degrees(const Vector& a, const Vector& b) {
  const double cosine = std::clamp(a[0] * b[0] + a[1] * b[1], -1.0, 1.0);
  return std::acos(cosine) * 180.0 / std::numbers::pi;
}

/// Detection on `shape`, scored against its reference. Angles are taken over the detected nodes
/// that are on the reference perimeter, or over every detected node if the shape has a reference
/// normal everywhere (the discs).
Score score(const Shape& shape, const FreeSurfaceOptions& options, FreeSurface* result = nullptr) {
  const CellList cells(shape.cloud, 2.0 * options.smoothing_length);
  FreeSurface local;
  FreeSurface& out = result != nullptr ? *result : local;
  detect_free_surface(shape.cloud, cells, options, out);
  Score s;
  s.candidates = out.candidates;
  std::size_t angles = 0;
  for (std::size_t i = 0; i < shape.cloud.size(); ++i) {
    const bool reference = shape.surface[i] != 0;
    const bool detected = out.on_surface[i] != 0;
    if (reference) {
      s.max_surface_lambda = std::max(s.max_surface_lambda, out.lambda[i]);
      ++s.surface;
      if (!detected) ++s.missed;
    } else {
      s.min_interior_lambda = std::min(s.min_interior_lambda, out.lambda[i]);
      ++s.interior;
      if (detected) {
        ++s.false_positive;
        if (shape.second_row[i] == 0) ++s.false_beyond_second;
      }
    }
    if (!detected) continue;
    Vector expected;
    if (shape.reference_normal_at) {
      expected = shape.reference_normal_at(shape.cloud.point(i));
    } else if (reference) {
      expected = shape.normal[i];
    } else {
      continue;
    }
    const double angle = angle_degrees({out.normal[0][i], out.normal[1][i], 0.0}, expected);
    s.max_angle = std::max(s.max_angle, angle);
    if (shape.corner[i] == 0) s.max_face_angle = std::max(s.max_face_angle, angle);
    s.mean_angle += angle;
    ++angles;
  }
  if (angles > 0) s.mean_angle /= static_cast<double>(angles);
  return s;
}

void print(const std::string& name, const Score& s) {
  std::printf(
      "| %-27s | %4zu | %4zu | %2zu | %3zu (%4.2f%%) | %3zu | %4zu | %5.3f | %5.3f | %5.2f | "
      "%5.2f | %5.2f |\n",
      name.c_str(), s.surface, s.interior, s.missed, s.false_positive,
      100.0 * static_cast<double>(s.false_positive) / static_cast<double>(s.interior),
      s.false_beyond_second, s.candidates, s.max_surface_lambda, s.min_interior_lambda, s.max_angle,
      s.max_face_angle, s.mean_angle);
}

void print_header() {
  std::printf(
      "| shape                       | surf | int. | FN | FP (rate)    | FP>2 | cand | max "
      "lam surf | min lam int | max deg | max deg no corner | mean deg |\n");
}

FreeSurfaceOptions cubic(double h_over_dx, double dx = 1.0) {
  FreeSurfaceOptions options;
  options.kernel = KernelType::CubicSpline;
  options.smoothing_length = h_over_dx * dx;
  options.lattice_spacing = dx;
  return options;
}

// ---------------------------------------------------------------------------------------------
// The test shapes. dx = 0.1 m so that nothing depends on unit spacing.

constexpr double kDx = 0.1;

Shape moved_rectangle(double angle) {
  const Vector shift{3.7, -1.9, 0.0};
  return lattice_shape(
      30, 20, kDx, keep_all,
      [=](double x, double y, std::size_t) {
        const Vector r = rotated({x, y, 0.0}, angle);
        return Vector{r[0] + shift[0], r[1] + shift[1], 0.0};
      },
      [=](const Vector& n) { return rotated(n, angle); });
}

/// 30 x 20 with a 10 x 8 notch cut from the top face, 10 nodes from the left side.
Shape notched_rectangle() {
  return lattice_shape(
      30, 20, kDx, [](int i, int j) { return !(i >= 10 && i < 20 && j >= 12); }, identity_map,
      identity_normal);
}

/// 30 x 20 with each node moved by a uniform +-amplitude dx in x and y (fixed seed).
Shape jittered_rectangle(double amplitude, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> jitter(-amplitude * kDx, amplitude * kDx);
  std::vector<Vector> moves(600);
  for (auto& move : moves)
    move = {jitter(generator), jitter(generator), 0.0};
  return lattice_shape(
      30, 20, kDx, keep_all,
      [&](double x, double y, std::size_t k) {
        return Vector{x + moves[k][0], y + moves[k][1], 0.0};
      },
      identity_normal);
}

/// 30 x 20 after simple shear x += gamma y: area-preserving, faces y = const stay, faces
/// x = const tilt; normals map with F^-T, F^-T (a, b) = (a, b - gamma a).
Shape sheared_rectangle(double gamma) {
  return lattice_shape(
      30, 20, kDx, keep_all,
      [=](double x, double y, std::size_t) {
        return Vector{x + gamma * y, y, 0.0};
      },
      [=](const Vector& n) {
        return Vector{n[0], n[1] - gamma * n[0], 0.0};
      });
}

struct NamedShape {
  std::string name;
  Shape shape;
  double h_over_dx;
};

std::vector<NamedShape> all_shapes() {
  std::vector<NamedShape> shapes;
  for (const double h : {1.2, 1.3}) {
    const std::string suffix = h == 1.2 ? " h1.2" : " h1.3";
    shapes.push_back({"rectangle" + suffix, rectangle(30, 20, kDx), h});
    shapes.push_back({"rectangle moved+rot30" + suffix, moved_rectangle(std::numbers::pi / 6), h});
    shapes.push_back({"notched rectangle" + suffix, notched_rectangle(), h});
    shapes.push_back({"lattice disc R=15dx" + suffix, lattice_disc(15.0, kDx), h});
    shapes.push_back({"polar disc 15 rings" + suffix, polar_disc(15, kDx), h});
    shapes.push_back({"jittered +-0.2dx" + suffix, jittered_rectangle(0.2, 12345u), h});
    shapes.push_back({"sheared gamma=1" + suffix, sheared_rectangle(1.0), h});
  }
  return shapes;
}

// ---------------------------------------------------------------------------------------------

TEST(FreeSurfaceDetection, LambdaOnARegularLatticeMatchesTheHeaderTable) {
  // The calibration table of free_surface_detection.hpp, measured here so that it cannot drift:
  // interior, second row, flat face and corner of a 30 x 20 block.
  struct Row {
    KernelType kernel;
    double h_over_dx;
    double second, flat, corner;
  };
  const std::vector<Row> table = {
      {KernelType::CubicSpline, 1.0, 1.000, 0.500, 0.337},
      {KernelType::CubicSpline, 1.2, 0.942, 0.500, 0.295},
      {KernelType::CubicSpline, 1.3, 0.891, 0.500, 0.271},
      {KernelType::CubicSpline, 1.5, 0.814, 0.500, 0.235},
      {KernelType::QuinticSpline, 1.0, 0.925, 0.500, 0.283},
      {KernelType::QuinticSpline, 1.2, 0.826, 0.500, 0.244},
      {KernelType::QuinticSpline, 1.3, 0.781, 0.500, 0.229},
      {KernelType::QuinticSpline, 1.5, 0.709, 0.500, 0.207},
      {KernelType::Gaussian, 1.0, 0.917, 0.500, 0.286},
      {KernelType::Gaussian, 1.3, 0.785, 0.500, 0.231},
  };
  const Shape shape = rectangle(30, 20, 1.0);
  const auto node = [](int i, int j) { return static_cast<std::size_t>(j * 30 + i); };
  for (const Row& row : table) {
    FreeSurfaceOptions options = cubic(row.h_over_dx);
    options.kernel = row.kernel;
    FreeSurface out;
    score(shape, options, &out);
    const double interior = out.lambda[node(15, 10)];
    const double second = out.lambda[node(15, 1)];
    const double flat = out.lambda[node(15, 0)];
    const double corner = out.lambda[node(0, 0)];
    std::printf("%-8s h/dx %.1f: interior %.3f second %.3f flat %.3f corner %.3f\n",
                kernel_type_name(row.kernel).c_str(), row.h_over_dx, interior, second, flat,
                corner);
    // The table is printed to three decimals.
    EXPECT_NEAR(interior, 1.0, 1e-9);
    EXPECT_NEAR(second, row.second, 6e-4);
    EXPECT_NEAR(flat, row.flat, 6e-4);
    EXPECT_NEAR(corner, row.corner, 6e-4);
  }
}

class RegularRectangle : public testing::TestWithParam<std::pair<KernelType, double>> {};

TEST_P(RegularRectangle, IsExactlyItsPerimeter) {
  const auto [kernel, h_over_dx] = GetParam();
  FreeSurfaceOptions options = cubic(h_over_dx, 0.1);
  options.kernel = kernel;
  const Score s = score(rectangle(30, 20, 0.1), options);
  print(kernel_type_name(kernel) + " rectangle h/dx " + std::to_string(h_over_dx).substr(0, 3), s);
  EXPECT_EQ(s.missed, 0u);
  EXPECT_EQ(s.false_positive, 0u);
}

INSTANTIATE_TEST_SUITE_P(KernelsAndSmoothingLengths, RegularRectangle,
                         testing::Values(std::pair{KernelType::CubicSpline, 1.0},
                                         std::pair{KernelType::CubicSpline, 1.2},
                                         std::pair{KernelType::CubicSpline, 1.3},
                                         std::pair{KernelType::CubicSpline, 1.5},
                                         std::pair{KernelType::QuinticSpline, 1.0},
                                         std::pair{KernelType::QuinticSpline, 1.2},
                                         std::pair{KernelType::QuinticSpline, 1.3},
                                         std::pair{KernelType::QuinticSpline, 1.5},
                                         std::pair{KernelType::Gaussian, 1.0},
                                         std::pair{KernelType::Gaussian, 1.3}));

TEST(FreeSurfaceDetection, TableOfEveryShape) {
  // The table of the theory text: the default options (Marrone's normal, two smoothing passes).
  print_header();
  for (const NamedShape& named : all_shapes())
    print(named.name, score(named.shape, cubic(named.h_over_dx, kDx)));
}

TEST(FreeSurfaceDetection, MarroneNormalWithSmoothingIsTheBestChoice) {
  // The measurement behind the default normal: the mean angle error of each choice on the shapes
  // with a well-defined reference (the sheared block's corner reference is only approximate, and
  // the polar disc is below 0.3 degrees for every choice). The default must be the smallest.
  struct Choice {
    const char* name;
    FreeSurfaceNormal normal;
    int passes;
  };
  const std::vector<Choice> choices = {
      {"Marrone, 2 passes (default)", FreeSurfaceNormal::Marrone, 2},
      {"Marrone, no smoothing", FreeSurfaceNormal::Marrone, 0},
      {"indicator, no smoothing", FreeSurfaceNormal::Indicator, 0},
      {"indicator, 2 passes", FreeSurfaceNormal::Indicator, 2},
      {"average, no smoothing", FreeSurfaceNormal::Average, 0},
      {"average, 2 passes", FreeSurfaceNormal::Average, 2}};
  const std::vector<NamedShape> shapes = all_shapes();
  std::vector<std::vector<Score>> scores(choices.size());
  for (std::size_t c = 0; c < choices.size(); ++c) {
    std::printf("normal: %s\n", choices[c].name);
    print_header();
    for (const NamedShape& named : shapes) {
      FreeSurfaceOptions options = cubic(named.h_over_dx, kDx);
      options.normal = choices[c].normal;
      options.smoothing_passes = choices[c].passes;
      scores[c].push_back(score(named.shape, options));
      print(named.name, scores[c].back());
    }
  }
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const std::string& name = shapes[k].name;
    if (name.find("sheared") != std::string::npos || name.find("polar") != std::string::npos)
      continue;
    for (std::size_t c = 1; c < choices.size(); ++c)
      EXPECT_LT(scores[0][k].mean_angle, scores[c][k].mean_angle)
          << name << " vs " << choices[c].name;
  }
}

TEST(FreeSurfaceDetection, MovingAndRotatingTheRectangleChangesNothing) {
  // Detection is built from distances and directions only: a rigid motion must give the same
  // nodes and the rotated normals, up to round-off in the coordinates (1e-9 is far above it and
  // far below any angle the method could get wrong).
  const double angle = std::numbers::pi / 6;
  for (const double h : {1.2, 1.3}) {
    FreeSurface still;
    FreeSurface moved;
    const Score s_still = score(rectangle(30, 20, kDx), cubic(h, kDx), &still);
    const Score s_moved = score(moved_rectangle(angle), cubic(h, kDx), &moved);
    EXPECT_EQ(s_moved.missed, 0u);
    EXPECT_EQ(s_moved.false_positive, 0u);
    ASSERT_EQ(still.on_surface, moved.on_surface);
    for (std::size_t i = 0; i < still.on_surface.size(); ++i) {
      const Vector expected = rotated({still.normal[0][i], still.normal[1][i], 0.0}, angle);
      EXPECT_NEAR(moved.normal[0][i], expected[0], 1e-9);
      EXPECT_NEAR(moved.normal[1][i], expected[1], 1e-9);
    }
    EXPECT_NEAR(s_moved.max_angle, s_still.max_angle, 1e-6);
    // On a regular block the faces' normals are exact away from the corners; the two nodes next
    // to each corner lean towards its diagonal (measured 1.0 and 1.7 degrees at h = 1.2 and 1.3
    // dx); 3 degrees bounds both.
    EXPECT_LT(s_still.max_face_angle, 3.0) << "h/dx " << h;
  }
}

TEST(FreeSurfaceDetection, NotchedRectangleHasItsNotchFaces) {
  // The notch adds two concave corners, whose nodes keep all four lattice neighbours (interior by
  // the reference) while missing a diagonal one: they must not be flagged, nor may the notch's
  // faces be missed.
  for (const double h : {1.2, 1.3}) {
    const Score s = score(notched_rectangle(), cubic(h, kDx));
    EXPECT_EQ(s.missed, 0u) << "h/dx " << h;
    EXPECT_EQ(s.false_positive, 0u) << "h/dx " << h;
    // Measured max 9.3 and 10.4 degrees, at the faces' nodes next to the concave corners, where
    // the support sees the other face; mean 0.7 and 1.0 degrees.
    EXPECT_LT(s.max_angle, 15.0) << "h/dx " << h;
    EXPECT_LT(s.mean_angle, 1.5) << "h/dx " << h;
  }
}

TEST(FreeSurfaceDetection, PolarDiscNormalsAreRadialWithinFiveDegrees) {
  // A disc whose surface is resolved (a ring of nodes at one radius): the requirement,
  // every detected node's normal within 5 degrees of the radius, holds with a wide margin
  // (measured below 0.1 degree).
  for (const double h : {1.0, 1.2, 1.3, 1.5}) {
    const Score s = score(polar_disc(15, kDx), cubic(h, kDx));
    print("polar disc h/dx " + std::to_string(h).substr(0, 3), s);
    EXPECT_EQ(s.missed, 0u) << "h/dx " << h;
    EXPECT_EQ(s.false_positive, 0u) << "h/dx " << h;
    EXPECT_LE(s.max_angle, 5.0) << "h/dx " << h;
  }
}

TEST(FreeSurfaceDetection, LatticeDiscNormalsFollowItsStaircase) {
  // Lattice nodes inside R = 15 dx: the surface is a staircase, e.g. the column x = 14 dx runs
  // over 11 nodes (|y| <= 5 dx) while the radius turns by +-19.7 degrees along it. No normal built
  // from a support of 2.4-2.6 dx can tell this column from a flat face, so the radial reference
  // cannot be met to 5 degrees on every node (see the theory text). Measured with the defaults:
  // max 12.4 / 10.3 degrees, mean 5.4 / 5.1 degrees at h = 1.2 / 1.3 dx (unsmoothed Marrone
  // normals: 21.1 / 18.1 max, 9.5 / 8.6 mean). The bounds leave about 20 % margin.
  for (const double h : {1.2, 1.3}) {
    const Score s = score(lattice_disc(15.0, kDx), cubic(h, kDx));
    EXPECT_EQ(s.missed, 0u) << "h/dx " << h;
    // One concave staircase step at h = 1.2 dx has a node with its four neighbours whose
    // diagonal neighbour is missing; it is geometrically on the surface.
    EXPECT_LE(s.false_positive, 2u) << "h/dx " << h;
    EXPECT_EQ(s.false_beyond_second, 0u) << "h/dx " << h;
    EXPECT_LT(s.max_angle, 15.0) << "h/dx " << h;
    EXPECT_LT(s.mean_angle, 6.5) << "h/dx " << h;
  }
}

TEST(FreeSurfaceDetection, JitteredBlockKeepsItsPerimeter) {
  // Uniform jitter in x and y, 20 seeds. At +-0.2 dx (measured over the seeds): a face node stays
  // at lambda_hat <= 0.71 and every interior node >= 0.66, so the pre-screen (0.15, 0.85) never
  // decides wrongly and the scan region does the rest; no missed node and no false positive. The
  // bound of 1 % of the interior nodes (5) allows a node whose neighbours happen to leave an empty
  // umbrella. Normals: a face node's neighbours along the face are displaced by up to 0.4 dx
  // across it over 1-2 dx along it, a local tilt of up to about 20 degrees; measured max 15.1 /
  // 14.9 degrees away from the corners, mean <= 2.95 / 2.46 at h = 1.2 / 1.3 dx. (A corner node
  // whose neighbours moved can be 32 degrees off the diagonal: reported, not bounded.)
  // At +-0.25 dx a face node can be pushed behind its neighbours far enough to be geometrically
  // inside: measured 1 missed node in 20 seeds at h = 1.2 dx; at most 3 allowed.
  for (const double h : {1.2, 1.3}) {
    std::size_t missed_at_quarter = 0;
    for (unsigned seed = 1; seed <= 20; ++seed) {
      const Score s = score(jittered_rectangle(0.2, seed), cubic(h, kDx));
      if (seed <= 3)
        print("jitter 0.2 seed " + std::to_string(seed) + " h " + std::to_string(h).substr(0, 3),
              s);
      EXPECT_EQ(s.missed, 0u) << seed;
      EXPECT_LE(s.false_positive, s.interior / 100) << seed;
      EXPECT_LT(s.max_surface_lambda, 0.85) << seed;
      EXPECT_GT(s.min_interior_lambda, 0.15) << seed;
      EXPECT_LT(s.max_face_angle, 25.0) << seed;
      EXPECT_LT(s.mean_angle, 4.0) << seed;
      const Score quarter = score(jittered_rectangle(0.25, seed), cubic(h, kDx));
      missed_at_quarter += quarter.missed;
      EXPECT_LE(quarter.false_positive, quarter.interior / 100) << seed;
    }
    std::printf("jitter 0.25, h/dx %.1f: %zu missed nodes in 20 seeds\n", h, missed_at_quarter);
    EXPECT_LE(missed_at_quarter, 3u);
  }
}

TEST(FreeSurfaceDetection, ShearedBlockKeepsItsPerimeter) {
  // x += y: the block becomes a parallelogram with 45 and 135 degree corners. Measured: no missed
  // node; 2 and 3 false positives at h = 1.2 and 1.3 dx, all in the second row of the slanted
  // faces, which lies only dx/sqrt(2) behind a face whose nodes are sqrt(2) dx apart; 2 % of the
  // interior nodes (10) bounds them with margin, and none may be deeper than the second row.
  // Face normals (reference F^-T n): measured max 9.6 / 10.0 degrees next to the obtuse corners,
  // mean 0.6 / 0.7.
  for (const double h : {1.2, 1.3}) {
    const Score s = score(sheared_rectangle(1.0), cubic(h, kDx));
    EXPECT_EQ(s.missed, 0u) << "h/dx " << h;
    EXPECT_LE(s.false_positive, s.interior / 50) << "h/dx " << h;
    EXPECT_EQ(s.false_beyond_second, 0u) << "h/dx " << h;
    EXPECT_LT(s.max_face_angle, 15.0) << "h/dx " << h;
    EXPECT_LT(s.mean_angle, 1.5) << "h/dx " << h;
  }
}

TEST(FreeSurfaceDetection, LargeBlockRunsInParallelAndIsExact) {
  // 100 x 100 nodes: above kParallelThreshold, so the OpenMP loops run; the result must still be
  // exactly the perimeter.
  const Score s = score(rectangle(100, 100, kDx), cubic(1.3, kDx));
  EXPECT_EQ(s.surface, 396u);
  EXPECT_EQ(s.missed, 0u);
  EXPECT_EQ(s.false_positive, 0u);
}

TEST(FreeSurfaceDetection, RebuildingWithTheSameSizeDoesNotAllocate) {
  const Shape shape = rectangle(30, 20, kDx);
  const CellList cells(shape.cloud, 0.26);
  FreeSurface out;
  detect_free_surface(shape.cloud, cells, cubic(1.3, kDx), out);
  const std::uint8_t* flags = out.on_surface.data();
  const double* normal = out.normal[1].data();
  const double* lambda = out.lambda.data();
  const double* scratch = out.previous_normal[0].data();
  const std::vector<std::uint8_t> first = out.on_surface;
  detect_free_surface(shape.cloud, cells, cubic(1.3, kDx), out);
  EXPECT_EQ(out.on_surface.data(), flags);
  EXPECT_EQ(out.normal[1].data(), normal);
  EXPECT_EQ(out.lambda.data(), lambda);
  EXPECT_EQ(out.previous_normal[0].data(), scratch);
  EXPECT_EQ(out.on_surface, first);
}

TEST(FreeSurfaceDetection, ExcludedNodesAreNeverSurfaceButStillNeighbours) {
  // The bottom row is excluded (its velocity prescribed): none of it is flagged, and the rest is
  // unchanged, since the excluded nodes still fill the others' supports.
  const Shape shape = rectangle(30, 20, kDx);
  const CellList cells(shape.cloud, 0.26);
  std::vector<std::uint8_t> excluded(shape.cloud.size(), 0);
  for (std::size_t i = 0; i < 30; ++i)
    excluded[i] = 1;
  FreeSurface all;
  FreeSurface some;
  detect_free_surface(shape.cloud, cells, cubic(1.3, kDx), all);
  detect_free_surface(shape.cloud, cells, cubic(1.3, kDx), excluded, some);
  for (std::size_t i = 0; i < shape.cloud.size(); ++i) {
    if (excluded[i] != 0) {
      EXPECT_EQ(some.on_surface[i], 0) << i;
      EXPECT_EQ(some.normal[1][i], 0.0) << i;
    } else {
      EXPECT_EQ(some.on_surface[i], all.on_surface[i]) << i;
    }
  }
}

TEST(FreeSurfaceDetection, OneDimensionFlagsTheEnds) {
  PointCloud bar;
  bar.dimension = 1;
  for (const double x : {0.3, 0.0, 0.1, 0.2, 0.4})
    bar.push_back({x, 0.0, 0.0}, 0.1);
  const CellList cells(bar, 0.2);
  FreeSurface out;
  detect_free_surface(bar, cells, cubic(1.3, kDx), out);
  EXPECT_EQ(out.on_surface, (std::vector<std::uint8_t>{0, 1, 0, 0, 1}));
  EXPECT_EQ(out.normal[0][1], -1.0);
  EXPECT_EQ(out.normal[0][4], 1.0);
  EXPECT_EQ(out.normal[0][0], 0.0);
}

TEST(FreeSurfaceDetection, RejectsWhatItCannotDo) {
  PointCloud cube;
  cube.dimension = 3;
  cube.push_back({0.0, 0.0, 0.0}, 1.0);
  const CellList cube_cells(cube, 1.0);
  FreeSurface out;
  EXPECT_THROW(detect_free_surface(cube, cube_cells, cubic(1.3), out), std::invalid_argument);

  const Shape shape = rectangle(5, 4, kDx);
  const Shape other = rectangle(5, 4, kDx);
  const CellList cells(shape.cloud, 0.26);
  const CellList other_cells(other.cloud, 0.26);
  EXPECT_THROW(detect_free_surface(shape.cloud, other_cells, cubic(1.3, kDx), out),
               std::invalid_argument);
  FreeSurfaceOptions no_spacing = cubic(1.3, kDx);
  no_spacing.lattice_spacing = 0.0;
  EXPECT_THROW(detect_free_surface(shape.cloud, cells, no_spacing, out), std::invalid_argument);
  FreeSurfaceOptions no_length = cubic(1.3, kDx);
  no_length.smoothing_length = -1.0;
  EXPECT_THROW(detect_free_surface(shape.cloud, cells, no_length, out), std::invalid_argument);
  const std::vector<std::uint8_t> short_mask(3, 0);
  EXPECT_THROW(detect_free_surface(shape.cloud, cells, cubic(1.3, kDx), short_mask, out),
               std::invalid_argument);
}

}  // namespace
}  // namespace rktsph::free_surface_detection_test
