#include "rktsph/sph/adjoint_operator.hpp"

#include <fmt/format.h>
#include "rktsph/core/parallel.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace rktsph {

namespace {

// Calls visit(p, k, row) for every entry k of forward row p whose column is a target node (its
// adjoint row `row`), in forward-row order.
template <class Visit>
void for_each_target_entry(const WeightTable& forward, const std::vector<std::int32_t>& row_of,
                           Visit&& visit) {
  for (std::size_t p = 0; p < forward.rows(); ++p)
    for (auto k = static_cast<std::size_t>(forward.row_start[p]);
         k < static_cast<std::size_t>(forward.row_start[p + 1]); ++k) {
      const std::int32_t r = row_of[static_cast<std::size_t>(forward.source_of(p, k))];
      if (r >= 0) visit(p, k, static_cast<std::size_t>(r));
    }
}

}  // namespace

std::string describe_unreached_node(const PointCloud& nodes, std::int32_t node) {
  // Met where a node's cells have been crushed or stretched so far that none of their stress
  // points weighs the node any more: on a moving configuration, where fixed cells cannot follow
  // a flow (docs/theory.md §9.12, §9.14), where a finer lattice fails sooner, not later.
  return fmt::format(
      "the SPH node at {} lies out of reach of every stress point around it (its cells are "
      "crushed or stretched so far that none of them weighs it, so its velocity has nothing to "
      "update it): its cells cannot follow a flow this large. With the cells of the start a "
      "finer lattice fails sooner, not later (docs/theory.md §9.12); numerics.cells.policy: "
      "reformed forms the cells again as the body flows (§9.17), and formed cells fail so only "
      "where the flow stretches them faster than numerics.cells.reform_below forms them again. "
      "Stop the run before this deformation (time.end), lower the imposed velocity or load, or "
      "give the soil more strength where it flows",
      describe_point(nodes, static_cast<std::size_t>(node)));
}

AdjointOperator build_adjoint_operator(const WeightTable& forward,
                                       std::span<const double> row_volume,
                                       std::span<const std::int32_t> target,
                                       std::span<const std::int32_t> self_column) {
  AdjointOperator adjoint;
  build_adjoint_operator(forward, row_volume, target, self_column, adjoint);
  return adjoint;
}

void build_adjoint_operator(const WeightTable& forward, std::span<const double> row_volume,
                            std::span<const std::int32_t> target,
                            std::span<const std::int32_t> self_column, AdjointOperator& adjoint) {
  if (!forward.has_gradient || row_volume.size() != forward.rows() ||
      self_column.size() != target.size())
    throw std::invalid_argument("build_adjoint_operator: inconsistent forward table or sizes");
  const int d = forward.dimension;
  std::int32_t columns = 0;
  for (std::size_t p = 0; p < forward.rows(); ++p)
    for (auto k = static_cast<std::size_t>(forward.row_start[p]);
         k < static_cast<std::size_t>(forward.row_start[p + 1]); ++k)
      columns = std::max(columns, forward.source_of(p, k) + 1);
  for (std::int32_t n : target)
    columns = std::max(columns, n + 1);
  std::vector<std::int32_t>& row_of = adjoint.row_of;
  row_of.assign(static_cast<std::size_t>(columns), -1);
  for (std::size_t r = 0; r < target.size(); ++r)
    row_of[static_cast<std::size_t>(target[r])] = static_cast<std::int32_t>(r);

  // A transpose by counting sort: count each target's entries and sum its lumped volume in
  // forward-row order, then place the entries in that same order (the order, and the sums, of
  // the per-target lists this replaces).
  WeightTable& table = adjoint.table;
  table.dimension = d;
  table.row_start.assign(target.size() + 1, 0);
  adjoint.lumped_volume.assign(target.size(), 0.0);
  for_each_target_entry(forward, row_of, [&](std::size_t p, std::size_t k, std::size_t row) {
    ++table.row_start[row + 1];
    const auto weight =
        static_cast<std::size_t>(static_cast<std::int64_t>(k) + forward.weight_offset(p));
    adjoint.lumped_volume[row] += row_volume[p] * forward.interpolation[weight];
  });
  for (std::size_t r = 0; r < target.size(); ++r) {
    const double volume = adjoint.lumped_volume[r];
    if (table.row_start[r + 1] == 0 || !(volume > 0.0))
      throw UnreachedNode(target[r], "build_adjoint_operator: node " + std::to_string(target[r]) +
                                         " is in no forward row (zero lumped volume)");
    table.row_start[r + 1] += table.row_start[r];
  }
  const auto entries = static_cast<std::size_t>(table.row_start.back());
  table.source.resize(entries);
  table.reflection.resize(entries);
  table.interpolation.resize(entries);
  for (int c = 0; c < 3; ++c)
    table.gradient[static_cast<std::size_t>(c)].resize(c < d ? entries : 0);
  table.has_reflections = false;
  table.has_gradient = true;
  table.weight_start.clear();
  table.row_reflects.clear();
  table.row_base.clear();
  table.source_offset.clear();
  adjoint.cursor.assign(table.row_start.begin(), table.row_start.end() - 1);
  for_each_target_entry(forward, row_of, [&](std::size_t p, std::size_t k, std::size_t row) {
    const auto e = static_cast<std::size_t>(adjoint.cursor[row]++);
    const double volume = adjoint.lumped_volume[row];
    const auto weight = static_cast<std::size_t>(static_cast<std::int64_t>(k) +
                                                 forward.weight_offset(p));  // shared weights
    const std::uint8_t reflection = forward.has_reflections ? forward.reflection[weight] : 0;
    table.source[e] = static_cast<std::int32_t>(p);
    table.reflection[e] = reflection;
    table.has_reflections = table.has_reflections || reflection != 0;
    table.interpolation[e] = row_volume[p] * forward.interpolation[weight] / volume;
    for (int c = 0; c < d; ++c)
      table.gradient[static_cast<std::size_t>(c)][e] =
          -row_volume[p] * forward.gradient[static_cast<std::size_t>(c)][weight] / volume;
  });
  adjoint.target.assign(target.begin(), target.end());
  adjoint.self_column.assign(self_column.begin(), self_column.end());
}

void add_adjoint_interpolation(const AdjointOperator& adjoint, const FieldArray& in,
                               std::span<const Parity> parity,
                               std::span<const std::uint8_t> selected, FieldArray& out) {
  const WeightTable& table = adjoint.table;
  const int field_count = in.field_count();
  if (static_cast<int>(parity.size()) != field_count ||
      static_cast<int>(selected.size()) != field_count || out.field_count() < field_count)
    throw std::invalid_argument(
        "add_adjoint_interpolation: field count, parity and outputs disagree");
  // Rows in parallel: each target node is the row of one adjoint row only.
  const auto rows = static_cast<std::int64_t>(table.rows());
#pragma omp parallel for schedule(static) if (rows > kParallelThreshold)
  for (std::int64_t row = 0; row < rows; ++row) {
    const auto r = static_cast<std::size_t>(row);
    const auto node = static_cast<std::size_t>(adjoint.target[r]);
    for (int f = 0; f < field_count; ++f) {
      if (!selected[static_cast<std::size_t>(f)]) continue;
      const double* values = in.field(f);
      const auto odd = static_cast<unsigned>(parity[static_cast<std::size_t>(f)]);
      double sum = 0.0;
      const std::int64_t offset = table.weight_offset(r);  // shared weights (share_row_weights)
      for (auto k = static_cast<std::size_t>(table.row_start[r]);
           k < static_cast<std::size_t>(table.row_start[r + 1]); ++k) {
        const auto w = static_cast<std::size_t>(static_cast<std::int64_t>(k) + offset);
        sum += table.interpolation[w] * reflection_sign(table.reflection[w], odd) *
               values[table.source[k]];
      }
      out.field(f)[node] += sum;
    }
  }
}

void apply_adjoint_gradient(const AdjointOperator& adjoint, const FieldArray& in,
                            std::span<const Parity> parity, std::span<const std::uint8_t> selected,
                            FieldArray& out_gradient) {
  const WeightTable& table = adjoint.table;
  const int d = table.dimension;
  const int field_count = in.field_count();
  if (static_cast<int>(parity.size()) != field_count ||
      static_cast<int>(selected.size()) != field_count ||
      out_gradient.field_count() < field_count * d)
    throw std::invalid_argument("apply_adjoint_gradient: field count, parity and outputs disagree");
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const auto node = static_cast<std::size_t>(adjoint.target[r]);
    const std::int32_t self = adjoint.self_column[r];
    for (int f = 0; f < field_count; ++f) {
      if (!selected[static_cast<std::size_t>(f)]) continue;
      const double* values = in.field(f);
      const double own = self >= 0 ? values[self] : 0.0;
      for (int c = 0; c < d; ++c) {
        // Sign of a reflected entry: the parity of the momentum component this term feeds.
        const unsigned odd = static_cast<unsigned>(parity[static_cast<std::size_t>(f)]) ^ (1u << c);
        double sum = 0.0;
        const std::int64_t offset = table.weight_offset(r);  // shared weights
        for (auto k = static_cast<std::size_t>(table.row_start[r]);
             k < static_cast<std::size_t>(table.row_start[r + 1]); ++k) {
          const auto w = static_cast<std::size_t>(static_cast<std::int64_t>(k) + offset);
          sum += table.gradient[static_cast<std::size_t>(c)][w] *
                 reflection_sign(table.reflection[w], odd) * (values[table.source[k]] - own);
        }
        out_gradient.field(f * d + c)[node] = sum;
      }
    }
  }
}

}  // namespace rktsph
