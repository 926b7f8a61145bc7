// Checks shared by the cases that load a body and hold the load (issue 10): does the damped body
// come to rest, and is the state it reaches free of node-to-node (odd-even, zero-energy) patterns?
//
//   oddeven_residual                 the alternating part of a sequence along a lattice line
//   settlement_oddeven_ratio         ... of the surface settlement around a strip load
//   contact_pressure_oddeven_ratio   ... of the node-by-node contact pressure under a footing
//   checkerboard_amplitude           the (-1)^(i+j) part of a field on the 2D lattice
//   residual_velocity_ratio          largest |v| at the end over its peak (SpeedRecorder)
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rktsph/simulation/quantities.hpp"
#include "rktsph/simulation/simulation.hpp"
#include "rktsph/validation/validation_case.hpp"

namespace rktsph {

// --- Odd-even patterns along a lattice line ----------------------------------------------------

/// Largest |s_i − (s_{i−1} + 2 s_i + s_{i+1})/4| = |−s_{i−1} + 2 s_i − s_{i+1}|/4 over the
/// interior i = 1 … n−2: the amplitude of the node-to-node alternating component. A linear
/// sequence gives 0, A(−1)^i gives A, a smooth s gives dx²|s''|/4. With `mirror_first`, the first
/// node lies on a symmetry plane (s_{−1} = s_1) and i = 0 counts too. Fewer than 3 values (2 with
/// the mirror) give 0.
double oddeven_residual(std::span<const double> values, bool mirror_first = false);

/// Node values along one lattice row, sorted by x.
struct NodeLine {
  std::vector<double> x, value;
};

/// oddeven_residual of values at increasing abscissae s that need not be evenly spaced (a row or
/// a face of a triangle mesh): largest |s_i − L_i|/2, L_i the straight line through the two
/// neighbours at s_i, which on even spacing is the expression above. A linear field gives 0 on any
/// spacing, so a mesh's uneven nodes alone raise no pattern. Evenly spaced input (every gap equal
/// to 1e-9 of the first) is passed to oddeven_residual unchanged, so lattice values are the same
/// to the last bit. With `mirror_first`, the first node lies on a symmetry plane (s_{−1} = s_1).
double oddeven_residual_along(const NodeLine& line, bool mirror_first = false);

/// The nodes of the row y = `y` (within dx/4) with x_min <= x <= x_max (within dx/4), sorted by x,
/// with value(node).
NodeLine node_row(const Simulation& simulation, double y, double x_min, double x_max,
                  const std::function<double(std::size_t node)>& value);

/// The settlement s = −u_y of the surface row y = `surface` for x_min <= x <= x_max.
NodeLine surface_settlement(const Simulation& simulation, double surface, double x_min,
                            double x_max);

/// The node-by-node contact pressure −(total) σ_yy of the row y = `surface` for
/// x_min <= x <= x_max (the total stress of a saturated model, the stress of a dry one).
NodeLine contact_pressure(const Simulation& simulation, double surface, double x_min, double x_max);

/// Strip load of half width b (loaded width B = 2b) on a half model whose symmetry plane is
/// x = 0: oddeven_residual of the settlement over the surface nodes 0 <= x <= b + 2B (mirrored at
/// x = 0) over the largest |s| there. `settlement` is the surface row (surface_settlement), at
/// least over that range. The exact elastic profile gives about 0.007 at b = 8 dx (the kink of
/// the profile at the load edge); an odd-even pattern gives its full amplitude.
double settlement_oddeven_ratio(const NodeLine& settlement, double half_width);

/// Footing contact pressure (contact_pressure over the footing row, its two end nodes included):
/// oddeven_residual over the interior footing nodes (both neighbours on the footing) over the
/// mean pressure of those nodes.
double contact_pressure_oddeven_ratio(const NodeLine& pressure);

/// The contact pressure under a footing pushed into the ground, sampled on states where its
/// settlement (that of its node at x_min, over `width`) lies within [from, to]: the largest
/// contact_pressure_oddeven_ratio and the last pressure line.
struct FootingContactSampler {
  FootingContactSampler(double surface_y, double left, double right, double footing_width,
                        double window_from, double window_to)
      : surface(surface_y),
        x_min(left),
        x_max(right),
        width(footing_width),
        from(window_from),
        to(window_to) {}
  double surface = 0.0, x_min = 0.0, x_max = 0.0;  // the footing row (reference positions) [m]
  double width = 1.0, from = 0.0, to = 0.0;        // settlement window, over `width`
  NodeLine last;
  /// The largest odd-even ratio over the samples in the window; NaN (not measured, a failed
  /// check) until the settlement has entered it.
  double largest_ratio = std::numeric_limits<double>::quiet_NaN();
  /// Samples `simulation` if its settlement is in the window; returns the settlement over width.
  double sample(const Simulation& simulation);
};

// --- Odd-even patterns on the 2D lattice -------------------------------------------------------

/// A nodal field on the lattice (2D).
struct LatticeField {
  std::vector<double> value;  ///< by lattice index, NaN where there is no node
  int columns = 0, rows = 0;
  double spacing = 0.0, origin_x = 0.0, origin_y = 0.0;
  double at(int i, int j) const { return value[static_cast<std::size_t>(j) * columns + i]; }
  double x(int i) const { return origin_x + i * spacing; }
  double y(int j) const { return origin_y + j * spacing; }
};

/// Where the SPH nodes of a lattice body sit on their lattice, from their reference positions
/// (column i = (x - x_min)/dx, row j likewise; the smallest coordinates are the lattice's origin):
/// the lattice checks of odd-even patterns read this, not the builder's indices. RunError on a
/// body that is not a lattice (triangles).
struct LatticeView {
  std::vector<std::array<int, 2>> index;  ///< (column, row) of each node
  int columns = 0, rows = 0;
  double spacing = 0.0, origin_x = 0.0, origin_y = 0.0;
};
LatticeView lattice_view(const NodeSets& nodes);

/// value(node) of every SPH node, placed on the lattice.
LatticeField lattice_field(const Simulation& simulation,
                           const std::function<double(std::size_t node)>& value);
/// The model field `field` (an index of State::fields) on the lattice.
LatticeField lattice_field(const Simulation& simulation, int field);

/// Amplitude of the (-1)^(i+j) component around each node, largest over the nodes with a full
/// 3x3 neighbourhood that `skip(x, y)` does not leave out: the tensor product of the 1D filters
/// (1, -2, 1)/4 in x and in y, i.e. the stencil (1,2,1)⊗(1,2,1)/16 with alternating signs. A pure
/// checkerboard of amplitude A returns A; a smooth field returns dx^4 |f_xxyy|/16, and a field that
/// varies in one direction only (a boundary layer along a face) returns 0. (The 2x2 difference
/// f_ij - f_i+1,j - f_i,j+1 + f_i+1,j+1 is not used: it returns dx^2 |f_xy|/4 for a smooth field,
/// which near a load edge measures the analytical field rather than a checkerboard.)
double checkerboard_amplitude(const LatticeField& field,
                              const std::function<bool(double x, double y)>& skip = {});
/// Largest |value| over the nodes of the lattice field.
double max_abs(const LatticeField& field);

// --- Sampling a run while it goes, and coming to rest ------------------------------------------

/// Calls `sample` at t = 0, every `interval` s (every step if interval <= 0) and at the end of a
/// completed run: pass it to run_for_validation to measure states other than the last one.
class SampledObserver final : public Observer {
 public:
  SampledObserver(double interval, std::function<void(const Simulation&)> sample)
      : interval_(interval), sample_(std::move(sample)) {}
  void on_start(const Simulation& simulation) override;
  void after_step(const Simulation& simulation) override;
  void on_finish(const Simulation& simulation, RunStatus status,
                 const std::string& message) override;

 private:
  void take(const Simulation& simulation);
  double interval_;
  std::function<void(const Simulation&)> sample_;
  double next_time_ = 0.0;
  double last_time_ = -1.0;
};

/// History of the largest velocity magnitude |v| over all SPH nodes.
struct SpeedHistory {
  std::vector<double> time, speed;
};

/// Records largest_speed at t = 0, every `interval` s (every step if <= 0: use the case's
/// output.probe_interval) and at the end.
class SpeedRecorder {
 public:
  explicit SpeedRecorder(double interval);
  SpeedRecorder(const SpeedRecorder&) = delete;  // the observer refers to this recorder
  SpeedRecorder& operator=(const SpeedRecorder&) = delete;
  Observer& observer() { return observer_; }
  const SpeedHistory& history() const { return history_; }

 private:
  SpeedHistory history_;
  SampledObserver observer_;
};

/// Largest |v| over all nodes at the end of the history over its peak over the samples with
/// t >= `from` (a damped body under a held load must come to rest: a few 1e-5 for the slope
/// with the present step; a creeping zero-energy mode keeps it near its own level).
double residual_velocity_ratio(const SpeedHistory& history, double from = 0.0);

/// Zeros and negative values as NaN (gaps on a log axis).
std::vector<double> positive_or_nan(const std::vector<double>& values);

/// Report figure `name`: the largest |v| over all nodes against time on a log axis, with the
/// residual_velocity_ratio limit (`limit` times the peak over t >= `from`) drawn from `from` on.
Figure speed_figure(const std::string& name, const SpeedHistory& history, double from,
                    double limit);

/// Report figure `name`: the surface settlement against x (in mm), the load 0 <= x <= b named in
/// the axis label.
Figure settlement_figure(const std::string& name, const NodeLine& settlement, double half_width,
                         const std::string& title);

}  // namespace rktsph
