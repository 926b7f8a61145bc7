// Spectral radius of the one-step map x_{n+1} = M x_n of a simulation, built column by column.
// sigma_zz is left out: it is passive (nothing depends on it), so its block only adds a cluster
// of eigenvalues at exactly 1. The eigenvalues are computed in long double: the static states form
// a nearly defective cluster at 1 whose computed spread is O(sqrt(epsilon)), ~1e-8 in double,
// which would hide a 1e-9 criterion; in long double it is ~3e-10.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <vector>

#include "rktsph/simulation/simulation.hpp"

namespace rktsph::test {

/// The matrix of the one-step map on the first `size` unknowns (field-major), built column by
/// column; unknown k is measured in units of scale[k] (1 when `scale` is empty). `dt` 0: the
/// simulation's time step (another is for probing beyond the limits a case may ask for).
inline Eigen::MatrixXd step_matrix(Simulation& simulation, Eigen::Index size,
                                   const std::vector<double>& scale = {}, double dt = 0.0);

/// The matrix of the one-step map on `size` unknowns, unknown k being slot(k) in units of unit(k),
/// built column by column from a state that is zero elsewhere.
template <class Slot, class Unit>
Eigen::MatrixXd step_matrix_over(Simulation& simulation, Eigen::Index size, Slot slot, Unit unit,
                                 double dt) {
  State& state = simulation.state();
  Eigen::MatrixXd matrix(size, size);
  for (Eigen::Index column = 0; column < size; ++column) {
    for (FieldArray* part : state.arrays())  // the internal variables stay as they are
      if (part != &state.internal) std::fill(part->data().begin(), part->data().end(), 0.0);
    slot(column) = unit(column);
    state.time = 0.0;
    simulation.step().advance(state, dt > 0.0 ? dt : simulation.time_step());
    for (Eigen::Index row = 0; row < size; ++row)
      matrix(row, column) = slot(row) / unit(row);
  }
  return matrix;
}

inline Eigen::MatrixXd step_matrix(Simulation& simulation, Eigen::Index size,
                                   const std::vector<double>& scale, double dt) {
  State& state = simulation.state();
  return step_matrix_over(
      simulation, size,
      [&](Eigen::Index k) -> double& { return state.fields.data()[static_cast<std::size_t>(k)]; },
      [&](Eigen::Index k) { return scale.empty() ? 1.0 : scale[static_cast<std::size_t>(k)]; }, dt);
}

/// The state of the zero-energy controls' step (docs/theory.md §3.4): every field, then the
/// displacement and the strain the nodal stress received, then the cells' hourglass forces, which
/// the controls' forces depend on.
inline std::vector<double*> unknowns_with_displacement(State& state) {
  std::vector<double*> slots;
  for (double& x : state.fields.data())
    slots.push_back(&x);
  for (double& x : state.displacement.data())
    slots.push_back(&x);
  for (double& x : state.strain.data())
    slots.push_back(&x);
  for (double& x : state.hourglass_force.data())
    slots.push_back(&x);
  return slots;
}

/// The affine one-step map x -> M x + c on fields, displacement, received strain and hourglass
/// forces, with stresses in units of `impedance` (rho c_p), displacements in units of dt, strains
/// in units of dt / dx and hourglass forces (stress x length) in units of impedance x dx.
struct AffineStep {
  Eigen::MatrixXd matrix;
  Eigen::VectorXd constant;
  Eigen::Index velocities = 0;
};

inline AffineStep affine_step(Simulation& simulation, double impedance) {
  State& state = simulation.state();
  const std::vector<double*> slots = unknowns_with_displacement(state);
  const auto size = static_cast<Eigen::Index>(slots.size());
  const auto fields = static_cast<Eigen::Index>(state.fields.data().size());
  const auto points = static_cast<Eigen::Index>(state.fields.point_count());
  const double dt = simulation.time_step();
  AffineStep step;
  step.velocities = simulation.model().dimension() * points;
  Eigen::VectorXd unit = Eigen::VectorXd::Constant(size, impedance);
  unit.head(step.velocities).setOnes();
  const auto displacements = static_cast<Eigen::Index>(state.displacement.data().size());
  const auto strains = static_cast<Eigen::Index>(state.strain.data().size());
  const auto forces = static_cast<Eigen::Index>(state.hourglass_force.data().size());
  unit.segment(fields, displacements).setConstant(dt);
  unit.segment(fields + displacements, strains).setConstant(dt / simulation.nodes().spacing);
  unit.tail(forces).setConstant(impedance * simulation.nodes().spacing);
  auto advance = [&](const Eigen::VectorXd& x) {
    for (Eigen::Index k = 0; k < size; ++k)
      *slots[static_cast<std::size_t>(k)] = x(k) * unit(k);
    state.time = 0.0;
    simulation.step().advance(state, dt);
    Eigen::VectorXd y(size);
    for (Eigen::Index k = 0; k < size; ++k)
      y(k) = *slots[static_cast<std::size_t>(k)] / unit(k);
    return y;
  };
  step.constant = advance(Eigen::VectorXd::Zero(size));
  step.matrix.resize(size, size);
  for (Eigen::Index j = 0; j < size; ++j)
    step.matrix.col(j) = advance(Eigen::VectorXd::Unit(size, j)) - step.constant;
  return step;
}

/// The one-step map on the fields but sigma_zz and on the cells' hourglass forces (state since
/// docs/theory.md eq. 3.9), each force in units of `force_unit`, built column by column.
inline Eigen::MatrixXd step_matrix_with_forces(Simulation& simulation, double force_unit,
                                               double dt = 0.0) {
  State& state = simulation.state();
  const auto fields =
      static_cast<Eigen::Index>((state.fields.field_count() - 1) * state.fields.point_count());
  const auto forces = static_cast<Eigen::Index>(state.hourglass_force.data().size());
  return step_matrix_over(
      simulation, fields + forces,
      [&](Eigen::Index k) -> double& {
        return k < fields ? state.fields.data()[static_cast<std::size_t>(k)]
                          : state.hourglass_force.data()[static_cast<std::size_t>(k - fields)];
      },
      [&](Eigen::Index k) { return k < fields ? 1.0 : force_unit; }, dt);
}

/// The largest modulus of the eigenvalues of `matrix`, computed in long double (see above).
/// Compiled once in step_matrix.cpp: the eigen-solvers are the costliest templates to compile.
double largest_eigenvalue_modulus(const Eigen::MatrixXd& matrix);

/// Spectral radius of the one-step map of the fields (sigma_zz left out) and, when the hourglass
/// stiffness is on, of the cells' hourglass forces.
double spectral_radius(Simulation& simulation, double dt = 0.0);

/// Largest share of the velocity in the fixed points of the step of a damped, unloaded lattice:
/// the largest singular value of the velocity rows of an orthonormal basis of ker(I - M), with
/// the stresses scaled by `impedance` (rho c_p) so that all unknowns are of one size. Zero when
/// the only velocity a damped body can keep is rest (docs/theory.md §5.3).
double velocity_in_fixed_points(Simulation& simulation, double impedance);

}  // namespace rktsph::test
