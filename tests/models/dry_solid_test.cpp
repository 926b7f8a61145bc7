// The dry-solid model inside the step: the static state of a damped column under gravity
// (docs/theory.md §2.8) and the plane-stress source.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/materials/perzyna_von_mises.hpp"
#include "rktsph/models/dry_solid.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::dry_solid_test {
namespace {

std::string column_case(const std::string& coupling) {
  // A 10 m column, fixed at x = 0, free at x = 10, gravity along -x ramped over 0.5 s, mass
  // damping 20/s, 3 s: long enough for the damped transient (decay time 2/xi = 0.1 s) to die.
  return R"(
name: column
dimension: 1
geometry:
  spacing: 0.5
  shapes: [{segment: [0.0, 10.0], material: soil}]
materials:
  soil: {model: linear_elastic, density: 2000.0, young_modulus: 1.0e7, poisson_ratio: 0.0}
boundary_conditions:
  - {group: xmin, fixed: true}
loads:
  gravity: {acceleration: [-9.81], factor: {function: ramp, value: 1.0, duration: 0.5}}
  damping: {coefficient: 20.0}
numerics: {courant: 0.9, source_coupling: )" +
         coupling + R"(}
time: {end: 3.0}
)";
}

// Max over nodes of |sigma - sigma_exact| / (rho g L), sigma_exact = -rho g (L - x).
double static_stress_error(const std::string& coupling, double* xi_dt) {
  Simulation simulation(read_case_text(column_case(coupling), "column.yaml"));
  simulation.run();
  const double rho_g = 2000.0 * 9.81, length = 10.0;
  double error = 0.0, base_ratio = 0.0;
  const int stress_xx = simulation.model().stress_field(0, 0);
  for (std::size_t i = 0; i < simulation.nodes().sph_nodes.size(); ++i) {
    const double x = simulation.nodes().sph_nodes.position[0][i];
    const double exact = -rho_g * (length - x);
    const double stress = simulation.state().fields(stress_xx, i);
    error = std::max(error, std::abs(stress - exact) / (rho_g * length));
    if (x == 0.0) base_ratio = stress / exact;
  }
  *xi_dt = 20.0 * simulation.time_step();
  return coupling == "additive" ? 1.0 - base_ratio : error;
}

TEST(DrySolid, FrozenFluxCouplingReachesTheExactStaticStateUnderDamping) {
  double xi_dt = 0.0;
  // The lattice reproduces the linear static field exactly; what is left is the transient decayed
  // over 3 s (e^-30) and round-off.
  EXPECT_LT(static_stress_error("frozen_flux", &xi_dt), 1e-6);
}

TEST(DrySolid, AdditiveCouplingIsBiasedByHalfTheDampingPerStep) {
  // The additive split damps the gravity increment but not the flux increment, so the
  // static stress gradient comes out (1 - xi dt/2) rho g (docs/theory.md eq. 2.6).
  double xi_dt = 0.0;
  const double bias = static_stress_error("additive", &xi_dt);
  EXPECT_NEAR(bias, 0.5 * xi_dt, 0.1 * 0.5 * xi_dt) << "xi dt = " << xi_dt;
}

TEST(DrySolid, PlaneStressViscoplasticSourceKeepsTheOutOfPlaneStressZero) {
  // In plane stress sigma_zz is not carried; the material must see sigma_zz = 0 and the in-plane
  // relaxation must follow E' = E/(1-nu^2): under pure shear the shear stress relaxes as for
  // Von Mises with 3G (q = sqrt(3) |tau|).
  std::vector<std::unique_ptr<Material>> materials;
  const ElasticConstants elastic{1.0e7, 0.3};
  materials.push_back(std::make_unique<PerzynaVonMises>(
      2000.0, elastic, PerzynaVonMisesParameters{1.0e4, 0.0, 10.0, 1.0, 100.0}));
  const DrySolid model(Kinematics::PlaneStress, std::move(materials), Loads{}, SourceIntegration{});
  ASSERT_EQ(model.stress_field(2, 2), -1);
  FieldArray values(model.field_count(), 1), rate(model.field_count(), 1),
      internal(model.internal_count(), 1);
  model.initial_internal(0, internal, 0);
  const double tau0 = 2.0e4 / std::sqrt(3.0);  // q0 = 2 Y
  values(model.stress_field(0, 1), 0) = tau0;
  const std::int32_t material[] = {0};
  const double t = 0.01;
  model.advance(material, rate, 0.0, t, values, internal);
  // Closed form, N = 1, H = 0: q - Y decays as exp(-3 G gamma t / Y).
  const double shear = elastic.shear_modulus();
  const double q = std::sqrt(3.0) * values(model.stress_field(0, 1), 0);
  EXPECT_NEAR(q, 1.0e4 + 1.0e4 * std::exp(-3.0 * shear * 10.0 * t / 1.0e4), 1e-6 * 1e4);
  EXPECT_EQ(values(model.stress_field(0, 0), 0), 0.0);
  EXPECT_EQ(values(model.stress_field(1, 1), 0), 0.0);
}

// The tension cut-off (docs/theory.md §1.7): an update that ends with p = tr(sigma)/3 above the
// cut-off is returned onto it by shifting the carried normal stresses alike, so in plane strain
// the deviator is kept exactly; in plane stress sigma_zz stays 0. One node, an elastic rate only
// (Y far above the stresses, so the viscoplastic source does not act).
struct CutOffResult {
  double mean = 0.0, xx_minus_yy = 0.0, xy = 0.0, zz = 0.0;
};

CutOffResult advance_under_tension(Kinematics kinematics, double cutoff, double rate_xx) {
  std::vector<std::unique_ptr<Material>> materials;
  PerzynaVonMisesParameters parameters{1.0e9, 0.0, 1.0, 1.0, 1.0e7};
  parameters.tension_cutoff = cutoff;
  materials.push_back(
      std::make_unique<PerzynaVonMises>(2000.0, ElasticConstants{1.0e7, 0.3}, parameters));
  const DrySolid model(kinematics, std::move(materials), Loads{}, SourceIntegration{});
  FieldArray values(model.field_count(), 1), rate(model.field_count(), 1),
      internal(model.internal_count(), 1);
  model.initial_internal(0, internal, 0);
  values(model.stress_field(0, 0), 0) = 1.0e3;
  values(model.stress_field(1, 1), 0) = -2.0e3;
  values(model.stress_field(0, 1), 0) = 5.0e2;
  rate(model.stress_field(0, 0), 0) = rate_xx;
  rate(model.stress_field(1, 1), 0) = rate_xx;
  const std::int32_t material[] = {0};
  model.advance(material, rate, 0.0, 1.0, values, internal);
  CutOffResult result;
  const int zz = model.stress_field(2, 2);
  result.zz = zz >= 0 ? values(zz, 0) : 0.0;
  const double xx = values(model.stress_field(0, 0), 0), yy = values(model.stress_field(1, 1), 0);
  result.mean = (xx + yy + result.zz) / 3.0;
  result.xx_minus_yy = xx - yy;
  result.xy = values(model.stress_field(0, 1), 0);
  return result;
}

TEST(DrySolid, TensionCutOffReturnsTheMeanStressAndKeepsTheDeviator) {
  // Rates of 1e4 Pa/s on xx and yy over 1 s: p would end at (11e3 + 8e3)/3 = 6.33 kPa in plane
  // stress and, with sigma_zz = 0 carried and unchanged, the same in plane strain.
  const double unlimited = (11.0e3 + 8.0e3) / 3.0;
  const CutOffResult strain = advance_under_tension(Kinematics::PlaneStrain, 2.0e3, 1.0e4);
  EXPECT_NEAR(strain.mean, 2.0e3, 1e-9);
  EXPECT_NEAR(strain.xx_minus_yy, 3.0e3, 1e-9);  // the deviator: differences and shear kept
  EXPECT_NEAR(strain.xy, 5.0e2, 1e-9);
  EXPECT_NEAR(strain.zz, 2.0e3 - unlimited, 1e-9);
  const CutOffResult stress = advance_under_tension(Kinematics::PlaneStress, 2.0e3, 1.0e4);
  EXPECT_NEAR(stress.mean, 2.0e3, 1e-9);
  EXPECT_NEAR(stress.xx_minus_yy, 3.0e3, 1e-9);
  EXPECT_EQ(stress.zz, 0.0);
  // Below the cut-off, and with none, the update is the elastic one.
  const CutOffResult below = advance_under_tension(Kinematics::PlaneStrain, 1.0e4, 1.0e4);
  EXPECT_NEAR(below.mean, unlimited, 1e-9);
  const CutOffResult off = advance_under_tension(Kinematics::PlaneStrain,
                                                 std::numeric_limits<double>::infinity(), 1.0e4);
  EXPECT_NEAR(off.mean, unlimited, 1e-9);
  // Compression is never touched.
  const CutOffResult compressed = advance_under_tension(Kinematics::PlaneStrain, 0.0, -1.0e4);
  EXPECT_NEAR(compressed.mean, (-9.0e3 - 12.0e3) / 3.0, 1e-9);
}

}  // namespace
}  // namespace rktsph::dry_solid_test
