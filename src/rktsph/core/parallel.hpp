// OpenMP is used only where a loop is long enough to pay for the threads: on a busy machine a
// parallel region over a few hundred points can be 100x slower than the serial loop, because the
// threads wait at the barrier for a descheduled sibling (measured on the 1D bars).
#pragma once

#include <cstdint>

namespace rktsph {

inline constexpr std::int64_t kParallelThreshold = 4096;

}  // namespace rktsph
