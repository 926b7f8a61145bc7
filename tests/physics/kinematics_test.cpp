// The kinematic settings alone, on one material point: each stiffness is the 3D isotropic one
// restricted (plane strain) or condensed (plane stress, 1D bar) (docs/theory.md §1.6).
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "rktsph/physics/kinematics/kinematics.hpp"

namespace rktsph::kinematics_test {
namespace {

const ElasticConstants kElastic{2.0e7, 0.3};

Eigen::MatrixXd to_eigen(const StiffnessMatrix& stiffness) {
  Eigen::MatrixXd matrix(stiffness.size(), stiffness.size());
  for (int r = 0; r < stiffness.size(); ++r)
    for (int c = 0; c < stiffness.size(); ++c)
      matrix(r, c) = stiffness(r, c);
  return matrix;
}

TEST(ElasticStiffness, IsTheLameFormOnEngineeringShearStrains) {
  const StiffnessMatrix d = elastic_stiffness(kElastic);
  const double lambda = kElastic.lame_lambda(), shear = kElastic.shear_modulus();
  ASSERT_EQ(d.size(), 6);
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) {
      double expected = 0.0;
      if (r < 3 && c < 3) expected = r == c ? lambda + 2.0 * shear : lambda;
      if (r >= 3 && r == c) expected = shear;
      EXPECT_EQ(d(r, c), expected) << r << c;
    }
}

TEST(KinematicAssumption, PlaneStrainCarriesTheLameFormWithSigmaZz) {
  const KinematicAssumption& kinematics = plane_strain();
  EXPECT_EQ(kinematics.dimension(), 2);
  ASSERT_EQ(kinematics.stress_count(), 4);
  const int xx = kinematics.carried_index(0, 0), yy = kinematics.carried_index(1, 1),
            xy = kinematics.carried_index(0, 1), zz = kinematics.carried_index(2, 2);
  EXPECT_EQ(kinematics.stress_name(zz), "stress_zz");
  EXPECT_EQ(kinematics.carried_index(1, 0), xy);
  EXPECT_EQ(kinematics.carried_index(1, 2), -1);
  const StiffnessMatrix d = kinematics.stiffness(kElastic);
  const double lambda = kElastic.lame_lambda(), shear = kElastic.shear_modulus();
  EXPECT_EQ(d(xx, xx), lambda + 2.0 * shear);
  EXPECT_EQ(d(yy, yy), lambda + 2.0 * shear);
  EXPECT_EQ(d(xx, yy), lambda);
  EXPECT_EQ(d(zz, xx), lambda);  // sigma_zz = lambda (eps_xx + eps_yy)
  EXPECT_EQ(d(zz, yy), lambda);
  EXPECT_EQ(d(xy, xy), shear);
  EXPECT_EQ(d(xy, xx), 0.0);
}

TEST(KinematicAssumption, PlaneStressStiffnessLeavesSigmaZzZero) {
  const KinematicAssumption& kinematics = plane_stress();
  ASSERT_EQ(kinematics.stress_count(), 3);
  EXPECT_EQ(kinematics.carried_index(2, 2), -1);
  const StiffnessMatrix reduced = kinematics.stiffness(kElastic);
  const StiffnessMatrix full = elastic_stiffness(kElastic);
  const double in_plane_strains[][3] = {{1e-3, 0.0, 0.0}, {0.0, -2e-3, 0.0}, {3e-4, -7e-4, 5e-4}};
  for (const auto& strain : in_plane_strains) {
    // The free eps_zz is the one that makes sigma_zz vanish; then the 3D stress in the plane must
    // be the reduced stiffness times the in-plane strain.
    SymmetricTensor gamma{};
    gamma[0] = strain[0];
    gamma[1] = strain[1];
    gamma[3] = strain[2];
    gamma[2] = -(full(2, 0) * gamma[0] + full(2, 1) * gamma[1]) / full(2, 2);
    double sigma[6] = {};
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c)
        sigma[r] += full(r, c) * gamma[static_cast<std::size_t>(c)];
    EXPECT_NEAR(sigma[2], 0.0, 1e-9 * kElastic.young_modulus * 1e-3);
    for (int c = 0; c < 3; ++c) {
      const int slot = kinematics.stress_slot(c);
      double expected = 0.0;
      for (int k = 0; k < 3; ++k)
        expected += reduced(c, k) * gamma[static_cast<std::size_t>(kinematics.stress_slot(k))];
      EXPECT_NEAR(sigma[slot], expected, 1e-12 * kElastic.young_modulus * 1e-3);
    }
  }
  // The closed form E' [[1, nu, 0], [nu, 1, 0], [0, 0, (1 - nu)/2]].
  const double modulus = kElastic.plane_stress_modulus(), nu = kElastic.poisson_ratio;
  EXPECT_NEAR(reduced(0, 0), modulus, 1e-14 * modulus);
  EXPECT_NEAR(reduced(0, 1), nu * modulus, 1e-14 * modulus);
  EXPECT_NEAR(reduced(2, 2), 0.5 * (1.0 - nu) * modulus, 1e-14 * modulus);
}

TEST(KinematicAssumption, BarStiffnessIsYoungsModulus) {
  const KinematicAssumption& kinematics = bar_1d();
  EXPECT_EQ(kinematics.dimension(), 1);
  ASSERT_EQ(kinematics.stress_count(), 1);
  EXPECT_EQ(kinematics.stress_name(0), "stress_xx");
  const StiffnessMatrix d = kinematics.stiffness(kElastic);
  ASSERT_EQ(d.size(), 1);
  EXPECT_NEAR(d(0, 0), kElastic.young_modulus, 1e-14 * kElastic.young_modulus);
  // nu = 0 has no lateral coupling: the condensation is exact.
  EXPECT_EQ(kinematics.stiffness({1.0e7, 0.0})(0, 0), 1.0e7);
}

TEST(KinematicAssumption, StiffnessesAreSymmetricAndPositiveDefinite) {
  for (const KinematicAssumption* kinematics : {&bar_1d(), &plane_strain(), &plane_stress()})
    for (const double nu : {0.0, 0.25, 0.45}) {
      const Eigen::MatrixXd d = to_eigen(kinematics->stiffness({1.0e7, nu}));
      EXPECT_LT((d - d.transpose()).norm(), 1e-15 * d.norm());
      EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(d).info(), Eigen::Success);
    }
}

TEST(KinematicAssumption, StrainRatesComeFromTheInPlaneVelocityGradient) {
  const KinematicAssumption& kinematics = plane_strain();
  const StrainRateTerms xy = kinematics.strain_rate_terms(kinematics.carried_index(0, 1));
  ASSERT_EQ(xy.count, 2);  // engineering shear: dv_x/dy + dv_y/dx
  EXPECT_EQ(xy.term[0].velocity, 0);
  EXPECT_EQ(xy.term[0].axis, 1);
  EXPECT_EQ(xy.term[1].velocity, 1);
  EXPECT_EQ(xy.term[1].axis, 0);
  const StrainRateTerms yy = kinematics.strain_rate_terms(kinematics.carried_index(1, 1));
  ASSERT_EQ(yy.count, 1);
  EXPECT_EQ(yy.term[0].velocity, 1);
  EXPECT_EQ(yy.term[0].axis, 1);
  EXPECT_EQ(kinematics.strain_rate_terms(kinematics.carried_index(2, 2)).count, 0);
}

}  // namespace
}  // namespace rktsph::kinematics_test
