// Helpers shared by the validation cases: load a bundled case (with the quick variant's
// overrides), run it into the validation output folder, and read its probe histories back.
#pragma once

#include <cmath>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/simulation/simulation.hpp"
#include "rktsph/validation/band_angle.hpp"
#include "rktsph/validation/rest_checks.hpp"
#include "rktsph/validation/validation_case.hpp"

namespace rktsph {

/// probes.csv as columns.
class ProbeTable {
 public:
  static ProbeTable read(const std::filesystem::path& path);
  const std::vector<double>& column(const std::string& name) const;
  const std::vector<double>& time() const { return column("time"); }

  /// Mean, maximum and maximum magnitude of a column over times in [t0, t1].
  double mean(const std::string& name, double t0, double t1) const;
  double max(const std::string& name, double t0, double t1) const;
  double max_abs(const std::string& name, double t0, double t1) const;
  double rms(const std::string& name, double t0, double t1) const;
  /// First time the column crosses `level` (linear interpolation between samples), or NaN.
  double first_crossing(const std::string& name, double level) const;
  /// Arrival time of a step from 0 to `plateau` within [t0, t1], from the area under the
  /// normalised history: t_arrival = t1 - integral(value / plateau). Exact for a sharp step,
  /// insensitive to sampling and to ringing that averages out.
  double step_arrival(const std::string& name, double plateau, double t0, double t1) const;

 private:
  std::vector<std::string> names_;
  std::vector<std::vector<double>> columns_;
};

/// cases/<folder>/case.yaml with context.overrides, then `overrides`, applied.
CaseDescription load_bundled_case(const ValidationContext& context, const std::string& folder,
                                  const std::vector<CaseOverride>& overrides = {});

/// Runs `description` into <output>/<case>/<label>; throws RunError if it does not complete.
/// `inspect` sees the finished simulation; `observers` (e.g. a SampledObserver or a
/// SpeedRecorder's) watch the loop while it runs.
std::filesystem::path run_for_validation(const ValidationContext& context,
                                         const CaseDescription& description,
                                         const std::string& label,
                                         const std::function<void(const Simulation&)>& inspect = {},
                                         const std::vector<Observer*>& observers = {});

/// A run that may stop early (a diverged or failed run keeps its last good output and probes).
struct ValidationRun {
  std::filesystem::path directory;
  bool completed = false;
  std::string message;  ///< why it stopped, when it did not complete
};

/// As run_for_validation, but a run that does not complete is returned, not thrown: for the cases
/// that check how far a run gets (a settlement reached) and read the rest from what it wrote.
ValidationRun run_allowing_failure(const ValidationContext& context,
                                   const CaseDescription& description, const std::string& label,
                                   const std::function<void(const Simulation&)>& inspect = {},
                                   const std::vector<Observer*>& observers = {});

/// A numeric parameter of a material block of the case; RunError if it is absent.
double material_parameter(const CaseDescription& description, const std::string& material,
                          const std::string& key);

/// An axis-aligned rectangle of the x-y plane [m].
struct Rectangle {
  double x_min = 0.0, y_min = 0.0, x_max = 0.0, y_max = 0.0;
  double width() const { return x_max - x_min; }
  double height() const { return y_max - y_min; }
};

/// The shape `index` of the case's geometry, which must be a rectangle, or a polygon that draws
/// one (every vertex on the sides of its bounding box, its area the box's: a rectangle with more
/// vertices on its sides, for a triangle mesh); RunError otherwise.
Rectangle rectangle_shape(const CaseDescription& description, std::size_t index);

/// The box of the group `name`; RunError if the case has no such group or it is not a box.
Rectangle group_box(const CaseDescription& description, const std::string& name);

/// The point of the point group `name`; RunError if the case has no such point group.
Vec3 group_point(const CaseDescription& description, const std::string& name);

/// g of the case's gravity, which must point down (0, -g); RunError if there is none.
double downward_gravity(const CaseDescription& description);

/// The time function of component `axis` of the velocity or traction (`traction` true) imposed
/// on the group `group`; RunError if the case imposes none.
const TimeFunction& imposed_on(const CaseDescription& description, const std::string& group,
                               int axis, bool traction);

/// The value a ramped or stepped load settles at (`value` of a constant, step or ramp, the last
/// point of a table); RunError for a harmonic function, which settles at none.
double final_value(const TimeFunction& function, const std::string& what);

/// The footing of a footing case: the box group `footing`, one lattice row on the top of the body
/// (the first shape, a rectangle), either from the symmetry plane x = 0 of a half model (the left
/// side of the body) or flush with the crest of a cut (its right end on the right side, the cut
/// face). RunError if the case does not have that shape.
enum class FootingPlace { SymmetryPlane, Crest };
struct FootingRow {
  Rectangle body;
  double left = 0.0, right = 0.0;  // x of the box's ends [m]
  double surface = 0.0;            // y of the row, the top of the body [m]
  double length() const { return right - left; }
};
FootingRow footing_row(const CaseDescription& description, FootingPlace place);

/// A rigid footing pushed into a half model about x = 0 (the large-deformation footing cases):
/// cases/<folder>/case.yaml (geometry.spacing = quick_spacing in a quick run), its footing row from
/// the symmetry plane to the edge at B/2, the width B and the number of footing nodes.
struct HalfModelFooting {
  CaseDescription description;
  FootingRow row;
  double width = 0.0;  ///< B [m]
  int nodes = 0;       ///< on the row, both ends included
};
HalfModelFooting half_model_footing(const ValidationContext& context, const std::string& folder,
                                    double quick_spacing);

/// The flexible strip load of a half model about x = 0 (the elastic strip footing cases): the
/// traction -q(t) on the row `footing` from the symmetry plane to x = b, which acts on the facets
/// within it, so that the load sums to q b (docs/theory.md §5.1). RunError otherwise.
struct StripLoad {
  FootingRow row;
  double pressure = 0.0;                  // q, the held load [Pa]
  double half_width = 0.0;                // b [m]
  const TimeFunction* history = nullptr;  // -q(t) on the row, in the description read
};
StripLoad read_strip_load(const CaseDescription& description);

/// The weak zone of a localisation case: the second shape, a rectangle of another material than
/// the first (the later shape wins where they overlap); RunError otherwise.
struct WeakZone {
  Rectangle box;
  double centre_x() const { return 0.5 * (box.x_min + box.x_max); }
  double centre_y() const { return 0.5 * (box.y_min + box.y_max); }
  double half_diagonal() const { return 0.5 * std::hypot(box.width(), box.height()); }
};
WeakZone read_weak_zone(const CaseDescription& description);

/// The saturated column of the v-pw cases, read back from the case file so that a reference uses
/// exactly its numbers: the first shape (a rectangle from vertex 0 to vertex 1), the material
/// "soil" and the pore fluid.
struct SaturatedColumn {
  double base = 0.0, height = 0.0;  // y of the base, height of the column
  double x_min = 0.0, x_max = 0.0;  // lateral extent
  double spacing = 0.0;             // dx
  double oedometric_modulus = 0.0;  // M = E (1 - nu) / ((1 + nu)(1 - 2 nu)) of the soil
  double biot_modulus = 0.0;        // Q = K_w / n
};

/// RunError naming cases/<folder> if the case has no pore fluid.
SaturatedColumn read_saturated_column(const CaseDescription& description,
                                      const std::string& folder);

/// Adds, for each of `rows` lattice rows at y0, y0 + spacing, ..., a group "<prefix><row>" (a box
/// from x_min to x_max, +- spacing/4 in y) and a probe of the mean of `field` over it, named like
/// the group. Returns the heights of the rows.
std::vector<double> add_row_probes(CaseDescription& description, const std::string& prefix,
                                   double x_min, double x_max, double y0, double spacing, int rows,
                                   const std::string& field);

/// The report series of a band measurement (the localisation cases): the band centre on each
/// lattice row as points, as band_row_centres gives them.
Series band_centre_series(const std::vector<std::pair<double, double>>& centres);

/// A straight line x = x0 + (y - y0) tan(angle_deg) for y in [y_low, y_high]: angle_deg from the
/// vertical, positive when the line leans to the right going up.
Series line_from_vertical(std::string label, double x0, double y0, double angle_deg, double y_low,
                          double y_high, std::string style);

/// The ridge line `line` fitted by a band check, drawn for y in [y_low, y_high].
Series band_ridge_series(const BandLine& line, double y_low, double y_high);

/// |a/b - 1|
double relative_error(double value, double reference);

/// The SPH-node values of the model's internal variable `name` (e.g. "eps_vp") at the current
/// state; throws RunError naming `case_name` if the model has no such variable.
/// A footing pushed into the ground, from a run's probes: its pressure, the footing group's mean
/// of `stress` over its `node_count` lattice-spaced nodes with trapezoidal weights (the probes
/// `end_a` and `end_b` of its two end nodes count half), sign-flipped to compression positive, and
/// its settlement, minus the group's mean u_y. Probe columns: footing.<stress>,
/// footing.displacement_y, <end_a>.<stress>, <end_b>.<stress>.
struct FootingHistory {
  std::vector<double> time, settlement, pressure;  // [s], [m], [Pa]
  std::filesystem::path directory;
};
FootingHistory read_footing_history(const std::filesystem::path& directory, int node_count,
                                    const std::string& stress, const std::string& end_a,
                                    const std::string& end_b);

/// A report series (line) of a footing's pressure in kPa against its settlement over `width`.
Series footing_pressure_series(std::string label, const FootingHistory& history, double width);
/// The second resolution of a footing case's report: cases/<folder> run again at `spacing`
/// without field output (label "coarse"; a run that stops early is read as far as it got), its
/// footing history read as read_footing_history reads it, over the round(length/spacing) + 1
/// nodes of a footing of `length` in the model.
FootingHistory run_coarse_footing(const ValidationContext& context, const std::string& folder,
                                  double spacing, double length, const std::string& stress,
                                  const std::string& end_a, const std::string& end_b);
/// The shear band of eps_vp (measure_band with the default options) over the SPH nodes whose
/// reference position has x >= x_min and y >= y_min: the material band of a mechanism.
BandMeasurement measure_band_in_region(const Simulation& simulation, const std::string& case_name,
                                       double x_min, double y_min);

std::span<const double> internal_variable(const Simulation& simulation, const std::string& name,
                                          const std::string& case_name);

}  // namespace rktsph
