// Orientation of a shear band from a scalar field on scattered points (typically the equivalent
// viscoplastic strain on the SPH nodes), for the localisation cases (docs/theory.md §8.4).
//
// Method. The points whose value is above a quantile of the field take part, weighted by their
// excess over it. A Radon-type search over directions projects them on the normal of each
// direction, smooths the projection with a Gaussian one point spacing wide (which removes the
// preference of a lattice for its own directions) and takes the direction whose projection is
// most concentrated (largest integral of the squared profile). That direction is then refined by
// fitting the ridge of the band: the points in a strip around the line are cut into slices along
// it, the weighted centre of each slice is found across the band, and a Theil–Sen line (median of
// pairwise slopes, robust to the slices a crossing band contaminates) goes through the centres.
// Only the central part of the band is fitted: where a sample edge cuts the band obliquely the
// slices are truncated on one side, and a whole-strip fit (principal axes, or the Radon maximum
// alone) is tilted by about (width/length)² radians.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "rktsph/geometry/node_sets.hpp"

namespace rktsph {

struct BandAngleOptions {
  /// Points whose value exceeds this quantile of the field take part, weighted by the excess.
  double threshold_quantile = 0.8;
  /// The axis angles are measured from (any length). Default: the vertical (loading) axis.
  double axis_x = 0.0;
  double axis_y = 1.0;
  /// Smoothing length of the projections and width of the slices along the band [m]; 0: the mean
  /// point spacing sqrt(bounding-box area / point count).
  double resolution = 0.0;
  /// Angular step of the search over directions [deg]; the ridge fit refines below it.
  double search_step_deg = 0.5;
  /// Centred fraction of the band's length used by the ridge fit.
  double central_fraction = 0.7;
  /// A second band is reported if its direction differs from the first by at least this much and
  /// its projection energy is at least `secondary_min_strength` times the first one's.
  double secondary_separation_deg = 20.0;
  double secondary_min_strength = 0.3;
};

/// One band: a straight ridge line of the field.
struct BandLine {
  /// Acute angle between the band and the axis, in [0, 90] degrees.
  double angle_deg = 0.0;
  /// Angle from the axis to the band direction, counter-clockwise positive, in (-90, 90] degrees
  /// (for the vertical axis: positive when the band rises to the left).
  double direction_deg = 0.0;
  /// A point of the fitted ridge line, at the middle of the fitted part [m].
  double centre_x = 0.0;
  double centre_y = 0.0;
  /// Half-width of the strip around the ridge that was fitted [m].
  double half_width = 0.0;
  /// Share of the total excess weight inside that strip: about 1 for a single clean band, about
  /// 1/2 for each band of a symmetric cross, small for a field with no band.
  double weight_fraction = 0.0;
  /// RMS distance of the slice centres from the fitted line [m]: small for a straight band.
  double ridge_rms = 0.0;
  /// Projection energy in this band's direction over that of the primary band (1 for it).
  double strength = 1.0;
};

struct BandMeasurement {
  BandLine primary;                   ///< the dominant band
  std::optional<BandLine> secondary;  ///< a second, distinct band (e.g. the other arm of an X)
  double threshold = 0.0;             ///< field value at the threshold quantile
  std::size_t point_count = 0;        ///< points above the threshold
};

/// Measures the dominant band of `value` given at the points (x[i], y[i]).
/// std::invalid_argument for inputs of different sizes, fewer than 3 points, non-finite values or
/// points all on one line; RunError if no point exceeds the threshold (a uniform field) or the
/// band is too short to fit.
BandMeasurement measure_band(std::span<const double> x, std::span<const double> y,
                             std::span<const double> value, const BandAngleOptions& options = {});

/// Distance [m] from the point (x, y) to the centre line of `line`.
double distance_to_band(const BandLine& line, double x, double y);

/// Centre of the band on each lattice row of `nodes` with y in [y_low, y_high]: the mean x of the
/// row's nodes with x >= x_min, weighted by the excess of `strain` over `threshold` (as
/// measure_band weights them). Rows without such excess are left out. (x, y) pairs, bottom to top.
std::vector<std::pair<double, double>> band_row_centres(
    const NodeSets& nodes, std::span<const double> strain, double threshold, double y_low,
    double y_high, double x_min = -std::numeric_limits<double>::infinity());

}  // namespace rktsph
