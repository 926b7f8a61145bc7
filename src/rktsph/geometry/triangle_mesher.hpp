// Geometry to nodes on triangles (docs/theory.md §3.6): a constrained Delaunay triangulation of
// the shapes, every shape edge a constraint split evenly with a row of near-equilateral triangles
// along it (the boundary layer), refined until every edge is at most the spacing and every angle
// at least about 20.7°, then smoothed. The nodes are the triangles' corners, the stress points
// their centroids. The lattice builder (node_sets.hpp, §3.1) fills the same NodeSets.
#pragma once

#include <string>
#include <vector>

#include "rktsph/case/case_description.hpp"
#include "rktsph/geometry/node_sets.hpp"

namespace rktsph {

/// CGAL's shape bound B of Delaunay_mesh_size_criteria_2: the squared sine of the smallest angle
/// a refined triangle may keep, B = 0.125 for arcsin(sqrt(0.125)) ≈ 20.7°, the largest bound for
/// which Delaunay refinement is proven to terminate (Ruppert's bound; §3.6).
inline constexpr double kTriangleShapeBound = 0.125;

/// Sweeps of centroidal smoothing after refinement (§3.6): each moves every free vertex to the
/// centroid of the polygon its triangles make; measured in §3.6.
inline constexpr int kSmoothingSweeps = 10;

/// The boundary layer along straight shape edges (§3.6): the edges are split into equal segments
/// of about kBoundaryLayerSpacing times the spacing, with kBoundaryLayerRows rows of points
/// parallel to each edge (near-equilateral triangles), a row point left out nearer than
/// kBoundaryLayerClearance of a segment to another point or edge.
inline constexpr double kBoundaryLayerSpacing = 0.7;
inline constexpr int kBoundaryLayerRows = 2;
inline constexpr double kBoundaryLayerClearance = 0.75;
inline constexpr double kBoundaryLayerShortest = 4.0;

/// Meshes the shapes of a 2D `geometry` with triangles whose edges are at most geometry.spacing.
/// Shapes may overlap or touch (the later shape's material wins, as on the lattice) and their
/// vertices may lie anywhere; the space between disjoint shapes stays empty. A node's material is
/// that of the last shape covering it, a triangle's that of the last shape covering its centroid.
/// The nodes are numbered by (y, x), the triangles counter-clockwise by their corners, so the
/// result does not depend on the order CGAL builds them in.
NodeSets build_triangle_node_sets(const GeometrySpec& geometry,
                                  const std::vector<std::string>& material_names);

}  // namespace rktsph
