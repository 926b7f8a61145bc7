#include "rktsph/time/rk_taylor_step.hpp"
#include "rktsph/core/parallel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "rktsph/core/error.hpp"
#include "rktsph/physics/kinematics/objective_rate.hpp"

namespace rktsph {

RkTaylorStep::RkTaylorStep(const PhysicsModel& model, const NodeSets& reference,
                           const StepOptions& options, StepOperatorBuilder builder,
                           OperatorPolicy policy, const BoundaryConditions& conditions,
                           const Configuration& configuration, const CellFormation* formation)
    : model_(model),
      nodes_(reference),
      options_(options),
      builder_(std::move(builder)),
      policy_(policy),
      configuration_(make_configuration_policy(policy, model, reference, formation)),
      conditions_(conditions) {
  const int nf = model.field_count();
  const int nk = model.internal_count();
  const int d = model.dimension();
  const std::size_t nv = reference.stress_points.size();
  const std::size_t ns = reference.sph_nodes.size();
  // On a moving configuration no two rows are alike: no sharing from the first build (§4.7).
  if (policy == OperatorPolicy::CurrentConfiguration) builder_.keep_weights_per_row();
  // Cells formed again from a deformed body are not the case's: a stencil they leave degenerate
  // takes the uncorrected gradient and is counted, as on a moving configuration (§9.5, §9.17).
  if (formation) builder_.fall_back_on_degenerate_stencils();
  builder_.build(configuration, operators_);
  if (policy == OperatorPolicy::ReferenceConfiguration)
    builder_.release_buffers(operators_);  // built once: the buffers would only hold memory (§4.7)
  if (policy == OperatorPolicy::CurrentConfiguration) {
    // A stencil that degenerates as the body deforms (nodes squeezed into a line on a wall) takes
    // the uncorrected gradient and is counted; one that is degenerate from the start is an error
    // of the case, thrown by the build above (docs/theory.md §9.5).
    builder_.fall_back_on_degenerate_stencils();
    builder_.keep_stencil_candidates(options.neighbour_search_distance * reference.spacing);
    // Searched again with the skin, and the filter built with a weight per row, as every later
    // search does, so that a restart searching from the configuration of the last search gets
    // these stencils and tables bit for bit.
    search_neighbours(configuration);
  }
  // Before the step's arrays are allocated: the scratch of what it derives from the tables then
  // never adds up with them (§4.7).
  bind_operators(configuration);
  for (int a = 0; a < d; ++a)
    for (int c = 0; c < d; ++c) {
      velocity_gradient_of_fields_.push_back(model.velocity_field(a) * d + c);
      velocity_gradient_of_velocity_.push_back(a * d + c);
    }
  viscosity_length_ = options.artificial_viscosity * reference.spacing;
  internal_parity_.assign(static_cast<std::size_t>(nk), kEven);
  for (int f = 0; f < nf; ++f)
    momentum_flux_.push_back(model.feeds_momentum_only(f) ? 1 : 0);
  velocity_gradient_fields_.assign(static_cast<std::size_t>(nf * d), 0);
  for (int a = 0; a < d; ++a)
    for (int c = 0; c < d; ++c)
      velocity_gradient_fields_[static_cast<std::size_t>(model.velocity_field(a) * d + c)] = 1;
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < d; ++c)
      gradient_parities_.push_back(
          static_cast<Parity>(model.parities()[static_cast<std::size_t>(f)] ^ (1u << c)));
  half_step_ = FieldArray(nf, nv + ns);
  point_gradient_ = FieldArray(nf * d, nv);
  // One array for the rates of step 1 (stress points) and step 2 (nodes): the first are dead
  // before the second are computed.
  rate_ = FieldArray(nf, std::max(nv, ns));
  point_internal_ = FieldArray(nk, nv);
  point_velocity_ = FieldArray(d, nv);
  node_gradient_ = FieldArray(nf * d, ns);
  controls_ =
      make_zero_energy_controls(model, reference, options, operators_, builder_.filter_active(),
                                conditions, configuration, *configuration_);
  bool mean_velocity = options.stress_update == StressUpdate::MeanVelocity, follow_flow = false;
  for (const auto& control : controls_) {
    mean_velocity = mean_velocity || control->needs_mean_velocity();
    follow_flow = follow_flow || control->follows_flow();
  }
  for (int a = 0; a < d; ++a)
    velocity_parities_.push_back(
        model.parities()[static_cast<std::size_t>(model.velocity_field(a))]);
  for (int a = 0; a < d; ++a)
    for (int c = 0; c < d; ++c)
      velocity_gradient_parities_.push_back(
          static_cast<Parity>(velocity_parities_[static_cast<std::size_t>(a)] ^ (1u << c)));
  every_gradient_.assign(static_cast<std::size_t>(d * d), 1);
  if (mean_velocity) mean_velocity_ = FieldArray(d, ns);
  if (options.stress_update == StressUpdate::MeanVelocity) {
    start_fields_ = FieldArray(nf, ns);
    start_internal_ = FieldArray(nk, ns);
    mean_point_gradient_ = FieldArray(d * d, nv);
    mean_node_gradient_ = FieldArray(d * d, ns);
  }
  if (follow_flow) {
    point_flowing_.assign(nv, 0);
    node_near_flow_.assign(ns, 0);
  }
}

void RkTaylorStep::bind_operators(const Configuration& configuration) {
  // What the step derives from the operators: the boundary rows' materials and projected faces,
  // their scratch, the lumped average of the mean-velocity update.
  const int nf = model_.field_count();
  const int nk = model_.internal_count();
  const int d = model_.dimension();
  const std::size_t ns = configuration.sph_nodes.size();
  const std::size_t nb = operators_.boundary_nodes.size();
  boundary_material_.clear();
  for (std::int32_t node : operators_.boundary_nodes)
    boundary_material_.push_back(nodes_.node_material[static_cast<std::size_t>(node)]);
  if (boundary_values_.point_count() != nb || boundary_values_.field_count() != nf) {
    boundary_values_ = FieldArray(nf, nb);
    boundary_start_ = FieldArray(nf, nb);
    boundary_gradient_ = FieldArray(nf * d, nb);
    boundary_rate_ = FieldArray(nf, nb);
    boundary_internal_ = FieldArray(nk, nb);
  }
  if (options_.stress_update == StressUpdate::MeanVelocity) {
    every_node_.resize(ns);
    no_own_value_.assign(ns, -1);
    for (std::size_t i = 0; i < ns; ++i)
      every_node_[i] = static_cast<std::int32_t>(i);
    try {
      build_adjoint_operator(operators_.nodes_to_points, configuration.stress_points.volume,
                             every_node_, no_own_value_, node_average_);
    } catch (const UnreachedNode& unreached) {
      throw RunError(describe_unreached_node(configuration.sph_nodes, unreached.node()));
    }
    // Built once where the step's tables share their weights (a fixed lattice): so does their
    // adjoint, whose interior rows are alike too (docs/theory.md §4.7).
    if (!operators_.nodes_to_points.weight_start.empty()) {
      ShareWorkspace workspace;
      share_row_weights(node_average_.table, workspace);
    }
  }
}

void RkTaylorStep::rebuild_operators(const Configuration& configuration) {
  if (policy_ == OperatorPolicy::ReferenceConfiguration) {  // everything again, as at the start
    builder_.build(configuration, operators_);
    builder_.release_buffers(operators_);
    bind_operators(configuration);
    return;
  }
  builder_.classify(configuration, operators_);
  if (neighbours_out_of_date(configuration))
    search_neighbours(configuration);
  else
    builder_.build_step_tables(configuration, operators_, false);  // new weights, same stencils
  bind_operators(configuration);
}

bool RkTaylorStep::neighbours_out_of_date(const Configuration& configuration) const {
  // The stencils hold every source within the support plus twice this distance, and the filter
  // passes fields linear in the x of its build exactly (docs/theory.md §3.3): both stay right, to
  // within the motion since, while no node has moved this far from where it was at the last
  // search (§9.5).
  const double limit = options_.neighbour_search_distance * nodes_.spacing;
  const PointCloud& now = configuration.sph_nodes;
  const PointCloud& then = search_configuration_.sph_nodes;
  if (limit <= 0.0 || then.size() != now.size()) return true;  // not yet searched by this step
  const auto n = static_cast<std::int64_t>(now.size());
  const int d = model_.dimension();
  double largest = 0.0;
#pragma omp parallel for schedule(static) reduction(max : largest) if (n > kParallelThreshold)
  for (std::int64_t i = 0; i < n; ++i) {
    double squared = 0.0;
    for (int a = 0; a < d; ++a) {
      const double step = now.position[static_cast<std::size_t>(a)][static_cast<std::size_t>(i)] -
                          then.position[static_cast<std::size_t>(a)][static_cast<std::size_t>(i)];
      squared += step * step;
    }
    largest = std::max(largest, squared);
  }
  return largest > limit * limit;
}

void RkTaylorStep::search_neighbours(const Configuration& configuration) {
  builder_.build_step_tables(configuration, operators_, true);
  builder_.build_filter_tables(configuration, operators_);  // no-op with the filter off
  if (&configuration != &search_configuration_) search_configuration_ = configuration;
  ++neighbour_searches_;
}

void RkTaylorStep::save_checkpoint(CheckpointOut& out) const {
  const bool moving = policy_ == OperatorPolicy::CurrentConfiguration;
  out.put_u32(moving ? 1u : 0u);
  if (!moving) return;
  out.put_i64(neighbour_searches_);
  save_configuration(out, search_configuration_);
}

void RkTaylorStep::restore_checkpoint(CheckpointIn& in) {
  const bool moving = policy_ == OperatorPolicy::CurrentConfiguration;
  if (in.get_u32() != (moving ? 1u : 0u))
    in.fail("a search configuration where this case has none, or none where it has one");
  if (!moving) return;
  const long searches = static_cast<long>(in.get_i64());
  restore_configuration(in, search_configuration_);
  search_neighbours(search_configuration_);  // the stencils and filter the run had
  neighbour_searches_ = searches;
}

StepTimeSplit RkTaylorStep::time_split() const {
  StepTimeSplit split;
  split.cell_lists = cell_list_seconds_;
  split.operator_tables = std::max(0.0, rebuild_seconds_ - cell_list_seconds_);
  split.surface = surface_seconds_;
  split.integration = std::max(0.0, advance_seconds_ - rebuild_seconds_ - surface_seconds_);
  return split;
}

void RkTaylorStep::advance(State& state, double dt) {
  const auto start = std::chrono::steady_clock::now();
  auto clock = start;
  if (policy_ == OperatorPolicy::CurrentConfiguration) {
    const double cell_lists_before = builder_.cell_list_seconds();
    rebuild_operators(state.configuration);
    rebuild_seconds_ += lap(clock);
    cell_list_seconds_ += builder_.cell_list_seconds() - cell_lists_before;
  }
  step_stress_points(state, dt);
  step_boundary_nodes(state, dt);
  step_nodes(state, dt);
  if (projection_) projection_->project(state, state.time + dt, dt);
  finish_with_mean_velocity(state, dt);
  add_half_step_displacement(state, dt);  // the v^{n+1} half of the trapezoidal rule
  state.time += dt;
  ++state.step;
  if (configuration_->motion()) {  // the points move: timed as the surface's share (§9.5)
    lap(clock);
    configuration_->after_step(state);
    surface_seconds_ += lap(clock);
  }
  advance_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void RkTaylorStep::add_half_step_displacement(State& state, double dt) const {
  const auto ns = static_cast<std::int64_t>(state.displacement.point_count());
  for (int a = 0; a < model_.dimension(); ++a) {
    const double* v = state.fields.field(model_.velocity_field(a));
    double* u = state.displacement.field(a);
#pragma omp parallel for schedule(static) if (ns > kParallelThreshold)
    for (std::int64_t i = 0; i < ns; ++i)
      u[i] += 0.5 * dt * v[i];
  }
}

void RkTaylorStep::step_stress_points(const State& state, double dt) {
  // Step 1: interpolate and differentiate Phi^n at the stress points, advance half a step.
  apply_operator(operators_.nodes_to_points, state.fields, model_.parities(), &half_step_,
                 &point_gradient_);
  if (model_.internal_count() > 0)
    apply_operator(operators_.nodes_to_points, state.internal, internal_parity_, &point_internal_,
                   nullptr);
  for (int a = 0; a < model_.dimension(); ++a) {  // kept for the closure of step 2
    const int v = model_.velocity_field(a);
    parallel_copy(half_step_.field(v), nodes_.stress_points.size(), point_velocity_.field(a));
  }
  model_.flux_rate(nodes_.cells.materials(), point_gradient_, rate_);
  // On the current configuration (docs/theory.md eqs. 9.2, 9.3).
  configuration_->rotate_stress(point_gradient_, velocity_gradient_of_fields_, 0.5 * dt,
                                nodes_.stress_points.size(), half_step_);
  configuration_->scale_momentum_rate(rate_, nodes_.stress_points.size(),
                                      state.configuration.stress_points.volume.data(),
                                      nodes_.stress_points.volume.data(), nullptr);
  model_.advance(nodes_.cells.materials(), rate_, state.time, 0.5 * dt, half_step_,
                 point_internal_);
  if (!point_flowing_.empty()) update_flow_strengths(state);
  if (viscosity_length_ > 0.0)
    model_.add_artificial_viscosity(nodes_.cells.materials(), point_gradient_, viscosity_length_,
                                    half_step_);
}

void RkTaylorStep::update_flow_strengths(const State& state) {
  // The strength of each cell follows the flow, present or past, around it (docs/theory.md
  // eqs. 3.10, 3.14): a cell flows where its stress point does at the half step, and has flowed
  // where every corner node has (not one only: a drained loaded surface yields in its nodes alone).
  // On a moving configuration every cell counts as having flowed, the rule before eq. 3.10:
  // there the full strength held the cut of ld-slope-cohesive (N = 4.34 against 3.79, §3.4).
  model_.flowing(nodes_.cells.materials(), half_step_, point_internal_, point_flowing_);
  const bool moving = configuration_->motion() != nullptr;
  if (!moving) model_.flowing(nodes_.node_material, state.fields, state.internal, node_near_flow_);
  cell_flow_states(nodes_.cells, node_near_flow_, moving, point_flowing_);
  // node_near_flow_ is the factors' scratch from here on.
  for (const auto& control : controls_)
    if (control->follows_flow())
      control->follow_flow(nodes_.cells, point_flowing_, options_.hourglass_plastic_fraction,
                           node_near_flow_);
}

bool RkTaylorStep::carries_received_strain() const {
  return std::any_of(controls_.begin(), controls_.end(),
                     [](const auto& control) { return control->carries_received_strain(); });
}

bool RkTaylorStep::carries_cell_forces() const {
  return std::any_of(controls_.begin(), controls_.end(),
                     [](const auto& control) { return control->carries_cell_forces(); });
}

void RkTaylorStep::filter_fields(FilteredPart part, double time, FieldArray& fields) {
  bool changed = false;
  for (const auto& control : controls_)
    changed = control->filter(part, fields) || changed;
  if (changed) conditions_.apply(time, fields);
}

void RkTaylorStep::step_boundary_nodes(const State& state, double dt) {
  // To x^n + (dt/2) v^n, where the half-step values are, at t + dt/2.
  configuration_->turn_faces(state, dt, state.time + 0.5 * dt);
  // Step 1b: boundary nodes advance half a step with the collocated gradient; their half-step
  // values join the stress points as sources of step 2 (docs/theory.md §2.2, §7.3).
  const auto& boundary = operators_.boundary_nodes;
  const int nf = model_.field_count();
  for (std::size_t r = 0; r < boundary.size(); ++r) {
    const auto node = static_cast<std::size_t>(boundary[r]);
    for (int f = 0; f < nf; ++f)
      boundary_values_(f, r) = state.fields(f, node);
    for (int k = 0; k < model_.internal_count(); ++k)
      boundary_internal_(k, r) = state.internal(k, node);
  }
  std::copy(boundary_values_.data().begin(), boundary_values_.data().end(),
            boundary_start_.data().begin());
  apply_operator(operators_.boundary_gradient, state.fields, model_.parities(), nullptr,
                 &boundary_gradient_);
  model_.flux_rate(boundary_material_, boundary_gradient_, boundary_rate_);
  configuration_->rotate_stress(boundary_gradient_, velocity_gradient_of_fields_, 0.5 * dt,
                                boundary.size(), boundary_values_);
  configuration_->scale_momentum_rate(boundary_rate_, boundary.size(),
                                      state.configuration.sph_nodes.volume.data(),
                                      nodes_.sph_nodes.volume.data(), boundary.data());
  model_.advance(boundary_material_, boundary_rate_, state.time, 0.5 * dt, boundary_values_,
                 boundary_internal_);
  project_free_faces(boundary_start_, boundary_values_, true);
  if (viscosity_length_ > 0.0)  // before the BCs: a free face stays traction-free
    model_.add_artificial_viscosity(boundary_material_, boundary_gradient_, viscosity_length_,
                                    boundary_values_);
  conditions_.apply(state.time + 0.5 * dt, boundary_values_, operators_.node_to_boundary_row);
  const std::size_t nv = nodes_.stress_points.size();
  for (std::size_t r = 0; r < boundary.size(); ++r)
    for (int f = 0; f < nf; ++f)
      half_step_(f, nv + static_cast<std::size_t>(boundary[r])) = boundary_values_(f, r);
}

void RkTaylorStep::step_nodes(State& state, double dt) {
  const int d = model_.dimension();
  const std::size_t ns = nodes_.sph_nodes.size();
  const bool mean_update = options_.stress_update == StressUpdate::MeanVelocity;
  // Displacement by the trapezoidal rule: half with v^n now, the v^{n+1} half in advance(). The
  // strain hourglass stiffness acts on this u^{n+1/2} (docs/theory.md §3.4).
  add_half_step_displacement(state, dt);
  for (const auto& control : controls_)
    control->correct_half_step(state, point_gradient_, dt, half_step_);
  // Step 2: gradient of the half-step values at the SPH nodes, full step from Phi^n.
  apply_operator(operators_.points_to_nodes, half_step_, model_.parities(), nullptr,
                 &node_gradient_);
  close_incomplete_nodes(state);
  // The half-step values live on x^{n+1/2} (eq. 9.5).
  configuration_->to_midpoint_configuration(node_gradient_, model_.field_count(),
                                            velocity_gradient_of_fields_, dt, ns);
  if (!mean_update)
    for (const auto& control : controls_)
      control->record_strain_rate(node_gradient_, dt, state);
  model_.flux_rate(nodes_.node_material, node_gradient_, rate_);
  const auto& boundary = operators_.boundary_nodes;
  const int nf = model_.field_count();
  for (std::size_t r = 0; r < boundary.size(); ++r)
    for (int f = 0; f < nf; ++f)
      boundary_start_(f, r) = state.fields(f, static_cast<std::size_t>(boundary[r]));
  if (mean_velocity_.field_count() > 0)
    for (int a = 0; a < d; ++a)
      parallel_copy(state.fields.field(model_.velocity_field(a)), ns, mean_velocity_.field(a));
  // The controls' forces (the cells' hourglass forces at t + dt/2, docs/theory.md eq. 3.9).
  for (const auto& control : controls_)
    control->add_node_rate(state, dt, rate_);
  if (mean_update) {  // Phi^n of the fields advanced after the velocity (eq. 2.5)
    for (int f = 0; f < nf; ++f)
      if (model_.feeds_momentum_only(f))
        parallel_copy(state.fields.field(f), ns, start_fields_.field(f));
    parallel_copy(state.internal.data().data(), state.internal.data().size(),
                  start_internal_.data().data());
  }
  if (!mean_update)
    configuration_->rotate_stress(node_gradient_, velocity_gradient_of_fields_, dt, ns,
                                  state.fields);
  configuration_->scale_momentum_rate(rate_, ns, state.configuration.sph_nodes.volume.data(),
                                      nodes_.sph_nodes.volume.data(), nullptr);
  // With the mean-velocity update only the velocity is advanced here; the rest after it (eq. 2.5).
  model_.advance(nodes_.node_material, rate_, state.time, dt, state.fields, state.internal,
                 mean_update ? AdvancedFields::Velocity : AdvancedFields::All);
  // To x^{n+1} at t + dt: u holds u^n + (dt/2) v^n, v is v^{n+1}.
  configuration_->turn_faces(state, dt, state.time + dt);
  project_free_faces(boundary_start_, state.fields, false);
  conditions_.apply(state.time + dt, state.fields);
  // After the conditions: a fixed node's pre-condition velocity carries its reaction, which the
  // filter's round trip would otherwise spread to its neighbours; then again, as the filter moves
  // them. With the mean-velocity update the other fields are filtered after they are redone.
  filter_fields(mean_update ? FilteredPart::Velocity : FilteredPart::All, state.time + dt,
                state.fields);
}

void RkTaylorStep::finish_with_mean_velocity(State& state, double dt) {
  // After the projection of the saturated model, so that v^{n+1} is the velocity u moves with.
  const int d = model_.dimension();
  const std::size_t ns = nodes_.sph_nodes.size();
  if (mean_velocity_.field_count() > 0)  // (v^n + v^{n+1})/2
    for (int a = 0; a < d; ++a) {
      double* mean = mean_velocity_.field(a);
      const double* end = state.fields.field(model_.velocity_field(a));
      const auto n = static_cast<std::int64_t>(ns);
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
      for (std::int64_t i = 0; i < n; ++i)
        mean[i] = 0.5 * (mean[i] + end[i]);
    }
  if (options_.stress_update == StressUpdate::MeanVelocity)
    advance_stress_with_mean_velocity(state, dt);
  for (const auto& control : controls_)
    control->finish(mean_velocity_, mean_point_gradient_, dt, state);
}

void RkTaylorStep::advance_stress_with_mean_velocity(State& state, double dt) {
  // docs/theory.md eq. 2.5: every field but the velocity is advanced from Phi^n (the conditions of
  // t + dt have touched it) with the strain rate the lumped average of the stress points'
  // gradients of the mean velocity, the velocity the displacement is integrated with; so the nodal
  // strain is A G u exactly.
  const int d = model_.dimension();
  const int nf = model_.field_count();
  const std::size_t ns = nodes_.sph_nodes.size();
  apply_operator(operators_.nodes_to_points, mean_velocity_, velocity_parities_, nullptr,
                 &mean_point_gradient_);
  parallel_fill(mean_node_gradient_.data().data(), mean_node_gradient_.data().size(), 0.0);
  add_adjoint_interpolation(node_average_, mean_point_gradient_, velocity_gradient_parities_,
                            every_gradient_, mean_node_gradient_);
  // x^{n+1} = x^n + dt v_bar: on x^{n+1/2} (eq. 9.5); the stress points' for the cells' spin.
  configuration_->to_midpoint_configuration(mean_node_gradient_, d, velocity_gradient_of_velocity_,
                                            dt, ns);
  configuration_->to_midpoint_configuration(mean_point_gradient_, d, velocity_gradient_of_velocity_,
                                            dt, nodes_.stress_points.size());
  for (int a = 0; a < d; ++a)
    for (int c = 0; c < d; ++c)
      parallel_copy(mean_node_gradient_.field(a * d + c), ns,
                    node_gradient_.field(model_.velocity_field(a) * d + c));
  const int pore = model_.pore_pressure_field();  // p^{n+1} is the projection's
  for (int f = 0; f < nf; ++f)
    if (model_.feeds_momentum_only(f) && f != pore)
      parallel_copy(start_fields_.field(f), ns, state.fields.field(f));
  parallel_copy(start_internal_.data().data(), start_internal_.data().size(),
                state.internal.data().data());
  for (const auto& control : controls_)
    control->record_strain_rate(node_gradient_, dt, state);
  model_.flux_rate(nodes_.node_material, node_gradient_, rate_);
  // With the spin of the mean velocity (eq. 9.2).
  configuration_->rotate_stress(mean_node_gradient_, velocity_gradient_of_velocity_, dt, ns,
                                state.fields);
  model_.advance(nodes_.node_material, rate_, state.time, dt, state.fields, state.internal,
                 AdvancedFields::Others);
  project_free_faces(boundary_start_, state.fields, false);
  conditions_.apply(state.time + dt, state.fields);
  filter_fields(FilteredPart::OtherFields, state.time + dt, state.fields);
}

void RkTaylorStep::close_incomplete_nodes(const State& state) {
  // docs/theory.md §5.3. Momentum (eq. 5.2): the adjoint gradient of every field but the velocity.
  const AdjointOperator& closure = operators_.incomplete_closure;
  apply_adjoint_gradient(closure, half_step_, model_.parities(), momentum_flux_, node_gradient_);
  // Strain rate (eq. 5.3): of the step-2 velocity gradient G2(v^{n+1/2}) keep the part of the
  // half-step increments, G2(v^{n+1/2}) - G2(I v^n, v^n), and add as the level-n part the lumped
  // average of the stress points' own gradients of v^n.
  const WeightTable& step2 = operators_.points_to_nodes;
  const int d = model_.dimension();
  const std::size_t nv = nodes_.stress_points.size();
  for (std::int32_t target : closure.target) {
    const auto node = static_cast<std::size_t>(target);
    for (int a = 0; a < d; ++a) {
      const int v = model_.velocity_field(a);
      const auto parity = static_cast<unsigned>(model_.parities()[static_cast<std::size_t>(v)]);
      const std::int64_t offset = step2.weight_offset(node);  // shared weights (§4.7)
      for (auto k = static_cast<std::size_t>(step2.row_start[node]);
           k < static_cast<std::size_t>(step2.row_start[node + 1]); ++k) {
        const auto source = static_cast<std::size_t>(step2.source[k]);
        const auto weight = static_cast<std::size_t>(static_cast<std::int64_t>(k) + offset);
        const double level_n =
            (source < nv ? point_velocity_(a, source) : state.fields(v, source - nv)) *
            (step2.has_reflections ? reflection_sign(step2.reflection[weight], parity) : 1.0);
        for (int c = 0; c < d; ++c)
          node_gradient_(v * d + c, node) -=
              step2.gradient[static_cast<std::size_t>(c)][weight] * level_n;
      }
    }
  }
  add_adjoint_interpolation(closure, point_gradient_, gradient_parities_, velocity_gradient_fields_,
                            node_gradient_);
}

void RkTaylorStep::project_free_faces(const FieldArray& start, FieldArray& values,
                                      bool boundary_rows) const {
  const int nf = model_.field_count();
  double start_values[32];
  const SurfaceSet& surface = conditions_.surface();
  for (std::size_t k = 0; k < surface.size(); ++k) {
    const std::int32_t node = surface.node[k];
    const std::int32_t r = operators_.node_to_boundary_row[static_cast<std::size_t>(node)];
    const SurfaceNormals normals = surface.projected_normals(k);
    if (r < 0 || normals.count == 0) continue;
    const auto row = static_cast<std::size_t>(r);
    for (int f = 0; f < nf; ++f)
      start_values[f] = start(f, row);
    model_.project_traction_free_increment(
        nodes_.node_material[static_cast<std::size_t>(node)], normals,
        std::span<const double>(start_values, static_cast<std::size_t>(nf)), values,
        boundary_rows ? row : static_cast<std::size_t>(node));
  }
}

}  // namespace rktsph
