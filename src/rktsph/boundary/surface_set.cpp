#include "rktsph/boundary/surface_set.hpp"

#include <cmath>

namespace rktsph {

namespace {
/// n and m describe the same plane: the projection along n equals the one along -n.
bool parallel(const Vector3& n, const Vector3& m) {
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
}

void SurfaceSet::add_node(std::int32_t id) {
  if (first_facet.empty()) first_facet.push_back(0);
  node.push_back(id);
  first_facet.push_back(first_facet.back());
}

void SurfaceSet::add_facet(const Vector3& unit_normal) {
  for (std::size_t c = 0; c < 3; ++c)
    normal[c].push_back(unit_normal[c]);
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
    const Vector3 n = facet_normal(f);
    bool listed = false;
    for (int r = 0; r < normals.count; ++r)
      listed = listed || parallel(normals.normal[static_cast<std::size_t>(r)], n);
    if (!listed) normals.add(n);
  }
  return normals;
}

void lattice_surface(const NodeSets& nodes, std::span<const std::uint8_t> mirror_axes,
                     SurfaceSet& surface) {
  surface.clear();
  const int d = nodes.dimension;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    surface.add_node(static_cast<std::int32_t>(i));
    for (int a = 0; a < d; ++a) {
      if ((mirror_axes[i] >> a) & 1u) continue;  // a mirror plane closes both directions
      for (int sign : {-1, 1}) {
        LatticeIndex neighbour = nodes.node_index[i];
        neighbour[static_cast<std::size_t>(a)] += sign;
        if (nodes.node_at(neighbour) >= 0) continue;
        Vector3 n{};
        n[static_cast<std::size_t>(a)] = static_cast<double>(sign);
        surface.add_facet(n);
      }
    }
    surface.drop_node_without_facets();
  }
}

}  // namespace rktsph
