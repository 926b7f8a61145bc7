// The small elastic bar the command-line and driver tests run: 21 nodes, a piston at the right
// end, a probe at the free end; runs in well under a second.
#pragma once

namespace rktsph::test {

inline constexpr const char* kBar = R"(name: bar
dimension: 1
geometry:
  spacing: 0.5
  shapes:
    - segment: [0.0, 10.0]
      material: soil
materials:
  soil: {model: linear_elastic, density: 2000.0, young_modulus: 1.0e8, poisson_ratio: 0.0}
boundary_conditions:
  - {group: xmax, velocity: {x: -0.1}}
numerics: {courant: 0.9}
time: {end: 0.05}
output: {interval: 0.01}
probes:
  - {name: free, group: xmin, fields: [velocity_x]}
)";

}  // namespace rktsph::test
