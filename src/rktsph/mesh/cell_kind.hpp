// The kinds of cell a cell complex can hold (docs/theory.md §3.5). A cell's corners are SPH nodes
// and its stress point sits at its centroid; what a kind knows about its own shape (measure,
// centroid, corner Jacobians, faces, quality) is in cell_kinds/, one file per kind, and
// cell_geometry.hpp dispatches on the kind.
#pragma once

#include <cstdint>
#include <string_view>

namespace rktsph {

enum class CellKind : std::uint8_t {
  Segment,        ///< 1D: two corners, left to right
  Triangle,       ///< 2D: three corners, counter-clockwise
  Quadrilateral,  ///< 2D: four corners, counter-clockwise
};

/// Number of corners of a cell of `kind`.
constexpr int corner_count(CellKind kind) {
  switch (kind) {
    case CellKind::Segment:
      return 2;
    case CellKind::Triangle:
      return 3;
    case CellKind::Quadrilateral:
      return 4;
  }
  return 0;
}

/// Spatial dimension of a cell of `kind`.
constexpr int cell_dimension(CellKind kind) {
  return kind == CellKind::Segment ? 1 : 2;
}

/// Name of the kind for messages ("quadrilateral").
constexpr std::string_view kind_name(CellKind kind) {
  switch (kind) {
    case CellKind::Segment:
      return "segment";
    case CellKind::Triangle:
      return "triangle";
    case CellKind::Quadrilateral:
      return "quadrilateral";
  }
  return "cell";
}

/// The largest corner count of any kind (sizes fixed arrays of corner data).
inline constexpr int kMaxCellCorners = 4;

}  // namespace rktsph
