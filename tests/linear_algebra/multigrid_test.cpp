// The pore-pressure solver's linear algebra alone (docs/theory.md §6.7): conjugate gradients, the
// smoothed-aggregation preconditioner (symmetric, positive, independent of the number of threads,
// iterations independent of the grid) and its parts (aggregates, the spectral bound).
#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <vector>

#include "rktsph/linear_algebra/conjugate_gradient.hpp"
#include "rktsph/linear_algebra/smoothed_aggregation.hpp"
#include "rktsph/linear_algebra/sparse_rows.hpp"

namespace rktsph::multigrid_test {
namespace {

// The 5-point Laplacian on an m x m grid of interior points (Dirichlet values eliminated), scaled
// by h^2: diagonal 4, neighbours -1. Its spectrum is known, so its condition number bounds the
// error a residual allows.
SparseRows poisson_2d(int m) {
  std::vector<Eigen::Triplet<double, int>> entries;
  auto index = [m](int i, int j) { return i + m * j; };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      entries.emplace_back(index(i, j), index(i, j), 4.0);
      if (i > 0) entries.emplace_back(index(i, j), index(i - 1, j), -1.0);
      if (i + 1 < m) entries.emplace_back(index(i, j), index(i + 1, j), -1.0);
      if (j > 0) entries.emplace_back(index(i, j), index(i, j - 1), -1.0);
      if (j + 1 < m) entries.emplace_back(index(i, j), index(i, j + 1), -1.0);
    }
  SparseRows a(m * m, m * m);
  a.setFromTriplets(entries.begin(), entries.end());
  a.makeCompressed();
  return a;
}

double poisson_2d_condition(int m) {
  const double c = std::cos(std::numbers::pi / (m + 1));
  return (1.0 + c) / (1.0 - c);
}

// Tridiagonal (-1, 2, -1) of size n; `weak_link` replaces the coupling between rows n/2 - 1 and
// n/2 (0 keeps -1).
SparseRows chain(int n, double weak_link = 0.0) {
  std::vector<Eigen::Triplet<double, int>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 2.0);
    for (int j : {i - 1, i + 1}) {
      if (j < 0 || j >= n) continue;
      const bool link = std::min(i, j) == n / 2 - 1;
      entries.emplace_back(i, j, link && weak_link != 0.0 ? -weak_link : -1.0);
    }
  }
  SparseRows a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());
  a.makeCompressed();
  return a;
}

std::vector<double> random_vector(std::size_t n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<double> v(n);
  for (double& value : v)
    value = uniform(random);
  return v;
}

struct Identity final : Preconditioner {
  std::size_t n;
  explicit Identity(std::size_t rows) : n(rows) {}
  void apply(const double* r, double* z) const override {
    for (std::size_t i = 0; i < n; ++i)
      z[i] = r[i];
  }
};

double relative_residual(const SparseRows& a, const std::vector<double>& x,
                         const std::vector<double>& b) {
  std::vector<double> r(b.size());
  residual(a, x.data(), b.data(), r.data());
  return std::sqrt(dot(r.data(), r.data(), r.size()) / dot(b.data(), b.data(), b.size()));
}

TEST(ConjugateGradient, SolvesASmallSystemInAtMostItsSizeIterations) {
  // Without preconditioning, CG on an n x n matrix with n distinct eigenvalues ends in n steps in
  // exact arithmetic; rounding may cost one or two more.
  const SparseRows a = chain(12);
  const std::vector<double> b = random_vector(12, 1);
  std::vector<double> x(12, 0.0);
  ConjugateGradient solver(12);
  const ConjugateGradientResult result =
      solver.solve(a, Identity(12), b.data(), x.data(), 1e-12, 100);
  EXPECT_TRUE(result.converged);
  EXPECT_LE(result.iterations, 14);
  EXPECT_LE(relative_residual(a, x, b), 1e-12);
  EXPECT_NEAR(result.relative_residual, relative_residual(a, x, b), 1e-14);
}

TEST(ConjugateGradient, ZeroRightHandSideGivesZeroAndNoIteration) {
  const SparseRows a = chain(8);
  const std::vector<double> b(8, 0.0);
  std::vector<double> x = random_vector(8, 2);
  ConjugateGradient solver(8);
  const ConjugateGradientResult result = solver.solve(a, Identity(8), b.data(), x.data(), 1e-8, 10);
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(result.iterations, 0);
  for (double value : x)
    EXPECT_EQ(value, 0.0);
}

TEST(ConjugateGradient, ReportsAnIterationLimitAsNotConverged) {
  const SparseRows a = poisson_2d(20);
  const std::vector<double> b = random_vector(400, 3);
  std::vector<double> x(400, 0.0);
  ConjugateGradient solver(400);
  const ConjugateGradientResult result =
      solver.solve(a, Identity(400), b.data(), x.data(), 1e-10, 3);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.iterations, 3);
  EXPECT_GT(result.relative_residual, 1e-10);
}

TEST(ConjugateGradient, RefusesAMatrixOfAnotherSize) {
  const SparseRows a = chain(8);
  std::vector<double> b(9, 1.0), x(9, 0.0);
  ConjugateGradient solver(9);
  EXPECT_THROW(solver.solve(a, Identity(9), b.data(), x.data(), 1e-8, 10), std::invalid_argument);
}

TEST(SmoothedAggregation, AggregatesFollowStrongCouplingsOnly) {
  // Two chains joined by a link far below eps sqrt(a_ii a_jj) = 0.16: no aggregate crosses it,
  // every row is aggregated, and each aggregate is a run of neighbours (a chain's aggregates are
  // connected).
  const int n = 40;
  const SparseRows a = chain(n, 1e-3);
  int count = 0;
  const std::vector<int> aggregate = aggregate_rows(a, 0.08, &count);
  EXPECT_GE(count, n / 3);
  EXPECT_LE(count, n / 2);
  std::vector<std::set<int>> members(static_cast<std::size_t>(count));
  for (int i = 0; i < n; ++i) {
    ASSERT_GE(aggregate[static_cast<std::size_t>(i)], 0) << "row " << i;
    ASSERT_LT(aggregate[static_cast<std::size_t>(i)], count);
    members[static_cast<std::size_t>(aggregate[static_cast<std::size_t>(i)])].insert(i);
  }
  for (const std::set<int>& rows : members) {
    ASSERT_FALSE(rows.empty());
    EXPECT_EQ(*rows.rbegin() - *rows.begin() + 1, static_cast<int>(rows.size()));
    EXPECT_TRUE(*rows.rbegin() < n / 2 || *rows.begin() >= n / 2)
        << "an aggregate crosses the weak link";
  }
}

TEST(SmoothedAggregation, RowsWithoutStrongCouplingsAreLeftToTheSmoother) {
  // A decoupled (Dirichlet) row has no neighbours: it belongs to no aggregate.
  std::vector<Eigen::Triplet<double, int>> entries{
      {0, 0, 1.0}, {1, 1, 2.0}, {1, 2, -1.0}, {2, 1, -1.0}, {2, 2, 2.0}};
  SparseRows a(3, 3);
  a.setFromTriplets(entries.begin(), entries.end());
  int count = 0;
  const std::vector<int> aggregate = aggregate_rows(a, 0.08, &count);
  EXPECT_EQ(aggregate[0], -1);
  EXPECT_EQ(count, 1);
  EXPECT_EQ(aggregate[1], 0);
  EXPECT_EQ(aggregate[2], 0);
}

TEST(SmoothedAggregation, SpectralBoundLiesBetweenTheLargestEigenvalueAndGershgorin) {
  // D^-1 A of the (-1, 2, -1) chain of size n has eigenvalues 1 - cos(k pi / (n + 1)).
  const int n = 60;
  const SparseRows a = chain(n);
  const std::vector<double> inverse(static_cast<std::size_t>(n), 0.5);
  const double largest = 1.0 + std::cos(std::numbers::pi / (n + 1));
  const double bound = estimate_upper_eigenvalue(a, inverse);
  EXPECT_GE(bound, largest);
  EXPECT_LE(bound, 2.0);
}

TEST(SmoothedAggregation, RefusesANonPositiveDiagonal) {
  SparseRows a = chain(10);
  a.coeffRef(4, 4) = 0.0;
  EXPECT_THROW(SmoothedAggregation{a}, std::invalid_argument);
}

TEST(SmoothedAggregation, CycleIsSymmetricAndPositive) {
  // Conjugate gradients need M^-1 symmetric positive definite: u.M^-1 v = v.M^-1 u to rounding.
  const SparseRows a = poisson_2d(70);
  const SmoothedAggregation multigrid(a);
  ASSERT_GE(multigrid.levels(), 3u);
  const std::size_t n = 70 * 70;
  for (unsigned seed = 10; seed < 14; ++seed) {
    const std::vector<double> u = random_vector(n, seed), v = random_vector(n, seed + 100);
    std::vector<double> mu(n), mv(n);
    multigrid.apply(u.data(), mu.data());
    multigrid.apply(v.data(), mv.data());
    const double uv = dot(u.data(), mv.data(), n), vu = dot(v.data(), mu.data(), n);
    EXPECT_NEAR(uv, vu,
                1e-12 * std::sqrt(dot(u.data(), mu.data(), n) * dot(v.data(), mv.data(), n)));
    EXPECT_GT(dot(u.data(), mu.data(), n), 0.0);
  }
}

TEST(SmoothedAggregation, GivesTheSameBitsOnOneAndTwoThreads) {
  const SparseRows a = poisson_2d(150);  // 22 500 rows: the sweeps and products split
  const std::size_t n = 150 * 150;
  const std::vector<double> b = random_vector(n, 20);
  const int saved = omp_get_max_threads();
  std::vector<std::vector<double>> solutions;
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    const SmoothedAggregation multigrid(a);
    std::vector<double> x(n, 0.0);
    ConjugateGradient solver(n);
    EXPECT_TRUE(solver.solve(a, multigrid, b.data(), x.data(), 1e-10, 100).converged);
    solutions.push_back(x);
  }
  omp_set_num_threads(saved);
  EXPECT_EQ(solutions[0], solutions[1]);
}

TEST(SmoothedAggregation, IterationsDoNotGrowWithTheGridAndTheAnswerIsTheDirectOne) {
  // Multigrid's point: the iterations to a fixed relative residual stay nearly constant while the
  // condition number grows 16x (Jacobi-CG's grow 4x, with sqrt(kappa)). The error against a direct
  // solve is bounded by kappa times the relative residual.
  const double tolerance = 1e-10;
  std::vector<long> iterations;
  for (int m : {48, 192}) {
    const SparseRows a = poisson_2d(m);
    const auto n = static_cast<std::size_t>(m * m);
    const std::vector<double> b = random_vector(n, 30);
    const SmoothedAggregation multigrid(a);
    std::vector<double> x(n, 0.0);
    ConjugateGradient solver(n);
    const ConjugateGradientResult result =
        solver.solve(a, multigrid, b.data(), x.data(), tolerance, 200);
    ASSERT_TRUE(result.converged);
    EXPECT_LE(relative_residual(a, x, b), tolerance);
    iterations.push_back(result.iterations);

    const Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> direct{Eigen::SparseMatrix<double>(a)};
    const Eigen::VectorXd exact = direct.solve(Eigen::Map<const Eigen::VectorXd>(b.data(), m * m));
    const Eigen::VectorXd error = Eigen::Map<const Eigen::VectorXd>(x.data(), m * m) - exact;
    EXPECT_LE(error.norm() / exact.norm(), poisson_2d_condition(m) * tolerance);
  }
  EXPECT_LE(iterations[0], 20);
  EXPECT_LE(iterations[1], iterations[0] + 4) << "iterations grow with the grid";
}

}  // namespace
}  // namespace rktsph::multigrid_test
