// Corrective SPH operators as precomputed sparse weight tables (docs/theory.md §4).
//
// A WeightTable maps values on a source point set to a target point set:
//   interpolation   f_a       = sum_k interpolation[k] * s_k * f[source[k]]
//   gradient        df_a/dx_c = sum_k gradient[c][k]   * s_k * f[source[k]]
// where s_k = +1 or -1 is the parity of the field under the mirror reflections the entry went
// through (reflection[k], one bit per axis whose mirror plane reflected the source; docs/theory.md
// §4.5). Entries are kept per (source, reflection), never merged, so that a field's parity
// can be applied at use time: one table serves even and odd fields alike.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <exception>
#include <span>
#include <string>
#include <vector>

#include "rktsph/core/field_array.hpp"
#include "rktsph/core/parallel.hpp"
#include "rktsph/core/point_cloud.hpp"
#include "rktsph/sph/kernel.hpp"
#include "rktsph/sph/neighbour_search.hpp"

namespace rktsph {

/// A symmetry (or smooth rigid) plane x[axis] = coordinate; sources near it are reflected into
/// images so that points near the plane get full, symmetric stencils.
struct MirrorPlane {
  int axis = 0;
  double coordinate = 0.0;
};

struct WeightTable {
  int dimension = 1;
  std::vector<std::int64_t> row_start;   ///< size rows + 1
  std::vector<std::int32_t> source;      ///< column: index into the source values
  std::vector<std::uint8_t> reflection;  ///< bit a: reflected across the mirror plane normal to a
  std::vector<double> interpolation;
  std::array<std::vector<double>, 3> gradient;
  bool has_reflections = false;
  bool has_gradient = true;  ///< false once drop_gradients() freed them (interpolation-only use)
  /// Empty, or (after share_row_weights) where each row's weights and reflection bits start in
  /// `interpolation` and `reflection`, which are then pools shared by rows with equal stencils.
  std::vector<std::int64_t> weight_start;
  /// Empty, or (after share_row_weights) 1 for the rows with a reflected entry.
  std::vector<std::uint8_t> row_reflects;

  /// Empty, or (relative sources, build_shared_cross_operator) each row's first source: entry k of
  /// row r then reads column row_base[r] + source_offset[k + weight_offset(r)], and `source` is
  /// empty. On a lattice the interior rows share one pattern of offsets as they share weights.
  std::vector<std::int32_t> row_base;
  /// Empty, or the pool of source offsets beside the weights' pool (relative sources).
  std::vector<std::int32_t> source_offset;

  std::size_t rows() const { return row_start.empty() ? 0 : row_start.size() - 1; }
  /// Where row `row`'s weights and reflection bits are: entry k of the row (row_start[row] <= k <
  /// row_start[row + 1]) has them at k + weight_offset(row).
  std::int64_t weight_offset(std::size_t row) const {
    return weight_start.empty() ? 0 : weight_start[row] - row_start[row];
  }
  std::size_t entries() const {
    return row_start.empty() ? 0 : static_cast<std::size_t>(row_start.back());
  }
  /// The column of entry k of row `row`, whichever way the table stores its sources.
  std::int32_t source_of(std::size_t row, std::size_t k) const {
    return row_base.empty()
               ? source[k]
               : row_base[row] + source_offset[static_cast<std::size_t>(
                                     static_cast<std::int64_t>(k) + weight_offset(row))];
  }
};

/// Parity of a field under mirror reflections: bit a set means the field changes sign when
/// reflected across a plane normal to axis a (v_a; sigma_ab with exactly one index equal to a).
using Parity = std::uint8_t;
constexpr Parity kEven = 0;
/// Parity of vector component i.
constexpr Parity vector_parity(int i) {
  return static_cast<Parity>(1u << i);
}
/// Parity of tensor component (i, j).
constexpr Parity tensor_parity(int i, int j) {
  return static_cast<Parity>((1u << i) ^ (1u << j));
}
/// Sign of a value of parity `parity` seen through the mirror reflections `reflection`.
constexpr double reflection_sign(std::uint8_t reflection, unsigned parity) {
  return (std::popcount(static_cast<unsigned>(reflection) & parity) & 1) ? -1.0 : 1.0;
}

/// How the gradient at a point is referenced (docs/theory.md §4.2).
enum class GradientReference {
  /// Cross-set: differences against the point's own first-order estimate; the correction matrix is
  /// taken about the Shepard centroid, which makes the gradient exact for linear fields even on
  /// truncated stencils (equivalent to the gradient rows of the (d+1) system).
  ShepardCentroid,
  /// Collocated or self-including: differences against the point's own value, which is a column of
  /// the table (`self_column`).
  Self,
};

struct OperatorOptions {
  Kernel kernel{KernelType::CubicSpline, 1};
  double smoothing_length = 0.0;
  int interpolation_order = 0;  ///< 0: Shepard; 1: first-order ((d+1) system)
  std::vector<MirrorPlane> mirrors;
  /// A row is degenerate if |det A| < tolerance * (trace A / d)^d or it has no neighbour.
  double degeneracy_tolerance = 1e-6;
};

/// One candidate source of a stencil: where its value lives (column), where it is (the image
/// position for reflected sources), its volume and its reflection bits.
struct StencilSource {
  std::int32_t column = 0;
  std::uint8_t reflection = 0;
  std::array<double, 3> position{};
  double volume = 0.0;
};

/// Throws std::invalid_argument for more than 8 mirror planes (a stencil's reflection subsets).
void check_mirror_count(const OperatorOptions& options);

/// Gathers the sources of `cells` within the kernel support of `target`, with mirror images.
/// Sources lying on a mirror plane get no image there (the image would coincide with them).
/// `exclude` (if >= 0) is left out (the target itself, for same-set stencils).
void gather_stencil(const std::array<double, 3>& target, const CellList& cells,
                    const OperatorOptions& options, std::int32_t exclude,
                    std::vector<StencilSource>& stencil);

/// A source found by gather_candidates: its column, the subset of mirror planes whose image of it
/// was found (bit m: plane m), and that image's reflection bits.
struct StencilCandidate {
  std::int32_t column = 0;
  std::uint8_t subset = 0;
  std::uint8_t reflection = 0;
};

/// A neighbour list with a skin (docs/theory.md §9.5): the sources, and images, that
/// gather_stencil would find within `radius` (>= the support) instead of the support, in its
/// order, the images of sources lying on their plane included (they may leave it).
void gather_candidates(const std::array<double, 3>& target, const CellList& cells,
                       const OperatorOptions& options, std::int32_t exclude, double radius,
                       std::vector<StencilCandidate>& candidates);
/// The stencil gather_stencil would gather at `target` from the sources at their positions in
/// `sources` now, picked from `candidates` found when they were elsewhere: the same tests with the
/// same arithmetic, in the candidates' order. It is the stencil of a search in the cell lists as
/// long as no source or target has moved more than half the skin since the candidates were found.
void gather_stencil(const std::array<double, 3>& target, const PointCloud& sources,
                    std::span<const StencilCandidate> candidates, const OperatorOptions& options,
                    std::vector<StencilSource>& stencil);

/// Appends the weights of one row computed from `stencil`; for GradientReference::Self the row
/// also gets an entry for `self_column` that makes the gradient of a constant vanish.
/// Returns false if the stencil is degenerate; the row then holds the uncorrected SPH gradient
/// (finite, never a division by zero) and the caller decides what to do.
bool append_row(WeightTable& table, const std::array<double, 3>& target,
                std::span<const StencilSource> stencil, const OperatorOptions& options,
                GradientReference reference, std::int32_t self_column);

/// Where compute_row writes one row: row_size(stencil, reference) slots of each array, e.g. a
/// row's part of a table (so that rows can be computed in parallel into their own parts).
/// `gradient` may point at scratch when the table keeps no gradient weights; gradient[a] for
/// a >= dimension gets zeros, or nothing if it is null.
struct RowSlots {
  std::int32_t* source = nullptr;
  std::uint8_t* reflection = nullptr;
  double* interpolation = nullptr;
  std::array<double*, 3> gradient{};
};

/// Entries of a row from `stencil`: one per source, plus the self column with
/// GradientReference::Self.
inline std::size_t row_size(std::size_t stencil_size, GradientReference reference) {
  return stencil_size + (reference == GradientReference::Self ? 1 : 0);
}

/// The weights of append_row, written into `slots` instead of appended: the same arithmetic in
/// the same order, so a table computed row by row in any order is the table append_row makes.
/// `smoothing_length` > 0 is the row's own h (docs/theory.md §4.8); 0 takes the options'.
bool compute_row(int dimension, const std::array<double, 3>& target,
                 std::span<const StencilSource> stencil, const OperatorOptions& options,
                 GradientReference reference, std::int32_t self_column, const RowSlots& slots,
                 double smoothing_length = 0.0);

/// Whether append_row would call the row regular, without keeping its weights (thread-safe).
bool row_is_regular(int dimension, const std::array<double, 3>& target,
                    std::span<const StencilSource> stencil, const OperatorOptions& options,
                    GradientReference reference, std::int32_t self_column,
                    double smoothing_length = 0.0);

/// Where a row is taken and how its gradient is referenced (the arguments of append_row besides
/// its stencil).
struct RowTarget {
  std::array<double, 3> position{};
  GradientReference reference = GradientReference::ShepardCentroid;
  std::int32_t self_column = -1;
  /// The row's own smoothing length [m] (stencils from the cells, docs/theory.md §4.8); 0: the
  /// options' one.
  double smoothing_length = 0.0;
};

/// Rows the builder found degenerate (target indices).
struct StencilReport {
  std::vector<std::int32_t> degenerate_rows;
};

/// One thread's rows of a build (build_rows): each row's stencil is gathered into `stencil` and
/// its weights computed at once into the block's arrays, which are then copied into the table at
/// the block's offset. The stencil stays in the cache between the gather and the weights, and no
/// row keeps a buffer of its own. The arrays only grow, so a rebuild allocates nothing once they
/// have reached their size. Aligned to a cache line, so that one thread's counters, written every
/// row, never share a line with the next thread's block.
struct alignas(64) RowBlock {
  std::vector<StencilSource> stencil;
  std::vector<std::int32_t> source;
  std::vector<std::uint8_t> reflection;
  std::vector<double> interpolation;
  std::array<std::vector<double>, 3> gradient;
  std::size_t entries = 0;  ///< entries of the block's rows so far
  std::size_t offset = 0;   ///< where they start in the table
  bool reflections = false;
};

/// Buffers of the parallel table builders below, kept between builds: one RowBlock per thread,
/// each thread taking a contiguous range of rows. Row order and the arithmetic inside a row are
/// those of the serial build, so tables do not depend on the thread count.
struct OperatorWorkspace {
  std::vector<RowBlock> blocks;       ///< per thread
  std::vector<std::uint8_t> regular;  ///< per row
  std::exception_ptr failure;         ///< of the last build's sizing (build_rows rethrows it)
};

/// Buffers of the tables whose rows share their weights (share_row_weights,
/// build_shared_cross_operator; docs/theory.md §3.3), kept between builds. The per-entry arrays
/// hold one chunk of rows at a time.
struct ShareWorkspace {
  struct Slot {
    std::int64_t row = -1;   ///< the owner row of a key in the table being built; -1: empty
    std::uint64_t hash = 0;  ///< its key's hash
  };
  std::vector<std::int64_t> order;       ///< per entry: the row's sort permutation
  std::vector<std::int32_t> source;      ///< per entry, sorted by row
  std::vector<std::uint8_t> reflection;  ///< per entry, sorted by row
  /// Per kind of weight (the interpolation, then the gradient along each axis) and entry, sorted
  /// by row: the weight, and the weight rounded to the row's quantum for that kind.
  std::array<std::vector<double>, 4> weight;
  std::array<std::vector<std::int64_t>, 4> quantised;
  std::size_t quantities = 1;       ///< kinds of weight of the table being built
  bool relative_sources = false;    ///< the table being built keeps row_base and source_offset
  std::vector<std::int32_t> base;   ///< per row of the chunk: its first source (relative sources)
  std::vector<std::uint64_t> hash;  ///< per row of the chunk: hash of its key
  std::vector<std::uint8_t> reflects;  ///< per row of the chunk: 1 if it has a reflected entry
  std::vector<Slot> slot;              ///< open-addressing table of the owners by key
  std::size_t rows = 0;                ///< rows of the table being built
  WeightTable chunk;                   ///< build_shared_cross_operator's rows of one chunk
  WeightTable shared;                  ///< share_row_weights' result before it is moved in
};

/// Cross-set operator targets <- sources: interpolation (Shepard or first order) and the
/// centroid-referenced corrected gradient.
WeightTable build_cross_operator(const PointCloud& targets, const CellList& sources,
                                 const OperatorOptions& options, StencilReport* report = nullptr);

/// Collocated gradient within one set (the target itself is the reference, column = its index).
/// Row r is point rows[r] (all points, in order, if `rows` is empty); degenerate rows are reported
/// by row number. Interpolation weights of these tables reproduce the point's own value.
WeightTable build_collocated_gradient(const PointCloud& points, const CellList& cells,
                                      const OperatorOptions& options,
                                      std::span<const std::int32_t> rows = {},
                                      StencilReport* report = nullptr);

/// Empties a table for a rebuild, keeping the capacity of its arrays (docs/theory.md §2.6).
void reset_table(WeightTable& table, int dimension);

/// What a built table keeps: an interpolation-only table (the hourglass filter's) computes the
/// gradient weights that first-order interpolation needs in scratch and stores none; it is the
/// table drop_gradients() leaves.
enum class TableWeights { InterpolationAndGradient, InterpolationOnly };

/// The two builders above, into an existing table (overwritten) with reusable buffers, parallel
/// over rows (OpenMP): a rebuild on a configuration of the same size allocates nothing.
void build_cross_operator(const PointCloud& targets, const CellList& sources,
                          const OperatorOptions& options, WeightTable& table,
                          OperatorWorkspace& workspace, StencilReport* report = nullptr,
                          TableWeights weights = TableWeights::InterpolationAndGradient);
void build_collocated_gradient(const PointCloud& points, const CellList& cells,
                               const OperatorOptions& options, std::span<const std::int32_t> rows,
                               WeightTable& table, OperatorWorkspace& workspace,
                               StencilReport* report = nullptr);

/// The parts of build_rows around its gather (operators.cpp).
namespace row_blocks {
/// Sizes row_start, regular and the blocks for `row_count` rows; the threads to use.
int begin(std::size_t row_count, WeightTable& table, OperatorWorkspace& workspace);
/// This thread's block and its rows [first, last) among `row_count`.
RowBlock& own(std::size_t row_count, OperatorWorkspace& workspace, std::size_t& first,
              std::size_t& last);
/// Computes row `row` (its stencil in block.stencil) into the block; row_start[row + 1] gets the
/// block's entries so far.
void compute(int dimension, const OperatorOptions& options, const RowTarget& target,
             std::size_t row, WeightTable& table, OperatorWorkspace& workspace, RowBlock& block);
/// After every block is computed (one thread): the blocks' offsets and the table's size. A
/// failure to size the table (out of memory) is kept in the workspace, not thrown inside the
/// parallel region, and the blocks are then not placed.
void size_table(int dimension, TableWeights weights, WeightTable& table,
                OperatorWorkspace& workspace);
/// Each thread: its rows' starts shifted by the block's offset, its entries copied in.
/// Nothing if sizing failed.
void place(TableWeights weights, std::size_t first, std::size_t last, const RowBlock& block,
           WeightTable& table);
/// After the parallel region: throws the failure size_table kept, if any.
void rethrow(OperatorWorkspace& workspace);
}  // namespace row_blocks

/// The row machinery of the two builders, for tables whose rows need stencils of their own (the
/// step's points_to_nodes): for each row r, in parallel, gather(r, stencil) fills the reused
/// buffer `stencil` and returns the row's RowTarget, and compute_row computes the row's weights
/// at once; the table is overwritten. Rows compute_row calls degenerate get
/// workspace.regular[r] = 0. `gather` runs inside a parallel region: it must not throw.
template <class Gather>
void build_rows(std::size_t row_count, int dimension, const OperatorOptions& options,
                TableWeights weights, WeightTable& table, OperatorWorkspace& workspace,
                Gather&& gather) {
  check_mirror_count(options);  // gather_stencil's one throw, before the parallel region
  const int threads = row_blocks::begin(row_count, table, workspace);
#pragma omp parallel num_threads(threads) if (threads > 1)
  {
    std::size_t first = 0, last = 0;
    RowBlock& block = row_blocks::own(row_count, workspace, first, last);
    for (std::size_t row = first; row < last; ++row) {
      const RowTarget target = gather(row, block.stencil);
      row_blocks::compute(dimension, options, target, row, table, workspace, block);
    }
#pragma omp barrier
#pragma omp single
    row_blocks::size_table(dimension, weights, table, workspace);
    row_blocks::place(weights, first, last, block, table);
  }
  row_blocks::rethrow(workspace);
}

/// Frees the gradient weights of a table used only for interpolation (the hourglass filter).
void drop_gradients(WeightTable& table);

/// Orders each row's entries by source and lets rows whose weights and reflection bits agree (each
/// kind of weight to 1e-13 of the row's largest of that kind) share one copy. On a lattice every
/// interior row has the same stencil, so applying the table then streams only the source indices
/// from memory (4 bytes per entry instead of 13, or 29 with a 2D gradient). Results change by
/// rounding only.
void share_row_weights(WeightTable& table);
/// The same with reusable buffers, parallel over rows. The table's arrays are replaced by the
/// shared ones (a table shared once is built once: its old arrays are freed).
void share_row_weights(WeightTable& table, ShareWorkspace& workspace);
/// Frees the capacity of a table's arrays beyond their sizes (a table built once, shared).
void shrink_table(WeightTable& table);
/// The pieces of both: begin_shared_table empties `table` for `row_count` rows whose weights will
/// be shared; append_shared_rows appends the rows of an interpolation-only `chunk` to it, each
/// row ordered by source and pointing at the pool block of the first row with its key.
void begin_shared_table(std::size_t row_count, int dimension, bool gradient, bool relative_sources,
                        WeightTable& table, ShareWorkspace& workspace);
void append_shared_rows(const WeightTable& chunk, WeightTable& table, ShareWorkspace& workspace);
/// build_cross_operator (interpolation only) followed by share_row_weights, built `chunk_rows`
/// rows at a time: the table with a weight per entry never exists whole. The rows keep relative
/// sources (row_base, source_offset): rows whose weights, reflection bits and offsets from their
/// first source agree share one block of the pools, so that a lattice's table is a few blocks and
/// one base per row (docs/theory.md §4.7). Applied, it gives share_row_weights' sums term by term.
void build_shared_cross_operator(const PointCloud& targets, const CellList& sources,
                                 const OperatorOptions& options, WeightTable& table,
                                 OperatorWorkspace& workspace, ShareWorkspace& share_workspace,
                                 std::size_t chunk_rows = 8192);

/// Applies `table` to `field_count` fields: out_values (may be null) gets the interpolation,
/// out_gradient (may be null) gets dimension * field_count fields, gradient of field f along
/// axis c at index f * dimension + c. `parity[f]` is the mirror parity of field f.
/// Parallel over target rows (OpenMP).
void apply_operator(const WeightTable& table, const FieldArray& in, std::span<const Parity> parity,
                    FieldArray* out_values, FieldArray* out_gradient);

/// Interpolation only, on interleaved values: field f of point j at in[j * fields + f] (and the
/// same for out, by row). One cache line then carries all the fields of a source, which is what
/// a gather over a large lattice needs (the hourglass filter); the sums are those of
/// apply_operator, term by term.
void apply_interpolation_interleaved(const WeightTable& table, std::span<const double> in,
                                     std::span<const Parity> parity, std::span<double> out);

}  // namespace rktsph
