// Modified Cam-Clay with pressure-dependent elasticity (docs/theory.md §1.5, eqs. 1.10a–1.10c):
// drained and undrained compression of normally and lightly overconsolidated clay, four
// plane-strain samples of one run (cases/mcc-triaxial). Everything is read from the case: the
// materials, the isotropic p0 (initial stress), the top velocity, the sample height. Checks:
//   <sample>_critical_state_ratio  q_f / (M(theta_f) p_f) at the end of the run (mean stress of
//       the sample); 1 at the critical state whatever the path (the ellipse's top, p = pc / 2).
//   undrained_<nc|oc>_pressure     p_f against the closed form p0 (OCR / 2)^Lambda, which holds
//       for any Lode angle, so in plane strain (references/critical_state.hpp).
//   drained_<nc|oc>_pressure       p_f against the point driver on the same plane-strain path
//       (sigma_xx held, eps_zz = 0, the top's strain rate): plane strain has no closed form.
//   triaxial_<drained|undrained>_<nc|oc>_{pressure,critical_state_ratio}  the material alone on
//       the triaxial paths through the point driver against the triaxial closed forms,
//       p_f = 3 p0 / (3 - M) drained, p0 (OCR / 2)^Lambda undrained, q_f = M p_f.
// Every check within 2 % (the bound); the slow rate keeps the Perzyna overstress at
// ~0.2 % (see the case file) and 60 % nominal strain leaves the asymptotic approach to the critical
// state well inside it.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "rktsph/core/error.hpp"
#include "rktsph/materials/invariants.hpp"
#include "rktsph/materials/material_factory.hpp"
#include "rktsph/materials/perzyna_modified_cam_clay.hpp"
#include "rktsph/materials/point_driver.hpp"
#include "rktsph/validation/references/critical_state.hpp"
#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph::case_checks::mcc_triaxial {

namespace {

constexpr const char* kCase = "mcc-triaxial";
// Quick variant: 5 x 5 nodes a sample (the samples are homogeneous: the lattice hardly matters).
constexpr double kQuickSpacing = 0.25;
constexpr double kTolerance = 0.02;
// Point-driver time step [s]: RK4 sub-stepped by the source stiffness, so only the sampling of
// the path depends on it.
constexpr double kDriverStep = 0.01;

struct Sample {
  std::string name;   // probe and group name
  std::size_t shape;  // index of its rectangle
  bool drained;
};

const std::vector<Sample>& samples() {
  static const std::vector<Sample> list = {{"drained_nc", 0, true},
                                           {"drained_oc", 1, true},
                                           {"undrained_nc", 2, false},
                                           {"undrained_oc", 3, false}};
  return list;
}

std::string consolidation_label(double ocr) {
  return ocr > 1.0 + 1e-9 ? "oc" : "nc";
}

/// The material of a sample, built from its case block as the run builds it.
std::unique_ptr<Material> sample_material(const CaseDescription& description,
                                          const std::string& material) {
  std::unique_ptr<Material> built = create_material(description.materials.at(material));
  if (!dynamic_cast<const PerzynaModifiedCamClay*>(built.get()))
    throw RunError(
        fmt::format("{}: material '{}' is not perzyna_modified_cam_clay", kCase, material));
  return built;
}

/// The isotropic initial stress p0 [Pa, compression positive] of the case.
double initial_pressure(const CaseDescription& description) {
  const auto& stress = description.initial.stress;
  const auto component = [&](const char* key) {
    const auto found = stress.find(key);
    if (found == stress.end()) throw RunError(fmt::format("{}: no initial stress {}", kCase, key));
    return found->second.value;
  };
  const double xx = component("xx"), yy = component("yy"), zz = component("zz");
  if (std::abs(xx - yy) > 1e-9 * std::abs(xx) || std::abs(xx - zz) > 1e-9 * std::abs(xx))
    throw RunError(fmt::format("{}: the initial stress must be isotropic", kCase));
  return -xx;
}

struct Failure {
  double pressure = 0.0, q = 0.0, ratio = 0.0;  // p_f, q_f, M(theta_f)
  double critical_state_ratio() const { return q / (ratio * pressure); }
};

Failure failure_of(const PerzynaModifiedCamClay& clay, const SymmetricTensor& stress) {
  const StressInvariants invariants = stress_invariants(stress);
  return {invariants.pressure, invariants.q, clay.critical_state_ratio(invariants.sin_3theta)};
}

/// The material point driven along `path` from the isotropic p0; the state of every step.
std::vector<PointState> drive_point(const Material& clay, const StrainPath& path, double p0) {
  DriveOptions options;
  options.time_step = kDriverStep;
  options.record_every = 1;  // the plotted paths: 0.1 % of strain a step at the case's rate
  return drive(clay, path, initial_point_state(clay, {-p0, -p0, -p0, 0, 0, 0}), options);
}

/// Plane-strain compression with the sample's top velocity over its height: y strain rate
/// v(t) / H; drained holds sigma_xx, undrained imposes eps_xx = -eps_yy; eps_zz = 0.
StrainPath plane_strain_path(const TimeFunction& top_velocity, double height, bool drained,
                             double duration) {
  StrainPath path;
  if (drained) path.control[0] = PathControl::Stress;
  path.rate = [top_velocity, height, drained](double t) {
    const double axial = top_velocity(t) / height;
    return SymmetricTensor{drained ? 0.0 : -axial, axial, 0.0, 0.0, 0.0, 0.0};
  };
  path.duration = duration;
  return path;
}

/// Triaxial compression along x at the same axial strain rate: drained holds sigma_yy = sigma_zz,
/// undrained is isochoric (eps_yy = eps_zz = -eps_xx / 2).
StrainPath triaxial_path(const TimeFunction& top_velocity, double height, bool drained,
                         double duration) {
  StrainPath path;
  if (drained) path.control[1] = path.control[2] = PathControl::Stress;
  path.rate = [top_velocity, height, drained](double t) {
    const double axial = top_velocity(t) / height;
    const double lateral = drained ? 0.0 : -0.5 * axial;
    return SymmetricTensor{axial, lateral, lateral, 0.0, 0.0, 0.0};
  };
  path.duration = duration;
  return path;
}

/// The first sample's top displacement over its height at the end (the imposed velocity integrated
/// by the trapezoidal rule on steps far below its ramp).
double nominal_axial_strain(const CaseDescription& description) {
  const Sample& first = samples().front();
  const TimeFunction& top = imposed_on(description, first.name + "_top", 1, false);
  const double end = description.time.end;
  const int steps = 100000;
  double displacement = 0.0;
  for (int i = 0; i < steps; ++i)
    displacement += 0.5 * (top(end * i / steps) + top(end * (i + 1) / steps)) * end / steps;
  return std::abs(displacement) / rectangle_shape(description, first.shape).height();
}

SymmetricTensor sample_stress(const ProbeTable& probes, const std::string& sample,
                              std::size_t row) {
  const auto at = [&](const char* component) {
    return probes.column(sample + ".stress_" + component)[row];
  };
  return {at("xx"), at("yy"), at("zz"), at("xy"), 0.0, 0.0};
}

}  // namespace

std::vector<CheckResult> validate_mcc_triaxial(const ValidationContext& context) {
  std::vector<CaseOverride> overrides;
  if (context.quick) overrides.push_back({"geometry.spacing", std::to_string(kQuickSpacing)});
  const CaseDescription description = load_bundled_case(context, kCase, overrides);
  const std::filesystem::path directory =
      run_for_validation(context, description, context.quick ? "quick" : "full");
  const ProbeTable probes = ProbeTable::read(directory / "probes.csv");
  const std::size_t last = probes.time().size() - 1;
  const double p0 = initial_pressure(description);
  const double duration = description.time.end;

  std::vector<CheckResult> checks;
  std::vector<Series> paths;
  for (const Sample& sample : samples()) {
    const std::string& material_name = description.geometry.shapes.at(sample.shape).material;
    const std::unique_ptr<Material> material = sample_material(description, material_name);
    const auto& clay = static_cast<const PerzynaModifiedCamClay&>(*material);
    const PerzynaModifiedCamClayParameters& parameters = clay.parameters();
    const double ocr = parameters.preconsolidation_pressure / p0;
    const double height = rectangle_shape(description, sample.shape).height();
    const TimeFunction& top = imposed_on(description, sample.name + "_top", 1, false);

    const Failure measured = failure_of(clay, sample_stress(probes, sample.name, last));
    checks.push_back(check_within(sample.name + "_critical_state_ratio",
                                  measured.critical_state_ratio(), 1.0, kTolerance, "1"));
    const std::vector<PointState> point =
        drive_point(clay, plane_strain_path(top, height, sample.drained, duration), p0);
    const double reference =
        sample.drained ? failure_of(clay, point.back().stress).pressure
                       : references::undrained_failure_pressure(
                             p0, ocr, parameters.compression_index, parameters.swelling_index);
    checks.push_back(check_at_most(sample.name + "_pressure",
                                   relative_error(measured.pressure, reference), 0.0, kTolerance,
                                   "fraction"));

    if (context.report) {
      Series sph{sample.name + " (SPH)", {}, {}, "line"};
      for (std::size_t row = 0; row <= last; ++row) {
        const StressInvariants invariants =
            stress_invariants(sample_stress(probes, sample.name, row));
        sph.x.push_back(invariants.pressure / 1e3);
        sph.y.push_back(invariants.q / 1e3);
      }
      Series driver{sample.name + " (point driver)", {}, {}, "dashed"};
      for (const PointState& state : point) {
        const StressInvariants invariants = stress_invariants(state.stress);
        driver.x.push_back(invariants.pressure / 1e3);
        driver.y.push_back(invariants.q / 1e3);
      }
      paths.push_back(std::move(sph));
      paths.push_back(std::move(driver));
    }

    // The triaxial closed forms, through the material alone (the plane-strain sample has an
    // intermediate stress of its own and no such closed form when drained).
    const Failure triaxial = failure_of(
        clay,
        drive_point(clay, triaxial_path(top, height, sample.drained, duration), p0).back().stress);
    const double compression_ratio =
        references::critical_state_ratio_compression(parameters.friction_angle);
    const double triaxial_reference =
        sample.drained ? references::drained_triaxial_failure_pressure(p0, compression_ratio)
                       : references::undrained_failure_pressure(
                             p0, ocr, parameters.compression_index, parameters.swelling_index);
    const std::string prefix = fmt::format(
        "triaxial_{}_{}", sample.drained ? "drained" : "undrained", consolidation_label(ocr));
    checks.push_back(check_within(prefix + "_critical_state_ratio",
                                  triaxial.q / (compression_ratio * triaxial.pressure), 1.0,
                                  kTolerance, "1"));
    checks.push_back(check_at_most(prefix + "_pressure",
                                   relative_error(triaxial.pressure, triaxial_reference), 0.0,
                                   kTolerance, "fraction"));
  }

  if (context.report) {
    // Held here: the material lives as long as this pointer, not the full expression.
    const auto first_material =
        sample_material(description, description.geometry.shapes.at(0).material);
    const auto& first = static_cast<const PerzynaModifiedCamClay&>(*first_material);
    const double compression_ratio =
        references::critical_state_ratio_compression(first.parameters().friction_angle);
    double p_max = 0.0;
    for (const Series& series : paths)
      for (double p : series.x)
        p_max = std::max(p_max, p);
    paths.push_back(sample_curve(fmt::format("critical state line q = M p, M = {:.3f} "
                                             "(triaxial compression)",
                                             compression_ratio),
                                 0.0, 1.1 * p_max, 2,
                                 [&](double p) { return compression_ratio * p; }));
    paths.push_back(sample_curve("critical state line, plane strain M(theta = 0)", 0.0, 1.1 * p_max,
                                 2, [&](double p) { return first.critical_state_ratio(0.0) * p; }));
    context.report->describe(fmt::format(
        "Modified Cam-Clay with pressure-dependent elasticity K = (1 + e0) p/kappa: four "
        "plane-strain 1 m x 1 m samples compressed from p0 = {:g} kPa to {:.0f} % nominal axial "
        "strain, "
        "drained at a constant confining traction and undrained (isochoric imposed motion), "
        "normally consolidated and with OCR 1.5. Each ends on the critical state line "
        "q = M(theta) p; the undrained p_f is compared with p0 (OCR/2)^Lambda, the drained one "
        "with the point driver on the same path; the triaxial closed forms are checked on the "
        "material alone.",
        p0 / 1e3, 100.0 * nominal_axial_strain(description)));
    context.report->add_picture(
        {"final_q", directory.string(), "deviatoric_stress", -1, -1.0, 0.0,
         fmt::format("q at the end on the reference positions (the nominal {:.0f} % strain of the "
                     "small-deformation model drawn at true scale would squash the samples): left "
                     "to right drained NC, drained OC, undrained NC, undrained OC; each sample "
                     "uniform, q = M(theta) p' of its own p'",
                     100.0 * nominal_axial_strain(description))});
    context.report->add_figure({"stress_paths", "Effective stress paths (mean of each sample)",
                                "p' [kPa]", "q [kPa]", std::move(paths)});
  }
  return checks;
}

}  // namespace rktsph::case_checks::mcc_triaxial
