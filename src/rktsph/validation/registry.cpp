#include "rktsph/validation/validation_cases.hpp"

namespace rktsph {

const std::vector<ValidationCase>& validation_cases() {
  static const std::vector<ValidationCase> cases = {
      {"bar1d-elastic", "1D elastic bar at Courant 0.6 and 1 against characteristics (4.2)",
       &validate_bar1d_elastic},
      {"bar1d-viscoplastic", "shock in a 1D Perzyna bar against characteristics (4.3)",
       &validate_bar1d_viscoplastic},
      {"sample2d-localization", "shear band in a softening plane-strain sample (4.4)",
       &validate_sample2d_localization},
      {"slope-elastic", "elastic vertical slope under ramped gravity with damping (4.5.1)",
       &validate_slope_elastic},
      {"slope-viscoplastic", "critical stability number of a vertical cut (4.5.2)",
       &validate_slope_viscoplastic},
      {"slope-softening", "progressive failure of a softening vertical cut (4.5.3)",
       &validate_slope_softening},
      {"bar-wave-2d", "BAR-WAVE-2D plane wave, with and without artificial viscosity",
       &validate_bar_wave_2d},
      {"convergence", "spatial convergence order of the elastic bar and a smooth 2D wave",
       &validate_convergence},
      {"vpw-consolidation", "Terzaghi consolidation of a saturated column (6.4.2)",
       &validate_vpw_consolidation},
      {"vpw-harmonic-column", "saturated column under harmonic load, three permeabilities (6.4.3)",
       &validate_vpw_harmonic_column},
      {"vpw-strip-footing-elastic", "fast strip load on a nearly undrained elastic stratum (6.4.4)",
       &validate_vpw_strip_footing_elastic},
      {"vpw-localization", "shear band in a saturated softening sample (6.4.5)",
       &validate_vpw_localization},
      {"vpw-vertical-cut-footing", "footing on a saturated vertical cut, undrained limit (6.4.6)",
       &validate_vpw_vertical_cut_footing},
      {"strip-footing-elastic", "flexible strip load on a dry elastic stratum against Flamant",
       &validate_strip_footing_elastic},
      {"hanging-beam", "slender elastic beam hanging under ramped gravity, damped (V2-0)",
       &validate_hanging_beam},
      {"ld-bar1d-elastic", "1D elastic bar with the large-deformation model (5.3.2)",
       &validate_ld_bar1d_elastic},
      {"ld-bar2d-viscoplastic", "wave in a 2D viscoplastic bar, large-deformation model (5.3.3)",
       &validate_ld_bar2d_viscoplastic},
      {"ld-rotation-objectivity", "pre-stressed block in a rigid quarter turn: objective stress",
       &validate_ld_rotation_objectivity},
      {"ld-spinning-square", "free elastic square spinning at 50 rad/s (SPHinXsys test)",
       &validate_ld_spinning_square},
      {"ld-vertical-cut-footing", "footing on a vertical cut pushed to deep settlement (5.3.6)",
       &validate_ld_vertical_cut_footing},
      {"ld-strip-footing-bearing", "rigid strip footing pushed into a Von Mises stratum (5.3.7)",
       &validate_ld_strip_footing_bearing},
      {"ld-cantilever-plate", "oscillating cantilever plate (Gray, Monaghan & Swift 2001): period",
       &validate_ld_cantilever_plate},
      {"ld-slope-cohesive", "critical height and post-failure of a cut, large deformation (5.3.5)",
       &validate_ld_slope_cohesive},
      {"ld-slope-low-cohesion", "collapse and run-out of a block of very low cohesion (5.3.4)",
       &validate_ld_slope_low_cohesion},
  };
  return cases;
}

}  // namespace rktsph
