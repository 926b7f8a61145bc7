#include "rktsph/simulation/surface_watch.hpp"

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
