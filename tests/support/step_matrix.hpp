// Spectral radius of the one-step map x_{n+1} = M x_n of a simulation, built column by column.
// sigma_zz is left out: it is passive (nothing depends on it), so its block only adds a cluster
// of eigenvalues at exactly 1. The eigenvalues are computed in long double: the static states form
// a nearly defective cluster at 1 whose computed spread is O(sqrt(epsilon)), ~1e-8 in double,
// which would hide a 1e-9 criterion; in long double it is ~3e-10.
#pragma once

#include <Eigen/Dense>
#include <algorithm>

#include "rktsph/simulation/simulation.hpp"

namespace rktsph::test {

inline double spectral_radius(Simulation& simulation) {
  State& state = simulation.state();
  const int fields = state.fields.field_count() - 1;
  const std::size_t n = state.fields.point_count();
  const auto size = static_cast<Eigen::Index>(fields * n);
  Eigen::MatrixXd matrix(size, size);
  for (Eigen::Index column = 0; column < size; ++column) {
    std::fill(state.fields.data().begin(), state.fields.data().end(), 0.0);
    state.fields.data()[static_cast<std::size_t>(column)] = 1.0;
    state.time = 0.0;
    simulation.step().advance(state, simulation.time_step());
    for (Eigen::Index row = 0; row < size; ++row)
      matrix(row, column) = state.fields.data()[static_cast<std::size_t>(row)];
  }
  using LongMatrix = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  const Eigen::EigenSolver<LongMatrix> solver(matrix.cast<long double>(), false);
  return static_cast<double>(solver.eigenvalues().cwiseAbs().maxCoeff());
}

}  // namespace rktsph::test
