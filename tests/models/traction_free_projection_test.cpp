// The traction-free projection of DrySolid at one point, no SPH (docs/theory.md eq. 5.1): a normal
// strain along each unit normal keeps the normal traction increments at zero, and every carried
// stress moves by the elastic stiffness times that strain.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rktsph/materials/linear_elastic.hpp"
#include "rktsph/models/dry_solid.hpp"
#include "rktsph/models/saturated_vpw.hpp"

namespace rktsph::traction_free_projection_test {
namespace {

const ElasticConstants kElastic{2.0e7, 0.3};

std::vector<std::unique_ptr<Material>> one_material() {
  std::vector<std::unique_ptr<Material>> materials;
  materials.push_back(std::make_unique<LinearElastic>(2000.0, kElastic));
  return materials;
}

using Tensor = std::array<std::array<double, 3>, 3>;
using Vector = std::array<double, 3>;

Vector unit_normal(double degrees) {
  const double angle = degrees * std::numbers::pi / 180.0;
  return {std::cos(angle), std::sin(angle), 0.0};
}

// A start state and an increment on every carried stress component of point 0.
struct Point {
  std::vector<double> start;
  FieldArray values;
  FieldArray before;
};

Point loaded_point(const DrySolid& model) {
  Point point{std::vector<double>(static_cast<std::size_t>(model.field_count())),
              FieldArray(model.field_count(), 1), FieldArray(model.field_count(), 1)};
  const FieldLayout& layout = model.layout();
  for (int c = 0; c < layout.stress_count(); ++c) {
    const int f = layout.stress_component(c);
    point.start[static_cast<std::size_t>(f)] = -1.0e5 * (c + 1);
    point.values(f, 0) = point.start[static_cast<std::size_t>(f)] + 1.0e4 * (0.7 - 0.45 * c);
  }
  point.before = point.values;
  return point;
}

// Stress increment (now minus start) as a 3D tensor.
Tensor increment(const DrySolid& model, const Point& point) {
  Tensor sigma{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int f = model.stress_field(i, j);
      if (f >= 0) sigma[i][j] = point.values(f, 0) - point.start[static_cast<std::size_t>(f)];
    }
  return sigma;
}

double traction(const Tensor& sigma, const Vector& n, const Vector& m) {
  double sum = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      sum += n[i] * sigma[i][j] * m[j];
  return sum;
}

// D : (n (x) n) of the isotropic solid in plane strain, lambda I + 2G n (x) n, or in plane stress,
// E' [nu I_2 + (1 - nu) n (x) n] in the plane (n in the plane).
Tensor stress_of_normal_strain(Kinematics kinematics, const Vector& n) {
  Tensor sigma{};
  const bool plane_strain = kinematics == Kinematics::PlaneStrain;
  const double modulus = kElastic.plane_stress_modulus(), nu = kElastic.poisson_ratio;
  const double isotropic = plane_strain ? kElastic.lame_lambda() : nu * modulus;
  const double directional = plane_strain ? 2.0 * kElastic.shear_modulus() : (1.0 - nu) * modulus;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      sigma[i][j] = directional * n[i] * n[j];
  for (int a = 0; a < (plane_strain ? 3 : 2); ++a)
    sigma[a][a] += isotropic;
  return sigma;
}

// Projects with `normals` and checks the result against the independent closed form.
void check_projection(Kinematics kinematics, const std::vector<Vector>& normal_list) {
  const DrySolid model(kinematics, one_material(), Loads{}, SourceIntegration{});
  Point point = loaded_point(model);
  SurfaceNormals normals;
  for (const Vector& n : normal_list)
    normals.add(n);
  const Tensor before = increment(model, point);
  model.project_traction_free_increment(0, normals, point.start, point.values, 0);
  const Tensor after = increment(model, point);
  const double scale = 1.0e4;
  for (const Vector& n : normal_list)
    EXPECT_NEAR(traction(after, n, n), 0.0, 1e-10 * scale);
  // The correction is D : sum_m c_m n_m (x) n_m with sum_m (n_r (x) n_r : D : n_m (x) n_m) c_m =
  // -n_r . delta sigma . n_r; for orthogonal in-plane normals the matrix is diagonal plus a
  // uniform coupling.
  const std::size_t count = normal_list.size();
  double system[2][2], residual[2], c[2];
  for (std::size_t r = 0; r < count; ++r) {
    residual[r] = -traction(before, normal_list[r], normal_list[r]);
    for (std::size_t m = 0; m < count; ++m)
      system[r][m] = traction(stress_of_normal_strain(kinematics, normal_list[m]), normal_list[r],
                              normal_list[r]);
  }
  if (count == 1) {
    c[0] = residual[0] / system[0][0];
  } else {
    const double det = system[0][0] * system[1][1] - system[0][1] * system[1][0];
    c[0] = (system[1][1] * residual[0] - system[0][1] * residual[1]) / det;
    c[1] = (system[0][0] * residual[1] - system[1][0] * residual[0]) / det;
  }
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      if (model.stress_field(i, j) < 0) continue;
      double expected = 0.0;
      for (std::size_t m = 0; m < count; ++m)
        expected += c[m] * stress_of_normal_strain(kinematics, normal_list[m])[i][j];
      EXPECT_NEAR(after[i][j] - before[i][j], expected, 1e-10 * scale) << i << j;
    }
}

TEST(DrySolidProjection, NormalAt30DegreesInPlaneStrain) {
  check_projection(Kinematics::PlaneStrain, {unit_normal(30.0)});
}

TEST(DrySolidProjection, NormalAt30DegreesInPlaneStress) {
  check_projection(Kinematics::PlaneStress, {unit_normal(30.0)});
}

TEST(DrySolidProjection, RotatedCornerWithTwoNormals) {
  check_projection(Kinematics::PlaneStrain, {unit_normal(30.0), unit_normal(120.0)});
  check_projection(Kinematics::PlaneStress, {unit_normal(-20.0), unit_normal(70.0)});
}

// Axis-aligned normals give exactly the closed form of the lattice faces: in plane strain
// delta_eps_n = -delta sigma_nn / M, and sigma_kk += D_kn delta_eps_n on xx, yy, zz.
TEST(DrySolidProjection, AxisNormalsReproduceTheLatticeClosedForm) {
  const DrySolid model(Kinematics::PlaneStrain, one_material(), Loads{}, SourceIntegration{});
  const double lambda = kElastic.lame_lambda(), modulus = lambda + 2.0 * kElastic.shear_modulus();
  const int xx = model.stress_field(0, 0), yy = model.stress_field(1, 1),
            xy = model.stress_field(0, 1), zz = model.stress_field(2, 2);
  {
    Point point = loaded_point(model);
    SurfaceNormals normals;
    normals.add_axis(1, -1.0);
    model.project_traction_free_increment(0, normals, point.start, point.values, 0);
    const double correction =
        -(point.before(yy, 0) - point.start[static_cast<std::size_t>(yy)]) / modulus;
    EXPECT_EQ(point.values(yy, 0), point.before(yy, 0) + modulus * correction);
    EXPECT_EQ(point.values(xx, 0), point.before(xx, 0) + lambda * correction);
    EXPECT_EQ(point.values(zz, 0), point.before(zz, 0) + lambda * correction);
    EXPECT_EQ(point.values(xy, 0), point.before(xy, 0));
  }
  {  // a corner: both normal strains solved together (Cramer's rule)
    Point point = loaded_point(model);
    SurfaceNormals normals;
    normals.add_axis(0);
    normals.add_axis(1);
    model.project_traction_free_increment(0, normals, point.start, point.values, 0);
    const double rx = -(point.before(xx, 0) - point.start[static_cast<std::size_t>(xx)]);
    const double ry = -(point.before(yy, 0) - point.start[static_cast<std::size_t>(yy)]);
    const double det = modulus * modulus - lambda * lambda;
    const double cx = (modulus * rx - lambda * ry) / det, cy = (modulus * ry - lambda * rx) / det;
    EXPECT_EQ(point.values(xx, 0), point.before(xx, 0) + modulus * cx + lambda * cy);
    EXPECT_EQ(point.values(yy, 0), point.before(yy, 0) + lambda * cx + modulus * cy);
    EXPECT_EQ(point.values(zz, 0), point.before(zz, 0) + lambda * cx + lambda * cy);
    EXPECT_EQ(point.values(xy, 0), point.before(xy, 0));
    EXPECT_NEAR(point.values(xx, 0), point.start[static_cast<std::size_t>(xx)], 1e-9);
    EXPECT_NEAR(point.values(yy, 0), point.start[static_cast<std::size_t>(yy)], 1e-9);
  }
}

TEST(SaturatedVpwProjection, ActsOnTheEffectiveStressOnly) {
  const SaturatedVpw model(Kinematics::PlaneStrain, one_material(), Loads{}, SourceIntegration{},
                           PoreFluid{1.0, 1e-9, 1e-6, 1000.0, 0.3, std::nullopt});
  Point point = loaded_point(model);
  const int pore = model.pore_pressure_field();
  point.values(pore, 0) = 3.0e4;
  SurfaceNormals normals;
  normals.add(unit_normal(30.0));
  model.project_traction_free_increment(0, normals, point.start, point.values, 0);
  EXPECT_EQ(point.values(pore, 0), 3.0e4);
  EXPECT_NEAR(traction(increment(model, point), unit_normal(30.0), unit_normal(30.0)), 0.0, 1e-6);
}

}  // namespace
}  // namespace rktsph::traction_free_projection_test
