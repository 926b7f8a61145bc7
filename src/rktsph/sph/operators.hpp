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
#include <span>
#include <string>
#include <vector>

#include "rktsph/core/field_array.hpp"
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

  std::size_t rows() const { return row_start.empty() ? 0 : row_start.size() - 1; }
  std::size_t entries() const { return source.size(); }
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

/// Gathers the sources of `cells` within the kernel support of `target`, with mirror images.
/// Sources lying on a mirror plane get no image there (the image would coincide with them).
/// `exclude` (if >= 0) is left out (the target itself, for same-set stencils).
void gather_stencil(const std::array<double, 3>& target, const CellList& cells,
                    const OperatorOptions& options, std::int32_t exclude,
                    std::vector<StencilSource>& stencil);

/// Appends the weights of one row computed from `stencil`; for GradientReference::Self the row
/// also gets an entry for `self_column` that makes the gradient of a constant vanish.
/// Returns false if the stencil is degenerate; the row then holds the uncorrected SPH gradient
/// (finite, never a division by zero) and the caller decides what to do.
bool append_row(WeightTable& table, const std::array<double, 3>& target,
                std::span<const StencilSource> stencil, const OperatorOptions& options,
                GradientReference reference, std::int32_t self_column);

/// Rows the builder found degenerate (target indices).
struct StencilReport {
  std::vector<std::int32_t> degenerate_rows;
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

/// The two builders above, into an existing table and stencil buffer (reset first): a rebuild on
/// a configuration of the same size allocates nothing.
void build_cross_operator(const PointCloud& targets, const CellList& sources,
                          const OperatorOptions& options, WeightTable& table,
                          std::vector<StencilSource>& stencil, StencilReport* report = nullptr);
void build_collocated_gradient(const PointCloud& points, const CellList& cells,
                               const OperatorOptions& options, std::span<const std::int32_t> rows,
                               WeightTable& table, std::vector<StencilSource>& stencil,
                               StencilReport* report = nullptr);

/// Frees the gradient weights of a table used only for interpolation (the hourglass filter).
void drop_gradients(WeightTable& table);

/// For an interpolation-only table: orders each row's entries by source and lets rows whose
/// weights and reflection bits agree (to 1e-13 of their largest weight) share one copy. On a
/// lattice every interior row has the same stencil, so applying the table then streams only the
/// source indices from memory (4 bytes per entry instead of 13). Results change by rounding only.
void share_row_weights(WeightTable& table);

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
