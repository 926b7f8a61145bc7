#include "rktsph/stabilisation/flow_strength.hpp"

#include <algorithm>

#include "rktsph/core/parallel.hpp"
#include "rktsph/physics/physics_model.hpp"

namespace rktsph {

std::vector<double> near_flow_ratios(const CellComplex& cells, const PhysicsModel& model,
                                     double viscoplastic) {
  std::vector<double> ratio(cells.cell_count());
  for (std::size_t p = 0; p < ratio.size(); ++p)
    ratio[p] = model.elastic(cells.material(p)) ? 1.0 : viscoplastic;
  return ratio;
}

void cell_flow_states(const CellComplex& cells, std::span<const std::uint8_t> node_flowing,
                      bool every_flowed, std::span<std::uint8_t> point_flowing) {
  const auto has_flowed = [&](std::int32_t node) {
    return node_flowing[static_cast<std::size_t>(node)] != 0;
  };
  for (std::size_t p = 0; p < point_flowing.size(); ++p) {
    if (point_flowing[p] == 1) continue;
    const auto corners = cells.corners(p);
    point_flowing[p] = every_flowed || std::all_of(corners.begin(), corners.end(), has_flowed)
                           ? std::uint8_t{2}
                           : std::uint8_t{0};
  }
}

void flow_strength_factors(const CellComplex& cells, std::span<const double> near_flow,
                           std::span<const std::uint8_t> flowing, double plastic_fraction,
                           std::span<std::uint8_t> near_node, std::span<double> factor) {
  const auto nodes = static_cast<std::int64_t>(near_node.size());
  const auto count = static_cast<std::int64_t>(factor.size());
  // near_node[n] = 1 where a cell of node n is marked (a gather over the node's cells, so that
  // the loop runs in parallel without atomics).
  const auto mark_nodes = [&](const auto& marked) {
#pragma omp parallel for schedule(static) if (nodes > kParallelThreshold)
    for (std::int64_t n = 0; n < nodes; ++n) {
      std::uint8_t near = 0;
      for (const std::int32_t cell : cells.cells_of(static_cast<std::size_t>(n)))
        near |= marked(static_cast<std::size_t>(cell)) ? 1 : 0;
      near_node[static_cast<std::size_t>(n)] = near;
    }
  };
  const auto touches_marked_node = [&](std::size_t cell) {
    bool near = false;
    for (const std::int32_t node : cells.corners(cell))
      near = near || near_node[static_cast<std::size_t>(node)] != 0;
    return near;
  };
  // The cells that flow or have flowed, then kFlowNeighbourhood rings of cells around them
  // (factor holds the marks of the rings in between).
  mark_nodes([&](std::size_t cell) { return flowing[cell] != 0; });
  for (int ring = 1; ring < kFlowNeighbourhood; ++ring) {
#pragma omp parallel for schedule(static) if (count > kParallelThreshold)
    for (std::int64_t p = 0; p < count; ++p)
      factor[static_cast<std::size_t>(p)] =
          touches_marked_node(static_cast<std::size_t>(p)) ? 1.0 : 0.0;
    mark_nodes([&](std::size_t cell) { return factor[cell] != 0.0; });
  }
#pragma omp parallel for schedule(static) if (count > kParallelThreshold)
  for (std::int64_t p = 0; p < count; ++p) {
    const auto cell = static_cast<std::size_t>(p);
    factor[cell] = flowing[cell] == 1          ? plastic_fraction * near_flow[cell]
                   : touches_marked_node(cell) ? near_flow[cell]
                                               : 1.0;
  }
}

}  // namespace rktsph
