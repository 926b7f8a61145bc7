#include "rktsph/simulation/quantities.hpp"

#include <algorithm>
#include <cmath>

#include "rktsph/core/axes.hpp"
#include "rktsph/materials/invariants.hpp"

namespace rktsph {

NodeQuantity find_quantity(const Simulation& simulation, const std::string& name) {
  const PhysicsModel& model = simulation.model();
  const auto& fields = model.field_names();
  const int pore = model.pore_pressure_field();
  // With a water table the carried field is the excess: p_w = p_h + it (docs/theory.md eq. 6.7).
  const auto pore_pressure = [&model, pore](const State& s, std::size_t i) {
    return s.fields(pore, i) + model.hydrostatic_pore_pressure(i, s.time);
  };
  if (pore >= 0 && model.has_water_table() && fields[static_cast<std::size_t>(pore)] == name)
    return pore_pressure;
  for (std::size_t f = 0; f < fields.size(); ++f)
    if (fields[f] == name) {
      const int field = static_cast<int>(f);
      return [field](const State& s, std::size_t i) { return s.fields(field, i); };
    }
  for (int a = 0; a < model.dimension(); ++a)
    if (name == std::string("displacement_") + axis_letter(a))
      return [a](const State& s, std::size_t i) { return s.displacement(a, i); };
  const auto& internal = model.internal_names();
  for (std::size_t k = 0; k < internal.size(); ++k)
    if (internal[k] == name) {
      const int index = static_cast<int>(k);
      return [index](const State& s, std::size_t i) { return s.internal(index, i); };
    }
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      if (name != std::string("total_stress_") + axis_letter(i) + axis_letter(j)) continue;
      const int field = model.stress_field(i, j);
      if (pore < 0) return {};
      const double alpha = model.biot_coefficient();
      const double diagonal = i == j ? 1.0 : 0.0;
      if (model.has_water_table())
        return [field, pore_pressure, alpha, diagonal](const State& s, std::size_t k) {
          return (field >= 0 ? s.fields(field, k) : 0.0) - diagonal * alpha * pore_pressure(s, k);
        };
      return [field, pore, alpha, diagonal](const State& s, std::size_t k) {
        return (field >= 0 ? s.fields(field, k) : 0.0) - diagonal * alpha * s.fields(pore, k);
      };
    }
  if (name == "pressure")
    return [&model](const State& s, std::size_t i) {
      return mean_pressure(model.stress_tensor(s.fields, i));
    };
  if (name == "deviatoric_stress")
    return [&model](const State& s, std::size_t i) {
      return von_mises_stress(model.stress_tensor(s.fields, i));
    };
  return {};
}

std::vector<std::string> quantity_names(const Simulation& simulation) {
  const PhysicsModel& model = simulation.model();
  std::vector<std::string> names = model.field_names();
  for (int a = 0; a < model.dimension(); ++a)
    names.push_back(std::string("displacement_") + axis_letter(a));
  for (const std::string& name : model.internal_names())
    names.push_back(name);
  names.push_back("pressure");
  names.push_back("deviatoric_stress");
  if (model.pore_pressure_field() >= 0)
    for (const char* c : {"xx", "yy", "zz", "xy"})
      names.push_back(std::string("total_stress_") + c);
  return names;
}

double largest_speed(const Simulation& simulation) {
  const PhysicsModel& model = simulation.model();
  const FieldArray& fields = simulation.state().fields;
  const std::size_t count = simulation.nodes().sph_nodes.size();
  double largest = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    double square = 0.0;
    for (int a = 0; a < model.dimension(); ++a) {
      const double v = fields(model.velocity_field(a), k);
      square += v * v;
    }
    largest = std::max(largest, square);
  }
  return std::sqrt(largest);
}

}  // namespace rktsph
