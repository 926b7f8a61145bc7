// A run: the case turned into nodes, materials, a physics model, boundary conditions, the step
// operators and the state; and the time loop, which observers watch (docs/theory.md §2.2, §2.5).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rktsph/boundary/boundary_conditions.hpp"
#include "rktsph/case/case_description.hpp"
#include "rktsph/core/checkpoint.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/models/dry_solid.hpp"
#include "rktsph/models/pressure_projection.hpp"
#include "rktsph/physics/state.hpp"
#include "rktsph/time/rk_taylor_step.hpp"

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
  virtual void on_finish(const Simulation& simulation, RunStatus status,
                         const std::string& message) {
    (void)simulation;
    (void)status;
    (void)message;
  }
};

/// What a run may ask for; checked from the case before anything is built.
struct SimulationLimits {
  /// Largest estimated number of SPH nodes (the `--max-nodes` flag of run and check).
  double max_nodes = 1e7;
};

/// Resident memory of a run [bytes] with this many SPH nodes, lattice points of the node lookup
/// and smoothing length h/dx: measured peak RSS per node (/usr/bin/time -v, runs of 10k-160k nodes,
/// docs/input-reference.md "Limits"): 3.1 KB dry and 3.5 KB saturated at h = 0.75 dx, 6.7 KB
/// saturated at 1.3 dx; the larger figures, linear in h, plus 4 bytes per lattice point.
double estimated_run_memory(double sph_nodes, double lattice_points, double h_over_dx);

/// The largest Courant number at which the step is stable, measured as the spectral radius of the
/// full step matrix (<= 1 + 1e-9) on a 12 x 5 block with every boundary type (docs/theory.md
/// §2.5, tests CourantLimit*): on compact stencils the Lax-Wendroff limit 1 lowered by the
/// artificial viscosity alpha to sqrt(1 + alpha^2) - alpha (measured 1.013, 0.791, 0.643, 0.433
/// at alpha = 0, 0.25, 0.5, 1; the formula gives 1, 0.781, 0.618, 0.414); 2D stencils wider than
/// a cell are stable only up to 0.766 at h = 1.3 dx without viscosity, so they are held to 0.75.
double stable_courant_limit(double viscosity, bool compact_stencils);

class Simulation final : public Checkpointed {
 public:
  /// Builds everything; InputError for inconsistent input or a case above `limits`, RunError for
  /// an unusable lattice.
  explicit Simulation(CaseDescription description, SimulationLimits limits = {});

  void add_observer(Observer& observer) { observers_.push_back(&observer); }
  void set_stop_check(StopCheck check) { stop_check_ = std::move(check); }
  /// Runs to the end time. A value that is not finite or beyond the model's divergence bound stops
  /// the run with status Diverged and a message naming the step, time, field, node and position;
  /// the observers are not shown that state, so the last output written is the last good one.
  /// An exception from an observer (an output that cannot be written) ends the run with status
  /// Failed and its text; the stop check ends it with status Interrupted. Every way out calls
  /// every observer's on_finish (one that throws there turns a completed or interrupted run into
  /// a failed one), so the summary always records how the run ended.
  RunStatus run();
  const std::string& message() const { return message_; }

  const CaseDescription& description() const { return description_; }
  const NodeSets& nodes() const { return nodes_; }
  const std::map<std::string, std::vector<std::int32_t>>& groups() const { return groups_; }
  const DrySolid& model() const { return *model_; }
  const BoundaryConditions& boundary_conditions() const { return *conditions_; }
  const RkTaylorStep& step() const { return *step_; }
  const State& state() const { return state_; }
  /// Direct access for drivers that step by hand (tests, step-matrix analysis, restarts).
  RkTaylorStep& step() { return *step_; }
  State& state() { return state_; }
  double time_step() const { return time_step_; }
  /// The pressure projection of the saturated model, or null for a dry one.
  const PressureProjection* pressure_projection() const { return projection_.get(); }
  long total_steps() const { return total_steps_; }
  /// The size estimated from the shapes before the lattice was built.
  const NodeEstimate& node_estimate() const { return node_estimate_; }
  /// estimated_run_memory() of the lattice that was built [bytes].
  double estimated_memory() const;
  double wall_seconds() const { return wall_seconds_; }

  /// The state and every other value the next step depends on (the pressure projection's
  /// warm start); what the case determines (operators, the strain hourglass stiffness's
  /// reference stresses of t = 0) is rebuilt from it instead.
  void save_checkpoint(CheckpointOut& out) const override;
  /// Restores what save_checkpoint wrote; run() then continues from that step.
  void restore_checkpoint(CheckpointIn& in) override;

 private:
  void initialise_state();
  /// Where dt comes from, with the values, for messages.
  std::string time_step_origin(const std::vector<std::string>& material_names) const;
  /// The step of the run's step `index` (0-based): dt, or what is left to time.end for the last.
  double step_length(long index) const;
  /// Describes the first value that is not finite or beyond the model's divergence bound (field,
  /// node, position), or returns an empty string.
  std::string find_divergence(const State& state) const;
  /// Calls `notify` for every observer; false (status Failed, message set) if one threw.
  bool notify_observers(const std::function<void(Observer&)>& notify);
  /// on_finish for every observer, even after one threw; returns the final status.
  RunStatus finish_observers(RunStatus status);

  CaseDescription description_;
  NodeSets nodes_;
  std::map<std::string, std::vector<std::int32_t>> groups_;
  std::unique_ptr<DrySolid> model_;
  std::unique_ptr<BoundaryConditions> conditions_;
  std::unique_ptr<RkTaylorStep> step_;
  std::unique_ptr<PressureProjection> projection_;
  State state_;
  NodeEstimate node_estimate_;
  double time_step_ = 0.0;
  long total_steps_ = 0;
  double wall_seconds_ = 0.0;
  std::string message_;
  std::vector<Observer*> observers_;
  StopCheck stop_check_;
  bool resumed_ = false;
};

}  // namespace rktsph
