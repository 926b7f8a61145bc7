// Materials are created by the name written in the case file ("model: linear_elastic").
// Adding a material: one file pair in this folder and one line in material_factory.cpp.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rktsph/case/case_description.hpp"
#include "rktsph/materials/material.hpp"

namespace rktsph {

std::unique_ptr<Material> create_material(const ParameterBlock& block);
std::vector<std::string> material_model_names();

}  // namespace rktsph
