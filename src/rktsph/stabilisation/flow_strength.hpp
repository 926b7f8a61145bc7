// The strength of a zero-energy control that follows viscoplastic flow (docs/theory.md §3.4,
// eq. 3.10), on the cells of any complex: the lattice's Flanagan–Belytschko stiffness (eq. 3.9)
// and the triangles' patch strain stiffness (eq. 3.12) both scale their cells by these factors,
// so that neither resists a mechanism once it has formed while elastic cells keep their strength.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "rktsph/mesh/cell_complex.hpp"

namespace rktsph {

class PhysicsModel;

/// Rings of cells around a cell that flows or has flowed that take the near-flow strength (eq.
/// 3.10; measured in docs/theory.md §3.4: with none, the cells around a forming mechanism hold it
/// and Taylor's stability number rises).
inline constexpr int kFlowNeighbourhood = 2;

/// The near-flow ratio r_P of eq. 3.10 of every cell: `viscoplastic` in cells of viscoplastic
/// materials, 1 in elastic ones (which never flow).
std::vector<double> near_flow_ratios(const CellComplex& cells, const PhysicsModel& model,
                                     double viscoplastic);

/// flowing[P] for every cell (1 flows, 2 has flowed, 0 never) from the cells' own state
/// (`point_flowing`, 1 where the stress point flows at the half step) and the nodes'
/// (`node_flowing`, nonzero where the node has flowed): a cell has flowed where every corner node
/// has, not one only (docs/theory.md §3.4: a drained loaded surface yields in its nodes alone).
/// `every_flowed` marks every cell that does not flow as having flowed (the moving configuration's
/// rule).
void cell_flow_states(const CellComplex& cells, std::span<const std::uint8_t> node_flowing,
                      bool every_flowed, std::span<std::uint8_t> point_flowing);

/// factor_P of eq. 3.10 for every cell from its flow state (flowing: 1 in flow, 2 flowed before,
/// 0 never): plastic_fraction * near_flow_P in flowing cells, near_flow_P in the other cells within
/// kFlowNeighbourhood rings of a cell that flows or has flowed (itself included), 1 elsewhere.
/// near_node is scratch of one entry per node; nothing is allocated.
void flow_strength_factors(const CellComplex& cells, std::span<const double> near_flow,
                           std::span<const std::uint8_t> flowing, double plastic_fraction,
                           std::span<std::uint8_t> near_node, std::span<double> factor);

}  // namespace rktsph
