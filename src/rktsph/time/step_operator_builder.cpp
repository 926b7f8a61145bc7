#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "rktsph/core/error.hpp"
#include "rktsph/core/parallel.hpp"
#include "rktsph/core/step_time_split.hpp"
#include "rktsph/mesh/node_classification.hpp"
#include "rktsph/sph/cell_stencils.hpp"
#include "rktsph/time/step_operators.hpp"

namespace rktsph {

namespace {

/// The rows of the last build_rows that compute_row found degenerate, into `report`.
void collect_degenerate_rows(const OperatorWorkspace& workspace, std::size_t rows,
                             StencilReport& report) {
  for (std::size_t r = 0; r < rows; ++r)
    if (!workspace.regular[r]) report.degenerate_rows.push_back(static_cast<std::int32_t>(r));
}

}  // namespace

StepOperatorBuilder::StepOperatorBuilder(const NodeSets& reference, const StepOptions& options,
                                         std::vector<MirrorPlane> mirrors,
                                         std::span<const std::uint8_t> mirror_axes)
    : reference_(reference),
      options_(options),
      mirror_axes_(mirror_axes.begin(), mirror_axes.end()) {
  operator_options_.kernel = Kernel(options.kernel, reference.dimension);
  operator_options_.smoothing_length = options.h_over_dx * reference.spacing;
  operator_options_.interpolation_order = options.interpolation_order;
  operator_options_.mirrors = std::move(mirrors);
  // A round trip through the stress points with first-order interpolation on a wider support, so
  // that linear fields pass unchanged up to the boundary (docs/theory.md §3.3). Made once: a copy
  // per build would allocate its mirrors.
  filter_options_ = operator_options_;
  filter_options_.smoothing_length = options.hourglass_h_over_dx * reference.spacing;
  filter_options_.interpolation_order = 1;
  mirror_axes_.resize(reference.sph_nodes.size(), 0);
  // A lattice's radius search picks each cell's corners at h = 0.75 dx; other cells take their
  // stencils from the complex (docs/theory.md §4.8).
  cell_stencils_ = !reference.on_lattice();
  // A stress point's value is its cell's linear interpolant there (the corners' mean on a
  // simplex), not a kernel-weighted mean of corners at unequal distances.
  cell_corner_options_ = operator_options_;
  cell_corner_options_.interpolation_order = 1;
  simplices_ = true;
  for (std::size_t p = 0; p < reference.cells.cell_count(); ++p)
    simplices_ = simplices_ && reference.cells.corners(p).size() ==
                                   static_cast<std::size_t>(reference.dimension + 1);
}

bool StepOperatorBuilder::filter_active() const {
  // Only cells with more corners than a simplex have motions their centroid's gradient does not
  // see (the quadrilaterals' checkerboard, §3.3); a mesh of simplices has none to filter.
  return options_.hourglass_filter && reference_.dimension >= 2 && options_.hourglass_kappa > 0.0 &&
         !simplices_;
}

void StepOperatorBuilder::build(const Configuration& configuration, StepOperators& operators) {
  classify(configuration, operators);
  build_step_tables(configuration, operators);
  build_filter_tables(configuration, operators);
}

void StepOperatorBuilder::classify(const Configuration& configuration, StepOperators& operators) {
  if (classified_) {
    operators.boundary_nodes.assign(boundary_nodes_.begin(), boundary_nodes_.end());
    operators.node_to_boundary_row.assign(node_to_boundary_row_.begin(),
                                          node_to_boundary_row_.end());
    operators.incomplete_nodes.assign(incomplete_nodes_.begin(), incomplete_nodes_.end());
    return;
  }
  // Where each node sits, from the angle its cells fill around it; a node on a mirror plane also
  // has the images of its cells across it, which double its fraction once per plane (docs/theory.md
  // §2.6, §3.5). A node not inside gets the half-step of step 1b, except at a re-entrant corner
  // (2D, e.g. the toe of a cut): there the stress points surround the node on more than a
  // half-plane, so the cross-set gradient is already linear-exact, while the self-including
  // boundary closure is unstable (spectral radius 1.2-1.45 per step on an L-shaped lattice at
  // C = 0.3-0.9; the corner lies on no face, so nothing constrains its half-step).
  const std::size_t n = configuration.sph_nodes.size();
  operators.node_to_boundary_row.assign(n, -1);
  operators.boundary_nodes.clear();
  operators.incomplete_nodes.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const NodePlace place =
        place_of_node(reference_.cells, reference_.sph_nodes, i, unsigned{mirror_axes_[i]});
    if (place == NodePlace::Isolated)
      throw RunError(fmt::format(
          "the SPH node at {} belongs to no cell (a shape vertex or a one-node-wide strip "
          "that touches no cell), so nothing moves it; widen the shape to whole cells",
          describe_point(configuration.sph_nodes, i)));
    if (place != NodePlace::Interior)
      operators.incomplete_nodes.push_back(static_cast<std::int32_t>(i));
    if (place == NodePlace::Boundary) {
      operators.node_to_boundary_row[i] =
          static_cast<std::int32_t>(operators.boundary_nodes.size());
      operators.boundary_nodes.push_back(static_cast<std::int32_t>(i));
    }
  }
  boundary_nodes_ = operators.boundary_nodes;
  node_to_boundary_row_ = operators.node_to_boundary_row;
  incomplete_nodes_ = operators.incomplete_nodes;
  classified_ = true;
}

void StepOperatorBuilder::search_candidates(const PointCloud& nodes, const PointCloud& points,
                                            const std::vector<std::int32_t>& boundary_nodes,
                                            double radius) {
  // The three kinds of rows and their sources, as build_step_tables gathers them (§9.5).
  const OperatorOptions& options = operator_options_;
  check_mirror_count(options);  // gather_candidates' one throw, before the parallel regions
  // Each row into its own scratch buffer in parallel, then all rows into one contiguous table:
  // the builds between searches stream through it instead of visiting a buffer per row.
  std::vector<std::vector<StencilCandidate>>& rows = candidate_scratch_;
  const auto search = [&](CandidateTable& table, std::size_t count, const PointCloud& targets,
                          const CellList& cells, bool same_set,
                          std::span<const std::int32_t> row_target) {
    if (rows.size() < count) rows.resize(count);
    const auto n = static_cast<std::int64_t>(count);
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
    for (std::int64_t r = 0; r < n; ++r) {
      const auto target = row_target.empty() ? static_cast<std::int32_t>(r)
                                             : row_target[static_cast<std::size_t>(r)];
      gather_candidates(targets.point(static_cast<std::size_t>(target)), cells, options,
                        same_set ? target : -1, radius, rows[static_cast<std::size_t>(r)]);
    }
    table.start.resize(count + 1);
    table.start[0] = 0;
    for (std::size_t r = 0; r < count; ++r)
      table.start[r + 1] = table.start[r] + static_cast<std::int64_t>(rows[r].size());
    table.entries.resize(static_cast<std::size_t>(table.start[count]));
#pragma omp parallel for schedule(static) if (n > kParallelThreshold)
    for (std::int64_t r = 0; r < n; ++r) {
      const auto row = static_cast<std::size_t>(r);
      std::copy(rows[row].begin(), rows[row].end(), table.entries.begin() + table.start[row]);
    }
  };
  search(point_row_candidates_, points.size(), points, node_cells_, false, {});
  search(node_row_candidates_, nodes.size(), nodes, point_cells_, false, {});
  search(boundary_row_candidates_, boundary_nodes.size(), nodes, node_cells_, true, boundary_nodes);
}

void StepOperatorBuilder::build_step_tables(const Configuration& configuration, StepOperators& ops,
                                            bool search) {
  const int d = reference_.dimension;
  const PointCloud& nodes = configuration.sph_nodes;
  const PointCloud& points = configuration.stress_points;
  const OperatorOptions& options = operator_options_;
  const double support = options.kernel.support_radius(options.smoothing_length);
  // With a skin the stencils come from the candidates, searched again only when asked; without,
  // from the cell lists every build.
  const bool from_candidates = candidate_skin_ > 0.0;
  if (!cell_stencils_ && (search || !from_candidates)) {
    auto clock = std::chrono::steady_clock::now();
    const double radius = from_candidates ? support + candidate_skin_ : support;
    node_cells_.rebuild(nodes, radius);
    point_cells_.rebuild(points, radius);
    if (from_candidates) search_candidates(nodes, points, ops.boundary_nodes, radius);
    cell_list_seconds_ += lap(clock);
  }
  const CellList& node_cells = node_cells_;
  const CellList& point_cells = point_cells_;
  // Row r's stencil of sources `sources` around x, from the candidates or the cell lists.
  const auto gather = [&](const CandidateTable& table, std::size_t r, const CellList& cells,
                          const PointCloud& sources, std::int32_t exclude,
                          const std::array<double, 3>& x, std::vector<StencilSource>& stencil) {
    if (from_candidates)
      gather_stencil(x, sources,
                     std::span<const StencilCandidate>(table.entries.data() + table.start[r],
                                                       table.entries.data() + table.start[r + 1]),
                     options, stencil);
    else
      gather_stencil(x, cells, options, exclude, stencil);
  };

  StencilReport report;
  build_rows(points.size(), d, cell_stencils_ ? cell_corner_options_ : options,
             TableWeights::InterpolationAndGradient, ops.nodes_to_points, workspace_,
             [&](std::size_t p, std::vector<StencilSource>& stencil) {
               const auto x = points.point(p);
               if (cell_stencils_) {
                 gather_cell_corners(reference_.cells, nodes, p, stencil);
                 return RowTarget{x, GradientReference::ShepardCentroid, -1,
                                  configuration.point_smoothing_length[p]};
               }
               gather(point_row_candidates_, p, node_cells, nodes, -1, x, stencil);
               return RowTarget{x, GradientReference::ShepardCentroid, -1};
             });
  collect_degenerate_rows(workspace_, points.size(), report);
  ops.fallback_rows = 0;
  if (!report.degenerate_rows.empty())
    degenerate(
        report.degenerate_rows.size(), ops,
        fmt::format("the stress point at {} has a degenerate stencil (h/dx = {} is too "
                    "small for its neighbourhood)",
                    describe_point(points, static_cast<std::size_t>(report.degenerate_rows[0])),
                    options_.h_over_dx));
  ops.compact_stencils = true;
  for (std::size_t p = 0; p < ops.nodes_to_points.rows(); ++p)
    ops.compact_stencils =
        ops.compact_stencils &&
        ops.nodes_to_points.row_start[p + 1] - ops.nodes_to_points.row_start[p] <= (1 << d);

  // The incomplete nodes' closure: the lumped adjoint of the stress points' operator, with the
  // node's own half-step value (which carries the face tractions) where it has one (docs/theory.md
  // §5.3).
  const std::size_t n = nodes.size();
  const auto n_points = static_cast<std::int32_t>(points.size());
  own_column_.assign(ops.incomplete_nodes.size(), -1);
  for (std::size_t r = 0; r < ops.incomplete_nodes.size(); ++r)
    if (ops.node_to_boundary_row[static_cast<std::size_t>(ops.incomplete_nodes[r])] >= 0)
      own_column_[r] = n_points + ops.incomplete_nodes[r];
  try {
    build_adjoint_operator(ops.nodes_to_points, points.volume, ops.incomplete_nodes, own_column_,
                           ops.incomplete_closure);
  } catch (const UnreachedNode& unreached) {
    throw RunError(describe_unreached_node(nodes, unreached.node()));
  }

  // Each node's stencil in parallel (build_rows). A boundary node's own half-step value is the
  // reference (docs/theory.md §2.2, step 2); where that leaves its compact stencil rank-deficient
  // (e.g. a corner at h = 0.75 dx) the half-step values of the neighbouring boundary nodes are
  // added (docs/theory.md §4.2, §7.1). Whether even they cannot complete it is recorded per node
  // and thrown for the first such node after the parallel loop.
  if (retry_stencils_.size() < n) retry_stencils_.resize(n);
  const std::vector<std::int32_t>& boundary_row = ops.node_to_boundary_row;
  build_rows(n, d, options, TableWeights::InterpolationAndGradient, ops.points_to_nodes, workspace_,
             [&](std::size_t i, std::vector<StencilSource>& stencil) {
               const auto x = nodes.point(i);
               const auto self = static_cast<std::int32_t>(i);
               if (cell_stencils_)
                 return cell_node_row(configuration, i, n_points, boundary_row, stencil);
               gather(node_row_candidates_, i, point_cells, points, -1, x, stencil);
               if (boundary_row[i] < 0) return RowTarget{x, GradientReference::ShepardCentroid, -1};
               const RowTarget row{x, GradientReference::Self, n_points + self};
               if (row_is_regular(d, x, stencil, options, row.reference, row.self_column))
                 return row;
               std::vector<StencilSource>& neighbours = retry_stencils_[i];
               gather(boundary_row_candidates_, static_cast<std::size_t>(boundary_row[i]),
                      node_cells, nodes, self, x, neighbours);
               for (StencilSource s : neighbours)
                 if (boundary_row[static_cast<std::size_t>(s.column)] >= 0) {
                   s.column += n_points;
                   stencil.push_back(s);
                 }
               return row;
             });
  for (std::size_t i = 0; i < n; ++i)
    if (!workspace_.regular[i])
      degenerate(1, ops,
                 fmt::format("the SPH node at {} has a degenerate stencil that even its "
                             "boundary neighbours cannot complete",
                             describe_point(nodes, i)));

  report.degenerate_rows.clear();
  if (ops.boundary_nodes.empty())  // every face is a mirror plane: no half-step rows
    reset_table(ops.boundary_gradient, d);
  else {
    const std::vector<std::int32_t>& rows = ops.boundary_nodes;
    build_rows(rows.size(), d, options, TableWeights::InterpolationAndGradient,
               ops.boundary_gradient, workspace_,
               [&](std::size_t r, std::vector<StencilSource>& stencil) {
                 const std::int32_t self = rows[r];
                 const auto x = nodes.point(static_cast<std::size_t>(self));
                 if (cell_stencils_) {
                   gather_cell_neighbours(reference_.cells, nodes, static_cast<std::size_t>(self),
                                          options.mirrors, plane_tolerance(), stencil);
                   return RowTarget{x, GradientReference::Self, self,
                                    cell_stencil_smoothing_length(x, stencil, d, options_.h_over_dx,
                                                                  CellStencilKind::CellNeighbours)};
                 }
                 gather(boundary_row_candidates_, r, node_cells, nodes, self, x, stencil);
                 return RowTarget{x, GradientReference::Self, self};
               });
    collect_degenerate_rows(workspace_, rows.size(), report);
  }
  if (!report.degenerate_rows.empty())
    degenerate(
        report.degenerate_rows.size(), ops,
        fmt::format("the boundary node at {} has a degenerate collocated stencil",
                    describe_point(nodes, static_cast<std::size_t>(
                                              ops.boundary_nodes[report.degenerate_rows[0]]))));
  if (share_weights_) {
    // On a lattice the interior rows of both tables have one stencil each: the step then streams
    // 4 bytes per entry instead of 29 (docs/theory.md §4.7). After the closure, which is built
    // from the rows as computed. Tables that share are built once: their scratch is freed before
    // the filter's tables are built, so that the two never add up.
    share_row_weights(ops.nodes_to_points, share_workspace_);
    share_row_weights(ops.points_to_nodes, share_workspace_);
    workspace_ = OperatorWorkspace{};
    share_workspace_ = ShareWorkspace{};
  }
}

RowTarget StepOperatorBuilder::cell_node_row(const Configuration& configuration, std::size_t node,
                                             std::int32_t n_points,
                                             std::span<const std::int32_t> boundary_row,
                                             std::vector<StencilSource>& stencil) {
  // docs/theory.md §4.8: the node's cells' centroids, images included; a boundary node's own
  // half-step value is its reference, and where that leaves the row rank-deficient the half-step
  // values of its boundary neighbours complete it, as in the radius search's retry.
  const PointCloud& nodes = configuration.sph_nodes;
  const int d = reference_.dimension;
  const auto x = nodes.point(node);
  gather_cell_centroids(reference_.cells, nodes, configuration.stress_points, node,
                        operator_options_.mirrors, plane_tolerance(), stencil);
  double h = configuration.node_smoothing_length[node];
  if (boundary_row[node] < 0) return RowTarget{x, GradientReference::ShepardCentroid, -1, h};
  const auto self_column = n_points + static_cast<std::int32_t>(node);
  if (row_is_regular(d, x, stencil, operator_options_, GradientReference::Self, self_column, h))
    return RowTarget{x, GradientReference::Self, self_column, h};
  std::vector<StencilSource>& neighbours = retry_stencils_[node];
  gather_cell_neighbours(reference_.cells, nodes, node, operator_options_.mirrors,
                         plane_tolerance(), neighbours);
  h = std::max(h, cell_stencil_smoothing_length(x, neighbours, d, options_.h_over_dx,
                                                CellStencilKind::CellNeighbours));
  for (StencilSource s : neighbours)
    if (boundary_row[static_cast<std::size_t>(s.column)] >= 0) {
      s.column += n_points;
      stencil.push_back(s);
    }
  return RowTarget{x, GradientReference::Self, self_column, h};
}

void StepOperatorBuilder::degenerate(std::size_t rows, StepOperators& operators,
                                     const std::string& message) const {
  if (!fall_back_) throw RunError(message);
  operators.fallback_rows += rows;
}

void StepOperatorBuilder::build_filter_tables(const Configuration& configuration,
                                              StepOperators& ops) {
  if (!filter_active()) return;
  const OperatorOptions& filter_options = filter_options_;
  const double filter_support =
      filter_options.kernel.support_radius(filter_options.smoothing_length);
  auto clock = std::chrono::steady_clock::now();
  node_cells_.rebuild(configuration.sph_nodes, filter_support);
  point_cells_.rebuild(configuration.stress_points, filter_support);
  cell_list_seconds_ += lap(clock);
  const CellList& filter_node_cells = node_cells_;
  const CellList& filter_point_cells = point_cells_;
  if (share_weights_) {
    // Interior rows share one stencil: less memory traffic in the filter (docs/theory.md §3.3).
    // Built and shared a chunk of rows at a time, so that the table with a weight per entry, six
    // times the shared one, never exists whole (§4.7).
    build_shared_cross_operator(configuration.stress_points, filter_node_cells, filter_options,
                                ops.filter_to_points, workspace_, share_workspace_);
    build_shared_cross_operator(configuration.sph_nodes, filter_point_cells, filter_options,
                                ops.filter_to_nodes, workspace_, share_workspace_);
    return;
  }
  // The round trip only interpolates: the gradient weights are computed in scratch, not kept.
  build_cross_operator(configuration.stress_points, filter_node_cells, filter_options,
                       ops.filter_to_points, workspace_, nullptr, TableWeights::InterpolationOnly);
  build_cross_operator(configuration.sph_nodes, filter_point_cells, filter_options,
                       ops.filter_to_nodes, workspace_, nullptr, TableWeights::InterpolationOnly);
}

void StepOperatorBuilder::release_buffers(StepOperators& operators) {
  for (WeightTable* table : {&operators.nodes_to_points, &operators.points_to_nodes,
                             &operators.boundary_gradient, &operators.incomplete_closure.table,
                             &operators.filter_to_points, &operators.filter_to_nodes})
    shrink_table(*table);
  workspace_ = OperatorWorkspace{};
  share_workspace_ = ShareWorkspace{};
  retry_stencils_ = {};
  candidate_scratch_ = {};
  point_row_candidates_ = {};
  node_row_candidates_ = {};
  boundary_row_candidates_ = {};
  node_cells_ = CellList{};
  point_cells_ = CellList{};
}

}  // namespace rktsph
