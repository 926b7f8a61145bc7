#include "step_matrix.hpp"

namespace rktsph::test {

double largest_eigenvalue_modulus(const Eigen::MatrixXd& matrix) {
  using LongMatrix = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  const Eigen::EigenSolver<LongMatrix> solver(matrix.cast<long double>(), false);
  return static_cast<double>(solver.eigenvalues().cwiseAbs().maxCoeff());
}

double spectral_radius(Simulation& simulation, double dt) {
  const double force_unit = simulation.nodes().spacing;  // a force k q of 1 Pa m per unit field
  return largest_eigenvalue_modulus(step_matrix_with_forces(simulation, force_unit, dt));
}

double velocity_in_fixed_points(Simulation& simulation, double impedance) {
  const FieldArray& fields = simulation.state().fields;
  const auto size = static_cast<Eigen::Index>(fields.field_count() * fields.point_count());
  const auto velocities =
      static_cast<Eigen::Index>(simulation.model().dimension() * fields.point_count());
  std::vector<double> scale(static_cast<std::size_t>(size), impedance);
  std::fill_n(scale.begin(), velocities, 1.0);
  const Eigen::MatrixXd identity_minus_step =
      Eigen::MatrixXd::Identity(size, size) - step_matrix(simulation, size, scale);
  Eigen::FullPivLU<Eigen::MatrixXd> lu(identity_minus_step);
  lu.setThreshold(1e-9);
  const Eigen::MatrixXd kernel = lu.kernel();
  if (kernel.cols() == 0 || kernel.norm() == 0.0) return 0.0;
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(kernel);
  const Eigen::MatrixXd basis = qr.householderQ() * Eigen::MatrixXd::Identity(size, kernel.cols());
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(basis.topRows(velocities));
  return svd.singularValues()(0);
}

}  // namespace rktsph::test
