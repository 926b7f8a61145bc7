// The adjoint (weak) gradient: the momentum closure of the nodes whose lattice cells are not all
// present (docs/theory.md §5.3, eq. 5.2).
//
// The stress points' velocity gradient G (a WeightTable, rows = stress points, columns = nodes)
// pairs with a nodal divergence through the discrete power identity
//     sum_P V_P sigma_P : (G v)_P  =  - sum_n V_n v_n . (div sigma)_n  +  boundary work,
// which fixes (div sigma)_n as the adjoint of G with the lumped volume V_n = sum_P V_P w_Pn.
// On a complete lattice stencil at h = 0.75 dx this is the corrected SPH divergence itself; at
// boundary nodes it is what makes the discrete momentum balance exert no force on velocity
// patterns that G does not see, so a damped body can come to rest (§5.3). The boundary work is
// the traction carried by the node's own half-step value: the gradient of field f along c is
//     (grad_c f)_n = sum_P a_Pn,c s (f_P - f_n),   a_Pn = - V_P g_Pn / V_n,
// which vanishes on constants; without an own value (a node on no face) the traction is zero.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "rktsph/core/field_array.hpp"
#include "rktsph/sph/operators.hpp"

namespace rktsph {

struct AdjointGradient {
  /// Rows = `target` nodes; source = forward row (stress point); gradient = a_Pn; the reflection
  /// bits are those of the forward entry. Interpolation weights are not used (zero).
  WeightTable table;
  std::vector<std::int32_t> target;       ///< node of each row
  std::vector<std::int32_t> self_column;  ///< column of the node's own value in `in`, or -1
  std::vector<double> lumped_volume;      ///< V_n of each row
};

/// Transposes the gradient of `forward` (rows with volumes `row_volume`) onto the nodes `target`;
/// `self_column[r]` is where row r's own value lives in the array the result is applied to (-1:
/// none, traction-free). Throws std::invalid_argument if a target has no forward entry.
AdjointGradient build_adjoint_gradient(const WeightTable& forward,
                                       std::span<const double> row_volume,
                                       std::span<const std::int32_t> target,
                                       std::span<const std::int32_t> self_column);

/// Writes the adjoint gradient of every field f with `selected[f]` into `out_gradient` (field f
/// along axis c at f * dimension + c, point = target node). A reflected entry enters with the
/// parity of the momentum component the term belongs to, parity[f] ^ bit c (the adjoint reflects
/// the result, not the source).
void apply_adjoint_gradient(const AdjointGradient& adjoint, const FieldArray& in,
                            std::span<const Parity> parity, std::span<const std::uint8_t> selected,
                            FieldArray& out_gradient);

}  // namespace rktsph
