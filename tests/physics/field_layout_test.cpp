// Where the solid models keep their unknowns: names, parities and gradient slots in one place.
#include <gtest/gtest.h>

#include "rktsph/physics/field_layout.hpp"

namespace rktsph::field_layout_test {
namespace {

TEST(FieldLayout, PlaneStrainWithPorePressure) {
  const FieldLayout layout(plane_strain(), true);
  const std::vector<std::string> names = {"velocity_x", "velocity_y", "stress_xx",    "stress_yy",
                                          "stress_xy",  "stress_zz",  "pore_pressure"};
  EXPECT_EQ(layout.names(), names);
  EXPECT_EQ(layout.field_count(), 7);
  EXPECT_EQ(layout.velocity(1), 1);
  EXPECT_EQ(layout.velocity(2), -1);
  EXPECT_EQ(layout.stress(1, 0), 4);
  EXPECT_EQ(layout.stress(2, 2), 5);
  EXPECT_EQ(layout.stress(0, 2), -1);
  EXPECT_EQ(layout.pore_pressure(), 6);
  EXPECT_EQ(layout.gradient(layout.stress(0, 1), 1), 9);
  const std::vector<Parity> parities(layout.parities().begin(), layout.parities().end());
  EXPECT_EQ(parities, (std::vector<Parity>{vector_parity(0), vector_parity(1), kEven, kEven,
                                           tensor_parity(0, 1), kEven, kEven}));
}

TEST(FieldLayout, DryBarAndPlaneStress) {
  const FieldLayout bar(bar_1d(), false);
  EXPECT_EQ(bar.names(), (std::vector<std::string>{"velocity_x", "stress_xx"}));
  EXPECT_EQ(bar.pore_pressure(), -1);
  EXPECT_EQ(bar.stress(1, 1), -1);
  EXPECT_EQ(bar.gradient(bar.stress(0, 0), 0), 1);
  const FieldLayout plane(plane_stress(), false);
  EXPECT_EQ(plane.field_count(), 5);
  EXPECT_EQ(plane.stress(2, 2), -1);
}

}  // namespace
}  // namespace rktsph::field_layout_test
