// The amplitude of a plane P-wave after its reflections (docs/theory.md §2.4, issue 28):
// a bar driven by a piston (v = V0) at one end, free at the other, on rollers at its sides, in
// uniaxial strain: the exact solution has sigma = -rho c_p V0 behind the first front, sigma = 0
// after the free-face reflection and the tension plateau +rho c_p V0 at mid-bar from 2.5 L/c_p.
// The plateau error is measured as BAR-WAVE-2D does (docs/theory.md §8.11): the mean over
// 2.75-2.95 L/c_p of the mid-bar column's sigma_aa against +rho c_p V0. That window lies
// 0.25-0.45 L behind the front, so on a coarse bar it still holds the front's dispersive tail (the
// ringing of a step). To tell what the faces do from what the front carries, the same error is
// measured on a front that met no face: a bar three times as long, read at 2.5 L from the piston
// over the same window, against -rho c_p V0. The two differ by what the free face and the piston
// do to the plateau.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::wave_amplitude_test {
namespace {

constexpr double kDensity = 2000.0, kYoung = 1.5e8, kPoisson = 0.25, kPiston = 0.3;

struct Bar {
  int cells = 60;             // along the bar, from the piston to the free face
  double spacing = 0.01;      // dx [m]
  double courant = 0.5;       // C
  double viscosity = 0.0;     // alpha of the artificial viscosity
  bool plane_stress = false;  // plane strain otherwise
  int axis = 0;               // 0: along x, 1: along y
  std::string update = "mean_velocity";
};

/// The P-wave speed of the bar in uniaxial strain (in the plane): lambda + 2G, or E/(1 - nu^2).
double wave_speed(bool plane_stress) {
  const double modulus =
      plane_stress ? kYoung / (1.0 - kPoisson * kPoisson)
                   : kYoung * (1.0 - kPoisson) / ((1.0 + kPoisson) * (1.0 - 2.0 * kPoisson));
  return std::sqrt(modulus / kDensity);
}

/// The stable Courant limit without and with the viscosity (docs/theory.md §2.5).
double largest_courant(double viscosity) {
  return std::sqrt(1.0 + viscosity * viscosity) - viscosity;
}

/// Relative error of the mid-column plateau over 2.75-2.95 L/c_p. `length_factor` 1: the reflected
/// tension plateau at L/2, against +rho c_p V0; 3: the unreflected compression at 2.5 L from the
/// piston of a bar 3 L long, against -rho c_p V0.
double plateau_error(const Bar& bar, int length_factor) {
  const double dx = bar.spacing, length = bar.cells * dx, width = 2.0 * dx;
  const double extent = length_factor * length;
  const double probe = length_factor == 1 ? 0.5 * length : 2.5 * length;
  const double c = wave_speed(bar.plane_stress), transit = length / c;
  const char* const along = bar.axis == 0 ? "x" : "y";
  const char* const across = bar.axis == 0 ? "y" : "x";
  const std::string rectangle =
      bar.axis == 0 ? fmt::format("{{min: [0, 0], max: [{:.17g}, {:.17g}]}}", extent, width)
                    : fmt::format("{{min: [0, 0], max: [{:.17g}, {:.17g}]}}", width, extent);
  const std::string text = fmt::format(
      R"(
name: wave-amplitude
dimension: 2
plane: {}
geometry:
  spacing: {:.17g}
  shapes: [{{rectangle: {}, material: solid}}]
materials:
  solid: {{model: linear_elastic, density: {}, young_modulus: {}, poisson_ratio: {}}}
boundary_conditions:
  - {{group: {}min, velocity: {{{}: {}, {}: 0.0}}}}
  - {{group: {}min, roller: {}}}
  - {{group: {}max, roller: {}}}
numerics: {{courant: {:.17g}, artificial_viscosity: {}, stress_update: {}}}
time: {{end: {:.17g}}}
)",
      bar.plane_stress ? "stress" : "strain", dx, rectangle, kDensity, kYoung, kPoisson, along,
      along, kPiston, across, across, across, across, across, bar.courant, bar.viscosity,
      bar.update, 3.0 * transit);
  Simulation simulation(read_case_text(text, "wave-amplitude.yaml"));
  const NodeSets& nodes = simulation.nodes();
  std::vector<std::size_t> column;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i)
    if (std::abs(nodes.sph_nodes.position[static_cast<std::size_t>(bar.axis)][i] - probe) <
        0.25 * dx)
      column.push_back(i);
  EXPECT_EQ(column.size(), 3u);
  const int stress = simulation.model().stress_field(bar.axis, bar.axis);
  const double dt = simulation.time_step();
  // The window in steps, so that which samples it holds does not depend on rounding.
  const long first = std::lround(std::ceil(2.75 * transit / dt - 1e-9));
  const long last = std::lround(std::floor(2.95 * transit / dt + 1e-9));
  double sum = 0.0;
  for (long s = 1; s <= last; ++s) {
    simulation.step().advance(simulation.state(), dt);
    if (s < first) continue;
    double mean = 0.0;
    for (std::size_t i : column)
      mean += simulation.state().fields(stress, i);
    sum += mean / static_cast<double>(column.size());
  }
  const double plateau = sum / static_cast<double>(last - first + 1);
  const double exact = (length_factor == 1 ? 1.0 : -1.0) * kDensity * c * kPiston;
  return plateau / exact - 1.0;
}

struct Measured {
  double reflected = 0.0, unreflected = 0.0;
};

Measured measure(const Bar& bar) {
  return {plateau_error(bar, 1), plateau_error(bar, 3)};
}

/// Every combination the issue names: C in {0.1, 0.25, 0.5, the limit}, with and without the
/// viscosity, plane strain and plane stress, along x and along y.
std::vector<Bar> every_bar(int cells, double spacing) {
  std::vector<Bar> bars;
  for (bool plane_stress : {false, true})
    for (int axis : {0, 1})
      for (double viscosity : {0.0, 0.25})
        for (double courant : {0.1, 0.25, 0.5, largest_courant(viscosity)}) {
          Bar bar;
          bar.cells = cells;
          bar.spacing = spacing;
          bar.courant = courant;
          bar.viscosity = viscosity;
          bar.plane_stress = plane_stress;
          bar.axis = axis;
          bars.push_back(bar);
        }
  return bars;
}

// What the two faces may change in the plateau: measured at most 0.11 % (C = 0.1, 60 cells) for
// either update; a quarter of a per cent is the round value above it, an eighth of BAR-WAVE-2D's
// 2 % tolerance on the tension plateau.
constexpr double kFaceTolerance = 0.0025;

void expect_faces_keep_the_plateau(const Bar& bar, const Measured& m) {
  EXPECT_NEAR(m.reflected, m.unreflected, kFaceTolerance)
      << bar.update << " C = " << bar.courant << " alpha = " << bar.viscosity
      << (bar.plane_stress ? " plane stress" : " plane strain") << " along "
      << (bar.axis == 0 ? "x" : "y");
}

/// The criterion where it holds (with the viscosity), and the faces' share everywhere: see
/// docs/theory.md §2.4 for why no update whose nodal strain is a fixed function of u (§3.4) can be
/// as close as the half-step update to rho c_p V0 without the viscosity at C = 1.
std::pair<Measured, Measured> check_both_updates(Bar bar) {
  bar.update = "half_step";
  const Measured half = measure(bar);
  expect_faces_keep_the_plateau(bar, half);
  bar.update = "mean_velocity";
  const Measured mean = measure(bar);
  expect_faces_keep_the_plateau(bar, mean);
  // With the viscosity (docs/theory.md §2.7) the front carries no ringing into the window: the
  // default is as close to rho c_p V0 as the half-step update, to the faces' tolerance (measured
  // excess at most 0.18 %, at C = 0.5, and the same on the front that met no face: it is the
  // interior's), and both are within 0.5 %.
  if (bar.viscosity > 0.0) {
    EXPECT_LE(std::abs(mean.reflected), std::abs(half.reflected) + kFaceTolerance)
        << "C = " << bar.courant;
    EXPECT_LT(std::abs(mean.reflected), 0.005) << "C = " << bar.courant;
    EXPECT_LT(std::abs(half.reflected), 0.005) << "C = " << bar.courant;
  }
  return {half, mean};
}

TEST(WaveAmplitudeSlow, FacesKeepThePlateauAndTheDefaultIsAsCloseAsTheHalfStepUpdateWithViscosity) {
  // A cheap subset of the slow test below: 60 cells; the limit along x in plane strain, C = 0.25
  // along y in plane stress; with and without the viscosity.
  for (double viscosity : {0.0, 0.25}) {
    Bar bar;
    bar.viscosity = viscosity;
    bar.courant = largest_courant(viscosity);
    check_both_updates(bar);
    bar.courant = 0.25;
    bar.plane_stress = true;
    bar.axis = 1;
    check_both_updates(bar);
  }
}

TEST(WaveAmplitudeSlow, ReflectedPlateauOfBothUpdatesOnEveryCombination) {
  // Prints the table of docs/theory.md §2.4.
  std::printf("plane  axis alpha C      | half_step refl. unrefl. | mean_velocity refl. unrefl.\n");
  for (const Bar& bar : every_bar(60, 0.01)) {
    const auto [half, mean] = check_both_updates(bar);
    std::printf("%-6s %-4s %.2f  %.4f | %+7.3f %% %+7.3f %% | %+7.3f %% %+7.3f %%\n",
                bar.plane_stress ? "stress" : "strain", bar.axis == 0 ? "x" : "y", bar.viscosity,
                bar.courant, 100.0 * half.reflected, 100.0 * half.unreflected,
                100.0 * mean.reflected, 100.0 * mean.unreflected);
  }
}

TEST(WaveAmplitudeSlow, PlateauWithoutViscosityApproachesTheImpedanceTimesThePistonSpeed) {
  // Without the viscosity the 60-cell errors above (up to 2 %) are the front's ringing, which the
  // window still holds 15-27 cells behind the front; on 240 cells it is 60-108 cells behind and
  // both updates are within a quarter of a per cent at every C (measured at most 0.13 %).
  for (const std::string update : {"mean_velocity", "half_step"})
    for (double courant : {0.1, 0.25, 0.5, largest_courant(0.0)}) {
      Bar bar;
      bar.cells = 240;
      bar.spacing = 0.0025;
      bar.courant = courant;
      bar.update = update;
      const double error = plateau_error(bar, 1);
      std::printf("240 cells, %s, C = %.4f: %+7.3f %%\n", update.c_str(), courant, 100.0 * error);
      EXPECT_LT(std::abs(error), kFaceTolerance) << update << " C = " << courant;
    }
}

}  // namespace
}  // namespace rktsph::wave_amplitude_test
