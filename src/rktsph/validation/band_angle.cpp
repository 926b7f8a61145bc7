#include "rktsph/validation/band_angle.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "rktsph/core/error.hpp"
#include "rktsph/validation/rest_checks.hpp"

namespace rktsph {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
// The Gaussian smoothing of a projection is cut at this many standard deviations.
constexpr double kKernelReach = 4.0;
// The strip fitted around a ridge extends this factor beyond where the projected profile falls to
// a quarter of its peak: about 2.5 standard deviations of a Gaussian band, so that the slices hold
// nearly all of the band and the window barely truncates it.
constexpr double kQuarterPeakToStrip = 1.5;
// Slices lighter than this fraction of the median slice are ignored (a few stray points).
constexpr double kLightSliceFraction = 0.1;
constexpr int kMaxRefinements = 20;
constexpr double kConvergedSlope = 1e-6;

struct WeightedPoint {
  double x = 0.0;  // relative to the weighted centroid of the selected points
  double y = 0.0;
  double weight = 0.0;
};

struct Direction {
  double along_x, along_y;    // unit vector along the band
  double normal_x, normal_y;  // unit vector across it

  explicit Direction(double theta)
      : along_x(std::cos(theta)),
        along_y(std::sin(theta)),
        normal_x(-std::sin(theta)),
        normal_y(std::cos(theta)) {}
  double along(const WeightedPoint& p) const { return p.x * along_x + p.y * along_y; }
  double across(const WeightedPoint& p) const { return p.x * normal_x + p.y * normal_y; }
};

/// The selected points projected on a normal and smoothed with a Gaussian, on a fixed grid that
/// covers every direction (allocated once; the search only refills it).
class ProjectionProfile {
 public:
  ProjectionProfile(double radius, double smoothing)
      : smoothing_(smoothing),
        cell_(0.5 * smoothing),
        origin_(-(radius + kKernelReach * smoothing)),
        values_(static_cast<std::size_t>(std::ceil(-2.0 * origin_ / cell_)) + 1, 0.0) {}

  void build(const std::vector<WeightedPoint>& points, const Direction& direction) {
    std::fill(values_.begin(), values_.end(), 0.0);
    const double reach = kKernelReach * smoothing_;
    const double inverse_variance = 1.0 / (smoothing_ * smoothing_);
    const auto last = static_cast<std::ptrdiff_t>(values_.size()) - 1;
    for (const WeightedPoint& p : points) {
      const double s = direction.across(p);
      const auto first_cell = std::max<std::ptrdiff_t>(
          0, static_cast<std::ptrdiff_t>(std::ceil((s - reach - origin_) / cell_)));
      const auto last_cell = std::min<std::ptrdiff_t>(
          last, static_cast<std::ptrdiff_t>(std::floor((s + reach - origin_) / cell_)));
      for (std::ptrdiff_t c = first_cell; c <= last_cell; ++c) {
        const double offset = position(static_cast<std::size_t>(c)) - s;
        values_[static_cast<std::size_t>(c)] +=
            p.weight * std::exp(-0.5 * offset * offset * inverse_variance);
      }
    }
  }

  /// Integral of the squared profile: largest when the projection is most concentrated.
  double energy() const {
    double sum = 0.0;
    for (double v : values_)
      sum += v * v;
    return sum * cell_;
  }

  double position(std::size_t cell) const { return origin_ + static_cast<double>(cell) * cell_; }
  std::size_t peak_cell() const {
    return static_cast<std::size_t>(std::max_element(values_.begin(), values_.end()) -
                                    values_.begin());
  }

  /// Largest distance from the peak at which the profile first falls below a quarter of it.
  double quarter_peak_half_width(std::size_t peak) const {
    const double level = 0.25 * values_[peak];
    std::size_t right = peak, left = peak;
    while (right + 1 < values_.size() && values_[right] >= level)
      ++right;
    while (left > 0 && values_[left] >= level)
      --left;
    return cell_ * static_cast<double>(std::max(right - peak, peak - left));
  }

 private:
  double smoothing_;
  double cell_;
  double origin_;
  std::vector<double> values_;
};

double quantile(std::vector<double> values, double fraction) {
  const auto rank = static_cast<std::ptrdiff_t>(
      std::floor(std::clamp(fraction, 0.0, 1.0) * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + rank, values.end());
  return values[static_cast<std::size_t>(rank)];
}

double median(std::vector<double>& values) {
  const std::size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(middle),
                   values.end());
  const double upper = values[middle];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(),
                                          values.begin() + static_cast<std::ptrdiff_t>(middle)));
}

/// Weighted quantile of `keys` (the weights need not be normalised).
double weighted_quantile(std::vector<std::pair<double, double>> key_weight, double fraction) {
  std::sort(key_weight.begin(), key_weight.end());
  double total = 0.0;
  for (const auto& kw : key_weight)
    total += kw.second;
  double running = 0.0;
  for (const auto& kw : key_weight) {
    running += kw.second;
    if (running >= fraction * total) return kw.first;
  }
  return key_weight.back().first;
}

/// Maps an angle to (-90, 90] degrees (lines have no sense).
double line_angle_deg(double angle_deg) {
  double a = std::fmod(angle_deg, 180.0);
  if (a <= -90.0) a += 180.0;
  if (a > 90.0) a -= 180.0;
  return a;
}

struct Ridge {
  double theta = 0.0;   // direction of the band [rad]
  double offset = 0.0;  // its distance from the origin along the normal [m]
  double centre_along = 0.0;
  double half_width = 0.0;
  double strip_weight = 0.0;
  double rms = 0.0;
};

struct Slice {
  double along = 0.0;
  double across = 0.0;
  double weight = 0.0;
};

/// The weighted centre across the band of each slice of the central part of the strip
/// |across - offset| <= half_width. Returns the middle of the central part along the band.
double slice_centres(const std::vector<WeightedPoint>& points, const Direction& direction,
                     double offset, double half_width, double slice_width, double central_fraction,
                     std::vector<Slice>& slices, double& strip_weight) {
  std::vector<std::pair<double, double>> along_weight;
  strip_weight = 0.0;
  for (const WeightedPoint& p : points)
    if (std::abs(direction.across(p) - offset) <= half_width) {
      along_weight.emplace_back(direction.along(p), p.weight);
      strip_weight += p.weight;
    }
  slices.clear();
  if (along_weight.size() < 3) return 0.0;
  // The band's extent from weighted 2 % quantiles, so that stray points do not stretch it.
  const double start = weighted_quantile(along_weight, 0.02);
  const double end = weighted_quantile(along_weight, 0.98);
  const double trim = 0.5 * (1.0 - central_fraction) * (end - start);
  const double low = start + trim, high = end - trim;
  const auto count = static_cast<std::size_t>(std::max(1.0, std::ceil((high - low) / slice_width)));
  slices.assign(count, Slice{});
  for (const WeightedPoint& p : points) {
    const double along = direction.along(p), across = direction.across(p) - offset;
    if (std::abs(across) > half_width || along < low || along > high) continue;
    const auto k = std::min(count - 1, static_cast<std::size_t>((along - low) / slice_width));
    slices[k].along += p.weight * along;
    slices[k].across += p.weight * across;
    slices[k].weight += p.weight;
  }
  std::vector<double> weights;
  for (const Slice& s : slices)
    if (s.weight > 0.0) weights.push_back(s.weight);
  const double light = weights.empty() ? 0.0 : kLightSliceFraction * median(weights);
  std::erase_if(slices, [&](const Slice& s) { return s.weight <= light; });
  for (Slice& s : slices) {
    s.along /= s.weight;
    s.across /= s.weight;
  }
  return 0.5 * (low + high);
}

struct LineFit {
  double slope = 0.0;
  double intercept = 0.0;
  double rms = 0.0;
};

/// Theil–Sen line through the slice centres: across = intercept + slope * along.
LineFit theil_sen(const std::vector<Slice>& slices, double min_separation) {
  std::vector<double> slopes;
  for (std::size_t i = 0; i < slices.size(); ++i)
    for (std::size_t j = i + 1; j < slices.size(); ++j) {
      const double run = slices[j].along - slices[i].along;
      if (std::abs(run) >= min_separation)
        slopes.push_back((slices[j].across - slices[i].across) / run);
    }
  if (slopes.empty()) throw RunError("band angle: the band is too short to fit a ridge line");
  LineFit fit;
  fit.slope = median(slopes);
  std::vector<double> intercepts;
  for (const Slice& s : slices)
    intercepts.push_back(s.across - fit.slope * s.along);
  fit.intercept = median(intercepts);
  double sum = 0.0;
  for (const Slice& s : slices) {
    const double residual = s.across - fit.intercept - fit.slope * s.along;
    sum += residual * residual;
  }
  fit.rms =
      std::sqrt(sum / static_cast<double>(slices.size())) / std::sqrt(1.0 + fit.slope * fit.slope);
  return fit;
}

/// Fits the ridge of the band whose coarse direction is `theta`, iterating the slice fit until the
/// direction no longer changes.
Ridge fit_ridge(const std::vector<WeightedPoint>& points, ProjectionProfile& profile, double theta,
                double resolution, double central_fraction) {
  Ridge ridge;
  ridge.theta = theta;
  profile.build(points, Direction(theta));
  const std::size_t peak = profile.peak_cell();
  ridge.offset = profile.position(peak);
  ridge.half_width =
      std::max(kQuarterPeakToStrip * profile.quarter_peak_half_width(peak), 2.0 * resolution);
  std::vector<Slice> slices;
  for (int iteration = 0; iteration < kMaxRefinements; ++iteration) {
    const Direction direction(ridge.theta);
    const double middle = slice_centres(points, direction, ridge.offset, ridge.half_width,
                                        resolution, central_fraction, slices, ridge.strip_weight);
    if (slices.size() < 3) throw RunError("band angle: the band is too short to fit a ridge line");
    const LineFit fit = theil_sen(slices, resolution);
    // The fitted line passes through this point; re-express it in the turned frame.
    const double ridge_x = middle * direction.along_x +
                           (ridge.offset + fit.intercept + fit.slope * middle) * direction.normal_x;
    const double ridge_y = middle * direction.along_y +
                           (ridge.offset + fit.intercept + fit.slope * middle) * direction.normal_y;
    ridge.theta += std::atan(fit.slope);
    const Direction turned(ridge.theta);
    ridge.offset = ridge_x * turned.normal_x + ridge_y * turned.normal_y;
    ridge.centre_along = ridge_x * turned.along_x + ridge_y * turned.along_y;
    ridge.rms = fit.rms;
    if (std::abs(fit.slope) < kConvergedSlope) break;
  }
  return ridge;
}

BandLine describe(const Ridge& ridge, double axis_angle_deg, double total_weight, double centroid_x,
                  double centroid_y) {
  const Direction direction(ridge.theta);
  BandLine line;
  line.direction_deg = line_angle_deg(ridge.theta / kDegree - axis_angle_deg);
  line.angle_deg = std::abs(line.direction_deg);
  line.centre_x =
      centroid_x + ridge.centre_along * direction.along_x + ridge.offset * direction.normal_x;
  line.centre_y =
      centroid_y + ridge.centre_along * direction.along_y + ridge.offset * direction.normal_y;
  line.half_width = ridge.half_width;
  line.weight_fraction = ridge.strip_weight / total_weight;
  line.ridge_rms = ridge.rms;
  return line;
}

double angular_distance_deg(double a_deg, double b_deg) {
  return std::abs(line_angle_deg(a_deg - b_deg));
}

void check_inputs(std::span<const double> x, std::span<const double> y,
                  std::span<const double> value) {
  if (x.size() != y.size() || x.size() != value.size())
    throw std::invalid_argument("measure_band: x, y and value differ in size");
  if (x.size() < 3) throw std::invalid_argument("measure_band: fewer than 3 points");
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i]) || !std::isfinite(y[i]) || !std::isfinite(value[i]))
      throw std::invalid_argument("measure_band: a coordinate or value is not finite");
  // Collinear points have a singular covariance: its determinant vanishes against trace².
  double mean_x = 0.0, mean_y = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mean_x += x[i];
    mean_y += y[i];
  }
  mean_x /= static_cast<double>(x.size());
  mean_y /= static_cast<double>(x.size());
  double xx = 0.0, yy = 0.0, xy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    xx += (x[i] - mean_x) * (x[i] - mean_x);
    yy += (y[i] - mean_y) * (y[i] - mean_y);
    xy += (x[i] - mean_x) * (y[i] - mean_y);
  }
  if (!(xx * yy - xy * xy > 1e-12 * (xx + yy) * (xx + yy)))
    throw std::invalid_argument("measure_band: the points lie on one line");
}

double mean_spacing(std::span<const double> x, std::span<const double> y) {
  const auto [x_min, x_max] = std::minmax_element(x.begin(), x.end());
  const auto [y_min, y_max] = std::minmax_element(y.begin(), y.end());
  const double area = (*x_max - *x_min) * (*y_max - *y_min);
  return std::sqrt(area / static_cast<double>(x.size()));
}

}  // namespace

BandMeasurement measure_band(std::span<const double> x, std::span<const double> y,
                             std::span<const double> value, const BandAngleOptions& options) {
  check_inputs(x, y, value);
  const double resolution = options.resolution > 0.0 ? options.resolution : mean_spacing(x, y);

  BandMeasurement result;
  result.threshold =
      quantile(std::vector<double>(value.begin(), value.end()), options.threshold_quantile);
  std::vector<WeightedPoint> points;
  double total_weight = 0.0, centroid_x = 0.0, centroid_y = 0.0;
  for (std::size_t i = 0; i < value.size(); ++i)
    if (value[i] > result.threshold) {
      const double weight = value[i] - result.threshold;
      points.push_back({x[i], y[i], weight});
      total_weight += weight;
      centroid_x += weight * x[i];
      centroid_y += weight * y[i];
    }
  result.point_count = points.size();
  if (points.size() < 3)
    throw RunError("band angle: fewer than 3 points exceed the threshold (no band in the field)");
  centroid_x /= total_weight;
  centroid_y /= total_weight;
  double radius = 0.0;
  for (WeightedPoint& p : points) {
    p.x -= centroid_x;
    p.y -= centroid_y;
    radius = std::max(radius, std::hypot(p.x, p.y));
  }

  // Search over directions in [0, 180) degrees.
  ProjectionProfile profile(radius, resolution);
  const auto direction_count =
      static_cast<std::size_t>(std::max(4.0, std::round(180.0 / options.search_step_deg)));
  const double step = 180.0 / static_cast<double>(direction_count);
  std::vector<double> energy(direction_count);
  for (std::size_t k = 0; k < direction_count; ++k) {
    profile.build(points, Direction(static_cast<double>(k) * step * kDegree));
    energy[k] = profile.energy();
  }
  const std::size_t best =
      static_cast<std::size_t>(std::max_element(energy.begin(), energy.end()) - energy.begin());

  const double axis_angle_deg = std::atan2(options.axis_y, options.axis_x) / kDegree;
  const Ridge primary = fit_ridge(points, profile, static_cast<double>(best) * step * kDegree,
                                  resolution, options.central_fraction);
  result.primary = describe(primary, axis_angle_deg, total_weight, centroid_x, centroid_y);

  // A second band: the strongest local maximum of the energy well away from the first band.
  std::optional<std::size_t> second;
  for (std::size_t k = 0; k < direction_count; ++k) {
    const double previous = energy[(k + direction_count - 1) % direction_count];
    const double next = energy[(k + 1) % direction_count];
    const bool local_maximum = energy[k] >= previous && energy[k] >= next;
    const bool distinct =
        angular_distance_deg(static_cast<double>(k) * step, primary.theta / kDegree) >=
        options.secondary_separation_deg;
    if (local_maximum && distinct && (!second || energy[k] > energy[*second])) second = k;
  }
  if (second && energy[*second] >= options.secondary_min_strength * energy[best]) {
    const Ridge other = fit_ridge(points, profile, static_cast<double>(*second) * step * kDegree,
                                  resolution, options.central_fraction);
    if (angular_distance_deg(other.theta / kDegree, primary.theta / kDegree) >=
        options.secondary_separation_deg) {
      result.secondary = describe(other, axis_angle_deg, total_weight, centroid_x, centroid_y);
      result.secondary->strength = energy[*second] / energy[best];
    }
  }
  return result;
}

double distance_to_band(const BandLine& line, double x, double y) {
  // The band direction is the reference (vertical) axis turned by direction_deg counter-clockwise.
  const double turn = line.direction_deg * std::numbers::pi / 180.0;
  const double along_x = -std::sin(turn), along_y = std::cos(turn);
  return std::abs((x - line.centre_x) * along_y - (y - line.centre_y) * along_x);
}

std::vector<std::pair<double, double>> band_row_centres(const NodeSets& nodes,
                                                        std::span<const double> strain,
                                                        double threshold, double y_low,
                                                        double y_high, double x_min) {
  const LatticeView view = lattice_view(nodes);
  const auto rows = static_cast<std::size_t>(view.rows);
  std::vector<double> weight(rows, 0.0), moment(rows, 0.0);
  for (std::size_t k = 0; k < nodes.sph_nodes.size(); ++k) {
    const double x = view.origin_x + static_cast<double>(view.index[k][0]) * nodes.spacing;
    if (x < x_min || strain[k] <= threshold) continue;
    const auto row = static_cast<std::size_t>(view.index[k][1]);
    weight[row] += strain[k] - threshold;
    moment[row] += (strain[k] - threshold) * x;
  }
  std::vector<std::pair<double, double>> centres;
  for (std::size_t row = 0; row < rows; ++row) {
    const double y = view.origin_y + static_cast<double>(row) * nodes.spacing;
    if (y < y_low - 1e-9 || y > y_high + 1e-9 || weight[row] <= 0.0) continue;
    centres.emplace_back(moment[row] / weight[row], y);
  }
  return centres;
}

}  // namespace rktsph
