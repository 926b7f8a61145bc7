// The top-level keys that are not sections: name, description, model, dimension, plane
// (docs/input-reference.md, "Top level").
#include <fmt/format.h>

#include <algorithm>

#include "rktsph/case/model_names.hpp"
#include "rktsph/case/sections/sections.hpp"
#include "rktsph/case/sections/value_readers.hpp"

namespace rktsph {

namespace {

Choices<ModelKind> model_choices() {
  Choices<ModelKind> choices;
  for (const ModelName& model : model_names())
    choices.emplace_back(model.name, model.kind);
  return choices;
}

/// "dry_solid: 1, 2; saturated_vpw: 1, 2"
std::string dimensions_by_model() {
  std::vector<std::string> entries;
  for (const ModelName& model : model_names())
    entries.push_back(fmt::format("{}: {}", model.name, fmt::join(model.dimensions, ", ")));
  return fmt::format("{}", fmt::join(entries, "; "));
}

std::string dimension_list(const std::vector<int>& dimensions) {
  std::vector<std::string> words;
  for (int dimension : dimensions)
    words.push_back(fmt::format("{}", dimension));
  return fmt::format("{}", fmt::join(words, " or "));
}

Key<CaseDescription> name_key() {
  Key<CaseDescription> key{"name",     "word",       "",
                           "required", "[a-z0-9-]+", "Name of the case; used for output names.",
                           true,       {},           {}};
  key.read = [](const YamlNode& node, CaseDescription& description, Reading&) {
    description.name = to_identifier(node, kCaseNameAlphabet,
                                     "lower-case letters, digits and '-' (e.g. bar1d-elastic)");
  };
  key.emit = [](YAML::Emitter& out, const CaseDescription& description, const CaseDescription&) {
    out << YAML::Key << "name" << YAML::Value << description.name;
  };
  return key;
}

Key<CaseDescription> description_key() {
  Key<CaseDescription> key{
      "description", "text", "", "empty", "any", "Free text, copied to the output.", false, {}, {}};
  key.read = [](const YamlNode& node, CaseDescription& description, Reading&) {
    description.description = to_text(node);
  };
  key.emit = [](YAML::Emitter& out, const CaseDescription& description, const CaseDescription&) {
    if (description.description.empty()) return;
    out << YAML::Key << "description" << YAML::Value << YAML::DoubleQuoted
        << description.description;
  };
  return key;
}

/// Space has at most three dimensions; within them, the chosen model's own list decides
/// (model_names.hpp).
constexpr long kMaxSpaceDimension = 3;

Key<CaseDescription> dimension_key() {
  Key<CaseDescription> key{
      "dimension", "integer", "", "required", dimensions_by_model(), "1D uniaxial bar or 2D.",
      true,        {},        {}};
  key.read = [](const YamlNode& node, CaseDescription& description, Reading&) {
    const int dimension = static_cast<int>(to_integer(node, 1, kMaxSpaceDimension));
    const ModelName& model = model_name(description.model);
    if (std::find(model.dimensions.begin(), model.dimensions.end(), dimension) ==
        model.dimensions.end())
      fail_at(node, fmt::format("the model '{}' does not support {}D", model.name, dimension),
              fmt::format("{} with model: {}", dimension_list(model.dimensions), model.name));
    description.dimension = dimension;
  };
  key.emit = [](YAML::Emitter& out, const CaseDescription& description, const CaseDescription&) {
    out << YAML::Key << "dimension" << YAML::Value << description.dimension;
  };
  return key;
}

Key<CaseDescription> plane_key() {
  Key<CaseDescription> key = choice_key<CaseDescription, PlaneKind>(
      "plane", &CaseDescription::plane,
      {{"strain", PlaneKind::Strain}, {"stress", PlaneKind::Stress}},
      "Plane strain or plane stress; 2D only (the 1D case is always the uniaxial bar).");
  const auto read_choice = key.read;
  key.read = [read_choice](const YamlNode& node, CaseDescription& description, Reading& reading) {
    reject_unless_2d(node, description.dimension, "'plane' is");
    read_choice(node, description, reading);
  };
  const auto emit_choice = key.emit;
  key.emit = [emit_choice](YAML::Emitter& out, const CaseDescription& description,
                           const CaseDescription& whole) {
    if (description.dimension == 2) emit_choice(out, description, whole);
  };
  return key;
}

}  // namespace

KeyTable<CaseDescription> header_keys() {
  return {name_key(), description_key(),
          choice_key<CaseDescription, ModelKind>(
              "model", &CaseDescription::model, model_choices(),
              "Dry solid (one phase) or saturated soil in the v–p_w formulation."),
          dimension_key(), plane_key()};
}

}  // namespace rktsph
