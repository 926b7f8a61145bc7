#include "rktsph/time/configuration_policy.hpp"

#include <fmt/format.h>

#include "rktsph/core/error.hpp"
#include "rktsph/core/parallel.hpp"
#include "rktsph/physics/kinematics/objective_rate.hpp"

namespace rktsph {

MovingConfiguration::MovingConfiguration(const PhysicsModel& model, const NodeSets& reference,
                                         const CellFormation* formation)
    : model_(model),
      reference_(reference),
      origin_(formation ? *formation->origin : reference.sph_nodes),
      motion_(reference, formation),
      predicted_nodes_(reference.sph_nodes) {}

void MovingConfiguration::rotate_stress(const FieldArray& gradient,
                                        std::span<const int> velocity_gradient, double interval,
                                        std::size_t count, FieldArray& values) const {
  model_.rotate_stress(gradient, velocity_gradient, interval, count, values);  // eq. 9.2
}

void MovingConfiguration::scale_momentum_rate(FieldArray& rate, std::size_t count,
                                              const double* current_volume,
                                              const double* reference_volume,
                                              const std::int32_t* row_point) const {
  for (int a = 0; a < model_.dimension(); ++a) {
    double* r = rate.field(model_.velocity_field(a));
    for (std::size_t i = 0; i < count; ++i) {
      const auto point = row_point ? static_cast<std::size_t>(row_point[i]) : i;
      r[i] *= current_volume[point] / reference_volume[point];
    }
  }
}

void MovingConfiguration::to_midpoint_configuration(FieldArray& gradient, int fields,
                                                    std::span<const int> velocity_gradient,
                                                    double dt, std::size_t count) const {
  const int d = model_.dimension();
  const auto n = static_cast<std::int64_t>(count);
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
  for (std::int64_t i = 0; i < n; ++i) {
    // F = I + (dt/2) G and its inverse (d <= 2: the model's dimensions).
    double f[2][2] = {{1.0, 0.0}, {0.0, 1.0}};
    for (int a = 0; a < d; ++a)
      for (int c = 0; c < d; ++c)
        f[a][c] += 0.5 * dt * gradient(velocity_gradient[static_cast<std::size_t>(a * d + c)], i);
    double inverse[2][2];
    if (d == 1) {
      inverse[0][0] = 1.0 / f[0][0];
    } else {
      const double det = f[0][0] * f[1][1] - f[0][1] * f[1][0];
      inverse[0][0] = f[1][1] / det;
      inverse[0][1] = -f[0][1] / det;
      inverse[1][0] = -f[1][0] / det;
      inverse[1][1] = f[0][0] / det;
    }
    for (int field = 0; field < fields; ++field) {
      double row[2] = {0.0, 0.0};
      for (int c = 0; c < d; ++c)
        for (int k = 0; k < d; ++k)
          row[c] += gradient(field * d + k, i) * inverse[k][c];
      for (int c = 0; c < d; ++c)
        gradient(field * d + c, i) = row[c];
    }
  }
}

void MovingConfiguration::turn_faces(const State& state, double dt, double time) {
  // The faces' normals at X + u + (dt/2) v (docs/theory.md §9.7): the traction-free condition of
  // the half-step and of the end of the step then acts on the faces where those values are.
  if (!faces_) return;
  const std::size_t ns = reference_.sph_nodes.size();
  for (int a = 0; a < model_.dimension(); ++a) {
    const auto axis = static_cast<std::size_t>(a);
    const double* u = state.displacement.field(a);
    const double* v = state.fields.field(model_.velocity_field(a));
    for (std::size_t i = 0; i < ns; ++i)
      predicted_nodes_.position[axis][i] = origin_.position[axis][i] + u[i] + 0.5 * dt * v[i];
  }
  faces_->follow_configuration(predicted_nodes_, time);
}

void MovingConfiguration::after_step(State& state) {
  motion_.move(state.displacement, state.configuration);
  if (faces_) faces_->follow_configuration(state.configuration.sph_nodes, state.time);
  const CellQuality& quality = motion_.quality();
  if (quality.inverted_cells == 0) return;
  const std::string why =
      motion_.formed()
          ? "The cells were formed again from the nodes (docs/theory.md §9.17), and this one "
            "folded "
            "within the steps before the next forming: two of its nodes closed on each other "
            "faster than a cell distorts past numerics.cells.reform_below, as nodes that clump in "
            "a zero-energy mode do (§9.17). A larger reform_below forms the cells again sooner"
          : "The cells are those of the start and a cell beside a velocity jump of a few spacings "
            "cannot follow it (docs/theory.md §9.12, §9.14): a finer lattice folds sooner, not "
            "later, and a smaller time step does not help. numerics.cells.policy: reformed forms "
            "the cells again as the body flows (§9.17)";
  throw RunError(fmt::format(
      "{} cell(s) of the moving configuration folded over at step {} (t = {:.6g} s), first the "
      "cell of the stress point at {}: its nodes have crossed and its area is no longer "
      "positive, so the cell has no volume to integrate (docs/theory.md §9.1). {}. Else stop the "
      "run before this deformation (time.end), lower the imposed velocity or load, or give the "
      "soil more strength where it flows",
      quality.inverted_cells, state.step, state.time,
      describe_point(state.configuration.stress_points,
                     static_cast<std::size_t>(quality.first_inverted_cell)),
      why));
}

std::unique_ptr<ConfigurationPolicy> make_configuration_policy(OperatorPolicy policy,
                                                               const PhysicsModel& model,
                                                               const NodeSets& reference,
                                                               const CellFormation* formation) {
  if (policy == OperatorPolicy::CurrentConfiguration)
    return std::make_unique<MovingConfiguration>(model, reference, formation);
  return std::make_unique<FixedConfiguration>();
}

}  // namespace rktsph
