// The bundled validation cases, one function each, listed in registry.cpp. Each runs its case
// file(s) under cases/<name>/ and returns its checks. The checks of validation/cases/<file>.cpp
// live in namespace case_checks::<file>, so that each file's own helpers and constants stay
// its own when the files are compiled together (the unity build, CMakeLists.txt).
#pragma once

#include <string>
#include <vector>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/validation/validation_case.hpp"

namespace rktsph::case_checks {

namespace bar1d_elastic {
std::vector<CheckResult> validate_bar1d_elastic(const ValidationContext& context);
}  // namespace bar1d_elastic

namespace bar1d_viscoplastic {
std::vector<CheckResult> validate_bar1d_viscoplastic(const ValidationContext& context);
}  // namespace bar1d_viscoplastic

namespace bar_wave_2d {
std::vector<CheckResult> validate_bar_wave_2d(const ValidationContext& context);
std::vector<CheckResult> validate_triangles_bar_wave_2d(const ValidationContext& context);
}  // namespace bar_wave_2d

namespace convergence {
std::vector<CheckResult> validate_convergence(const ValidationContext& context);

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
}  // namespace convergence

namespace hanging_beam {
std::vector<CheckResult> validate_hanging_beam(const ValidationContext& context);
}  // namespace hanging_beam

namespace ld_bar1d_elastic {
std::vector<CheckResult> validate_ld_bar1d_elastic(const ValidationContext& context);
}  // namespace ld_bar1d_elastic

namespace ld_bar2d_viscoplastic {
std::vector<CheckResult> validate_ld_bar2d_viscoplastic(const ValidationContext& context);
}  // namespace ld_bar2d_viscoplastic

namespace ld_cantilever_plate {
std::vector<CheckResult> validate_ld_cantilever_plate(const ValidationContext& context);
}  // namespace ld_cantilever_plate

namespace ld_rigid_motion {
std::vector<CheckResult> validate_ld_rotation_objectivity(const ValidationContext& context);
std::vector<CheckResult> validate_ld_spinning_square(const ValidationContext& context);
}  // namespace ld_rigid_motion

namespace ld_slope_cohesive {
std::vector<CheckResult> validate_ld_slope_cohesive(const ValidationContext& context);
}  // namespace ld_slope_cohesive

namespace ld_slope_low_cohesion {
std::vector<CheckResult> validate_ld_slope_low_cohesion(const ValidationContext& context);
}  // namespace ld_slope_low_cohesion

namespace ld_footing_penetration {
std::vector<CheckResult> validate_ld_footing_penetration(const ValidationContext& context);
}  // namespace ld_footing_penetration

namespace ld_strip_footing_bearing {
std::vector<CheckResult> validate_ld_strip_footing_bearing(const ValidationContext& context);
}  // namespace ld_strip_footing_bearing

namespace ld_vertical_cut_footing {
std::vector<CheckResult> validate_ld_vertical_cut_footing(const ValidationContext& context);
}  // namespace ld_vertical_cut_footing

namespace mcc_triaxial {
std::vector<CheckResult> validate_mcc_triaxial(const ValidationContext& context);
}  // namespace mcc_triaxial

namespace sample2d_localization {
std::vector<CheckResult> validate_sample2d_localization(const ValidationContext& context);
}  // namespace sample2d_localization

namespace slope_elastic {
std::vector<CheckResult> validate_slope_elastic(const ValidationContext& context);
}  // namespace slope_elastic

namespace slope_fos {
std::vector<CheckResult> validate_slope_fos_homogeneous(const ValidationContext& context);
std::vector<CheckResult> validate_vertical_cut_frictional(const ValidationContext& context);
}  // namespace slope_fos

namespace slope_softening {
std::vector<CheckResult> validate_slope_softening(const ValidationContext& context);
}  // namespace slope_softening

namespace slope_viscoplastic {
std::vector<CheckResult> validate_slope_viscoplastic(const ValidationContext& context);
std::vector<CheckResult> validate_triangles_slope_viscoplastic(const ValidationContext& context);
}  // namespace slope_viscoplastic

namespace strip_footing_elastic {
std::vector<CheckResult> validate_strip_footing_elastic(const ValidationContext& context);
std::vector<CheckResult> validate_triangles_strip_footing_elastic(const ValidationContext& context);
}  // namespace strip_footing_elastic

namespace triangles_slope_elastic {
std::vector<CheckResult> validate_triangles_slope_elastic(const ValidationContext& context);
}  // namespace triangles_slope_elastic

namespace vpw_consolidation {
std::vector<CheckResult> validate_vpw_consolidation(const ValidationContext& context);
std::vector<CheckResult> validate_triangles_vpw_consolidation(const ValidationContext& context);
}  // namespace vpw_consolidation

namespace vpw_harmonic_column {
std::vector<CheckResult> validate_vpw_harmonic_column(const ValidationContext& context);
}  // namespace vpw_harmonic_column

namespace vpw_localization {
std::vector<CheckResult> validate_vpw_localization(const ValidationContext& context);
}  // namespace vpw_localization

namespace vpw_strip_footing_elastic {
std::vector<CheckResult> validate_vpw_strip_footing_elastic(const ValidationContext& context);
}  // namespace vpw_strip_footing_elastic

namespace vpw_strip_footing_plastic {
std::vector<CheckResult> validate_vpw_strip_footing_plastic(const ValidationContext& context);
}  // namespace vpw_strip_footing_plastic

namespace vpw_vertical_cut_footing {
std::vector<CheckResult> validate_vpw_vertical_cut_footing(const ValidationContext& context);
}  // namespace vpw_vertical_cut_footing

namespace vpw_water_table {
std::vector<CheckResult> validate_vpw_water_table(const ValidationContext& context);
}  // namespace vpw_water_table

}  // namespace rktsph::case_checks
