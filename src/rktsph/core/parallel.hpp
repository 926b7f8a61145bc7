// OpenMP is used only where a loop is long enough to pay for the threads: on a busy machine a
// parallel region over a few hundred points can be 100x slower than the serial loop, because the
// threads wait at the barrier for a descheduled sibling (measured on the 1D bars).
#pragma once

#include <cstddef>
#include <cstdint>

namespace rktsph {

inline constexpr std::int64_t kParallelThreshold = 4096;

/// to[i] = from[i] for i < count, split over the threads for long arrays: the step copies about
/// twenty arrays per node, which a single thread streams at a fraction of the machine's bandwidth.
inline void parallel_copy(const double* from, std::size_t count, double* to) {
  const auto n = static_cast<std::int64_t>(count);
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
  for (std::int64_t i = 0; i < n; ++i)
    to[i] = from[i];
}

/// to[i] = value for i < count, split over the threads for long arrays.
inline void parallel_fill(double* to, std::size_t count, double value) {
  const auto n = static_cast<std::int64_t>(count);
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
  for (std::int64_t i = 0; i < n; ++i)
    to[i] = value;
}

}  // namespace rktsph
