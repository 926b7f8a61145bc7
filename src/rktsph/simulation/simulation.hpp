// A run: the assembly of its case (assembly.hpp) and the time loop, which observers watch and may
// end (docs/theory.md §2.6).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rktsph/core/checkpoint.hpp"
#include "rktsph/models/pressure_projection.hpp"
#include "rktsph/simulation/assembly.hpp"

namespace rktsph {

class Simulation;

/// How a run ended: reached the end time; a value not finite or beyond its bound; a step or an
/// observer (an output write, say) failed; stopped on request (SIGINT, SIGTERM) between steps.
enum class RunStatus { Completed, Diverged, Failed, Interrupted };
/// "completed", "diverged", "failed", "interrupted" (the status in summary.json).
const char* run_status_name(RunStatus status);

/// Asked before every step whether the run should stop there: a non-empty answer (the reason,
/// e.g. "SIGINT received") ends it with status Interrupted. It must not throw.
using StopCheck = std::function<std::string()>;

/// Something that watches the loop: output, probes, progress, validation metrics.
class Observer {
 public:
  virtual ~Observer() = default;
  virtual void on_start(const Simulation& simulation) { (void)simulation; }
  /// Called instead of on_start when the run continues from a checkpoint (the observers that
  /// write files have restored their own state from it by then).
  virtual void on_resume(const Simulation& simulation) { (void)simulation; }
  virtual void after_step(const Simulation& simulation) { (void)simulation; }
  /// Asked after every step, after after_step: a non-empty answer (the reason) ends the run there,
  /// as completed (e.g. the body has come to rest). It must not throw.
  virtual std::string stop_reason() const { return {}; }
  virtual void on_finish(const Simulation& simulation, RunStatus status,
                         const std::string& message) {
    (void)simulation;
    (void)status;
    (void)message;
  }
};

class Simulation final : public Checkpointed {
 public:
  /// Assembles the run (Assembly); InputError for inconsistent input or a case above `limits`,
  /// RunError for an unusable lattice.
  explicit Simulation(CaseDescription description, SimulationLimits limits = {});

  void add_observer(Observer& observer) { observers_.push_back(&observer); }
  /// One step of the loop without its checks and observers (tests, benchmarks): the step (in
  /// parts where formed cells are narrow), then the cells formed again where they have distorted
  /// (docs/theory.md §9.17). Throws what the step or the forming throws.
  void take_step();
  void set_stop_check(StopCheck check) { stop_check_ = std::move(check); }
  /// Runs to the end time. A value that is not finite or beyond the model's divergence bound stops
  /// the run with status Diverged and a message naming the step, time, field, node and position;
  /// the observers are not shown that state, so the last output written is the last good one.
  /// An exception from an observer (an output that cannot be written) ends the run with status
  /// Failed and its text; the stop check ends it with status Interrupted; an observer that asks
  /// to stop (Observer::stop_reason) ends it early with status Completed and its reason in the
  /// message. Every way out calls every observer's on_finish (one that throws there turns a
  /// completed or interrupted run into a failed one), so the summary always records how the run
  /// ended.
  RunStatus run();
  const std::string& message() const { return message_; }

  const Assembly& assembly() const { return assembly_; }
  const CaseDescription& description() const { return assembly_.description(); }
  /// The reference configuration (stable ids, materials, cells); the current one is
  /// state().configuration.
  const NodeSets& nodes() const { return assembly_.nodes(); }
  /// The cells the step integrates over now (Assembly::cells()).
  const NodeSets& cells() const { return assembly_.cells(); }
  const std::map<std::string, std::vector<std::int32_t>>& groups() const {
    return assembly_.groups();
  }
  const PhysicsModel& model() const { return assembly_.model(); }
  const BoundaryConditions& boundary_conditions() const { return assembly_.boundary_conditions(); }
  const RkTaylorStep& step() const { return assembly_.step(); }
  const State& state() const { return assembly_.state(); }
  /// Direct access for drivers that step by hand (tests, step-matrix analysis, restarts).
  RkTaylorStep& step() { return assembly_.step(); }
  State& state() { return assembly_.state(); }
  double time_step() const { return assembly_.time_step(); }
  /// The pressure projection of the saturated model, or null for a dry one.
  const PressureProjection* pressure_projection() const {
    return dynamic_cast<const PressureProjection*>(assembly_.projection());
  }
  long total_steps() const { return assembly_.total_steps(); }
  /// The size estimated from the shapes before the lattice was built.
  const NodeEstimate& node_estimate() const { return assembly_.node_estimate(); }
  /// estimated_run_memory() of the lattice that was built [bytes].
  double estimated_memory() const { return assembly_.estimated_memory(); }
  double wall_seconds() const { return wall_seconds_; }
  /// True when an observer ended the run early (its reason is in message()).
  bool stopped_early() const { return stopped_early_; }
  /// The last good state of a run that diverged or failed inside a step: the state before that
  /// step, for the output to show where things stood; null for a run that did not stop so.
  const State* state_before_stop() const { return stopped_in_step_ ? &before_step_ : nullptr; }

  /// The state and every other value the next step depends on (the projection's warm start);
  /// what the case determines (operators, the strain hourglass stiffness's reference stresses of
  /// t = 0) is rebuilt from it instead.
  void save_checkpoint(CheckpointOut& out) const override;
  /// Restores what save_checkpoint wrote; run() then continues from that step.
  void restore_checkpoint(CheckpointIn& in) override;

 private:
  /// The step of the run's step `index` (0-based): dt, or what is left to time.end for the last.
  double step_length(long index) const;
  /// Describes the first value that is not finite or beyond the model's divergence bound (field,
  /// node, position), or returns an empty string.
  std::string find_divergence(const State& state) const;
  /// Calls `notify` for every observer; false (status Failed, message set) if one threw.
  bool notify_observers(const std::function<void(Observer&)>& notify);
  /// The first observer's request to stop, or an empty string.
  std::string observer_stop_reason() const;
  /// on_finish for every observer, even after one threw; returns the final status.
  RunStatus finish_observers(RunStatus status);

  Assembly assembly_;
  double wall_seconds_ = 0.0;
  std::string message_;
  std::vector<Observer*> observers_;
  StopCheck stop_check_;
  bool resumed_ = false;
  bool stopped_early_ = false;
  /// Copies into before_step_ what the next step will change.
  void keep_state_before_step();
  /// Forms the cells again where they have distorted (Assembly::cells_need_forming); false, with
  /// the message, when that fails.
  bool form_cells_if_distorted();
  /// One step, or part of one, of `dt`, with the loaded rigid bodies' motion over it.
  void advance_part(double dt);
  /// Advances one step of length dt, in Assembly::step_parts() equal parts.
  void advance_in_parts(double dt);
  State before_step_;  ///< the state before the current step (state_before_stop)
  bool stopped_in_step_ = false;
};

}  // namespace rktsph
