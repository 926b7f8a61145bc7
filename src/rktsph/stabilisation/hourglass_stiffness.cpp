#include "rktsph/stabilisation/hourglass_stiffness.hpp"

#include <fmt/format.h>

#include "rktsph/core/error.hpp"
#include "rktsph/core/parallel.hpp"
#include "rktsph/physics/physics_model.hpp"

namespace rktsph {

namespace {

constexpr std::array<double, 4> kHourglass = {1.0, -1.0, 1.0, -1.0};

struct CellGeometry {
  double area = 0.0;
  std::array<double, 4> gamma{};
  double gradient_norm = 0.0;  // sum_a |b_a|^2
};

// Area, hourglass vector (eq. 3.2) and sum of |b_a|^2 of the quadrilateral with corners (x, y),
// counter-clockwise; b = gradient of the bilinear shape functions at the centroid (Flanagan and
// Belytschko 1981).
CellGeometry cell_geometry(const std::array<double, 4>& x, const std::array<double, 4>& y) {
  CellGeometry cell;
  cell.area = 0.5 * ((x[2] - x[0]) * (y[3] - y[1]) - (x[3] - x[1]) * (y[2] - y[0]));
  const double scale = 1.0 / (2.0 * cell.area);
  const std::array<double, 4> bx = {scale * (y[1] - y[3]), scale * (y[2] - y[0]),
                                    scale * (y[3] - y[1]), scale * (y[0] - y[2])};
  const std::array<double, 4> by = {scale * (x[3] - x[1]), scale * (x[0] - x[2]),
                                    scale * (x[1] - x[3]), scale * (x[2] - x[0])};
  double hx = 0.0, hy = 0.0;
  for (int a = 0; a < 4; ++a) {
    hx += kHourglass[a] * x[a];
    hy += kHourglass[a] * y[a];
  }
  for (int a = 0; a < 4; ++a) {
    cell.gamma[a] = kHourglass[a] - hx * bx[a] - hy * by[a];
    cell.gradient_norm += bx[a] * bx[a] + by[a] * by[a];
  }
  return cell;
}

}  // namespace

HourglassStiffness build_hourglass_stiffness(const NodeSets& nodes, const PhysicsModel& model,
                                             HourglassStrength epsilon) {
  HourglassStiffness control;
  if (nodes.dimension != 2 || !epsilon.active()) return control;
  const std::size_t cells = nodes.stress_points.size();
  const std::size_t count = nodes.sph_nodes.size();
  control.corners.resize(cells);
  control.gamma.resize(cells);
  control.stiffness.resize(cells);
  control.near_flow.resize(cells);
  std::vector<double> volume(count, 0.0);
  std::vector<std::int32_t> incidence(count + 1, 0);
  const CellComplex& complex = nodes.cells;
  for (std::size_t p = 0; p < cells; ++p) {
    if (complex.kind(p) != CellKind::Quadrilateral)
      throw RunError(fmt::format(
          "the cell of the stress point at {} is a {}: the Flanagan-Belytschko hourglass "
          "stiffness needs quadrilaterals; set numerics.hourglass.stiffness: 0 (its default on "
          "triangles)",
          describe_point(nodes.stress_points, p), kind_name(complex.kind(p))));
    std::array<double, 4> x{}, y{};
    const auto corners = complex.corners(p);
    for (std::size_t a = 0; a < 4; ++a) {
      const std::int32_t node = corners[a];
      control.corners[p][a] = node;
      x[a] = nodes.sph_nodes.position[0][static_cast<std::size_t>(node)];
      y[a] = nodes.sph_nodes.position[1][static_cast<std::size_t>(node)];
    }
    const CellGeometry cell = cell_geometry(x, y);
    control.gamma[p] = cell.gamma;
    const std::int32_t material = nodes.cells.material(p);
    const auto moduli = model.in_plane_moduli(material);
    // Every cell has the elastic strength while it and its neighbours do not flow (eq. 3.10).
    const double fraction = epsilon.elastic > 0.0 ? epsilon.elastic : epsilon.viscoplastic;
    control.stiffness[p] =
        fraction * (moduli[0] + moduli[2]) * cell.area * cell.gradient_norm / 24.0;
    control.near_flow[p] = model.elastic(material) ? 1.0 : epsilon.viscoplastic / fraction;
    for (std::int32_t node : control.corners[p]) {
      volume[static_cast<std::size_t>(node)] += 0.25 * cell.area;
      ++incidence[static_cast<std::size_t>(node) + 1];
    }
  }
  control.inverse_mass.assign(count, 0.0);
  for (std::size_t n = 0; n < count; ++n)
    if (volume[n] > 0.0)
      control.inverse_mass[n] = 1.0 / (model.density(nodes.node_material[n]) * volume[n]);
  // Node -> (cell, corner) lists by a counting sort.
  for (std::size_t n = 0; n < count; ++n)
    incidence[n + 1] += incidence[n];
  control.node_start = incidence;
  control.cell_of.resize(static_cast<std::size_t>(incidence[count]));
  control.corner_of.resize(control.cell_of.size());
  for (std::size_t p = 0; p < cells; ++p)
    for (int a = 0; a < 4; ++a) {
      const auto slot = static_cast<std::size_t>(incidence[control.corners[p][a]]++);
      control.cell_of[slot] = static_cast<std::int32_t>(p);
      control.corner_of[slot] = static_cast<std::uint8_t>(a);
    }
  return control;
}

void advance_hourglass_force(const HourglassStiffness& control, const FieldArray& fields,
                             const std::array<int, 2>& velocity_field, double interval,
                             std::span<const double> factor, const FieldArray& force_in,
                             FieldArray& force_out) {
  const auto cells = static_cast<std::int64_t>(control.corners.size());
  const double* vx = fields.field(velocity_field[0]);
  const double* vy = fields.field(velocity_field[1]);
  const double* in_x = force_in.field(0);
  const double* in_y = force_in.field(1);
  double* out_x = force_out.field(0);
  double* out_y = force_out.field(1);
#pragma omp parallel for schedule(static) if (cells > kParallelThreshold)
  for (std::int64_t p = 0; p < cells; ++p) {
    const auto cell = static_cast<std::size_t>(p);
    double qx = 0.0, qy = 0.0;
    for (int a = 0; a < 4; ++a) {
      const auto node = static_cast<std::size_t>(control.corners[cell][a]);
      qx += control.gamma[cell][a] * vx[node];
      qy += control.gamma[cell][a] * vy[node];
    }
    const double scale = interval * factor[cell] * control.stiffness[cell];
    out_x[cell] = in_x[cell] + scale * qx;
    out_y[cell] = in_y[cell] + scale * qy;
  }
}

void add_hourglass_acceleration(const HourglassStiffness& control, const FieldArray& force,
                                const std::array<int, 2>& velocity_field, FieldArray& rate) {
  const double* force_x = force.field(0);
  const double* force_y = force.field(1);
  // The share of every cell's force at each node (eq. 3.4), gathered.
  const auto nodes = static_cast<std::int64_t>(control.inverse_mass.size());
  double* rate_x = rate.field(velocity_field[0]);
  double* rate_y = rate.field(velocity_field[1]);
#pragma omp parallel for schedule(static) if (nodes > kParallelThreshold)
  for (std::int64_t n = 0; n < nodes; ++n) {
    const auto node = static_cast<std::size_t>(n);
    double fx = 0.0, fy = 0.0;
    for (auto k = static_cast<std::size_t>(control.node_start[node]);
         k < static_cast<std::size_t>(control.node_start[node + 1]); ++k) {
      const auto cell = static_cast<std::size_t>(control.cell_of[k]);
      const double gamma = control.gamma[cell][control.corner_of[k]];
      fx += force_x[cell] * gamma;
      fy += force_y[cell] * gamma;
    }
    rate_x[node] -= control.inverse_mass[node] * fx;
    rate_y[node] -= control.inverse_mass[node] * fy;
  }
}

}  // namespace rktsph
