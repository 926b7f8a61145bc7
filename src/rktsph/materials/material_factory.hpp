// Materials are created by the name written in the case file ("model: linear_elastic").
// Adding a material: one file pair in this folder and one line in material_factory.cpp.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rktsph/case/case_description.hpp"
#include "rktsph/materials/material.hpp"

namespace rktsph {

/// The material of one block; every mistake of the block (missing, out-of-range and unknown
/// keys) is thrown as one InputError.
std::unique_ptr<Material> create_material(const ParameterBlock& block);
/// The materials of every block, in the map's order; the mistakes of all blocks are thrown as one
/// InputError, so that a case's material section is corrected in one go.
std::vector<std::unique_ptr<Material>> create_materials(
    const std::map<std::string, ParameterBlock>& blocks);
std::vector<std::string> material_model_names();

}  // namespace rktsph
