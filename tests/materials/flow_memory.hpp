// The flow memory of a viscoplastic material (Material::has_flowed, docs/theory.md eqs. 3.10,
// 3.14), checked alike for every frictional material: a point driven to failure and unloaded no
// longer flows but remembers that it has.
#pragma once

#include <gtest/gtest.h>

#include "rktsph/materials/point_driver.hpp"

namespace rktsph::test_support {

/// Drives `material` from the isotropic stress `isotropic` along uniaxial compression until it
/// flows, then checks has_flowed before (false), at failure (true) and back at `isotropic`
/// (no flow, but true).
inline void expect_remembers_its_flow(const Material& material, const SymmetricTensor& isotropic) {
  const PointState start = initial_point_state(material, isotropic);
  EXPECT_FALSE(material.has_flowed(start.internal));
  DriveOptions options;
  options.time_step = 0.01;
  options.record_every = 10;
  const auto history = drive(material, StrainPath::uniaxial_stress(-1e-3, 30.0), start, options);
  const PointState& failed = history.back();
  EXPECT_TRUE(material.flows(failed.stress, failed.internal));
  EXPECT_TRUE(material.has_flowed(failed.internal));
  // Unloaded to the isotropic start: no flow now, but flowed before.
  EXPECT_FALSE(material.flows(isotropic, failed.internal));
  EXPECT_TRUE(material.has_flowed(failed.internal));
}

}  // namespace rktsph::test_support
