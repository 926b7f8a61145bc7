// The models a case can choose with the top-level `model` key, and the spatial dimensions each
// supports (docs/input-reference.md, "Top level"). The case reader accepts a dimension only if the
// chosen model supports it; the models layer registers the same names.
#pragma once

#include <string>
#include <vector>

#include "rktsph/case/case_description.hpp"

namespace rktsph {

struct ModelName {
  ModelKind kind;
  std::string name;             ///< as written in the case file
  std::vector<int> dimensions;  ///< the spatial dimensions the model supports
};

/// Every model, in the order the documentation lists them.
inline const std::vector<ModelName>& model_names() {
  static const std::vector<ModelName> names = {
      {ModelKind::DrySolid, "dry_solid", {1, 2}},  // V1: one phase, small deformation
      // V2: one phase, updated Lagrangian on the moving configuration, docs/theory.md §9
      {ModelKind::DryLargeDeformation, "dry_large_deformation", {1, 2}},
      {ModelKind::SaturatedVpw, "saturated_vpw", {1, 2}},  // V3: v-p_w, docs/theory.md §6
  };
  return names;
}

inline const ModelName& model_name(ModelKind kind) {
  for (const ModelName& model : model_names())
    if (model.kind == kind) return model;
  return model_names().front();
}

}  // namespace rktsph
