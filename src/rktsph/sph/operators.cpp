#include "rktsph/sph/operators.hpp"
#include "rktsph/core/parallel.hpp"
#include "rktsph/core/small_tensor.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <type_traits>

namespace rktsph {

namespace {

using Matrix = std::array<std::array<double, 3>, 3>;

// Largest number of fields one apply_operator call handles (v and sigma in 3D plus spares).
constexpr int kMaxFields = 24;

double determinant(const Matrix& a, int d) {
  switch (d) {
    case 1:
      return a[0][0];
    case 2:
      return a[0][0] * a[1][1] - a[0][1] * a[1][0];
    default:
      return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
             a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
             a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  }
}

Matrix inverse(const Matrix& a, int d, double det) {
  Matrix inv{};
  if (d == 1) {
    inv[0][0] = 1.0 / det;
  } else if (d == 2) {
    inv[0][0] = a[1][1] / det;
    inv[0][1] = -a[0][1] / det;
    inv[1][0] = -a[1][0] / det;
    inv[1][1] = a[0][0] / det;
  } else {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
        inv[r][c] = (a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1]) / det;
      }
  }
  return inv;
}

// Reflects x across the planes selected by the bits of `subset` (indices into mirrors).
Vec3 reflect(Vec3 x, const std::vector<MirrorPlane>& mirrors, unsigned subset) {
  for (std::size_t m = 0; m < mirrors.size(); ++m)
    if (subset & (1u << m)) {
      const MirrorPlane& plane = mirrors[m];
      x[plane.axis] = 2.0 * plane.coordinate - x[plane.axis];
    }
  return x;
}

// x^n for the small exponents of a dimension, without a call to pow in every row.
double integer_power(double x, int n) {
  double result = 1.0;
  for (int k = 0; k < n; ++k)
    result *= x;
  return result;
}

}  // namespace

void check_mirror_count(const OperatorOptions& options) {
  if (options.mirrors.size() > 8)
    throw std::invalid_argument("at most 8 mirror planes are supported");
}

namespace {

/// Whether the target is within `radius` of every plane of `subset` (a set of planes contributes
/// images only then), and the subset's reflection bits (one per axis reflected an odd number of
/// times).
bool near_every_plane(const Vec3& target, const std::vector<MirrorPlane>& mirrors, unsigned subset,
                      double radius, std::uint8_t& reflection) {
  bool near_all = true;
  reflection = 0;
  for (std::size_t m = 0; m < mirrors.size(); ++m)
    if (subset & (1u << m)) {
      near_all = near_all && std::abs(target[mirrors[m].axis] - mirrors[m].coordinate) < radius;
      reflection ^= static_cast<std::uint8_t>(1u << mirrors[m].axis);
    }
  return near_all;
}

/// True if source x lies on a plane of `subset`: its image there coincides with a point already
/// counted.
bool on_a_plane(const Vec3& x, const std::vector<MirrorPlane>& mirrors, unsigned subset,
                double tolerance) {
  for (std::size_t m = 0; m < mirrors.size(); ++m)
    if ((subset & (1u << m)) && std::abs(x[mirrors[m].axis] - mirrors[m].coordinate) <= tolerance)
      return true;
  return false;
}

/// Calls visit(j, subset, reflection, x_j) for every source j of `cells` within `radius` of
/// `target` or of its mirror images: the subsets of planes in turn, the sources of each in cell
/// order. With `skip_on_plane` the image of a source lying on a plane of its subset is left out.
template <class Visit>
void for_each_stencil_source(const Vec3& target, const CellList& cells,
                             const OperatorOptions& options, std::int32_t exclude, double radius,
                             bool skip_on_plane, Visit&& visit) {
  const double on_plane_tolerance = 1e-8 * options.smoothing_length;
  const PointCloud& sources = cells.points();
  const auto& mirrors = options.mirrors;
  for (unsigned subset = 0; subset < (1u << mirrors.size()); ++subset) {
    std::uint8_t reflection = 0;
    if (!near_every_plane(target, mirrors, subset, radius, reflection)) continue;
    // |target - R(x_j)| = |R(target) - x_j|: search around the reflected target.
    const Vec3 query = reflect(target, mirrors, subset);
    cells.for_each_within(query, radius, [&](std::int32_t j, const Vec3&, double) {
      if (subset == 0 && j == exclude) return;
      const Vec3 x = sources.point(static_cast<std::size_t>(j));
      if (skip_on_plane && on_a_plane(x, mirrors, subset, on_plane_tolerance)) return;
      visit(j, subset, reflection, x);
    });
  }
}

}  // namespace

void gather_stencil(const Vec3& target, const CellList& cells, const OperatorOptions& options,
                    std::int32_t exclude, std::vector<StencilSource>& stencil) {
  stencil.clear();
  check_mirror_count(options);
  const double support = options.kernel.support_radius(options.smoothing_length);
  const PointCloud& sources = cells.points();
  for_each_stencil_source(
      target, cells, options, exclude, support, true,
      [&](std::int32_t j, unsigned subset, std::uint8_t reflection, const Vec3& x) {
        stencil.push_back(StencilSource{j, reflection, reflect(x, options.mirrors, subset),
                                        sources.volume[static_cast<std::size_t>(j)]});
      });
}

void gather_candidates(const Vec3& target, const CellList& cells, const OperatorOptions& options,
                       std::int32_t exclude, double radius,
                       std::vector<StencilCandidate>& candidates) {
  candidates.clear();
  check_mirror_count(options);
  // Images of sources on a plane are kept: the source may leave the plane before the next search,
  // and the picking tests where it is then.
  for_each_stencil_source(
      target, cells, options, exclude, radius, false,
      [&](std::int32_t j, unsigned subset, std::uint8_t reflection, const Vec3&) {
        candidates.push_back(StencilCandidate{j, static_cast<std::uint8_t>(subset), reflection});
      });
}

void gather_stencil(const Vec3& target, const PointCloud& sources,
                    std::span<const StencilCandidate> candidates, const OperatorOptions& options,
                    std::vector<StencilSource>& stencil) {
  // The tests of the search in the cell lists at the support, with the same arithmetic, on the
  // candidates in the order that search visited them.
  stencil.clear();
  const double support = options.kernel.support_radius(options.smoothing_length);
  const double support_squared = support * support;
  const double on_plane_tolerance = 1e-8 * options.smoothing_length;
  const auto& mirrors = options.mirrors;
  const int d = sources.dimension;
  unsigned subset = ~0u;
  bool near_all = false;
  Vec3 query{};
  for (const StencilCandidate& candidate : candidates) {
    if (candidate.subset != subset) {
      subset = candidate.subset;
      std::uint8_t reflection = 0;
      near_all = near_every_plane(target, mirrors, subset, support, reflection);
      query = reflect(target, mirrors, subset);
    }
    if (!near_all) continue;
    const Vec3 x = sources.point(static_cast<std::size_t>(candidate.column));
    double distance_squared = 0.0;
    for (int a = 0; a < d; ++a) {
      const double offset = query[a] - x[a];
      distance_squared += offset * offset;
    }
    if (!(distance_squared < support_squared)) continue;
    if (on_a_plane(x, mirrors, subset, on_plane_tolerance)) continue;
    stencil.push_back(StencilSource{candidate.column, candidate.reflection,
                                    reflect(x, mirrors, subset),
                                    sources.volume[static_cast<std::size_t>(candidate.column)]});
  }
}

namespace {

// compute_row for a dimension known at compile time: the loops over axes unrolled, the kernel's
// factors of h computed once per row. The arithmetic is the generic one's, term by term.
template <int D>
bool compute_row_in(const Vec3& target, std::span<const StencilSource> stencil,
                    const OperatorOptions& options, GradientReference reference,
                    std::int32_t self_column, const RowSlots& slots, double smoothing_length) {
  const Kernel& kernel = options.kernel;
  const Kernel::Scales scales = kernel.scales(smoothing_length);
  const std::size_t n = stencil.size();
  double* interpolation = slots.interpolation;
  const std::array<double*, 3>& gradient = slots.gradient;

  // Kernel values w_b = W V_b and gradients g_b = grad_a W(x_a - x_b) V_b (docs/theory.md eq. 4.2).
  double weight_sum = 0.0;
  Vec3 gradient_sum{};
  for (std::size_t k = 0; k < n; ++k) {
    const StencilSource& s = stencil[k];
    Vec3 offset{};
    double r2 = 0.0;
    for (int a = 0; a < D; ++a) {
      offset[a] = target[a] - s.position[a];
      r2 += offset[a] * offset[a];
    }
    const double distance = std::sqrt(r2);
    const double w = kernel.value(distance, scales) * s.volume;
    // grad W = (dW/dr / r) offset, and the zero vector at r = 0, where dW/dr -> 0 (Kernel).
    const double scale = distance == 0.0 ? 0.0 : kernel.derivative(distance, scales) / distance;
    slots.source[k] = s.column;
    slots.reflection[k] = s.reflection;
    interpolation[k] = w;
    for (int a = 0; a < D; ++a) {
      const double g = (distance == 0.0 ? 0.0 : scale * offset[a]) * s.volume;
      gradient[a][k] = g;
      gradient_sum[a] += g;
    }
    for (int a = D; a < 3; ++a)
      if (gradient[a]) gradient[a][k] = 0.0;
    weight_sum += w;
  }

  // Reference point: the Shepard centroid (cross-set) or the target itself (self-referenced).
  Vec3 reference_point = target;
  if (reference == GradientReference::ShepardCentroid && weight_sum > 0.0) {
    reference_point = {0.0, 0.0, 0.0};
    for (std::size_t k = 0; k < n; ++k)
      for (int a = 0; a < D; ++a)
        reference_point[a] += interpolation[k] / weight_sum * stencil[k].position[a];
  }

  // Correction matrix A = sum_b g_b (x_b - x_ref)^T and its scale sum_b |g_b||x_b - x_ref|.
  Matrix correction{};
  double scale = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    double g_norm = 0.0, x_norm = 0.0;
    for (int a = 0; a < D; ++a) {
      const double g = gradient[a][k];
      g_norm += g * g;
      const double x = stencil[k].position[a] - reference_point[a];
      x_norm += x * x;
      for (int b = 0; b < D; ++b)
        correction[a][b] += g * (stencil[k].position[b] - reference_point[b]);
    }
    scale += std::sqrt(g_norm * x_norm);
  }
  const double det = determinant(correction, D);
  const bool regular = n > 0 && weight_sum > 0.0 && scale > 0.0 &&
                       std::abs(det) >= options.degeneracy_tolerance * integer_power(scale / D, D);

  Matrix inverse_correction{};
  if (regular) {
    inverse_correction = inverse(correction, D, det);
  } else {
    for (int a = 0; a < D; ++a)
      inverse_correction[a][a] = 1.0;  // uncorrected SPH gradient
  }

  // Gradient weights K_b = A^-1 (g_b - G w^_b) (centroid) or A^-1 g_b (self).
  for (std::size_t k = 0; k < n; ++k) {
    const double shepard = weight_sum > 0.0 ? interpolation[k] / weight_sum : 0.0;
    Vec3 raw{};
    for (int a = 0; a < D; ++a)
      raw[a] = gradient[a][k] -
               (reference == GradientReference::ShepardCentroid ? gradient_sum[a] * shepard : 0.0);
    for (int a = 0; a < D; ++a) {
      double value = 0.0;
      for (int b = 0; b < D; ++b)
        value += inverse_correction[a][b] * raw[b];
      gradient[a][k] = value;
    }
    interpolation[k] = shepard;
  }

  if (reference == GradientReference::ShepardCentroid) {
    // First-order interpolation: f_a = f^ - (x_ref - x_a) . grad f (docs/theory.md eq. 4.4).
    if (options.interpolation_order == 1 && regular)
      for (std::size_t k = 0; k < n; ++k)
        for (int a = 0; a < D; ++a)
          interpolation[k] -= (reference_point[a] - target[a]) * gradient[a][k];
  } else {
    // Self column: its value is the reference, so its weight cancels the others' sum.
    Vec3 self_gradient{};
    for (std::size_t k = 0; k < n; ++k) {
      interpolation[k] = 0.0;
      for (int a = 0; a < D; ++a)
        self_gradient[a] -= gradient[a][k];
    }
    slots.source[n] = self_column;
    slots.reflection[n] = 0;
    interpolation[n] = 1.0;
    for (int a = 0; a < 3; ++a)
      if (gradient[a]) gradient[a][n] = self_gradient[a];
  }
  return regular;
}

}  // namespace

bool compute_row(int dimension, const Vec3& target, std::span<const StencilSource> stencil,
                 const OperatorOptions& options, GradientReference reference,
                 std::int32_t self_column, const RowSlots& slots, double smoothing_length) {
  const double h = smoothing_length > 0.0 ? smoothing_length : options.smoothing_length;
  switch (dimension) {
    case 1:
      return compute_row_in<1>(target, stencil, options, reference, self_column, slots, h);
    case 2:
      return compute_row_in<2>(target, stencil, options, reference, self_column, slots, h);
    default:
      return compute_row_in<3>(target, stencil, options, reference, self_column, slots, h);
  }
}

namespace {

// Scratch for one row whose weights are not kept (row_is_regular): on the stack for the stencils
// of the step and the filter (up to ~50 entries with mirror images), on the heap beyond.
class RowScratch {
 public:
  explicit RowScratch(std::size_t size) {
    if (size > kStack) {
      heap_source_.resize(size);
      heap_reflection_.resize(size);
      heap_values_.resize(4 * size);
    }
    const bool stack = size <= kStack;
    slots_.source = stack ? source_ : heap_source_.data();
    slots_.reflection = stack ? reflection_ : heap_reflection_.data();
    double* values = stack ? values_ : heap_values_.data();
    const std::size_t stride = stack ? kStack : size;
    slots_.interpolation = values;
    for (std::size_t a = 0; a < 3; ++a)
      slots_.gradient[a] = values + (a + 1) * stride;
  }
  const RowSlots& slots() const { return slots_; }

 private:
  static constexpr std::size_t kStack = 128;
  std::int32_t source_[kStack];
  std::uint8_t reflection_[kStack];
  double values_[4 * kStack];
  std::vector<std::int32_t> heap_source_;
  std::vector<std::uint8_t> heap_reflection_;
  std::vector<double> heap_values_;
  RowSlots slots_;
};

}  // namespace

bool row_is_regular(int dimension, const Vec3& target, std::span<const StencilSource> stencil,
                    const OperatorOptions& options, GradientReference reference,
                    std::int32_t self_column, double smoothing_length) {
  const RowScratch scratch(row_size(stencil.size(), reference));
  return compute_row(dimension, target, stencil, options, reference, self_column, scratch.slots(),
                     smoothing_length);
}

bool append_row(WeightTable& table, const Vec3& target, std::span<const StencilSource> stencil,
                const OperatorOptions& options, GradientReference reference,
                std::int32_t self_column) {
  const std::size_t first = table.source.size();
  const std::size_t size = first + row_size(stencil.size(), reference);
  table.source.resize(size);
  table.reflection.resize(size);
  table.interpolation.resize(size);
  RowSlots slots{table.source.data() + first,
                 table.reflection.data() + first,
                 table.interpolation.data() + first,
                 {}};
  for (std::size_t a = 0; a < static_cast<std::size_t>(table.dimension); ++a) {
    table.gradient[a].resize(size);  // none along the axes beyond the dimension
    slots.gradient[a] = table.gradient[a].data() + first;
  }
  const bool regular =
      compute_row(table.dimension, target, stencil, options, reference, self_column, slots);
  for (const StencilSource& s : stencil)
    if (s.reflection) table.has_reflections = true;
  table.row_start.push_back(static_cast<std::int64_t>(size));
  return regular;
}

void reset_table(WeightTable& table, int dimension) {
  table.dimension = dimension;
  table.row_start.clear();
  table.row_start.push_back(0);
  table.source.clear();
  table.reflection.clear();
  table.interpolation.clear();
  for (auto& g : table.gradient)
    g.clear();
  table.has_reflections = false;
  table.has_gradient = true;
  table.weight_start.clear();
  table.row_reflects.clear();
  table.row_base.clear();
  table.source_offset.clear();
}

namespace row_blocks {

int begin(std::size_t row_count, WeightTable& table, OperatorWorkspace& workspace) {
  table.row_start.resize(row_count + 1);
  table.row_start[0] = 0;
  workspace.regular.resize(row_count);
  int threads = 1;
#ifdef _OPENMP
  if (static_cast<std::int64_t>(row_count) > kParallelThreshold) threads = omp_get_max_threads();
#endif
  if (workspace.blocks.size() < static_cast<std::size_t>(threads))
    workspace.blocks.resize(static_cast<std::size_t>(threads));
  return threads;
}

RowBlock& own(std::size_t row_count, OperatorWorkspace& workspace, std::size_t& first,
              std::size_t& last) {
  std::size_t thread = 0, threads = 1;
#ifdef _OPENMP
  thread = static_cast<std::size_t>(omp_get_thread_num());
  threads = static_cast<std::size_t>(omp_get_num_threads());
#endif
  first = row_count * thread / threads;
  last = row_count * (thread + 1) / threads;
  RowBlock& block = workspace.blocks[thread];
  block.entries = 0;
  block.reflections = false;
  return block;
}

void compute(int dimension, const OperatorOptions& options, const RowTarget& target,
             std::size_t row, WeightTable& table, OperatorWorkspace& workspace, RowBlock& block) {
  const std::size_t first = block.entries;
  const std::size_t end = first + row_size(block.stencil.size(), target.reference);
  const auto axes = static_cast<std::size_t>(dimension);
  // Grows geometrically, then never again (and for a higher dimension than the block has seen).
  if (block.source.size() < end || block.gradient[axes - 1].size() < end) {
    block.source.resize(end);
    block.reflection.resize(end);
    block.interpolation.resize(end);
    for (std::size_t a = 0; a < axes; ++a)  // the axes beyond the dimension hold nothing
      block.gradient[a].resize(end);
  }
  RowSlots slots{block.source.data() + first,
                 block.reflection.data() + first,
                 block.interpolation.data() + first,
                 {}};
  for (std::size_t a = 0; a < axes; ++a)
    slots.gradient[a] = block.gradient[a].data() + first;
  workspace.regular[row] =
      compute_row(dimension, target.position, block.stencil, options, target.reference,
                  target.self_column, slots, target.smoothing_length)
          ? 1
          : 0;
  for (const StencilSource& s : block.stencil)
    block.reflections = block.reflections || s.reflection != 0;
  block.entries = end;
  table.row_start[row + 1] = static_cast<std::int64_t>(end);
}

void size_table(int dimension, TableWeights weights, WeightTable& table,
                OperatorWorkspace& workspace) {
  std::size_t threads = 1;
#ifdef _OPENMP
  threads = static_cast<std::size_t>(omp_get_num_threads());
#endif
  std::size_t entries = 0;
  bool reflections = false;
  for (std::size_t t = 0; t < threads; ++t) {
    RowBlock& block = workspace.blocks[t];
    block.offset = entries;
    entries += block.entries;
    reflections = reflections || block.reflections;
  }
  const bool keep_gradient = weights == TableWeights::InterpolationAndGradient;
  table.dimension = dimension;
  workspace.failure = nullptr;
  try {
    // resize, not clear + resize: a table of the same size is neither freed nor refilled.
    table.source.resize(entries);
    table.reflection.resize(entries);
    table.interpolation.resize(entries);
    for (int a = 0; a < 3; ++a)  // none along the axes beyond the dimension
      table.gradient[static_cast<std::size_t>(a)].resize(keep_gradient && a < dimension ? entries
                                                                                        : 0);
  } catch (...) {  // thrown inside a parallel region it would terminate the program
    workspace.failure = std::current_exception();
    table.source.clear();  // place() then copies nothing
  }
  table.has_gradient = keep_gradient;
  table.has_reflections = reflections;
  table.weight_start.clear();
  table.row_reflects.clear();
  table.row_base.clear();
  table.source_offset.clear();
}

void place(TableWeights weights, std::size_t first, std::size_t last, const RowBlock& block,
           WeightTable& table) {
  if (block.entries > 0 && table.source.size() < block.offset + block.entries) return;  // failed
  const auto offset = static_cast<std::int64_t>(block.offset);
  for (std::size_t row = first; row < last; ++row)
    table.row_start[row + 1] += offset;
  const std::size_t n = block.entries;
  std::copy_n(block.source.data(), n, table.source.data() + block.offset);
  std::copy_n(block.reflection.data(), n, table.reflection.data() + block.offset);
  std::copy_n(block.interpolation.data(), n, table.interpolation.data() + block.offset);
  if (weights == TableWeights::InterpolationAndGradient)
    for (std::size_t a = 0; a < static_cast<std::size_t>(table.dimension); ++a)
      std::copy_n(block.gradient[a].data(), n, table.gradient[a].data() + block.offset);
}

void rethrow(OperatorWorkspace& workspace) {
  if (workspace.failure) {
    const std::exception_ptr failure = workspace.failure;
    workspace.failure = nullptr;
    std::rethrow_exception(failure);
  }
}

}  // namespace row_blocks

namespace {

void report_degenerate(const OperatorWorkspace& workspace, std::size_t rows,
                       StencilReport* report) {
  if (!report) return;
  for (std::size_t r = 0; r < rows; ++r)
    if (!workspace.regular[r]) report->degenerate_rows.push_back(static_cast<std::int32_t>(r));
}

// The gather of a cross-set row: target `first` + r, its stencil from the cell list, referenced to
// the Shepard centroid.
auto cross_rows(const PointCloud& targets, const CellList& sources, const OperatorOptions& options,
                std::size_t first = 0) {
  return [&targets, &sources, &options, first](std::size_t r, std::vector<StencilSource>& stencil) {
    const Vec3 x = targets.point(first + r);
    gather_stencil(x, sources, options, -1, stencil);
    return RowTarget{x, GradientReference::ShepardCentroid, -1};
  };
}

}  // namespace

void build_cross_operator(const PointCloud& targets, const CellList& sources,
                          const OperatorOptions& options, WeightTable& table,
                          OperatorWorkspace& workspace, StencilReport* report,
                          TableWeights weights) {
  build_rows(targets.size(), targets.dimension, options, weights, table, workspace,
             cross_rows(targets, sources, options));
  report_degenerate(workspace, targets.size(), report);
}

WeightTable build_cross_operator(const PointCloud& targets, const CellList& sources,
                                 const OperatorOptions& options, StencilReport* report) {
  WeightTable table;
  OperatorWorkspace workspace;
  build_cross_operator(targets, sources, options, table, workspace, report);
  return table;
}

void build_collocated_gradient(const PointCloud& points, const CellList& cells,
                               const OperatorOptions& options, std::span<const std::int32_t> rows,
                               WeightTable& table, OperatorWorkspace& workspace,
                               StencilReport* report) {
  const std::size_t row_count = rows.empty() ? points.size() : rows.size();
  build_rows(row_count, points.dimension, options, TableWeights::InterpolationAndGradient, table,
             workspace, [&](std::size_t r, std::vector<StencilSource>& stencil) {
               const auto self = rows.empty() ? static_cast<std::int32_t>(r) : rows[r];
               const Vec3 x = points.point(static_cast<std::size_t>(self));
               gather_stencil(x, cells, options, self, stencil);
               return RowTarget{x, GradientReference::Self, self};
             });
  report_degenerate(workspace, row_count, report);
}

WeightTable build_collocated_gradient(const PointCloud& points, const CellList& cells,
                                      const OperatorOptions& options,
                                      std::span<const std::int32_t> rows, StencilReport* report) {
  WeightTable table;
  OperatorWorkspace workspace;
  build_collocated_gradient(points, cells, options, rows, table, workspace, report);
  return table;
}

namespace {

// Parity signs per field and reflection pattern (three axes: eight patterns), so that the inner
// loop multiplies instead of branching.
struct ParitySigns {
  double sign[kMaxFields * 8];
};

ParitySigns parity_signs(std::span<const Parity> parity) {
  ParitySigns signs{};
  for (std::size_t f = 0; f < parity.size(); ++f)
    for (unsigned bits = 0; bits < 8; ++bits)
      signs.sign[f * 8 + bits] =
          (std::popcount(static_cast<unsigned>(parity[f] & bits)) & 1u) ? -1.0 : 1.0;
  return signs;
}

struct Inputs {
  const double* field[kMaxFields];
};

// Interpolation only (the hourglass filter's round trip). FieldCount > 0 fixes the number of
// fields at compile time so that the field loop unrolls; 0 reads it at run time.
template <int FieldCount, bool Reflect>
void interpolate_rows(const WeightTable& table, const Inputs& input, int runtime_fields,
                      const ParitySigns& signs, FieldArray& out) {
  const int fields = FieldCount > 0 ? FieldCount : runtime_fields;
  const auto rows = static_cast<std::int64_t>(table.rows());
  const std::int64_t* row_start = table.row_start.data();
  // Shared weights (share_row_weights): row i's weights start at weight_start[i] in the pool.
  const std::int64_t* weight_start =
      table.weight_start.empty() ? row_start : table.weight_start.data();
  const bool relative = !table.row_base.empty();
  double* output[kMaxFields];
  for (int f = 0; f < fields; ++f)
    output[f] = out.field(f);
#pragma omp parallel for schedule(static) if (rows > kParallelThreshold)
  for (std::int64_t i = 0; i < rows; ++i) {
    double value[kMaxFields] = {};
    const std::int64_t offset = weight_start[i] - row_start[i];
    const double* weight = table.interpolation.data() + offset;
    const std::uint8_t* reflection = table.reflection.data() + offset;
    // Relative sources: the row's base plus the pool's offsets (WeightTable::row_base).
    const std::int32_t* source =
        relative ? table.source_offset.data() + offset : table.source.data();
    const std::int32_t base = relative ? table.row_base[static_cast<std::size_t>(i)] : 0;
    for (std::int64_t k = row_start[i]; k < row_start[i + 1]; ++k) {
      const std::int32_t j = base + source[k];
      const double w = weight[k];
      if constexpr (Reflect) {
        const double* sign = signs.sign + reflection[k];
        for (int f = 0; f < fields; ++f)
          value[f] += w * sign[f * 8] * input.field[f][j];
      } else {
        for (int f = 0; f < fields; ++f)
          value[f] += w * input.field[f][j];
      }
    }
    for (int f = 0; f < fields; ++f)
      output[f][i] = value[f];
  }
}

// Interpolation (optional) and gradient in D dimensions.
template <int FieldCount, int D, bool Reflect>
void differentiate_rows(const WeightTable& table, const Inputs& input, int runtime_fields,
                        const ParitySigns& signs, FieldArray* out_values,
                        FieldArray& out_gradient) {
  const int fields = FieldCount > 0 ? FieldCount : runtime_fields;
  const auto rows = static_cast<std::int64_t>(table.rows());
  const std::int64_t* row_start = table.row_start.data();
  // Shared weights (share_row_weights): row i's weights start at weight_start[i] in the pools.
  const std::int64_t* weight_start =
      table.weight_start.empty() ? row_start : table.weight_start.data();
  const std::int32_t* source = table.source.data();
#pragma omp parallel for schedule(static) if (rows > kParallelThreshold)
  for (std::int64_t i = 0; i < rows; ++i) {
    const std::int64_t offset = weight_start[i] - row_start[i];
    const std::uint8_t* reflection = table.reflection.data() + offset;
    const double* weight = table.interpolation.data() + offset;
    const double* gradient[D];
    for (int c = 0; c < D; ++c)
      gradient[c] = table.gradient[static_cast<std::size_t>(c)].data() + offset;
    double value[kMaxFields] = {};
    double derivative[kMaxFields * D] = {};
    for (std::int64_t k = row_start[i]; k < row_start[i + 1]; ++k) {
      const std::int32_t j = source[k];
      const double w = weight[k];
      double g[D];
      for (int c = 0; c < D; ++c)
        g[c] = gradient[c][k];
      const double* sign = signs.sign + (Reflect ? reflection[k] : 0);
      for (int f = 0; f < fields; ++f) {
        const double v = Reflect ? sign[f * 8] * input.field[f][j] : input.field[f][j];
        value[f] += w * v;
        for (int c = 0; c < D; ++c)
          derivative[f * D + c] += g[c] * v;
      }
    }
    if (out_values)
      for (int f = 0; f < fields; ++f)
        out_values->field(f)[i] = value[f];
    for (int f = 0; f < fields; ++f)
      for (int c = 0; c < D; ++c)
        out_gradient.field(f * D + c)[i] = derivative[f * D + c];
  }
}

// interpolate_rows on interleaved values (apply_interpolation_interleaved). Rows without a
// reflected entry (all interior rows) skip the parity signs when the table says which they are.
template <int FieldCount, bool Reflect>
void interpolate_interleaved_rows(const WeightTable& table, const double* in, int runtime_fields,
                                  const ParitySigns& signs, double* out) {
  const int fields = FieldCount > 0 ? FieldCount : runtime_fields;
  const auto rows = static_cast<std::int64_t>(table.rows());
  const std::int64_t* row_start = table.row_start.data();
  const std::int64_t* weight_start =
      table.weight_start.empty() ? row_start : table.weight_start.data();
  const std::uint8_t* row_reflects =
      table.row_reflects.empty() ? nullptr : table.row_reflects.data();
  const bool relative = !table.row_base.empty();
#pragma omp parallel for schedule(static) if (rows > kParallelThreshold)
  for (std::int64_t i = 0; i < rows; ++i) {
    double value[kMaxFields] = {};
    const std::int64_t offset = weight_start[i] - row_start[i];
    const double* weight = table.interpolation.data() + offset;
    const std::uint8_t* reflection = table.reflection.data() + offset;
    // Relative sources: the row's base plus the pool's offsets (WeightTable::row_base), so a
    // lattice's rows stream one index each instead of one per entry.
    const std::int32_t* source =
        relative ? table.source_offset.data() + offset : table.source.data();
    const double* base =
        in + (relative
                  ? static_cast<std::int64_t>(table.row_base[static_cast<std::size_t>(i)]) * fields
                  : 0);
    if (Reflect && (row_reflects == nullptr || row_reflects[i])) {
      for (std::int64_t k = row_start[i]; k < row_start[i + 1]; ++k) {
        const double* v = base + static_cast<std::int64_t>(source[k]) * fields;
        const double w = weight[k];
        const double* sign = signs.sign + reflection[k];
        for (int f = 0; f < fields; ++f)
          value[f] += w * sign[f * 8] * v[f];
      }
    } else {
      for (std::int64_t k = row_start[i]; k < row_start[i + 1]; ++k) {
        const double* v = base + static_cast<std::int64_t>(source[k]) * fields;
        const double w = weight[k];
        for (int f = 0; f < fields; ++f)
          value[f] += w * v[f];
      }
    }
    double* o = out + i * fields;
    for (int f = 0; f < fields; ++f)
      o[f] = value[f];
  }
}

// Calls call(std::integral_constant<int, N>) with N = fields for the common field counts (the
// field loops of the kernels then unroll) and N = 0 (read at run time) otherwise.
template <typename Call>
void with_field_count(int fields, Call call) {
  switch (fields) {
    case 1:
      return call(std::integral_constant<int, 1>{});
    case 2:
      return call(std::integral_constant<int, 2>{});
    case 5:
      return call(std::integral_constant<int, 5>{});
    case 6:
      return call(std::integral_constant<int, 6>{});
    case 7:
      return call(std::integral_constant<int, 7>{});
    default:
      return call(std::integral_constant<int, 0>{});
  }
}

template <bool Reflect>
void dispatch_interleaved(const WeightTable& table, const double* in, int fields,
                          const ParitySigns& signs, double* out) {
  with_field_count(fields, [&](auto count) {
    interpolate_interleaved_rows<decltype(count)::value, Reflect>(table, in, fields, signs, out);
  });
}

template <bool Reflect>
void dispatch_interpolation(const WeightTable& table, const Inputs& input, int fields,
                            const ParitySigns& signs, FieldArray& out) {
  with_field_count(fields, [&](auto count) {
    interpolate_rows<decltype(count)::value, Reflect>(table, input, fields, signs, out);
  });
}

template <int D, bool Reflect>
void dispatch_gradient(const WeightTable& table, const Inputs& input, int fields,
                       const ParitySigns& signs, FieldArray* values, FieldArray& gradient) {
  with_field_count(fields, [&](auto count) {
    differentiate_rows<decltype(count)::value, D, Reflect>(table, input, fields, signs, values,
                                                           gradient);
  });
}

template <bool Reflect>
void dispatch_dimension(const WeightTable& table, const Inputs& input, int fields,
                        const ParitySigns& signs, FieldArray* values, FieldArray& gradient) {
  switch (table.dimension) {
    case 1:
      return dispatch_gradient<1, Reflect>(table, input, fields, signs, values, gradient);
    case 2:
      return dispatch_gradient<2, Reflect>(table, input, fields, signs, values, gradient);
    default:
      return dispatch_gradient<3, Reflect>(table, input, fields, signs, values, gradient);
  }
}

}  // namespace

void drop_gradients(WeightTable& table) {
  for (auto& g : table.gradient)
    std::vector<double>().swap(g);
  table.has_gradient = false;
}

void apply_interpolation_interleaved(const WeightTable& table, std::span<const double> in,
                                     std::span<const Parity> parity, std::span<double> out) {
  const auto fields = static_cast<int>(parity.size());
  if (fields < 1 || fields > kMaxFields)
    throw std::invalid_argument("apply_interpolation_interleaved: bad field count");
  if (out.size() < table.rows() * static_cast<std::size_t>(fields))
    throw std::invalid_argument("apply_interpolation_interleaved: output smaller than the table");
  const ParitySigns signs = parity_signs(parity);
  if (table.has_reflections)
    dispatch_interleaved<true>(table, in.data(), fields, signs, out.data());
  else
    dispatch_interleaved<false>(table, in.data(), fields, signs, out.data());
}

void share_row_weights(WeightTable& table) {
  ShareWorkspace workspace;
  share_row_weights(table, workspace);
}

namespace {

// One step of a row key's hash: a quantised weight and its reflection bits mixed in with one
// multiplication (the key is confirmed entry by entry on a match, so the hash need only spread).
std::uint64_t hash_entry(std::uint64_t hash, std::int64_t quantised, std::uint8_t reflection) {
  hash ^= static_cast<std::uint64_t>(quantised) + (std::uint64_t{reflection} << 56);
  hash *= 0x9e3779b97f4a7c15ull;
  return hash ^ (hash >> 29);
}

// The quantum of a row's key: 1e-13 of its largest weight. Rows that round alike differ by less
// than that and share the first one's weights.
double key_quantum(const double* weight, std::int64_t count) {
  double largest = 0.0;
  for (std::int64_t k = 0; k < count; ++k)
    largest = std::max(largest, std::abs(weight[k]));
  return 1e-13 * (largest > 0.0 ? largest : 1.0);
}

// Whether the chunk row [begin, end) of the workspace has the key of pool block `pool_start` (the
// owner's weights, sorted as the row's are, so their quantised values are the owner's own key).
bool same_key(const ShareWorkspace& w, std::int64_t begin, std::int64_t end,
              const WeightTable& table, std::int64_t pool_start) {
  const std::int64_t length = end - begin;
  const std::uint8_t* reflection = table.reflection.data() + pool_start;
  for (std::int64_t k = 0; k < length; ++k)
    if (w.reflection[static_cast<std::size_t>(begin + k)] != reflection[k]) return false;
  if (w.relative_sources && length > 0) {
    const std::int32_t* offset = table.source_offset.data() + pool_start;
    const std::int32_t base = w.source[static_cast<std::size_t>(begin)];
    for (std::int64_t k = 0; k < length; ++k)
      if (w.source[static_cast<std::size_t>(begin + k)] - base != offset[k]) return false;
  }
  for (std::size_t q = 0; q < w.quantities; ++q) {
    const double* weight =
        (q == 0 ? table.interpolation : table.gradient[q - 1]).data() + pool_start;
    const double quantum = key_quantum(weight, length);
    const std::int64_t* quantised = w.quantised[q].data() + begin;
    for (std::int64_t k = 0; k < length; ++k)
      if (quantised[k] != std::llround(weight[k] / quantum)) return false;
  }
  return true;
}

}  // namespace

void begin_shared_table(std::size_t row_count, int dimension, bool gradient, bool relative_sources,
                        WeightTable& table, ShareWorkspace& workspace) {
  // The gradient readers (differentiate_rows, the adjoint builder's products) take a source per
  // entry: relative sources are for interpolation-only tables.
  if (gradient && relative_sources)
    throw std::invalid_argument(
        "begin_shared_table: relative sources need an interpolation-only "
        "table");
  table.dimension = dimension;
  table.row_start.assign(1, 0);
  table.row_start.reserve(row_count + 1);
  table.source.clear();
  table.reflection.clear();
  table.interpolation.clear();
  for (auto& g : table.gradient)
    g.clear();
  table.has_gradient = gradient;
  table.has_reflections = false;
  table.weight_start.clear();
  table.weight_start.reserve(row_count);
  table.row_reflects.clear();
  table.row_reflects.reserve(row_count);
  table.row_base.clear();
  table.source_offset.clear();
  if (relative_sources) table.row_base.reserve(row_count);
  workspace.relative_sources = relative_sources;
  std::size_t capacity = 16;
  while (capacity < 2 * row_count)
    capacity *= 2;
  workspace.slot.assign(capacity, ShareWorkspace::Slot{});
  workspace.rows = row_count;
  workspace.quantities = gradient ? 1 + static_cast<std::size_t>(dimension) : 1;
}

void append_shared_rows(const WeightTable& chunk, WeightTable& table, ShareWorkspace& workspace) {
  if (chunk.has_gradient != table.has_gradient || chunk.dimension != table.dimension)
    throw std::invalid_argument("append_shared_rows: the rows' weights are not the table's kind");
  const std::size_t row_count = chunk.rows();
  const std::size_t entries = chunk.entries();
  if (table.rows() + row_count > workspace.rows)
    throw std::invalid_argument("append_shared_rows: more rows than begin_shared_table was told");
  const auto rows = static_cast<std::int64_t>(row_count);
  ShareWorkspace& w = workspace;
  const std::size_t quantities = w.quantities;  // the interpolation, then each gradient axis
  w.order.resize(entries);
  w.source.resize(entries);
  w.reflection.resize(entries);
  for (std::size_t q = 0; q < quantities; ++q) {
    w.weight[q].resize(entries);
    w.quantised[q].resize(entries);
  }
  w.hash.resize(row_count);
  w.reflects.resize(row_count);
  w.base.resize(row_count);
  const bool relative = w.relative_sources;
  const double* chunk_weight[4] = {chunk.interpolation.data(), chunk.gradient[0].data(),
                                   chunk.gradient[1].data(), chunk.gradient[2].data()};

  // Each row on its own, in parallel: order its entries by source (the same std::sort on the same
  // index sequence as a serial pass, so ties fall alike), then its key: the reflection bits and
  // each kind of weight rounded to 1e-13 of the row's largest of that kind.
#pragma omp parallel for schedule(static) if (rows > kParallelThreshold)
  for (std::int64_t i = 0; i < rows; ++i) {
    const auto row = static_cast<std::size_t>(i);
    const std::int64_t begin = chunk.row_start[row], end = chunk.row_start[row + 1];
    const auto order = w.order.begin() + begin;
    std::iota(order, w.order.begin() + end, begin);
    std::sort(order, w.order.begin() + end, [&](std::int64_t a, std::int64_t b) {
      return std::tie(chunk.source[a], chunk.reflection[a]) <
             std::tie(chunk.source[b], chunk.reflection[b]);
    });
    bool reflects = false;
    for (std::int64_t k = begin; k < end; ++k) {
      const auto e = static_cast<std::size_t>(w.order[k]);
      w.source[k] = chunk.source[e];
      w.reflection[k] = chunk.reflection[e];
      for (std::size_t q = 0; q < quantities; ++q)
        w.weight[q][k] = chunk_weight[q][e];
      reflects = reflects || w.reflection[k] != 0;
    }
    std::uint64_t hash = static_cast<std::uint64_t>(end - begin);
    for (std::int64_t k = begin; k < end; ++k)
      hash = hash_entry(hash, 0, w.reflection[k]);
    w.base[row] = end > begin ? w.source[begin] : 0;
    if (relative)
      for (std::int64_t k = begin; k < end; ++k)
        hash = hash_entry(hash, w.source[k] - w.base[row], 0);
    for (std::size_t q = 0; q < quantities; ++q) {
      const double quantum = key_quantum(w.weight[q].data() + begin, end - begin);
      for (std::int64_t k = begin; k < end; ++k) {
        w.quantised[q][k] = static_cast<std::int64_t>(std::llround(w.weight[q][k] / quantum));
        hash = hash_entry(hash, w.quantised[q][k], 0);
      }
    }
    w.hash[row] = hash;
    w.reflects[row] = reflects ? 1 : 0;
  }

  // Serial, in row order, so that the first row of each key owns the pool's copy: an
  // open-addressing table of the owners, probed by hash and confirmed on the whole key.
  const std::size_t mask = w.slot.size() - 1;
  if (!relative) table.source.reserve(table.source.size() + entries);  // one growth per chunk
  for (std::size_t row = 0; row < row_count; ++row) {
    const std::int64_t begin = chunk.row_start[row], end = chunk.row_start[row + 1];
    const auto length = end - begin;
    std::size_t probe = static_cast<std::size_t>(w.hash[row]) & mask;
    std::int64_t pool_start = -1;
    for (; w.slot[probe].row >= 0; probe = (probe + 1) & mask) {
      const ShareWorkspace::Slot& other = w.slot[probe];
      const auto owner = static_cast<std::size_t>(other.row);
      if (other.hash != w.hash[row] ||
          table.row_start[owner + 1] - table.row_start[owner] != length)
        continue;
      if (same_key(w, begin, end, table, table.weight_start[owner])) {
        pool_start = table.weight_start[owner];
        break;
      }
    }
    if (pool_start < 0) {  // the first row of its key: its weights start a pool block
      w.slot[probe] = ShareWorkspace::Slot{static_cast<std::int64_t>(table.rows()), w.hash[row]};
      pool_start = static_cast<std::int64_t>(table.interpolation.size());
      for (std::size_t q = 0; q < quantities; ++q) {
        std::vector<double>& pool = q == 0 ? table.interpolation : table.gradient[q - 1];
        pool.insert(pool.end(), w.weight[q].begin() + begin, w.weight[q].begin() + end);
      }
      table.reflection.insert(table.reflection.end(), w.reflection.begin() + begin,
                              w.reflection.begin() + end);
      if (relative)
        for (std::int64_t k = begin; k < end; ++k)
          table.source_offset.push_back(w.source[k] - w.base[row]);
    }
    table.weight_start.push_back(pool_start);
    if (relative)
      table.row_base.push_back(w.base[row]);
    else
      table.source.insert(table.source.end(), w.source.begin() + begin, w.source.begin() + end);
    table.row_start.push_back(table.row_start.back() + length);
    table.row_reflects.push_back(w.reflects[row]);
    table.has_reflections = table.has_reflections || w.reflects[row] != 0;
  }
}

void share_row_weights(WeightTable& table, ShareWorkspace& workspace) {
  if (!table.weight_start.empty()) return;  // already shared
  WeightTable& shared = workspace.shared;
  begin_shared_table(table.rows(), table.dimension, table.has_gradient, false, shared, workspace);
  append_shared_rows(table, shared, workspace);
  table = std::move(shared);  // the arrays with a weight per entry are freed
  shared = WeightTable{};
}

void shrink_table(WeightTable& table) {
  table.row_start.shrink_to_fit();
  table.source.shrink_to_fit();
  table.reflection.shrink_to_fit();
  table.interpolation.shrink_to_fit();
  for (auto& g : table.gradient)
    g.shrink_to_fit();
  table.weight_start.shrink_to_fit();
  table.row_reflects.shrink_to_fit();
  table.row_base.shrink_to_fit();
  table.source_offset.shrink_to_fit();
}

void build_shared_cross_operator(const PointCloud& targets, const CellList& sources,
                                 const OperatorOptions& options, WeightTable& table,
                                 OperatorWorkspace& workspace, ShareWorkspace& share_workspace,
                                 std::size_t chunk_rows) {
  if (chunk_rows == 0)
    throw std::invalid_argument("build_shared_cross_operator: chunks need at least one row");
  const std::size_t row_count = targets.size();
  begin_shared_table(row_count, targets.dimension, false, true, table, share_workspace);
  WeightTable& chunk = share_workspace.chunk;
  for (std::size_t first = 0; first < row_count; first += chunk_rows) {
    const std::size_t count = std::min(chunk_rows, row_count - first);
    build_rows(count, targets.dimension, options, TableWeights::InterpolationOnly, chunk, workspace,
               cross_rows(targets, sources, options, first));
    append_shared_rows(chunk, table, share_workspace);
  }
}

void apply_operator(const WeightTable& table, const FieldArray& in, std::span<const Parity> parity,
                    FieldArray* out_values, FieldArray* out_gradient) {
  const int field_count = in.field_count();
  const int d = table.dimension;
  if (field_count > kMaxFields || static_cast<int>(parity.size()) != field_count)
    throw std::invalid_argument("apply_operator: field count and parity list disagree");
  if ((out_values &&
       (out_values->point_count() < table.rows() || out_values->field_count() < field_count)) ||
      (out_gradient && (out_gradient->point_count() < table.rows() ||
                        out_gradient->field_count() < field_count * d)))
    throw std::invalid_argument("apply_operator: output arrays smaller than the table");
  if (out_gradient && !table.has_gradient)
    throw std::invalid_argument("apply_operator: this table holds no gradient weights");
  Inputs input{};
  for (int f = 0; f < field_count; ++f)
    input.field[f] = in.field(f);
  const ParitySigns signs = parity_signs(parity);
  const bool reflect = table.has_reflections;
  if (out_gradient) {
    if (reflect)
      dispatch_dimension<true>(table, input, field_count, signs, out_values, *out_gradient);
    else
      dispatch_dimension<false>(table, input, field_count, signs, out_values, *out_gradient);
  } else if (out_values) {
    if (reflect)
      dispatch_interpolation<true>(table, input, field_count, signs, *out_values);
    else
      dispatch_interpolation<false>(table, input, field_count, signs, *out_values);
  }
}

}  // namespace rktsph
