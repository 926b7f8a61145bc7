#include "rktsph/linear_algebra/smoothed_aggregation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "rktsph/core/parallel.hpp"

namespace rktsph {

namespace {

bool strong(double value, double diagonal_i, double diagonal_j, double threshold) {
  return std::abs(value) >= threshold * std::sqrt(std::abs(diagonal_i * diagonal_j));
}

SparseRows tentative_prolongator(const std::vector<int>& aggregate, int count) {
  std::vector<Eigen::Triplet<double, int>> entries;
  entries.reserve(aggregate.size());
  for (std::size_t i = 0; i < aggregate.size(); ++i)
    if (aggregate[i] >= 0) entries.emplace_back(static_cast<int>(i), aggregate[i], 1.0);
  SparseRows p(static_cast<Eigen::Index>(aggregate.size()), count);
  p.setFromTriplets(entries.begin(), entries.end());
  return p;
}

std::vector<double> inverted_diagonal(const SparseRows& a) {
  std::vector<double> d = diagonal(a);
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (!(d[i] > 0.0))
      throw std::invalid_argument(
          "SmoothedAggregation: a diagonal entry is not positive; the matrix is not positive "
          "definite");
    d[i] = 1.0 / d[i];
  }
  return d;
}

// The position of each row's diagonal among the entries (rows are sorted by column).
std::vector<int> diagonal_entries(const SparseRows& a) {
  std::vector<int> position(static_cast<std::size_t>(a.rows()));
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    const int* begin = a.innerIndexPtr() + a.outerIndexPtr()[i];
    const int* end = a.innerIndexPtr() + a.outerIndexPtr()[i + 1];
    const int* found = std::lower_bound(begin, end, static_cast<int>(i));
    if (found == end || *found != i)
      throw std::invalid_argument("SmoothedAggregation: a row has no diagonal entry");
    position[static_cast<std::size_t>(i)] = static_cast<int>(found - a.innerIndexPtr());
  }
  return position;
}

// The row arrays a Gauss-Seidel sweep reads; `middle` is the position of each row's diagonal.
struct SweepRows {
  const int* start;
  const int* column;
  const double* value;
  const int* middle;
  SweepRows(const SparseRows& a, const std::vector<int>& diagonal_entry)
      : start(a.outerIndexPtr()),
        column(a.innerIndexPtr()),
        value(a.valuePtr()),
        middle(diagonal_entry.data()) {}
};

// body(begin, end) over the Gauss-Seidel chunks of `rows` rows, split over the threads. The chunks
// are fixed by the number of rows alone (max(1024, rows / 256) each).
template <typename Body>
void for_each_chunk(std::size_t rows, Body body) {
  const auto n = static_cast<std::int64_t>(rows);
  const std::int64_t chunk = std::max<std::int64_t>(1024, (n + 255) / 256);
  const std::int64_t chunks = (n + chunk - 1) / chunk;
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::int64_t c = 0; c < chunks; ++c)
    body(c * chunk, std::min(n, (c + 1) * chunk));
}

}  // namespace

std::vector<int> aggregate_rows(const SparseRows& a, double strength_threshold, int* count) {
  const auto n = static_cast<std::size_t>(a.rows());
  const std::vector<double> d = diagonal(a);
  // The strong neighbours of each row, j != i.
  std::vector<int> start(n + 1, 0), neighbour;
  std::vector<double> coupling;
  for (std::size_t i = 0; i < n; ++i) {
    for (SparseRows::InnerIterator it(a, static_cast<Eigen::Index>(i)); it; ++it) {
      const auto j = static_cast<std::size_t>(it.col());
      if (j != i && strong(it.value(), d[i], d[j], strength_threshold)) {
        neighbour.push_back(static_cast<int>(j));
        coupling.push_back(std::abs(it.value()));
      }
    }
    start[i + 1] = static_cast<int>(neighbour.size());
  }
  std::vector<int> aggregate(n, -1);
  int aggregates = 0;
  auto has_neighbours = [&](std::size_t i) { return start[i + 1] > start[i]; };
  // 1. A row whose strong neighbourhood is still free becomes an aggregate with it.
  for (std::size_t i = 0; i < n; ++i) {
    if (aggregate[i] >= 0 || !has_neighbours(i)) continue;
    bool free = true;
    for (int k = start[i]; k < start[i + 1] && free; ++k)
      free = aggregate[static_cast<std::size_t>(neighbour[static_cast<std::size_t>(k)])] < 0;
    if (!free) continue;
    aggregate[i] = aggregates;
    for (int k = start[i]; k < start[i + 1]; ++k)
      aggregate[static_cast<std::size_t>(neighbour[static_cast<std::size_t>(k)])] = aggregates;
    ++aggregates;
  }
  // 2. The rows left join the aggregate of phase 1 they are most strongly coupled to.
  const std::vector<int> first = aggregate;
  for (std::size_t i = 0; i < n; ++i) {
    if (first[i] >= 0) continue;
    double best = -1.0;
    for (int k = start[i]; k < start[i + 1]; ++k) {
      const int target = first[static_cast<std::size_t>(neighbour[static_cast<std::size_t>(k)])];
      if (target >= 0 && coupling[static_cast<std::size_t>(k)] > best) {
        best = coupling[static_cast<std::size_t>(k)];
        aggregate[i] = target;
      }
    }
  }
  // 3. Rows still free (all their strong neighbours taken in phase 2 only) form aggregates with
  // their free strong neighbours.
  for (std::size_t i = 0; i < n; ++i) {
    if (aggregate[i] >= 0 || !has_neighbours(i)) continue;
    aggregate[i] = aggregates;
    for (int k = start[i]; k < start[i + 1]; ++k) {
      const auto j = static_cast<std::size_t>(neighbour[static_cast<std::size_t>(k)]);
      if (aggregate[j] < 0) aggregate[j] = aggregates;
    }
    ++aggregates;
  }
  *count = aggregates;
  return aggregate;
}

double estimate_upper_eigenvalue(const SparseRows& a, const std::vector<double>& inverse_diagonal) {
  const auto n = static_cast<std::size_t>(a.rows());
  if (n == 0) return 0.0;
  double gershgorin = 0.0;
  for (Eigen::Index i = 0; i < a.outerSize(); ++i) {
    double row = 0.0;
    for (SparseRows::InnerIterator it(a, i); it; ++it)
      row += std::abs(it.value());
    gershgorin = std::max(gershgorin, row * inverse_diagonal[static_cast<std::size_t>(i)]);
  }
  // Power iteration on the symmetric S = D^-1/2 A D^-1/2 (same spectrum as D^-1 A) from a fixed
  // pseudo-random start, with the Rayleigh quotient as the estimate.
  std::vector<double> v(n), w(n), scaled(n);
  std::uint64_t seed = 0x9E3779B97F4A7C15ull;
  for (double& value : v) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    value = static_cast<double>(seed >> 11) / 9007199254740992.0 - 0.5;
  }
  double estimate = 0.0;
  for (int iteration = 0; iteration < 20; ++iteration) {
    const double norm = std::sqrt(dot(v.data(), v.data(), n));
    if (norm == 0.0) break;
    for (std::size_t i = 0; i < n; ++i)
      scaled[i] = v[i] / norm * std::sqrt(inverse_diagonal[i]);
    multiply(a, scaled.data(), w.data());
    for (std::size_t i = 0; i < n; ++i) {
      w[i] *= std::sqrt(inverse_diagonal[i]);
      v[i] /= norm;
    }
    estimate = dot(v.data(), w.data(), n);
    v.swap(w);
  }
  return std::min(1.1 * estimate, gershgorin);
}

SmoothedAggregation::SmoothedAggregation(const SparseRows& a, const MultigridOptions& options)
    : options_(options) {
  if (a.rows() != a.cols() || !a.isCompressed())
    throw std::invalid_argument("SmoothedAggregation: the matrix must be square and compressed");
  // Never more than max_levels levels: reserved, the vector does not move, so each level's pointer
  // to its own coarse matrix stays valid.
  levels_.reserve(static_cast<std::size_t>(std::max(options_.max_levels, 1)));
  levels_.emplace_back();
  levels_.back().matrix = &a;
  double threshold = options_.strength_threshold;
  for (;;) {
    Level& level = levels_.back();
    const SparseRows& matrix = *level.matrix;
    const auto n = static_cast<std::size_t>(matrix.rows());
    level.inverse_diagonal = inverted_diagonal(matrix);
    level.diagonal_entry = diagonal_entries(matrix);
    level.residual.assign(n, 0.0);
    level.snapshot.assign(n, 0.0);
    if (levels_.size() > 1) {  // the finest level's right-hand side and solution are the caller's
      level.rhs.assign(n, 0.0);
      level.solution.assign(n, 0.0);
    }
    if (n <= options_.coarsest_rows || static_cast<int>(levels_.size()) >= options_.max_levels)
      break;
    int count = 0;
    const std::vector<int> aggregate = aggregate_rows(matrix, threshold, &count);
    // No aggregate, or too little coarsening to pay for a level: this level is the coarsest.
    if (count == 0 || static_cast<double>(count) > 0.8 * static_cast<double>(n)) break;
    const SparseRows tentative = tentative_prolongator(aggregate, count);
    // P = (I - omega D^-1 A) P0, omega = 4 / (3 lambda_max(D^-1 A)).
    SparseRows scaled = matrix;
    for (Eigen::Index i = 0; i < scaled.outerSize(); ++i)
      for (SparseRows::InnerIterator it(scaled, i); it; ++it)
        it.valueRef() *= level.inverse_diagonal[static_cast<std::size_t>(i)];
    const double omega = 4.0 / (3.0 * estimate_upper_eigenvalue(matrix, level.inverse_diagonal));
    const SparseRows smoothing = scaled * tentative;
    level.prolongator = SparseRows(tentative - omega * smoothing).pruned();
    level.prolongator.makeCompressed();
    level.restriction = SparseRows(level.prolongator.transpose());
    level.restriction.makeCompressed();
    const SparseRows fine_product = matrix * level.prolongator;
    SparseRows coarse = SparseRows(level.restriction * fine_product).pruned();
    // Symmetric by construction up to rounding; make it exactly so for the Cholesky factors.
    const SparseRows transposed = coarse.transpose();
    coarse = SparseRows(0.5 * (coarse + transposed));
    coarse.makeCompressed();
    levels_.emplace_back();
    levels_.back().coarse_matrix = std::move(coarse);
    levels_.back().matrix = &levels_.back().coarse_matrix;
    threshold *= 0.5;
  }
  coarsest_.compute(Eigen::SparseMatrix<double>(*levels_.back().matrix));
  if (coarsest_.info() != Eigen::Success)
    throw std::invalid_argument(
        "SmoothedAggregation: the coarsest matrix has no LDL^T factorisation; the matrix is not "
        "positive definite");
}

std::size_t SmoothedAggregation::rows(std::size_t level) const {
  return static_cast<std::size_t>(levels_.at(level).matrix->rows());
}

double SmoothedAggregation::operator_complexity() const {
  double entries = 0.0;
  for (const Level& level : levels_)
    entries += static_cast<double>(level.matrix->nonZeros());
  return entries / static_cast<double>(levels_.front().matrix->nonZeros());
}

void SmoothedAggregation::apply(const double* r, double* z) const {
  cycle(0, r, z);
}

// Gauss-Seidel in chunks of rows fixed by the size of the level alone (not by the number of
// threads), so that the result does not depend on it. Within a chunk a sweep uses the values it has
// just updated; across chunks the values from before the sweep (zero in the forward sweep from a
// zero guess, a snapshot in the backward one). The backward sweep is the adjoint of the forward
// one, which keeps the cycle symmetric. Rows are sorted, so the entries before a row's diagonal are
// its lower part.
void SmoothedAggregation::forward_gauss_seidel(const Level& level, const double* b,
                                               double* x) const {
  const SweepRows a(*level.matrix, level.diagonal_entry);
  const double* inverse = level.inverse_diagonal.data();
  double* r = level.residual.data();
  for_each_chunk(level.residual.size(), [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i) {
      double sum = b[i];
      for (int k = a.start[i]; k < a.middle[i]; ++k)
        if (a.column[k] >= begin) sum -= a.value[k] * x[a.column[k]];
      x[i] = sum * inverse[i];
    }
  });
  // The sweep zeroed each row's residual against the entries it used, so b - A x is minus the
  // entries it did not use: the upper part, and the lower part in earlier chunks.
  for_each_chunk(level.residual.size(), [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i) {
      double sum = 0.0;
      for (int k = a.start[i]; k < a.middle[i] && a.column[k] < begin; ++k)
        sum -= a.value[k] * x[a.column[k]];
      for (int k = a.middle[i] + 1; k < a.start[i + 1]; ++k)
        sum -= a.value[k] * x[a.column[k]];
      r[i] = sum;
    }
  });
}

void SmoothedAggregation::backward_gauss_seidel(const Level& level, const double* b,
                                                double* x) const {
  const SweepRows a(*level.matrix, level.diagonal_entry);
  const double* inverse = level.inverse_diagonal.data();
  double* before = level.snapshot.data();
  parallel_copy(x, level.snapshot.size(), before);
  for_each_chunk(level.snapshot.size(), [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = end - 1; i >= begin; --i) {
      // Lower part and diagonal: not updated yet in this sweep, or in another chunk: the snapshot.
      double sum = b[i];
      for (int k = a.start[i]; k <= a.middle[i]; ++k)
        sum -= a.value[k] * before[a.column[k]];
      // Upper part: this chunk's rows are already updated.
      for (int k = a.middle[i] + 1; k < a.start[i + 1]; ++k) {
        const int j = a.column[k];
        sum -= a.value[k] * (j < end ? x[j] : before[j]);
      }
      x[i] += sum * inverse[i];
    }
  });
}

void SmoothedAggregation::cycle(std::size_t l, const double* b, double* x) const {
  const Level& level = levels_[l];
  if (l + 1 == levels_.size()) {
    const auto n = static_cast<Eigen::Index>(level.residual.size());
    Eigen::Map<Eigen::VectorXd>(x, n) = coarsest_.solve(Eigen::Map<const Eigen::VectorXd>(b, n));
    return;
  }
  const Level& coarse = levels_[l + 1];
  forward_gauss_seidel(level, b, x);
  multiply(level.restriction, level.residual.data(), coarse.rhs.data());
  cycle(l + 1, coarse.rhs.data(), coarse.solution.data());
  add_product(level.prolongator, coarse.solution.data(), x);
  backward_gauss_seidel(level, b, x);
}

}  // namespace rktsph
