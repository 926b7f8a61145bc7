#include "rktsph/simulation/energy_budget.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "rktsph/core/small_tensor.hpp"

namespace rktsph {

namespace {

// The total stress of node i as a 3 x 3 matrix: the carried stress, less alpha p_w on the
// diagonal in the saturated model.
std::array<Vec3, 3> total_stress(const PhysicsModel& model, const FieldArray& values,
                                 std::size_t i) {
  const SymmetricTensor s = model.stress_tensor(values, i);
  std::array<Vec3, 3> sigma{{{s[0], s[3], s[5]}, {s[3], s[1], s[4]}, {s[5], s[4], s[2]}}};
  if (const int p = model.pore_pressure_field(); p >= 0)
    for (std::size_t a = 0; a < 3; ++a)
      sigma[a][a] -= model.biot_coefficient() * values(p, i);
  return sigma;
}

// The area of facet f of a surface node: half the current lengths of the outline facets it
// gathers (the node's share of each); 1 in 1D.
double facet_area(const Simulation& simulation, const SurfaceSet& surface, std::int32_t node,
                  std::int32_t f) {
  const NodeSets& nodes = simulation.cells();  // the outline the surface's facets index
  if (nodes.dimension == 1) return 1.0;
  const PointCloud& current = simulation.state().configuration.sph_nodes;
  const auto i = static_cast<std::size_t>(node);
  double area = 0.0;
  for (const std::int32_t piece : surface.pieces(f)) {
    const auto j =
        static_cast<std::size_t>(nodes.outline.other_node(static_cast<std::size_t>(piece), node));
    area += 0.5 * std::hypot(current.position[0][j] - current.position[0][i],
                             current.position[1][j] - current.position[1][i]);
  }
  return area;
}

double boundary_power(const Simulation& simulation) {
  const PhysicsModel& model = simulation.model();
  const SurfaceSet& surface = simulation.boundary_conditions().surface();
  const FieldArray& values = simulation.state().fields;
  const int d = model.dimension();
  double power = 0.0;
  for (std::size_t k = 0; k < surface.size(); ++k) {
    const std::int32_t node = surface.node[k];
    const auto i = static_cast<std::size_t>(node);
    const std::int32_t begin = surface.facets_begin(k), end = surface.facets_end(k);
    const std::array<Vec3, 3> sigma = total_stress(model, values, i);
    for (std::int32_t f = begin; f < end; ++f) {
      const Vec3 n = surface.facet_normal(f);
      double traction_velocity = 0.0;  // (sigma n) . v
      for (int a = 0; a < d; ++a) {
        double traction = 0.0;
        for (std::size_t b = 0; b < 3; ++b)
          traction += sigma[static_cast<std::size_t>(a)][b] * n[b];
        traction_velocity += traction * values(model.velocity_field(a), i);
      }
      power += traction_velocity * facet_area(simulation, surface, node, f);
    }
  }
  return power;
}

// sigma : eps_dot^vp of node i (the material's rate has tensor shear components).
double plastic_power_density(const Material& material, const SymmetricTensor& sigma,
                             std::span<const double> internal) {
  if (material.is_elastic() || !material.flows(sigma, internal)) return 0.0;
  SymmetricTensor rate{};
  std::array<double, 16> internal_rate{};
  material.viscoplastic_rate(sigma, internal, rate,
                             std::span<double>(internal_rate.data(), internal.size()));
  double power = 0.0;
  for (std::size_t slot = 0; slot < 6; ++slot)
    power += (slot < 3 ? 1.0 : 2.0) * sigma[slot] * rate[slot];
  return power;
}

}  // namespace

EnergyRates measure_energy(const Simulation& simulation) {
  const PhysicsModel& model = simulation.model();
  const NodeSets& nodes = simulation.nodes();
  const State& state = simulation.state();
  const FieldArray& values = state.fields;
  const int d = model.dimension();
  const std::array<double, 3> b = model.body_force(state.time);
  const double xi = model.damping(state.time);
  const int internal_count = state.internal.field_count();
  std::array<double, 16> internal{};
  // With a water table each node's body force is weighted (docs/theory.md eq. 6.8).
  const auto& names = model.internal_names();
  const auto weight_name = std::find(names.begin(), names.end(), "gravity_weight");
  const int weight =
      weight_name == names.end() ? -1 : static_cast<int>(weight_name - names.begin());
  EnergyRates rates;
  for (std::size_t i = 0; i < nodes.sph_nodes.size(); ++i) {
    const std::int32_t material = nodes.node_material[i];
    const double mass = model.density(material) * nodes.sph_nodes.volume[i];
    const double volume = state.configuration.sph_nodes.volume[i];
    double speed2 = 0.0, body = 0.0;
    for (int a = 0; a < d; ++a) {
      const double v = values(model.velocity_field(a), i);
      speed2 += v * v;
      if (weight < 0)
        body += b[static_cast<std::size_t>(a)] * v;
      else if (a == d - 1)
        body += state.internal(weight, i) * b[static_cast<std::size_t>(a)] * v;
      else  // the seepage weight s, after w (2D)
        body += (b[0] + state.internal(weight + 1, i) * b[1]) * v;
    }
    rates.kinetic += 0.5 * mass * speed2;
    rates.body_power += mass * body;
    rates.damping_power += mass * xi * speed2;
    rates.stored_elastic += model.elastic_energy_density(material, values, i) * volume;
    const Material& law = model.material(material);
    if (law.is_elastic()) continue;
    const auto count =
        static_cast<std::size_t>(std::clamp(std::min(law.internal_count(), internal_count), 0, 16));
    for (std::size_t k = 0; k < count; ++k)
      internal[k] = state.internal(static_cast<int>(k), i);
    rates.plastic_power += plastic_power_density(law, model.stress_tensor(values, i),
                                                 std::span<const double>(internal.data(), count)) *
                           volume;
  }
  rates.boundary_power = boundary_power(simulation);
  return rates;
}

void EnergyBudget::on_start(const Simulation& simulation) {
  last_ = measure_energy(simulation);
  last_time_ = simulation.state().time;
  totals_ = {};
  totals_.initial_kinetic = totals_.kinetic = last_.kinetic;
  totals_.initial_stored_elastic = totals_.stored_elastic = last_.stored_elastic;
}

void EnergyBudget::after_step(const Simulation& simulation) {
  const EnergyRates now = measure_energy(simulation);
  const double half_step = 0.5 * (simulation.state().time - last_time_);
  totals_.work_of_body_force += half_step * (last_.body_power + now.body_power);
  totals_.work_of_boundary += half_step * (last_.boundary_power + now.boundary_power);
  totals_.damping_dissipation += half_step * (last_.damping_power + now.damping_power);
  totals_.plastic_dissipation += half_step * (last_.plastic_power + now.plastic_power);
  totals_.kinetic = now.kinetic;
  totals_.stored_elastic = now.stored_elastic;
  last_ = now;
  last_time_ = simulation.state().time;
}

void EnergyBudget::save_checkpoint(CheckpointOut& out) const {
  out.put_doubles(std::vector<double>{
      totals_.initial_kinetic, totals_.initial_stored_elastic, totals_.kinetic,
      totals_.stored_elastic, totals_.work_of_body_force, totals_.work_of_boundary,
      totals_.damping_dissipation, totals_.plastic_dissipation, last_.kinetic, last_.stored_elastic,
      last_.body_power, last_.boundary_power, last_.damping_power, last_.plastic_power,
      last_time_});
}

void EnergyBudget::restore_checkpoint(CheckpointIn& in) {
  std::array<double, 15> v{};
  in.get_doubles_into(v.data(), v.size());
  totals_ = {v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]};
  last_ = {v[8], v[9], v[10], v[11], v[12], v[13]};
  last_time_ = v[14];
}

EnergyClosure energy_closure(const EnergyTotals& totals) {
  EnergyClosure closure;
  closure.scale = std::max({std::abs(totals.work_of_loads()),
                            totals.initial_kinetic + totals.initial_stored_elastic,
                            totals.kinetic + totals.stored_elastic, totals.damping_dissipation});
  const double dissipated = totals.dissipated();
  if (std::isnan(closure.scale) || std::isnan(dissipated)) {
    closure.residual = std::numeric_limits<double>::quiet_NaN();
    closure.closes = false;
  } else if (closure.scale > 0.0) {
    closure.residual = dissipated / closure.scale;
    closure.closes = closure.residual >= -kCreatedEnergyLimit;
  }
  return closure;
}

std::string energy_closure_warning(const EnergyTotals& totals) {
  const EnergyClosure closure = energy_closure(totals);
  if (closure.closes) return {};
  return fmt::format(
      "the energy budget does not close: the run created {:.3g} J, {:.0f} % of the largest energy "
      "of its balance ({:.4g} J), where discretisation errors stay below {:.0f} %: its kinetic and "
      "stored elastic energy ({:.4g} J) and what damping took ({:.4g} J) exceed the work of the "
      "loads ({:.4g} J) and the initial energy ({:.4g} J) (summary.json, energy). Energy from "
      "nowhere is an instability of the discretisation: look for a growing or odd-even pattern in "
      "the velocity of the last output files, and treat the results with suspicion",
      -closure.residual * closure.scale, -100.0 * closure.residual, closure.scale,
      100.0 * kCreatedEnergyLimit, totals.kinetic + totals.stored_elastic,
      totals.damping_dissipation, totals.work_of_loads(),
      totals.initial_kinetic + totals.initial_stored_elastic);
}

}  // namespace rktsph
