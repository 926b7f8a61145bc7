// The `numerics` section: kernel, time step, source integration and the hourglass controls
// (docs/input-reference.md, "numerics").
#include <fmt/format.h>

#include <limits>

#include "rktsph/case/computed_defaults.hpp"
#include "rktsph/case/sections/sections.hpp"
#include "rktsph/case/sections/value_readers.hpp"

namespace rktsph {

namespace {

const NumberRange kSmoothingRatioRange{0.5, 3.0, true, false};
// The two-step Lax-Wendroff limit; lower limits for the options that lower it are checked when the
// simulation is built (docs/theory.md §2.5: 1.2 and 1.5 diverged on a plain block).
const NumberRange kCourantRange{0.0, 1.0, true, false};
const NumberRange kUnitInterval{0.0, 1.0, false, false};

const Choices<StressUpdate> kStressUpdates = {{"mean_velocity", StressUpdate::MeanVelocity},
                                              {"half_step", StressUpdate::HalfStep}};
const Choices<HourglassFields> kHourglassFields = {{"velocity", HourglassFields::Velocity},
                                                   {"all", HourglassFields::All}};

const KeyTable<NumericsSpec>& hourglass_keys() {
  using N = NumericsSpec;
  static const KeyTable<NumericsSpec> keys = {
      boolean_key<N>("enabled", &N::hourglass_filter,
                     "Whether the filter runs (2D; ignored in 1D)."),
      number_key<N>("kappa", &N::hourglass_kappa, kUnitInterval, "–", "Filter strength."),
      number_key<N>("h_over_dx", &N::hourglass_h_over_dx, kSmoothingRatioRange, "–",
                    "Smoothing length of the filter over dx."),
      optional_number_key<N>(
          "stiffness", &N::hourglass_stiffness, kUnitInterval, "–",
          fmt::format("with stress_update: mean_velocity {} in every cell away from viscoplastic "
                      "flow, {} in viscoplastic cells within two rings of flow, present or past "
                      "(in every viscoplastic cell on a moving configuration); with half_step 0",
                      documented_number(kDefaultHourglassStiffness),
                      documented_number(kDefaultViscoplasticHourglassStiffness)),
          "ε of the cells' hourglass stiffness (docs/theory.md eqs. 3.2–3.4, 3.9); 0 = off."),
      number_key<N>("plastic_fraction", &N::hourglass_plastic_fraction, kUnitInterval, "–",
                    "ψ of eq. 3.9: the fraction of the hourglass stiffness acting in flow."),
      number_key<N>("strain_stiffness", &N::strain_hourglass_stiffness, kUnitInterval, "–",
                    "ε_s of the strain hourglass stiffness (eqs. 3.5–3.8); 0 = off."),
      optional_number_key<N>(
          "patch_stiffness", &N::patch_stiffness, kUnitInterval, "–",
          fmt::format("{} with geometry.cells: triangles, 0 on a lattice",
                      documented_number(kDefaultTrianglePatchStiffness)),
          "β of the patch strain stiffness (docs/theory.md eq. 3.12): the soft modes of the "
          "nodal strain average on triangles; 0 = off. Not together with strain_stiffness."),
      computed_choice_key<N, HourglassFields>(
          "fields", &N::hourglass_fields, kHourglassFields,
          "velocity on compact stencils, all on wider ones",
          [](const CaseDescription& description) {
            return default_hourglass_fields(description.numerics, description.dimension);
          },
          "What the filter acts on (docs/theory.md §3.3)."),
  };
  return keys;
}

const KeyTable<NumericsSpec>& cell_keys() {
  using N = NumericsSpec;
  static const KeyTable<NumericsSpec> keys = {
      choice_key<N, CellPolicy>(
          "policy", &N::cell_policy,
          {{"moving", CellPolicy::Moving}, {"reformed", CellPolicy::Reformed}},
          "Large deformation: `moving` integrates over the cells of the start, their corners "
          "moved with the nodes (docs/theory.md §9.1); `reformed` forms Delaunay cells of the "
          "current nodes, trimmed by the alpha criterion, at the start and again whenever a "
          "cell has distorted (§9.17). Ignored by the small-deformation models."),
      number_key<N>(
          "alpha", &N::reform_alpha, NumberRange{0.5, 10.0, true, true}, "–",
          "α of eq. 3.15: a Delaunay triangle is a cell while its circumradius is at most "
          "α times its corners' mean spacing (1/√2 keeps a square lattice whole; 1 also "
          "closes the hole of one missing node)."),
      number_key<N>("reform_below", &N::reform_corner_ratio, kUnitInterval, "–",
                    "With policy: reformed, the cells are formed again once a corner's Jacobian "
                    "falls below this fraction of the one it had when its cell was formed, or "
                    "grows beyond its inverse, or a cell's squared reach (centroid to farthest "
                    "corner) does (a stretched cell, whose corners leave the support of its "
                    "stencil)."),
      number_key<N>("spread_below", &N::spread_below, NumberRange{0.0, 1.0, false, true}, "–",
                    "With policy: reformed, before the cells are formed again, a node whose "
                    "nearest neighbour is closer than this fraction of its spacing moves to the "
                    "centroid of its neighbours (on the outline, to the midpoint of its two "
                    "neighbours along it), its fields unchanged (docs/theory.md §9.19); 0 never."),
  };
  return keys;
}

const KeyTable<NumericsSpec>& numerics_keys() {
  using N = NumericsSpec;
  static const KeyTable<NumericsSpec> keys = {
      choice_key<N, KernelType>("kernel", &N::kernel,
                                {{"cubic_spline", KernelType::CubicSpline},
                                 {"quintic_spline", KernelType::QuinticSpline},
                                 {"gaussian", KernelType::Gaussian}},
                                "Smoothing kernel."),
      number_key<N>("h_over_dx", &N::h_over_dx, kSmoothingRatioRange, "–",
                    "Smoothing length over lattice spacing (docs/theory.md §7.1)."),
      integer_key<N, int>("interpolation_order", &N::interpolation_order, 0, 1,
                          "0: Shepard-normalised; 1: first-order corrected."),
      number_key<N>("neighbour_search_distance", &N::neighbour_search_distance, kUnitInterval, "–",
                    "On a moving configuration (large deformation): the stencils are searched "
                    "again, and the hourglass filter's tables built again, once a node has moved "
                    "this fraction of dx since the last search; the weights follow the nodes every "
                    "step (docs/theory.md §9.5). 0: a search before every step."),
      number_key<N>("courant", &N::courant, kCourantRange, "–",
                    "C in dt = C dx / c_p, c_p the P-wave speed of the stiffest material."),
      optional_number_key<N>("time_step", &N::time_step, NumberRange::positive(), "s",
                             "from courant", "A fixed time step instead of the Courant rule."),
      choice_key<N, bool>("source_coupling", &N::frozen_flux_source,
                          {{"frozen_flux", true}, {"additive", false}},
                          "How stiff sources are coupled to the flux step (docs/theory.md §7.1)."),
      number_key<N>("rk_substep_factor", &N::rk_substep_factor, NumberRange::positive(), "–",
                    "Sub-steps of the source integration: m = ceil(dt λ_src / factor)."),
      integer_key<N, int>("rk_max_substeps", &N::rk_max_substeps, 1,
                          std::numeric_limits<int>::max(), "Upper limit of m."),
      computed_choice_key<N, StressUpdate>(
          "stress_update", &N::stress_update, kStressUpdates,
          "mean_velocity in 2D, half_step in 1D",
          [](const CaseDescription& description) {
            return default_stress_update(description.dimension);
          },
          "How step 2 advances the nodal stress (docs/theory.md §2.2)."),
      Key<N>{"hourglass", "map", "", "see below", "",
             "Hourglass filter and zero-energy-mode stiffnesses (2D).", false,
             [](const YamlNode& node, N& numerics, Reading& reading) {
               read_keys(node, hourglass_keys(), numerics, reading);
             },
             [](YAML::Emitter& out, const N& numerics, const CaseDescription& description) {
               out << YAML::Key << "hourglass" << YAML::Value << YAML::Flow << YAML::BeginMap;
               emit_keys(out, hourglass_keys(), numerics, description);
               out << YAML::EndMap;
             }},
      number_key<N>("artificial_viscosity", &N::artificial_viscosity, NumberRange::non_negative(),
                    "–", "α of the artificial viscosity (docs/theory.md §7.1); 0 = off."),
      Key<N>{"cells", "map", "", "see below", "",
             "The cells of a moving configuration (large deformation, docs/theory.md §9.17).",
             false,
             [](const YamlNode& node, N& numerics, Reading& reading) {
               read_keys(node, cell_keys(), numerics, reading);
             },
             [](YAML::Emitter& out, const N& numerics, const CaseDescription& description) {
               out << YAML::Key << "cells" << YAML::Value << YAML::Flow << YAML::BeginMap;
               emit_keys(out, cell_keys(), numerics, description);
               out << YAML::EndMap;
             }},
  };
  return keys;
}

}  // namespace

Key<CaseDescription> numerics_section() {
  return section_key<CaseDescription>(
      "numerics", "map", "the defaults below", "", "Kernel, time step and stabilisation.",
      [](const YamlNode& node, CaseDescription& description, Reading& reading) {
        description.numerics.where = YamlMap(node).where();
        read_keys(node, numerics_keys(), description.numerics, reading);
      },
      [](YAML::Emitter& out, const CaseDescription& description, const CaseDescription&) {
        out << YAML::Key << "numerics" << YAML::Value << YAML::BeginMap;
        emit_keys(out, numerics_keys(), description.numerics, description);
        out << YAML::EndMap;
      });
}

void declare_numerics_keys(std::vector<DeclaredKey>& list) {
  declare(list, "numerics.", numerics_keys());
  declare(list, "numerics.hourglass.", hourglass_keys());
  declare(list, "numerics.cells.", cell_keys());
}

}  // namespace rktsph
