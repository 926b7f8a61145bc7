// The surface of the body at one instant (docs/theory.md §5.1): its nodes, each with one or more
// facets (an outward unit normal, and how the stress on it is constrained). It is made from the
// outline of the body's cells (outline_surface): a node's facet gathers the outline facets at the
// node that share a normal (the node's share of a face). It is a structure of arrays that keeps
// its capacity, so that it can be rebuilt without allocating.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "rktsph/core/point_cloud.hpp"
#include "rktsph/core/small_tensor.hpp"
#include "rktsph/mesh/cell_complex.hpp"
#include "rktsph/mesh/outline.hpp"
#include "rktsph/physics/surface_normals.hpp"

namespace rktsph {

struct SurfaceSet {
  // Per surface node k, in increasing node id (one node may carry several facets: edges, corners).
  std::vector<std::int32_t> node;
  std::vector<std::int32_t> first_facet;  ///< facets of node k: [first_facet[k], first_facet[k+1])

  // Per facet f.
  std::array<std::vector<double>, 3> normal;  ///< outward unit normal, components x, y, z
  /// Bit c: component c of sigma·n is a reaction to an imposed velocity, not a traction (the
  /// facet lies on the face a velocity condition acts on).
  std::vector<std::uint8_t> reactions;
  /// 1: the facet's normal velocity is free, so the stress increment is projected traction-free
  /// along it (eq. 5.1); 0: the normal velocity is imposed.
  std::vector<std::uint8_t> projected;
  /// The outline facets a facet gathers: piece[first_piece[f], first_piece[f+1]) (none for a
  /// facet added without them).
  std::vector<std::int32_t> first_piece{0};
  std::vector<std::int32_t> piece;

  std::size_t size() const { return node.size(); }
  std::size_t facet_count() const { return reactions.size(); }
  std::int32_t facets_begin(std::size_t k) const { return first_facet[k]; }
  std::int32_t facets_end(std::size_t k) const { return first_facet[k + 1]; }
  Vec3 facet_normal(std::int32_t f) const {
    const auto i = static_cast<std::size_t>(f);
    return {normal[0][i], normal[1][i], normal[2][i]};
  }

  /// Empties the set and keeps its buffers.
  void clear();
  /// Starts surface node `id`; the facets added next belong to it.
  void add_node(std::int32_t id);
  /// Adds a facet of outward unit normal `unit_normal` to the last node, traction-free, made of
  /// the outline facets `pieces`.
  void add_facet(const Vec3& unit_normal, std::span<const std::int32_t> pieces = {});
  std::span<const std::int32_t> pieces(std::int32_t f) const {
    const auto i = static_cast<std::size_t>(f);
    const auto start = static_cast<std::size_t>(first_piece[i]);
    return {piece.data() + start, static_cast<std::size_t>(first_piece[i + 1]) - start};
  }
  /// Drops the last node if it received no facet.
  void drop_node_without_facets();

  /// The normals along which node k's stress increment is projected, in facet order; a facet
  /// parallel to one already listed (a one-node-wide strip: -n and +n) is the same constraint and
  /// is listed once.
  SurfaceNormals projected_normals(std::size_t k) const;
};

/// The surface of a body from the outline of its cells (docs/theory.md §3.5, §5.1). A node gets
/// one facet per distinct outward normal of the outline facets it lies on (normals at
/// `nodes`), in the order -x, +x, -y, +y of their dominant axis; a facet whose normal lies along
/// a mirror plane through the node (bit a of mirror_axes[node]) is closed by the plane. A node
/// inside the body or at a re-entrant corner (its cells, mirror images included, fill more than a
/// half-plane) carries no facet: its stress is the interior's. Every facet starts traction-free
/// and projected; the boundary conditions then mark the facets their velocity conditions act on
/// (BoundaryConditions::classify).
void outline_surface(const CellComplex& cells, const Outline& outline, const PointCloud& nodes,
                     std::span<const std::uint8_t> mirror_axes, SurfaceSet& surface);

}  // namespace rktsph
