// The oscillating cantilever plate of Gray, Monaghan & Swift (2001) with the large-deformation
// model (docs/theory.md §9.11): a plate clamped into a fixed block, set swinging in its first
// bending mode with the tip at V_f c0. It runs at three lattice spacings, dx = H/n for the n of
// kCells (cells across the thickness), and follows the mean v_y and u_y of the free end's nodes.
//
// The period is measured from the zero crossings of the tip velocity, each located by a straight
// line fitted over +-T/16 about the sign change (robust to the ringing of higher modes near the
// turning points), and averaged over every half period run: T = 2 (t_last - t_first)/(crossings -
// 1). The amplitude is |u_y| at the crossings (the turning points); its decay per period is
// 1 - exp(s T), s the least-squares slope of ln |u_y| against time. Checks:
//   period_error                the period at the finest spacing against the thin-plate period
//                               2 pi / omega, omega^2 = E H^2 k^4 / (12 rho (1 - nu^2)), computed
//                               from the case's L, H, E, nu, rho; relative.
//   period_change_finest        the relative change of the period between the two finest spacings.
//   amplitude_decay_per_period  the decay of the tip amplitude per period at the finest spacing;
//                               a growth counts as much as a decay (|value| <= tolerance).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "rktsph/validation/references/cantilever_plate.hpp"
#include "rktsph/validation/validation_cases.hpp"
#include "rktsph/validation/validation_support.hpp"

namespace rktsph::case_checks::ld_cantilever_plate {

namespace {

constexpr std::array<int, 3> kCells = {4, 6, 8};       // cells across H, full variant
constexpr std::array<int, 3> kQuickCells = {2, 3, 4};  // quick variant
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const std::string kTipGroup = "validation_tip";

// The plate as the case file sets it: the bending mode gives the root and the free length, the
// shapes the thickness (their extent in y) and the free end (their largest x), the first shape's
// material the elastic constants.
struct Plate {
  references::CantileverPlate reference;
  double root = 0.0;                // x of the clamped root [m]
  double y_min = 0.0, y_max = 0.0;  // faces [m]
  double tip_velocity = 0.0;        // initial v_y of the tip [m/s]
};

Plate read_plate(const CaseDescription& description) {
  const auto& mode = description.initial.bending_mode;
  if (!mode)
    throw RunError("case " + description.name + ": no initial_conditions.bending_mode to swing");
  if (description.geometry.shapes.empty())
    throw RunError("case " + description.name + ": no shapes");
  double x_max = -std::numeric_limits<double>::infinity();
  double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
  for (const ShapeSpec& shape : description.geometry.shapes)
    for (const Vec3& vertex : shape.vertices) {
      x_max = std::max(x_max, vertex[0]);
      y_min = std::min(y_min, vertex[1]);
      y_max = std::max(y_max, vertex[1]);
    }
  if (std::abs(x_max - (mode->root + mode->length)) > 1e-6 * description.geometry.spacing)
    throw RunError(fmt::format(
        "case {}: the plate ends at x = {} m but the bending mode's root + length is {} m",
        description.name, x_max, mode->root + mode->length));
  const std::string& material = description.geometry.shapes.front().material;
  Plate plate;
  plate.reference = {mode->length, y_max - y_min,
                     material_parameter(description, material, "young_modulus"),
                     material_parameter(description, material, "poisson_ratio"),
                     material_parameter(description, material, "density")};
  plate.root = mode->root;
  plate.y_min = y_min;
  plate.y_max = y_max;
  plate.tip_velocity = mode->tip_velocity;
  return plate;
}

// The mean v_y and u_y of the nodes of the free end, as a probe of the validation's own.
void add_tip_probe(CaseDescription& description, const Plate& plate) {
  GroupSpec group;
  group.name = kTipGroup;
  group.kind = GroupSpec::Kind::Box;
  const double x_tip = plate.root + plate.reference.length;
  group.min = {x_tip, plate.y_min, 0.0};
  group.max = {x_tip, plate.y_max, 0.0};
  description.groups.push_back(group);
  ProbeSpec probe;
  probe.name = kTipGroup;
  probe.group = kTipGroup;
  probe.fields = {"velocity_y", "displacement_y"};
  description.probes.push_back(probe);
}

struct Swing {
  std::vector<double> crossings;   // zero crossings of the tip velocity [s]
  std::vector<double> amplitudes;  // |u_y| there [m]
  double period = kNaN;            // [s]
  double decay = kNaN;             // per period
};

// The root of the least-squares line through (t, v) over |t - estimate| <= half_window; the
// estimate itself if the window holds fewer than three samples.
double fitted_root(const std::vector<double>& t, const std::vector<double>& v, double estimate,
                   double half_window) {
  double n = 0.0, st = 0.0, sv = 0.0, stt = 0.0, stv = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (std::abs(t[k] - estimate) > half_window) continue;
    const double s = t[k] - estimate;
    n += 1.0;
    st += s;
    sv += v[k];
    stt += s * s;
    stv += s * v[k];
  }
  const double denominator = n * stt - st * st;
  if (n < 3.0 || denominator <= 0.0) return estimate;
  const double slope = (n * stv - st * sv) / denominator;
  const double intercept = (sv - slope * st) / n;
  return slope != 0.0 ? estimate - intercept / slope : estimate;
}

double interpolate(const std::vector<double>& t, const std::vector<double>& y, double time) {
  const auto upper = std::lower_bound(t.begin(), t.end(), time);
  if (upper == t.begin()) return y.front();
  if (upper == t.end()) return y.back();
  const std::size_t k = static_cast<std::size_t>(upper - t.begin());
  const double a = (time - t[k - 1]) / (t[k] - t[k - 1]);
  return y[k - 1] + a * (y[k] - y[k - 1]);
}

// Crossings are sign changes of v once |v| has passed a third of its largest value since the
// previous one (so that ringing about zero near a turning point counts once), each refined by a
// line fitted over +-T/16 of the expected period and kept only if that window lies in the run.
Swing measure_swing(const std::vector<double>& t, const std::vector<double>& v,
                    const std::vector<double>& u, double expected_period) {
  Swing swing;
  if (t.size() < 2) return swing;
  double largest = 0.0;
  for (double value : v)
    largest = std::max(largest, std::abs(value));
  const double threshold = largest / 3.0, half_window = expected_period / 16.0;
  int sign = 0;  // the sign of the last excursion past the threshold
  for (std::size_t k = 1; k < t.size(); ++k) {
    if (sign != 0 && v[k] * sign < 0.0 && v[k - 1] * sign >= 0.0) {
      const double a = v[k - 1] / (v[k - 1] - v[k]);
      const double estimate = t[k - 1] + a * (t[k] - t[k - 1]);
      if (estimate - half_window >= t.front() && estimate + half_window <= t.back()) {
        const double crossing = fitted_root(t, v, estimate, half_window);
        swing.crossings.push_back(crossing);
        swing.amplitudes.push_back(std::abs(interpolate(t, u, crossing)));
      }
      sign = 0;
    }
    if (std::abs(v[k]) > threshold && sign == 0) sign = v[k] > 0.0 ? 1 : -1;
  }
  const std::size_t m = swing.crossings.size();
  if (m < 3) return swing;  // a full period needs three crossings
  swing.period = 2.0 * (swing.crossings.back() - swing.crossings.front()) / double(m - 1);
  double mean_t = 0.0, mean_log = 0.0;
  for (std::size_t k = 0; k < m; ++k) {
    mean_t += swing.crossings[k] / double(m);
    mean_log += std::log(swing.amplitudes[k]) / double(m);
  }
  double stt = 0.0, stl = 0.0;
  for (std::size_t k = 0; k < m; ++k) {
    stt += std::pow(swing.crossings[k] - mean_t, 2);
    stl += (swing.crossings[k] - mean_t) * (std::log(swing.amplitudes[k]) - mean_log);
  }
  swing.decay = 1.0 - std::exp(stl / stt * swing.period);
  return swing;
}

struct Resolution {
  int cells = 0;  // across H
  std::filesystem::path run;
  std::vector<double> time, velocity, displacement;
  Swing swing;
};

}  // namespace

std::vector<CheckResult> validate_ld_cantilever_plate(const ValidationContext& context) {
  const CaseDescription bundled = load_bundled_case(context, "ld-cantilever-plate");
  const Plate plate = read_plate(bundled);
  const double omega = references::cantilever_plate_angular_frequency(plate.reference);
  const double period = references::cantilever_plate_period(plate.reference);
  const double c0 = references::cantilever_plate_velocity_scale(plate.reference);
  // Crossings at T/4 + k T/2: `periods` full periods, with the last fit window inside the run and
  // room for a period some per cent longer than the thin-plate one.
  const int periods = context.quick ? 1 : 3;
  const double end = (periods + 0.45) * period;
  const auto& cells = context.quick ? kQuickCells : kCells;

  std::vector<Resolution> runs;
  for (int n : cells) {
    std::vector<CaseOverride> overrides = {
        {"geometry.spacing", fmt::format("{:.17g}", plate.reference.thickness / n)},
        {"time.end", fmt::format("{:.17g}", end)},
        {"output.interval", fmt::format("{:.17g}", period / 20.0)},
        {"output.probe_interval", fmt::format("{:.17g}", period / 400.0)}};
    // Quick: a longer step; on the root's faces, compressed by about 10 %, C stays below 0.9.
    if (context.quick) overrides.push_back({"numerics.courant", "0.8"});
    CaseDescription description = load_bundled_case(context, "ld-cantilever-plate", overrides);
    add_tip_probe(description, plate);
    Resolution resolution;
    resolution.cells = n;
    resolution.run = run_for_validation(context, description, fmt::format("cells_{}", n));
    const ProbeTable probes = ProbeTable::read(resolution.run / "probes.csv");
    resolution.time = probes.time();
    resolution.velocity = probes.column(kTipGroup + ".velocity_y");
    resolution.displacement = probes.column(kTipGroup + ".displacement_y");
    resolution.swing =
        measure_swing(resolution.time, resolution.velocity, resolution.displacement, period);
    runs.push_back(std::move(resolution));
  }
  const Resolution& finest = runs.back();
  const Resolution& next = runs[runs.size() - 2];
  const double period_error = relative_error(finest.swing.period, period);
  const double period_change =
      std::abs(finest.swing.period - next.swing.period) / finest.swing.period;

  if (context.report) {
    std::string periods_text;
    for (const Resolution& r : runs)
      periods_text += fmt::format("{}{} s at H/{}", periods_text.empty() ? "" : ", ",
                                  fmt::format("{:.4f}", r.swing.period), r.cells);
    context.report->describe(fmt::format(
        "The oscillating cantilever plate of Gray, Monaghan & Swift (2001): a plate of free length "
        "L = {:g} m and thickness H = {:g} m (E = {:g} Pa, nu = {:g}, rho = {:g} kg/m3, plane "
        "strain), clamped into a fixed block, set swinging in its first bending mode with the tip "
        "at {:.4g} m/s (V_f = {:.3g} of c0 = sqrt(K/rho) = {:.4g} m/s), run with the "
        "large-deformation model for {} period(s) at three spacings. Thin-plate period {:.4f} s; "
        "measured (zero crossings of the tip velocity): {}. The swing reaches about L/2, so the "
        "period is expected a few per cent longer than the linear one (docs/theory.md 9.11).",
        plate.reference.length, plate.reference.thickness, plate.reference.young_modulus,
        plate.reference.poisson_ratio, plate.reference.density, plate.tip_velocity,
        plate.tip_velocity / c0, c0, periods, period, periods_text));
    Figure displacement{"tip_displacement", "Tip deflection", "time [s]", "u_y at the tip [m]", {}};
    Figure velocity{"tip_velocity", "Tip velocity", "time [s]", "v_y at the tip [m/s]", {}};
    for (const Resolution& r : runs) {
      const std::string label = fmt::format("SPH, H/{}", r.cells);
      displacement.series.push_back({label, r.time, r.displacement, "line"});
      velocity.series.push_back({label, r.time, r.velocity, "line"});
    }
    const double amplitude = plate.tip_velocity / omega;
    displacement.series.push_back(sample_curve("thin plate, linear", 0.0, end, 2000, [&](double t) {
      return amplitude * std::sin(omega * t);
    }));
    velocity.series.push_back(sample_curve("thin plate, linear", 0.0, end, 2000, [&](double t) {
      return plate.tip_velocity * std::cos(omega * t);
    }));
    context.report->add_figure(std::move(displacement));
    context.report->add_figure(std::move(velocity));
    const double deepest =
        finest.swing.crossings.empty() ? 0.25 * period : finest.swing.crossings.front();
    context.report->add_picture(
        {"stress_xx_swing", finest.run.string(), "stress", 0, deepest, 1.0,
         fmt::format("sigma_xx on the plate at its first largest deflection (t = {:.3f} s), H/{}",
                     deepest, finest.cells)});
  }
  return {
      check_at_most("period_error", period_error, 0.0, 0.03, "fraction"),
      check_at_most("period_change_finest", period_change, 0.0, 0.01, "fraction"),
      check_within("amplitude_decay_per_period", finest.swing.decay, 0.0, 0.02, "fraction"),
  };
}

}  // namespace rktsph::case_checks::ld_cantilever_plate
