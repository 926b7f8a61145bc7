// The bundled validation cases, one function each (validation/cases/<name>.cpp), listed in
// registry.cpp. Each runs its case file(s) under cases/<name>/ and returns its checks.
#pragma once

#include <string>
#include <vector>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/validation/validation_case.hpp"

namespace rktsph {

std::vector<CheckResult> validate_bar1d_elastic(const ValidationContext& context);
std::vector<CheckResult> validate_bar1d_viscoplastic(const ValidationContext& context);
std::vector<CheckResult> validate_sample2d_localization(const ValidationContext& context);
std::vector<CheckResult> validate_mcc_triaxial(const ValidationContext& context);
std::vector<CheckResult> validate_slope_elastic(const ValidationContext& context);
std::vector<CheckResult> validate_triangles_slope_elastic(const ValidationContext& context);
std::vector<CheckResult> validate_triangles_slope_viscoplastic(const ValidationContext& context);
std::vector<CheckResult> validate_triangles_strip_footing_elastic(const ValidationContext& context);
std::vector<CheckResult> validate_triangles_vpw_consolidation(const ValidationContext& context);
std::vector<CheckResult> validate_slope_viscoplastic(const ValidationContext& context);
std::vector<CheckResult> validate_slope_fos_homogeneous(const ValidationContext& context);
std::vector<CheckResult> validate_vertical_cut_frictional(const ValidationContext& context);
std::vector<CheckResult> validate_slope_softening(const ValidationContext& context);
std::vector<CheckResult> validate_bar_wave_2d(const ValidationContext& context);
std::vector<CheckResult> validate_triangles_bar_wave_2d(const ValidationContext& context);
std::vector<CheckResult> validate_convergence(const ValidationContext& context);
std::vector<CheckResult> validate_vpw_consolidation(const ValidationContext& context);
std::vector<CheckResult> validate_vpw_harmonic_column(const ValidationContext& context);
std::vector<CheckResult> validate_vpw_strip_footing_elastic(const ValidationContext& context);
std::vector<CheckResult> validate_vpw_strip_footing_plastic(const ValidationContext& context);
std::vector<CheckResult> validate_vpw_localization(const ValidationContext& context);
std::vector<CheckResult> validate_vpw_vertical_cut_footing(const ValidationContext& context);
std::vector<CheckResult> validate_vpw_water_table(const ValidationContext& context);
std::vector<CheckResult> validate_strip_footing_elastic(const ValidationContext& context);
std::vector<CheckResult> validate_hanging_beam(const ValidationContext& context);
std::vector<CheckResult> validate_ld_bar1d_elastic(const ValidationContext& context);
std::vector<CheckResult> validate_ld_bar2d_viscoplastic(const ValidationContext& context);
std::vector<CheckResult> validate_ld_rotation_objectivity(const ValidationContext& context);
std::vector<CheckResult> validate_ld_spinning_square(const ValidationContext& context);
std::vector<CheckResult> validate_ld_vertical_cut_footing(const ValidationContext& context);
std::vector<CheckResult> validate_ld_strip_footing_bearing(const ValidationContext& context);
std::vector<CheckResult> validate_ld_cantilever_plate(const ValidationContext& context);
std::vector<CheckResult> validate_ld_slope_cohesive(const ValidationContext& context);
std::vector<CheckResult> validate_ld_slope_low_cohesion(const ValidationContext& context);

/// The smooth plane wave of `convergence` (cases/convergence-wave2d, refined over `cells` along x
/// with `overrides` applied, e.g. a triangle mesh): the relative L2 errors of sigma_xx, the
/// spacings and the least-squares order (validation/cases/convergence.cpp).
struct PlaneWaveConvergence {
  std::vector<int> cells;
  std::vector<double> spacing, error;
  double order = 0.0;
};
PlaneWaveConvergence plane_wave_convergence(const ValidationContext& context,
                                            const std::vector<int>& cells,
                                            const std::vector<CaseOverride>& overrides);
/// The order check of `convergence`: expected 2, passes at 1.8 or more.
CheckResult convergence_order_check(const std::string& name, double order);

}  // namespace rktsph
