#include "rktsph/materials/point_driver.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

#include "rktsph/core/error.hpp"
#include "rktsph/materials/invariants.hpp"
#include "rktsph/materials/overstress_integrator.hpp"

namespace rktsph {

StrainPath StrainPath::constant_strain_rate(const SymmetricTensor& strain_rate, double duration) {
  StrainPath path;
  path.rate = [strain_rate](double) { return strain_rate; };
  path.duration = duration;
  return path;
}

StrainPath StrainPath::uniaxial_stress(double axial_strain_rate, double duration) {
  StrainPath path;
  path.control[1] = PathControl::Stress;
  path.control[2] = PathControl::Stress;
  path.rate = [axial_strain_rate](double) {
    return SymmetricTensor{axial_strain_rate, 0.0, 0.0, 0.0, 0.0, 0.0};
  };
  path.duration = duration;
  return path;
}

PointState initial_point_state(const Material& material, const SymmetricTensor& stress) {
  PointState state;
  state.stress = stress;
  state.internal.assign(static_cast<std::size_t>(material.internal_count()), 0.0);
  material.initial_internal(state.internal);
  return state;
}

namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

// Layout of the integrated vector: stress, total strain, internal variables.
constexpr int kStressOffset = 0;
constexpr int kStrainOffset = 6;
constexpr int kInternalOffset = 12;

/// Evaluates the right-hand side of the point's ODE. All work arrays are sized once, so a step
/// allocates nothing.
class PointRates {
 public:
  PointRates(const Material& material, const StrainPath& path) : material_(material), path_(path) {
    set_stiffness(material.elastic());
    internal_rate_.assign(static_cast<std::size_t>(material.internal_count()), 0.0);
  }

  /// rate = f(time, state); `viscoplastic = false` gives the purely elastic rate (for the
  /// predictor used in choosing sub-steps).
  void evaluate(double time, const double* state, double* rate, bool viscoplastic) {
    SymmetricTensor stress;
    std::copy_n(state + kStressOffset, 6, stress.begin());
    const std::span<const double> internal(state + kInternalOffset, internal_rate_.size());
    // The tangent stiffness at this stage's stress (docs/theory.md eq. 1.10c).
    if (material_.stress_dependent_elasticity()) set_stiffness(material_.elastic_at(stress));
    SymmetricTensor viscoplastic_strain_rate{};
    std::fill(internal_rate_.begin(), internal_rate_.end(), 0.0);
    if (viscoplastic)
      material_.viscoplastic_rate(stress, internal, viscoplastic_strain_rate, internal_rate_);

    const SymmetricTensor prescribed = path_.rate(time);
    Vector6 strain_rate = Vector6::Zero();
    Vector6 plastic = Vector6::Zero();
    for (int i = 0; i < 6; ++i) {
      plastic[i] = viscoplastic_strain_rate[i];
      if (path_.control[i] == PathControl::Strain) strain_rate[i] = prescribed[i];
    }
    // Stress-controlled components: D_UU e_U = stress_rate_U - D_UK e_K + (D e_vp)_U.
    const Vector6 known_part = stiffness_ * (strain_rate - plastic);
    Vector6 residual = Vector6::Zero();
    for (int i = 0; i < 6; ++i)
      if (path_.control[i] == PathControl::Stress) residual[i] = prescribed[i] - known_part[i];
    strain_rate += stress_control_inverse_ * residual;
    const Vector6 stress_rate = stiffness_ * (strain_rate - plastic);

    for (int i = 0; i < 6; ++i) {
      rate[kStressOffset + i] = stress_rate[i];
      rate[kStrainOffset + i] = strain_rate[i];
    }
    std::copy(internal_rate_.begin(), internal_rate_.end(), rate + kInternalOffset);
  }

 private:
  /// D of `elastic` and the stress-control solver built on it.
  void set_stiffness(const ElasticConstants& elastic) {
    for (int column = 0; column < 6; ++column) {
      SymmetricTensor unit{};
      unit[column] = 1.0;
      const SymmetricTensor stress = apply_elastic_stiffness(elastic, unit);
      for (int row = 0; row < 6; ++row)
        stiffness_(row, column) = stress[row];
    }
    build_stress_control_solver();
  }

  /// inv(D_UU) embedded in a 6x6 matrix (zero outside U x U), U = stress-controlled components.
  void build_stress_control_solver() {
    std::vector<int> controlled;
    for (int i = 0; i < 6; ++i)
      if (path_.control[i] == PathControl::Stress) controlled.push_back(i);
    stress_control_inverse_.setZero();
    if (controlled.empty()) return;
    const int count = static_cast<int>(controlled.size());
    Eigen::MatrixXd block(count, count);
    for (int a = 0; a < count; ++a)
      for (int b = 0; b < count; ++b)
        block(a, b) = stiffness_(controlled[a], controlled[b]);
    const Eigen::MatrixXd inverse = block.inverse();
    for (int a = 0; a < count; ++a)
      for (int b = 0; b < count; ++b)
        stress_control_inverse_(controlled[a], controlled[b]) = inverse(a, b);
  }

  const Material& material_;
  const StrainPath& path_;
  Matrix6 stiffness_;
  Matrix6 stress_control_inverse_;
  std::vector<double> internal_rate_;
};

/// Classical RK4 over `substeps` equal sub-steps of [time, time + step]: the sub-stepping of the
/// step's stress update (rk4_substeps, materials/overstress_integrator.hpp) on the driver's rates.
///
/// The driver does not call OverstressIntegrator itself, on purpose: the SPH step integrates
/// sigma' = R - D : eps_dot^vp with R a constant over the interval, D condensed onto the carried
/// components and the stress-free ones at zero. Here the prescribed rates are functions of time
/// (read at every RK stage), the stress-controlled components are solved for at every evaluation,
/// so that they may be held at a non-zero stress (the confining stress of a triaxial test), and
/// the total strain is integrated along with the stress. Neither the exactly-elastic shortcut nor
/// the tension cut-off (docs/theory.md §1.7) applies: the material tests probe the flow itself.
class Rk4Integrator {
 public:
  explicit Rk4Integrator(std::size_t size)
      : stage_(size), k1_(size), k2_(size), k3_(size), k4_(size) {}

  void advance(PointRates& rates, double time, double step, int substeps,
               std::vector<double>& state) {
    double* const k[4] = {k1_.data(), k2_.data(), k3_.data(), k4_.data()};
    auto slope = [&rates](double t, const double* y, double* rate) {
      rates.evaluate(t, y, rate, true);
    };
    rk4_substeps(slope, time, step, substeps, static_cast<int>(state.size()), state.data(),
                 stage_.data(), k);
  }

 private:
  std::vector<double> stage_, k1_, k2_, k3_, k4_;
};

SymmetricTensor stress_of(const std::vector<double>& state) {
  SymmetricTensor stress;
  std::copy_n(state.begin() + kStressOffset, 6, stress.begin());
  return stress;
}

/// Sub-steps for one step: the source stiffness is taken at the start of the step and at its
/// elastic predictor, so that a point that starts the step elastic but ends it far outside the
/// yield surface is still sub-stepped.
int choose_substeps(const Material& material, PointRates& rates, double time, double step,
                    const std::vector<double>& state, std::vector<double>& predictor,
                    std::vector<double>& elastic_rate, const DriveOptions& options) {
  const auto internal_of = [](const std::vector<double>& y) {
    return std::span<const double>(y.data() + kInternalOffset, y.size() - kInternalOffset);
  };
  rates.evaluate(time, state.data(), elastic_rate.data(), false);
  for (std::size_t i = 0; i < state.size(); ++i)
    predictor[i] = state[i] + step * elastic_rate[i];
  const double stiffness =
      std::max(material.source_stiffness(stress_of(state), internal_of(state)),
               material.source_stiffness(stress_of(predictor), internal_of(predictor)));
  return substep_count(step, stiffness, options.substep_factor, options.max_substeps);
}

PointState to_point_state(double time, const std::vector<double>& state, int substeps) {
  PointState point;
  point.time = time;
  std::copy_n(state.begin() + kStressOffset, 6, point.stress.begin());
  std::copy_n(state.begin() + kStrainOffset, 6, point.strain.begin());
  point.internal.assign(state.begin() + kInternalOffset, state.end());
  point.substeps = substeps;
  return point;
}

void check_options(const Material& material, const StrainPath& path, const PointState& start,
                   const DriveOptions& options) {
  if (!path.rate) throw std::invalid_argument("point driver: the path has no rate function");
  if (!(path.duration >= 0.0) || !(options.time_step > 0.0) || !(options.substep_factor > 0.0) ||
      options.max_substeps < 1 || options.record_every < 1)
    throw std::invalid_argument("point driver: bad duration or options");
  if (start.internal.size() != static_cast<std::size_t>(material.internal_count()))
    throw std::invalid_argument("point driver: start state has the wrong number of internals");
}

}  // namespace

std::vector<PointState> drive(const Material& material, const StrainPath& path,
                              const PointState& start, const DriveOptions& options) {
  check_options(material, path, start, options);
  std::vector<double> state(kInternalOffset + start.internal.size());
  std::copy(start.stress.begin(), start.stress.end(), state.begin() + kStressOffset);
  std::copy(start.strain.begin(), start.strain.end(), state.begin() + kStrainOffset);
  std::copy(start.internal.begin(), start.internal.end(), state.begin() + kInternalOffset);

  PointRates rates(material, path);
  Rk4Integrator integrator(state.size());
  std::vector<double> predictor(state.size()), elastic_rate(state.size());
  std::vector<PointState> history{start};

  // Steps shorter than this fraction of the time step are round-off of the duration.
  const double end_tolerance = 1e-9 * options.time_step;
  double elapsed = 0.0;
  long step_index = 0;
  while (elapsed < path.duration - end_tolerance) {
    const double step = std::min(options.time_step, path.duration - elapsed);
    const int substeps =
        choose_substeps(material, rates, elapsed, step, state, predictor, elastic_rate, options);
    integrator.advance(rates, elapsed, step, substeps, state);
    elapsed += step;
    ++step_index;
    for (double value : state)
      if (!std::isfinite(value))
        throw RunError(fmt::format("point driver ({}): state not finite at t = {} s (step {})",
                                   material.model_name(), start.time + elapsed, step_index));
    const bool last = !(elapsed < path.duration - end_tolerance);
    if (last || step_index % options.record_every == 0)
      history.push_back(to_point_state(start.time + elapsed, state, substeps));
  }
  return history;
}

}  // namespace rktsph
