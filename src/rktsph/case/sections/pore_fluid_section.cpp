// The `pore_fluid` section: pore water and the pressure solve of the saturated model
// (docs/input-reference.md, "pore_fluid"; docs/theory.md §6).
#include "rktsph/case/computed_defaults.hpp"
#include "rktsph/case/sections/sections.hpp"
#include "rktsph/case/sections/value_readers.hpp"

#include <fmt/format.h>

#include <array>
#include <vector>

namespace rktsph {

namespace {

NumberRange open_unit_interval() {
  return {0.0, 1.0, true, true};
}
NumberRange biot_range() {
  return {0.0, 1.0, true, false};
}
NumberRange tolerance_range() {
  return {0.0, 1e-3, true, false};
}

// The polyline of a water table: two or more [x, y] vertices with x strictly increasing, so that
// it is a height y_w(x) (docs/theory.md §6.8).
std::vector<std::array<double, 2>> read_table_polyline(const YamlNode& node, int dimension) {
  reject_unless_2d(node, dimension, "'polyline' is");
  std::vector<std::array<double, 2>> vertices;
  for (const YamlNode& item : to_sequence(node, 2)) {
    const Vec3 vertex = read_vector(item, 2);
    if (!vertices.empty() && vertex[0] <= vertices.back()[0])
      fail_at(item,
              fmt::format("x = {} does not come after the previous vertex's x = {}", vertex[0],
                          vertices.back()[0]),
              "vertices [x, y] with x strictly increasing (the table is a height y(x))");
    vertices.push_back({vertex[0], vertex[1]});
  }
  return vertices;
}

const KeyTable<WaterTableSpec>& water_table_keys() {
  using W = WaterTableSpec;
  static const KeyTable<WaterTableSpec> keys = {
      optional_number_key<W>("level", &W::level, NumberRange::any(), "m",
                             "one of level and polyline",
                             "y of a horizontal water table (x in 1D)."),
      Key<W>{"polyline", "list of [x, y]", "m", "one of level and polyline",
             "2 or more vertices, x strictly increasing; 2D only",
             "The water table's height y(x), constant beyond the end vertices.", false,
             [](const YamlNode& node, W& table, Reading& reading) {
               table.polyline = read_table_polyline(node, reading.so_far.dimension);
             },
             [](YAML::Emitter& out, const W& table, const CaseDescription&) {
               if (table.polyline.empty()) return;
               out << YAML::Key << "polyline" << YAML::Value << YAML::Flow << YAML::BeginSeq;
               for (const auto& vertex : table.polyline)
                 out << YAML::Flow << YAML::BeginSeq << number(vertex[0]) << number(vertex[1])
                     << YAML::EndSeq;
               out << YAML::EndSeq;
             }},
      optional_number_key<W>("density_above", &W::density_above, NumberRange::positive(), "kg/m³",
                             "ρ − n ρ_w of each material",
                             "Mass density of the soil above the table (drained pores)."),
  };
  return keys;
}

void read_water_table(const YamlNode& node, PoreFluidSpec& fluid, Reading& reading) {
  WaterTableSpec table;
  table.where = YamlMap(node).where();
  const std::size_t errors_before = reading.errors.size();
  read_keys(node, water_table_keys(), table, reading);
  // A misspelt or refused key is reported once, not again as a missing shape.
  if (reading.errors.size() > errors_before) return;
  const YamlMap map(node);
  const bool level = map.find("level") != nullptr, polyline = map.find("polyline") != nullptr;
  if (level == polyline) {
    fail_at(level ? *map.find("polyline") : node,
            level ? "both 'level' and 'polyline' are given" : "neither 'level' nor 'polyline'",
            "exactly one of level: y and polyline: [[x, y], ...]", level);
  }
  fluid.water_table = table;
}

const KeyTable<PoreFluidSpec>& pore_fluid_keys() {
  using P = PoreFluidSpec;
  static const KeyTable<PoreFluidSpec> keys = {
      number_key<P>("bulk_modulus", &P::bulk_modulus, NumberRange::positive(), "Pa",
                    "K_w of the water; the Biot modulus is Q = K_w / n.", true),
      number_key<P>("density", &P::density, NumberRange::positive(), "kg/m³",
                    "ρ_w, to convert hydraulic_conductivity.", true),
      number_key<P>("porosity", &P::porosity, open_unit_interval(), "–", "n.", true),
      number_key<P>("hydraulic_conductivity", &P::hydraulic_conductivity,
                    NumberRange::non_negative(), "m/s", "Darcy's k; 0 is undrained.", true),
      number_key<P>("gravity", &P::gravity, NumberRange::positive(), "m/s²",
                    "g in the conversion k → k̄ = k / (ρ_w g) only; not a body force."),
      number_key<P>("biot_coefficient", &P::biot_coefficient, biot_range(), "–", "α."),
      // beta = 0 adds a spurious permeability of about dt/rho (docs/theory.md §7.2, S3): not
      // offered.
      Key<P>{"projection_beta", "integer", "", "1", "1", "Incremental projection.", false,
             [](const YamlNode& node, P& fluid, Reading&) {
               fluid.projection_beta = static_cast<double>(to_integer(node, 1, 1));
             },
             [](YAML::Emitter& out, const P& fluid, const CaseDescription&) {
               out << YAML::Key << "projection_beta" << YAML::Value
                   << static_cast<int>(fluid.projection_beta);
             }},
      choice_key<P, PressurePreconditioner>(
          "preconditioner", &P::preconditioner, preconditioner_words(),
          "Preconditioner of the conjugate-gradient pressure solve."),
      number_key<P>("solver_tolerance", &P::solver_tolerance, tolerance_range(), "–",
                    "Relative residual at which the solve stops."),
      // The default depends on the number of SPH nodes, known only once the lattice is built
      // (models/pressure_projection.cpp), so the resolved case leaves it out when unset.
      Key<P>{"solver_max_iterations", "integer", "", "2 × nodes + 10", "[1, 100000000]",
             "Iteration limit; a solve that does not converge stops the run.", false,
             [](const YamlNode& node, P& fluid, Reading&) {
               fluid.solver_max_iterations = to_integer(node, 1, 100000000);
             },
             [](YAML::Emitter& out, const P& fluid, const CaseDescription&) {
               if (fluid.solver_max_iterations > 0)
                 out << YAML::Key << "solver_max_iterations" << YAML::Value
                     << fluid.solver_max_iterations;
             }},
      Key<P>{
          "laplacian_scale", "number", "–", "computed", documented_range(NumberRange::positive()),
          "Factor of the pore-pressure Laplacian; computed so that L(|x|²) = 2d in the interior "
          "(1 on triangles).",
          false,
          [](const YamlNode& node, P& fluid, Reading&) {
            fluid.laplacian_scale = to_number(node, NumberRange::positive());
          },
          [](YAML::Emitter& out, const P& fluid, const CaseDescription& description) {
            const double scale = fluid.laplacian_scale > 0.0 ? fluid.laplacian_scale
                                                             : default_laplacian_scale(description);
            out << YAML::Key << "laplacian_scale" << YAML::Value << number(scale);
          }},
      number_key<P>("checkerboard_stabilisation", &P::checkerboard_stabilisation,
                    NumberRange::non_negative(), "–",
                    "θ of the pore-pressure checkerboard stabilisation (docs/theory.md §6.6)."),
      Key<P>{"water_table", "map", "", "none (fully saturated)", "",
             "A phreatic surface: hydrostatic p_w below it, drained soil above it "
             "(docs/theory.md §6.8).",
             false, read_water_table,
             [](YAML::Emitter& out, const P& fluid, const CaseDescription& description) {
               if (!fluid.water_table) return;
               out << YAML::Key << "water_table" << YAML::Value << YAML::BeginMap;
               emit_keys(out, water_table_keys(), *fluid.water_table, description);
               out << YAML::EndMap;
             }},
  };
  return keys;
}

void read_pore_fluid(const YamlNode& node, CaseDescription& description, Reading& reading) {
  if (description.model != ModelKind::SaturatedVpw) {
    fail_at(node, "'pore_fluid' only applies to the saturated model",
            "model: saturated_vpw, or remove 'pore_fluid'", true);
  }
  PoreFluidSpec fluid;
  fluid.where = YamlMap(node).where();
  read_keys(node, pore_fluid_keys(), fluid, reading);
  description.pore_fluid = fluid;
}

}  // namespace

Key<CaseDescription> pore_fluid_section() {
  return section_key<CaseDescription>(
      "pore_fluid", "map", "none", "required with model: saturated_vpw, an error otherwise",
      "Pore water and the pressure solve of the saturated model.", read_pore_fluid,
      [](YAML::Emitter& out, const CaseDescription& description, const CaseDescription&) {
        if (!description.pore_fluid) return;
        out << YAML::Key << "pore_fluid" << YAML::Value << YAML::BeginMap;
        emit_keys(out, pore_fluid_keys(), *description.pore_fluid, description);
        out << YAML::EndMap;
      });
}

void declare_pore_fluid_keys(std::vector<DeclaredKey>& list) {
  declare(list, "pore_fluid.", pore_fluid_keys());
  declare(list, "pore_fluid.water_table.", water_table_keys());
}

}  // namespace rktsph
