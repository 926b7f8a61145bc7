#include "rktsph/mesh/cell_geometry.hpp"

#include <algorithm>
#include <limits>

#include "rktsph/mesh/cell_kinds/quadrilateral.hpp"
#include "rktsph/mesh/cell_kinds/segment.hpp"
#include "rktsph/mesh/cell_kinds/triangle.hpp"

namespace rktsph {

namespace {

// Calls the function of the kind's namespace; one switch for every question a cell answers.
template <typename Segment, typename Triangle, typename Quadrilateral>
auto dispatch(CellKind kind, Segment&& on_segment, Triangle&& on_triangle,
              Quadrilateral&& on_quadrilateral) {
  switch (kind) {
    case CellKind::Segment:
      return on_segment();
    case CellKind::Triangle:
      return on_triangle();
    case CellKind::Quadrilateral:
      break;
  }
  return on_quadrilateral();
}

}  // namespace

double cell_measure(CellKind kind, const CellCorners& c) {
  return dispatch(
      kind, [&] { return segment::measure(c); }, [&] { return triangle::measure(c); },
      [&] { return quadrilateral::measure(c); });
}

std::array<double, 3> cell_centroid(CellKind kind, const CellCorners& c) {
  return dispatch(
      kind, [&] { return segment::centroid(c); }, [&] { return triangle::centroid(c); },
      [&] { return quadrilateral::centroid(c); });
}

void cell_corner_jacobians(CellKind kind, const CellCorners& c,
                           std::array<double, kMaxCellCorners>& jacobian) {
  dispatch(
      kind, [&] { segment::corner_jacobians(c, jacobian); },
      [&] { triangle::corner_jacobians(c, jacobian); },
      [&] { quadrilateral::corner_jacobians(c, jacobian); });
}

std::span<const CellFace> cell_faces(CellKind kind) {
  return dispatch(
      kind, [] { return std::span<const CellFace>(segment::kFaces); },
      [] { return std::span<const CellFace>(triangle::kFaces); },
      [] { return std::span<const CellFace>(quadrilateral::kFaces); });
}

double cell_width(CellKind kind, const CellCorners& c) {
  return dispatch(
      kind, [&] { return segment::width(c); }, [&] { return triangle::width(c); },
      [&] { return quadrilateral::width(c); });
}

double smallest_cell_width(const CellComplex& cells, const PointCloud& nodes) {
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < cells.cell_count(); ++p)
    smallest = std::min(smallest, cell_width(cells.kind(p), cells.corner_positions(nodes, p)));
  return smallest;
}

double cell_quality(CellKind kind, const CellCorners& c) {
  return dispatch(
      kind, [&] { return segment::quality(c); }, [&] { return triangle::quality(c); },
      [&] { return quadrilateral::quality(c); });
}

}  // namespace rktsph
