// The closed forms of critical-state soil mechanics (validation/references/critical_state.hpp)
// against the relations they are derived from, evaluated independently: the isochoric balance of
// elastic and plastic volumetric strain, the drained stress path dq/dp = 3 meeting q = M p, and
// the e-ln p unloading line. Tolerances are round-off (1e-12 relative).
#include <gtest/gtest.h>

#include <cmath>

#include "rktsph/validation/references/critical_state.hpp"

namespace rktsph::references::critical_state_test {
namespace {

TEST(CriticalStateReference, CompressionRatioOfThirtyDegreesIsOnePointTwo) {
  EXPECT_NEAR(critical_state_ratio_compression(30.0), 1.2, 1e-12);
}

TEST(CriticalStateReference, UnloadingLineIsStraightInLogPressure) {
  const double p0 = 2.0e5, e0 = 0.9, kappa = 0.04, strain = 3.0e-3;
  const double p = isotropic_unloading_pressure(p0, strain, e0, kappa);
  // Swelling: tension-positive volumetric strain lowers p; the void ratio change
  // de = (1 + e0) eps_v equals -kappa ln(p / p0).
  EXPECT_LT(p, p0);
  EXPECT_NEAR((1.0 + e0) * strain, -kappa * std::log(p / p0), 1e-12);
  EXPECT_DOUBLE_EQ(isotropic_unloading_pressure(p0, 0.0, e0, kappa), p0);
}

TEST(CriticalStateReference, UndrainedFailureBalancesElasticAndPlasticVolumeChange) {
  const double p0 = 1.5e5, lambda = 0.2, kappa = 0.05;
  for (const double ocr : {1.0, 1.5, 2.0, 3.0}) {
    const double pf = undrained_failure_pressure(p0, ocr, lambda, kappa);
    const double pc0 = ocr * p0, pcf = 2.0 * pf;  // critical state: p = pc / 2
    // Zero total volume change: kappa ln(p_f / p0) + (lambda - kappa) ln(pc_f / pc0) = 0.
    EXPECT_NEAR(kappa * std::log(pf / p0) + (lambda - kappa) * std::log(pcf / pc0), 0.0, 1e-12)
        << "OCR " << ocr;
  }
  // Normally consolidated clay loses pore-pressure-free strength; OCR = 2 keeps p.
  EXPECT_NEAR(undrained_failure_pressure(p0, 1.0, lambda, kappa), p0 * std::pow(0.5, 0.75), 1e-9);
  EXPECT_NEAR(undrained_failure_pressure(p0, 2.0, lambda, kappa), p0, 1e-9);
}

TEST(CriticalStateReference, DrainedTriaxialPathMeetsTheCriticalStateLine) {
  const double p0 = 1.0e5, ratio = 1.2;
  const double pf = drained_triaxial_failure_pressure(p0, ratio);
  const double qf = ratio * pf;
  EXPECT_NEAR(qf / (pf - p0), 3.0, 1e-12);  // the path dq/dp = 3 at constant cell pressure
  EXPECT_NEAR(pf, 1.66666666666667e5, 1e-6 * p0);
}

}  // namespace
}  // namespace rktsph::references::critical_state_test
