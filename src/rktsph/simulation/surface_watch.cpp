#include "rktsph/simulation/surface_watch.hpp"

#include <cmath>
#include <vector>

#include "rktsph/boundary/surface_set.hpp"

namespace rktsph {

void detect_current_surface(const Simulation& simulation, FreeSurface& out) {
  const PointCloud& nodes = simulation.state().configuration.sph_nodes;
  const double spacing = simulation.nodes().spacing;
  FreeSurfaceOptions options;
  options.kernel = KernelType::CubicSpline;
  options.smoothing_length = kDetectionSmoothingOverSpacing * spacing;
  options.lattice_spacing = spacing;
  const CellList cells(nodes, 2.0 * options.smoothing_length);
  detect_free_surface(nodes, cells, options, out);
}

void outline_free_surface(const Simulation& simulation, FreeSurface& out) {
  const std::size_t n = simulation.state().configuration.sph_nodes.size();
  out.on_surface.assign(n, 0);
  for (auto& component : out.normal)
    component.assign(n, 0.0);
  const SurfaceSet& surface = simulation.boundary_conditions().surface();
  for (std::size_t k = 0; k < surface.size(); ++k) {
    const auto i = static_cast<std::size_t>(surface.node[k]);
    Vec3 sum{0.0, 0.0, 0.0};
    for (std::int32_t f = surface.facets_begin(k); f < surface.facets_end(k); ++f) {
      if (!surface.projected[static_cast<std::size_t>(f)]) continue;
      const Vec3 facet = surface.facet_normal(f);
      for (std::size_t a = 0; a < 3; ++a)
        sum[a] += facet[a];
    }
    const double length = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    if (!(length > 0.0)) continue;
    out.on_surface[i] = 1;
    for (std::size_t a = 0; a < 3; ++a)
      out.normal[a][i] = sum[a] / length;
  }
}

void field_free_surface(const Simulation& simulation, FreeSurface& out) {
  if (simulation.assembly().forms_cells())
    outline_free_surface(simulation, out);
  else
    detect_current_surface(simulation, out);
}

std::vector<std::uint8_t> body_perimeter(const NodeSets& nodes) {
  // The faces of the outline with no mirror plane closing any of them: the detector sees no
  // images.
  SurfaceSet surface;
  outline_surface(nodes.cells, nodes.outline, nodes.sph_nodes, {}, surface);
  std::vector<std::uint8_t> perimeter(nodes.sph_nodes.size(), 0);
  for (std::int32_t node : surface.node)
    perimeter[static_cast<std::size_t>(node)] = 1;
  return perimeter;
}

SurfaceAgreement compare_with_perimeter(const Simulation& simulation, const FreeSurface& detected) {
  const std::vector<std::uint8_t> perimeter = body_perimeter(simulation.cells());
  SurfaceAgreement agreement;
  for (std::size_t i = 0; i < perimeter.size(); ++i) {
    agreement.perimeter_nodes += perimeter[i];
    if (perimeter[i] && !detected.on_surface[i]) ++agreement.missed;
    if (!perimeter[i] && detected.on_surface[i]) ++agreement.false_positive;
  }
  return agreement;
}

}  // namespace rktsph
