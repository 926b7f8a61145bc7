// The shapes of a case as regions of the plane (or intervals of the line), shared by the builders
// of the node sets (docs/theory.md §3.1 for the lattice, §3.6 for triangles): which shape covers
// a point, and the material that shape names.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rktsph/case/case_description.hpp"

namespace rktsph {

/// Tolerance, in units of the spacing, for "on the lattice" and "on the boundary" decisions.
inline constexpr double kSpacingTolerance = 1e-6;

/// True if (x, y) lies inside the polygon or on its boundary (within `tolerance`).
bool polygon_contains(const std::vector<Vec3>& vertices, double x, double y, double tolerance);

/// True if x lies in the shape or within `tolerance` of its boundary.
bool shape_contains(const ShapeSpec& shape, int dimension, const Vec3& x, double tolerance);

/// Index of the last shape containing x (later shapes override earlier ones), or -1.
int covering_shape(const GeometrySpec& geometry, int dimension, const Vec3& x, double tolerance);

/// Index into `material_names` of the material of geometry.shapes[shape] (InputError at the shape
/// if it names none of them).
std::int32_t shape_material(const GeometrySpec& geometry, int shape,
                            const std::vector<std::string>& material_names);

}  // namespace rktsph
