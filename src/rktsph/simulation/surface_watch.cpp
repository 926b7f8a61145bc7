#include "rktsph/simulation/surface_watch.hpp"

#include <vector>

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

SurfaceAgreement compare_with_perimeter(const Simulation& simulation, const FreeSurface& detected) {
  const SurfaceSet& surface = simulation.boundary_conditions().surface();
  std::vector<std::uint8_t> perimeter(detected.on_surface.size(), 0);
  for (std::int32_t node : surface.node)
    perimeter[static_cast<std::size_t>(node)] = 1;
  SurfaceAgreement agreement;
  for (std::size_t i = 0; i < perimeter.size(); ++i) {
    agreement.perimeter_nodes += perimeter[i];
    if (perimeter[i] && !detected.on_surface[i]) ++agreement.missed;
    if (!perimeter[i] && detected.on_surface[i]) ++agreement.false_positive;
  }
  return agreement;
}

}  // namespace rktsph
