// Hourglass stiffness of the stress-point cells (docs/theory.md §3.4, eqs. 3.2-3.4): the
// Flanagan–Belytschko control of the odd–even (zero-energy) mode, in its stiffness form.
//
// With stress points at cell centres the cell's hourglass mode u_a = q h_a, h = (+1, -1, +1, -1)
// around the corners, is invisible to every operator of the step, so a load with a kink (the edge
// of a strip footing) does work on it that nothing resists: under damping the edge nodes creep at a
// steady speed. Each cell gets the energy (k/2) |q|^2 of its hourglass coordinates
//   q_i = sum_a gamma_a u_ia,  gamma = h - (h . x) b_x - (h . y) b_y,                     (3.2)
// which is zero on linear (and rigid-body) displacement fields, with
//   k = epsilon (M' + G) A sum_a |b_a|^2 / 24,                                             (3.3)
// epsilon = 1 being the hourglass stiffness of the fully integrated bilinear element. Node n
// receives the acceleration
//   a_n = -(1 / (rho_n V_n)) sum_{cells P of n} k_P q_P gamma_{P,n},  V_n = sum_P A_P / 4.   (3.4)
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "rktsph/core/field_array.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/stabilisation/flow_strength.hpp"

namespace rktsph {

class PhysicsModel;

/// The per-cell data of eqs. 3.2-3.4 for a 2D lattice; empty (inactive) in 1D or when
/// epsilon = 0.
struct HourglassStiffness {
  std::vector<std::array<std::int32_t, 4>> corners;  ///< counter-clockwise from the lower left
  std::vector<std::array<double, 4>> gamma;          ///< hourglass vector of each cell (3.2)
  std::vector<double> stiffness;                     ///< k of each cell [N/m per unit thickness]
  /// epsilon_vp / epsilon_el in cells of viscoplastic materials, 1 in elastic ones: the part of k
  /// that acts next to viscoplastic flow (eq. 3.10)
  std::vector<double> near_flow;
  std::vector<double> inverse_mass;  ///< 1/(rho_n V_n) of each node [m/kg]
  /// The cells of node n are cell_of[k], corner corner_of[k] for k in [node_start[n],
  /// node_start[n+1]), so that the force on a node is a gather (parallel without atomics).
  std::vector<std::int32_t> node_start;
  std::vector<std::int32_t> cell_of;
  std::vector<std::uint8_t> corner_of;

  bool active() const { return !stiffness.empty(); }
};

/// The fraction epsilon of the fully integrated element's hourglass stiffness (docs/theory.md
/// §3.4, eq. 3.10): `elastic` in every cell away from viscoplastic flow, `viscoplastic` in cells of
/// viscoplastic materials around flow, present or past (flow_strength_factors); both 0 = off.
struct HourglassStrength {
  double elastic = 0.0;
  double viscoplastic = 0.0;
  bool active() const { return elastic > 0.0 || viscoplastic > 0.0; }
};

/// Builds the control for the cells of `nodes` at the current node positions.
HourglassStiffness build_hourglass_stiffness(const NodeSets& nodes, const PhysicsModel& model,
                                             HourglassStrength epsilon);

/// force_out = force_in + interval * factor_P k_P gamma_P . v for every cell P: the generalised
/// hourglass force k q advanced by the velocity `fields` (components velocity_field[a]) over
/// `interval` (eq. 3.9), with factor from flow_strength_factors (eq. 3.10).
void advance_hourglass_force(const HourglassStiffness& control, const FieldArray& fields,
                             const std::array<int, 2>& velocity_field, double interval,
                             std::span<const double> factor, const FieldArray& force_in,
                             FieldArray& force_out);

/// Adds the acceleration (3.4) of the cells' generalised hourglass forces `force` (two fields
/// over the cells) to the velocity rates `rate` (field velocity_field[a] for axis a).
void add_hourglass_acceleration(const HourglassStiffness& control, const FieldArray& force,
                                const std::array<int, 2>& velocity_field, FieldArray& rate);

}  // namespace rktsph
