#include "rktsph/physics/configuration.hpp"

namespace rktsph {

Configuration reference_configuration(const NodeSets& reference, double smoothing_length) {
  Configuration configuration;
  configuration.sph_nodes = reference.sph_nodes;
  configuration.stress_points = reference.stress_points;
  configuration.node_smoothing_length.assign(reference.sph_nodes.size(), smoothing_length);
  configuration.point_smoothing_length.assign(reference.stress_points.size(), smoothing_length);
  return configuration;
}

namespace {

void save_points(CheckpointOut& out, const PointCloud& points,
                 const std::vector<double>& smoothing_length) {
  for (int a = 0; a < points.dimension; ++a)
    out.put_doubles(points.position[static_cast<std::size_t>(a)]);
  out.put_doubles(points.volume);
  out.put_doubles(smoothing_length);
}

void restore_array(CheckpointIn& in, std::vector<double>& values) {
  in.get_doubles_into(values.data(), values.size());
}

void restore_points(CheckpointIn& in, PointCloud& points, std::vector<double>& smoothing_length) {
  for (int a = 0; a < points.dimension; ++a)
    restore_array(in, points.position[static_cast<std::size_t>(a)]);
  restore_array(in, points.volume);
  restore_array(in, smoothing_length);
}

}  // namespace

void save_configuration(CheckpointOut& out, const Configuration& configuration) {
  save_points(out, configuration.sph_nodes, configuration.node_smoothing_length);
  save_points(out, configuration.stress_points, configuration.point_smoothing_length);
}

void restore_configuration(CheckpointIn& in, Configuration& configuration) {
  restore_points(in, configuration.sph_nodes, configuration.node_smoothing_length);
  restore_points(in, configuration.stress_points, configuration.point_smoothing_length);
}

}  // namespace rktsph
