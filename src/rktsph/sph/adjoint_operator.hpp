// The lumped adjoint of the stress points' operator: the closure of the nodes whose lattice cells
// are not all present (docs/theory.md §5.3, eqs. 5.2 and 5.3).
//
// The stress points' interpolation I and velocity gradient G (one WeightTable, rows = stress
// points, columns = nodes, weights w_Pn and g_Pn) pair with nodal quantities through the lumped
// volume V_n = sum_P V_P w_Pn:
//   gradient (eq. 5.2): the discrete power identity
//       sum_P V_P sigma_P : (G v)_P  =  - sum_n V_n v_n . (div sigma)_n  +  boundary work
//     fixes (div sigma)_n as the adjoint of G. The boundary work is the traction carried by the
//     node's own half-step value: the gradient of field f along c is
//       (grad_c f)_n = sum_P a_Pn,c s (f_P - f_n),   a_Pn = - V_P g_Pn / V_n,
//     which vanishes on constants; without an own value (a node on no face) the traction is zero.
//   interpolation (eq. 5.3): the transpose of I, (I^T q)_n = sum_P b_Pn s q_P, b_Pn = V_P w_Pn /
//   V_n,
//     the volume-weighted average of stress-point values over the node's cells.
// On a complete lattice stencil at h = 0.75 dx the adjoint gradient is the corrected SPH
// divergence itself, and the step-2 gradient of interpolated values is the average of the
// stress points' gradients (the operators commute); the closure restores both pairings at the
// boundary, so that a damped body can come to rest (§5.3).
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "rktsph/core/field_array.hpp"
#include "rktsph/core/point_cloud.hpp"
#include "rktsph/sph/operators.hpp"

namespace rktsph {

/// Thrown by build_adjoint_operator for a target node that no forward row reaches (a node out of
/// the kernel's reach of every stress point, e.g. beside cells crushed on a moving
/// configuration): the caller, who knows where the node is, explains it to the user.
class UnreachedNode : public std::invalid_argument {
 public:
  UnreachedNode(std::int32_t node, const std::string& what)
      : std::invalid_argument(what), node_(node) {}
  std::int32_t node() const { return node_; }

 private:
  std::int32_t node_;
};

/// What a user is told about an UnreachedNode at `node` of `nodes` (its position, what happened in
/// physical words and what to change): the text of the RunError the step's builders throw.
std::string describe_unreached_node(const PointCloud& nodes, std::int32_t node);

struct AdjointOperator {
  /// Rows = `target` nodes; source = forward row (stress point); gradient = a_Pn, interpolation =
  /// b_Pn; the reflection bits are those of the forward entry.
  WeightTable table;
  std::vector<std::int32_t> target;       ///< node of each row
  std::vector<std::int32_t> self_column;  ///< column of the node's own value in `in`, or -1
  std::vector<double> lumped_volume;      ///< V_n of each row
  /// Scratch of a rebuild in place (the forward column -> row map, the rows' fill positions).
  std::vector<std::int32_t> row_of;
  std::vector<std::int64_t> cursor;
};

/// Transposes the interpolation and gradient of `forward` (rows with volumes `row_volume`) onto
/// the nodes `target`; `self_column[r]` is where row r's own value lives in the array the gradient
/// is applied to (-1: none, traction-free). Throws std::invalid_argument if a target has no forward
/// entry.
AdjointOperator build_adjoint_operator(const WeightTable& forward,
                                       std::span<const double> row_volume,
                                       std::span<const std::int32_t> target,
                                       std::span<const std::int32_t> self_column);

/// The same into an existing operator, reusing its arrays: a rebuild of the same size allocates
/// nothing (the large-deformation step rebuilds it every step).
void build_adjoint_operator(const WeightTable& forward, std::span<const double> row_volume,
                            std::span<const std::int32_t> target,
                            std::span<const std::int32_t> self_column, AdjointOperator& adjoint);

/// Adds the adjoint interpolation of every field f of `in` (values on the stress points) with
/// `selected[f]` to `out` (point = target node). A reflected entry enters with parity[f].
void add_adjoint_interpolation(const AdjointOperator& adjoint, const FieldArray& in,
                               std::span<const Parity> parity,
                               std::span<const std::uint8_t> selected, FieldArray& out);

/// Writes the adjoint gradient of every field f with `selected[f]` into `out_gradient` (field f
/// along axis c at f * dimension + c, point = target node). A reflected entry enters with the
/// parity of the momentum component the term belongs to, parity[f] ^ bit c (the adjoint reflects
/// the result, not the source).
void apply_adjoint_gradient(const AdjointOperator& adjoint, const FieldArray& in,
                            std::span<const Parity> parity, std::span<const std::uint8_t> selected,
                            FieldArray& out_gradient);

}  // namespace rktsph
