// Where a step's wall time goes (docs/theory.md §9.5): accumulated by the step and its operator
// builder with a few clock reads per step, read by the benchmarks and summary.json.
#pragma once

#include <chrono>

namespace rktsph {

struct StepTimeSplit {
  double cell_lists = 0.0;  ///< the neighbour search's cell lists (rebuilt on a moving body) [s]
  double operator_tables = 0.0;  ///< stencils gathered and weights computed, step and filter [s]
  double surface = 0.0;          ///< moving the configuration and turning its faces [s]
  double integration = 0.0;      ///< the rest of the step: the Taylor-Runge-Kutta update [s]
  double total() const { return cell_lists + operator_tables + surface + integration; }
  StepTimeSplit& operator+=(const StepTimeSplit& other) {
    cell_lists += other.cell_lists;
    operator_tables += other.operator_tables;
    surface += other.surface;
    integration += other.integration;
    return *this;
  }
};

/// Seconds since `start`, and restarts it.
inline double lap(std::chrono::steady_clock::time_point& start) {
  const auto now = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(now - start).count();
  start = now;
  return seconds;
}

}  // namespace rktsph
