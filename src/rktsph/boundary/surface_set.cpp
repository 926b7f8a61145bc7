#include "rktsph/boundary/surface_set.hpp"

#include <algorithm>
#include <cmath>

#include "rktsph/mesh/node_classification.hpp"

namespace rktsph {

namespace {
/// n and m describe the same plane: the projection along n equals the one along -n.
bool parallel(const Vec3& n, const Vec3& m) {
  const double dot = n[0] * m[0] + n[1] * m[1] + n[2] * m[2];
  return std::abs(dot) > 1.0 - 1e-9;
}
}  // namespace

void SurfaceSet::clear() {
  node.clear();
  first_facet.assign(1, 0);
  for (auto& component : normal)
    component.clear();
  reactions.clear();
  projected.clear();
  first_piece.assign(1, 0);
  piece.clear();
}

void SurfaceSet::add_node(std::int32_t id) {
  if (first_facet.empty()) first_facet.push_back(0);
  node.push_back(id);
  first_facet.push_back(first_facet.back());
}

void SurfaceSet::add_facet(const Vec3& unit_normal, std::span<const std::int32_t> pieces) {
  for (std::size_t c = 0; c < 3; ++c)
    normal[c].push_back(unit_normal[c]);
  if (first_piece.empty()) first_piece.push_back(0);
  piece.insert(piece.end(), pieces.begin(), pieces.end());
  first_piece.push_back(static_cast<std::int32_t>(piece.size()));
  reactions.push_back(0);
  projected.push_back(1);
  ++first_facet.back();
}

void SurfaceSet::drop_node_without_facets() {
  if (node.empty() || facets_begin(size() - 1) != facets_end(size() - 1)) return;
  node.pop_back();
  first_facet.pop_back();
}

SurfaceNormals SurfaceSet::projected_normals(std::size_t k) const {
  SurfaceNormals normals;
  for (std::int32_t f = facets_begin(k); f < facets_end(k); ++f) {
    if (!projected[static_cast<std::size_t>(f)]) continue;
    const Vec3 n = facet_normal(f);
    bool listed = false;
    for (int r = 0; r < normals.count; ++r)
      listed = listed || parallel(normals.normal[static_cast<std::size_t>(r)], n);
    if (!listed) normals.add(n);
  }
  return normals;
}

void outline_surface(const CellComplex& cells, const Outline& outline, const PointCloud& nodes,
                     std::span<const std::uint8_t> mirror_axes, SurfaceSet& surface) {
  surface.clear();
  struct Face {
    Vec3 normal;
    int order;  // 2 a + (n_a > 0) for the dominant axis a: -x, +x, -y, +y
    double angle;
    std::vector<std::int32_t> pieces;
  };
  std::vector<Face> faces;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const unsigned mirrors = mirror_axes.empty() ? 0u : unsigned{mirror_axes[i]};
    if (place_of_node(cells, nodes, i, mirrors) != NodePlace::Boundary) continue;
    faces.clear();
    for (const std::int32_t f : outline.facets_at(i)) {
      const Vec3 n = outline.normal(static_cast<std::size_t>(f));
      const int axis = std::abs(n[1]) > std::abs(n[0]) ? 1 : 0;
      if (((mirrors >> axis) & 1u) && std::abs(n[static_cast<std::size_t>(axis)]) > 1.0 - 1e-9)
        continue;  // a mirror plane closes this side
      auto same = std::find_if(faces.begin(), faces.end(),
                               [&](const Face& face) { return same_direction(face.normal, n); });
      if (same == faces.end()) {
        faces.push_back({n,
                         2 * axis + (n[static_cast<std::size_t>(axis)] > 0.0 ? 1 : 0),
                         std::atan2(n[1], n[0]),
                         {}});
        same = faces.end() - 1;
      }
      same->pieces.push_back(f);
    }
    std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) {
      return a.order != b.order ? a.order < b.order : a.angle < b.angle;
    });
    surface.add_node(static_cast<std::int32_t>(i));
    for (const Face& face : faces)
      surface.add_facet(face.normal, face.pieces);
    surface.drop_node_without_facets();
  }
}

}  // namespace rktsph
