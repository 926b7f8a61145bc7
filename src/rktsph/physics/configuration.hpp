// The configuration of a run: where its points are now (docs/theory.md §2.6).
#pragma once

#include <vector>

#include "rktsph/core/checkpoint.hpp"
#include "rktsph/core/point_cloud.hpp"
#include "rktsph/geometry/node_sets.hpp"

namespace rktsph {

/// Where the points are now (docs/theory.md §2.6): positions and volumes of the SPH nodes and the
/// stress points, and each point's smoothing length. Point i is point i of the reference
/// configuration (NodeSets), whose indices are the points' stable ids. In V1 and V3 it stays the
/// reference configuration; a large-deformation model moves it every step.
struct Configuration {
  PointCloud sph_nodes;
  PointCloud stress_points;
  std::vector<double> node_smoothing_length;   ///< h of each SPH node [m]
  std::vector<double> point_smoothing_length;  ///< h of each stress point [m]
};

/// The reference configuration as the current one: positions and volumes of `reference`, every
/// point with smoothing length `smoothing_length` [m].
Configuration reference_configuration(const NodeSets& reference, double smoothing_length);

/// Writes the positions, volumes and smoothing lengths of both point sets; restore reads them
/// into a configuration of the same sizes (CheckpointIn::fail otherwise).
void save_configuration(CheckpointOut& out, const Configuration& configuration);
void restore_configuration(CheckpointIn& in, Configuration& configuration);

}  // namespace rktsph
