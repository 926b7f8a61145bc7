#include "rktsph/materials/material_factory.hpp"

#include <functional>
#include <map>

#include "rktsph/materials/linear_elastic.hpp"
#include "rktsph/materials/parameter_reader.hpp"
#include "rktsph/materials/perzyna_drucker_prager.hpp"
#include "rktsph/materials/perzyna_modified_cam_clay.hpp"
#include "rktsph/materials/perzyna_mohr_coulomb.hpp"
#include "rktsph/materials/perzyna_von_mises.hpp"

namespace rktsph {

namespace {
using Creator = std::function<std::unique_ptr<Material>(ParameterReader&)>;

const std::map<std::string, Creator>& registry() {
  static const std::map<std::string, Creator> creators = {
      {"linear_elastic", &LinearElastic::from_parameters},
      {"perzyna_von_mises", &PerzynaVonMises::from_parameters},
      {"perzyna_modified_cam_clay", &PerzynaModifiedCamClay::from_parameters},
      {"perzyna_drucker_prager", &PerzynaDruckerPrager::from_parameters},
      {"perzyna_mohr_coulomb", &PerzynaMohrCoulomb::from_parameters},
  };
  return creators;
}
}  // namespace

std::vector<std::string> material_model_names() {
  std::vector<std::string> names;
  for (const auto& entry : registry())
    names.push_back(entry.first);
  return names;
}

std::unique_ptr<Material> create_material(const ParameterBlock& block) {
  const auto model = block.words.find("model");
  std::string allowed;
  for (const std::string& name : material_model_names())
    allowed += (allowed.empty() ? "" : ", ") + name;
  if (model == block.words.end())
    throw InputError(block.where, block.path + ".model", "", "missing required key", allowed);
  const auto creator = registry().find(model->second.first);
  if (creator == registry().end())
    throw InputError(model->second.second, block.path + ".model", model->second.first,
                     "unknown material model", allowed);
  ParameterReader reader(block);
  std::vector<InputError> errors;
  std::unique_ptr<Material> material;
  try {
    material = creator->second(reader);
  } catch (const InputError& error) {
    errors.push_back(error);  // a check across keys, made on the values read so far
  }
  reader.reject_unknown_keys();
  errors.insert(errors.begin(), reader.errors().begin(), reader.errors().end());
  if (!errors.empty()) throw InputError::combine(std::move(errors));
  return material;
}

std::vector<std::unique_ptr<Material>> create_materials(
    const std::map<std::string, ParameterBlock>& blocks) {
  std::vector<std::unique_ptr<Material>> materials;
  std::vector<InputError> errors;
  for (const auto& entry : blocks) {
    try {
      materials.push_back(create_material(entry.second));
    } catch (const InputError& error) {
      errors.push_back(error);
    }
  }
  if (!errors.empty()) throw InputError::combine(std::move(errors));
  return materials;
}

}  // namespace rktsph
