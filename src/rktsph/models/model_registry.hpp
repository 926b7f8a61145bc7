// The physics models a case can select with its `model` key: how each is made from the case, when
// its operators are built, and the correction it adds to the step.
// The assembly of a run (simulation/assembly.*) knows no model by name; a new model is one entry
// in model_registry.cpp (docs/theory.md §2.6).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rktsph/boundary/boundary_conditions.hpp"
#include "rktsph/case/case_description.hpp"
#include "rktsph/case/model_names.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/materials/material.hpp"
#include "rktsph/physics/physics_model.hpp"
#include "rktsph/time/rk_taylor_step.hpp"

namespace rktsph {

struct RegisteredModel {
  /// Its name in the case file and the dimensions it supports are the case layer's
  /// (case/model_names.hpp, which the reader checks a case against): model_name(kind).
  ModelKind kind;
  OperatorPolicy operator_policy = OperatorPolicy::ReferenceConfiguration;
  /// The model from the case and its materials (in the order of the case's material names).
  std::unique_ptr<PhysicsModel> (*create)(const CaseDescription& description,
                                          std::vector<std::unique_ptr<Material>> materials) =
      nullptr;
  /// The correction after the RK-TSPH pass (the pressure projection of V3), or null for none.
  std::unique_ptr<StepProjection> (*create_projection)(const PhysicsModel& model,
                                                       const NodeSets& nodes,
                                                       const OperatorOptions& options,
                                                       const BoundaryConditions& conditions,
                                                       const CaseDescription& description,
                                                       double dt) = nullptr;
};

/// Every model, in the order of model_names().
const std::vector<RegisteredModel>& registered_models();
/// The entry of `kind` (every ModelKind has one).
const RegisteredModel& registered_model(ModelKind kind);

}  // namespace rktsph
