#include "rktsph/simulation/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace rktsph {

const char* run_status_name(RunStatus status) {
  switch (status) {
    case RunStatus::Completed:
      return "completed";
    case RunStatus::Diverged:
      return "diverged";
    case RunStatus::Failed:
      return "failed";
    case RunStatus::Interrupted:
      return "interrupted";
  }
  return "unknown";
}

Simulation::Simulation(CaseDescription description, SimulationLimits limits)
    : assembly_(std::move(description), limits) {}

double Simulation::step_length(long index) const {
  if (index + 1 < total_steps()) return time_step();
  // The last step ends exactly at time.end: it is shorter than dt when time.end is not a multiple
  // of dt (a shorter step is only more stable; the pressure projection re-assembles for it).
  // end - t is exact here (Sterbenz: t >= end / 2 unless it is the only step), so t + (end - t)
  // is end to the bit.
  return description().time.end - state().time;
}

std::string Simulation::find_divergence(const State& state) const {
  const std::size_t n = nodes().sph_nodes.size();
  auto where = [&](std::size_t i) {
    std::string text = fmt::format("SPH node {} (x = {:.6g}", i, nodes().sph_nodes.position[0][i]);
    if (nodes().dimension > 1)
      text += fmt::format(", y = {:.6g}", nodes().sph_nodes.position[1][i]);
    return text + " m)";
  };
  for (int f = 0; f < state.fields.field_count(); ++f) {
    const double* values = state.fields.field(f);
    const double bound = model().divergence_bound(f);
    for (std::size_t i = 0; i < n; ++i)
      if (!(std::abs(values[i]) <= bound))  // also catches NaN
        return fmt::format("field '{}' = {:.4g} at {} (physical bound {:.3g})",
                           model().field_names()[static_cast<std::size_t>(f)], values[i], where(i),
                           bound);
  }
  for (int k = 0; k < state.internal.field_count(); ++k)
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite(state.internal(k, i)))
        return fmt::format("internal variable '{}' is not finite at {}",
                           model().internal_names()[static_cast<std::size_t>(k)], where(i));
  return {};
}

bool Simulation::notify_observers(const std::function<void(Observer&)>& notify) {
  for (Observer* observer : observers_) {
    try {
      notify(*observer);
    } catch (const std::exception& error) {  // e.g. a result file that cannot be written
      message_ = fmt::format("failed at step {} (t = {:.6g} s): {}", state().step, state().time,
                             error.what());
      return false;
    }
  }
  return true;
}

std::string Simulation::observer_stop_reason() const {
  for (const Observer* observer : observers_)
    if (std::string reason = observer->stop_reason(); !reason.empty()) return reason;
  return {};
}

RunStatus Simulation::finish_observers(RunStatus status) {
  for (Observer* observer : observers_) {
    try {
      observer->on_finish(*this, status, message_);
    } catch (const std::exception& error) {
      if (status == RunStatus::Completed || status == RunStatus::Interrupted) {
        status = RunStatus::Failed;
        message_ = fmt::format("failed at the end (step {}, t = {:.6g} s): {}", state().step,
                               state().time, error.what());
      } else {
        message_ += fmt::format("; then: {}", error.what());
      }
    }
  }
  return status;
}

void Simulation::keep_state_before_step() {
  // For the last output of a run that stops inside the step, into the same storage every step (no
  // allocation after the first). Only what the step changes: the configuration is copied where
  // the points move, and once where they do not (it is then the reference, a third of the state).
  const State& now = state();
  before_step_.time = now.time;
  before_step_.step = now.step;
  const auto from = now.arrays();
  const auto to = before_step_.arrays();
  for (std::size_t k = 0; k < from.size(); ++k)
    *to[k] = *from[k];
  if (step().motion() ||
      before_step_.configuration.sph_nodes.size() != now.configuration.sph_nodes.size())
    before_step_.configuration = now.configuration;
}

void Simulation::advance_part(double dt) {
  // A loaded rigid body moves over the step by its own equation of motion (docs/theory.md eq.
  // 9.17), from the soil's force at the step's start; the step's conditions then hold the nodes
  // in contact to that motion.
  assembly_.begin_body_step(dt);
  step().advance(state(), dt);
  assembly_.end_body_step();
}

void Simulation::advance_in_parts(double dt) {
  // One step of the loop, in equal parts where formed cells are narrower than the width that set
  // dt (§9.17); the state counts it as one step and ends it at t + dt to the bit.
  const int parts = assembly_.step_parts();
  if (parts == 1) {
    advance_part(dt);
    return;
  }
  const double end = state().time + dt;
  const long step_index = state().step;
  for (int k = 0; k < parts; ++k)
    advance_part(dt / parts);
  state().time = end;
  state().step = step_index + 1;
  assembly_.count_divided_step(parts);
}

void Simulation::take_step() {
  advance_in_parts(step_length(state().step));
  if (assembly_.cells_need_forming()) assembly_.form_cells();
}

bool Simulation::form_cells_if_distorted() {
  // Between whole steps, so that every step integrates over one set of cells (§9.17).
  if (!assembly_.cells_need_forming()) return true;
  try {
    assembly_.form_cells();
  } catch (const std::exception& error) {
    message_ = fmt::format("failed after step {} (t = {:.6g} s): {}", state().step, state().time,
                           error.what());
    return false;
  }
  return true;
}

RunStatus Simulation::run() {
  const auto start = std::chrono::steady_clock::now();
  RunStatus status = RunStatus::Completed;
  const auto begin = [this](Observer& observer) {
    if (resumed_)
      observer.on_resume(*this);
    else
      observer.on_start(*this);
  };
  if (!notify_observers(begin)) status = RunStatus::Failed;
  // Every step is checked; on divergence the observers keep the last good output on disk.
  for (long s = state().step; s < total_steps() && status == RunStatus::Completed; ++s) {
    // Between steps, so an interrupted run ends on a whole step its observers can record.
    if (const std::string reason = stop_check_ ? stop_check_() : std::string(); !reason.empty()) {
      message_ = fmt::format("interrupted at step {} (t = {:.6g} s): {}", state().step,
                             state().time, reason);
      status = RunStatus::Interrupted;
      break;
    }
    const double dt = step_length(s);
    if (!(dt > 0.0)) break;  // the round-off of t += dt already reached time.end
    keep_state_before_step();
    try {
      advance_in_parts(dt);
    } catch (const std::exception& error) {  // e.g. a pressure solve that does not converge
      message_ = fmt::format("failed at step {} (t = {:.6g} s): {}", state().step + 1,
                             state().time + dt, error.what());
      status = RunStatus::Failed;
      stopped_in_step_ = true;
      break;
    }
    const std::string problem = find_divergence(state());
    if (!problem.empty()) {
      // What to change: the explicit step is stable below the Courant limit (docs/theory.md §2.5),
      // so a smaller step removes a growth that the step makes; a growth that the physics makes
      // (a material or load out of range) shows in the plausibility warnings of `rktsph check`.
      message_ = fmt::format(
          "diverged at step {} (t = {:.6g} s): {}. The state before that step is the last field "
          "output. If the field grew over a few steps, lower numerics.courant; else check the "
          "material's moduli, density and strength and the loads (`rktsph check` warns of values "
          "outside those of real soils)",
          state().step, state().time, problem);
      status = RunStatus::Diverged;
      stopped_in_step_ = true;
      break;
    }
    if (!form_cells_if_distorted()) {
      status = RunStatus::Failed;
      break;
    }
    wall_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!notify_observers([this](Observer& observer) { observer.after_step(*this); })) {
      status = RunStatus::Failed;
      break;
    }
    if (const std::string reason = observer_stop_reason(); !reason.empty()) {
      message_ =
          fmt::format("stopped at step {} (t = {:.6g} s): {}", state().step, state().time, reason);
      stopped_early_ = true;
      break;
    }
  }
  wall_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return finish_observers(status);
}

void Simulation::save_checkpoint(CheckpointOut& out) const {
  out.put_f64(state().time);
  out.put_i64(state().step);
  for (const FieldArray* array : state().arrays())
    out.put_fields(*array);
  assembly_.save_cell_forming(out);
  save_configuration(out, state().configuration);
  assembly_.save_bodies(out);
  assembly_.step().save_checkpoint(out);
  if (assembly_.projection()) assembly_.projection()->save_checkpoint(out);
}

void Simulation::restore_checkpoint(CheckpointIn& in) {
  state().time = in.get_f64();
  state().step = in.get_i64();
  if (state().step < 0 || state().step > total_steps())
    in.fail(fmt::format("step {} outside this run's 0 to {}", state().step, total_steps()));
  for (FieldArray* array : state().arrays())
    in.get_fields_into(*array);
  assembly_.restore_cell_forming(in);  // before the configuration, whose sizes it sets
  restore_configuration(in, state().configuration);
  assembly_.restore_bodies(in);  // before the configuration finds their contacts
  assembly_.step().restore_checkpoint(in);
  assembly_.step().follow_state(state());
  if (assembly_.projection()) assembly_.projection()->restore_checkpoint(in);
  resumed_ = true;
}

}  // namespace rktsph
