// The factor of safety by strength reduction (docs/theory.md §10, `rktsph fos`): the strengths of
// a case (dry, or saturated and drained) are divided by a factor F (c' and tan phi' of the
// frictional materials, the yield stress of a Von Mises one; eq. 10.1), the case is run with its
// own loads and time span, and the run is classified stable or failing (eq. 10.2: it must come to
// rest before its end time, with its largest displacement within a multiple of the elastic one). F
// is bisected between a stable and a failing factor; the factor of safety is the middle of the
// final bracket.
#pragma once

#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "rktsph/case/case_description.hpp"
#include "rktsph/driver/run_case.hpp"

namespace rktsph {

/// The materials whose strength is reduced (the others must be linear_elastic, left as they are).
std::vector<std::string> reducible_material_models();

/// InputError (file, key, value, what is allowed) for a case strength reduction cannot treat: not
/// a 2D model, a material with a strength it does not reduce (Cam-Clay), no material with a
/// strength at all, or a saturated case whose excess pore pressures would not drain within its
/// time span (the factor is a drained one, docs/theory.md eq. 10.3).
void check_strength_reduction_case(const CaseDescription& description);

/// The case with every strength divided by `factor` > 0 (eq. 10.1): cohesion, minimum_cohesion,
/// cohesion_hardening_modulus and tension_cutoff over F, tan of friction_angle and of
/// minimum_friction_angle over F, dilatancy_angle kept below the reduced friction angle; for Von
/// Mises yield_stress, minimum_yield_stress, hardening_modulus and tension_cutoff over F.
CaseDescription reduce_strength(const CaseDescription& description, double factor);

/// The same case with every material of reducible_material_models() made linear_elastic with its
/// density and elastic constants: the elastic reference of the displacement test.
CaseDescription elastic_reference(const CaseDescription& description);

/// Eq. 10.2. A run is stable when the largest speed over the SPH nodes falls to rest_fraction of
/// its peak (and stays there for a P-wave transit, time.stop_when_at_rest) before time.end, with
/// the largest displacement at most displacement_ratio times that of the elastic reference.
struct FailureCriterion {
  double rest_fraction = 1e-3;
  double displacement_ratio = 10.0;
};

/// One run at a factor F.
struct ReductionRun {
  double factor = 0.0;
  bool failing = false;
  bool came_to_rest = false;          ///< stopped by the rest test before time.end
  bool diverged = false;              ///< the run diverged (counted as failing)
  double end_time = 0.0;              ///< time reached [s]
  double largest_displacement = 0.0;  ///< max over the SPH nodes of |u| at the end [m]
  std::string reason;                 ///< why it was classified so, for people
  std::filesystem::path directory;
  /// Sampled histories of the largest speed [m/s] and largest displacement [m].
  std::vector<double> time, speed, displacement;
};

struct StrengthReductionOptions {
  double stable = 1.0;      ///< lower end of the bracket: must be stable
  double failing = 2.0;     ///< upper end: must fail
  double tolerance = 0.01;  ///< bisect until failing - stable <= tolerance
  FailureCriterion criterion;
  ExistingResults existing_results = ExistingResults::Refuse;
  StopCheck stop_check;  ///< interrupts (SIGINT, SIGTERM)
  /// Called after each run (the elastic reference has factor 0).
  std::function<void(const ReductionRun&)> on_run;
};

struct StrengthReductionResult {
  /// Middle of the final bracket; NaN when the bracket does not hold.
  double factor = std::numeric_limits<double>::quiet_NaN();
  double stable = 0.0, failing = 0.0;  ///< the final bracket
  bool bracket_holds = false;
  bool interrupted = false;
  std::string message;             ///< why there is no factor, when there is none
  ReductionRun elastic;            ///< the elastic reference
  std::vector<ReductionRun> runs;  ///< in the order run
  /// The failing run with the smallest F (the mechanism picture), or null.
  const ReductionRun* first_failing() const;
};

/// Runs the elastic reference and the bisection into `directory` (elastic/, F<factor>/). Throws
/// InputError for a case it cannot treat or a bad bracket, RunError when a run cannot be set up.
StrengthReductionResult find_factor_of_safety(const CaseDescription& description,
                                              const StrengthReductionOptions& options,
                                              const std::filesystem::path& directory);

/// fos.json: the factor, its bracket, the criterion and every run with its F and outcome.
std::string strength_reduction_json(const CaseDescription& description,
                                    const StrengthReductionOptions& options,
                                    const StrengthReductionResult& result,
                                    const std::string& mechanism_picture);

}  // namespace rktsph
