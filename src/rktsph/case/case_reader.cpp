#include "rktsph/case/case_reader.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "rktsph/case/key_spec.hpp"
#include "rktsph/case/sections/sections.hpp"

namespace rktsph {

namespace {

/// Reads the top level of the case file by its key table, section by section. A mistake that the
/// rest depends on (the dimension) ends the reading there; the others are collected.
CaseDescription read_description(const YamlNode& root, const std::string& file) {
  if (root.is_null()) {
    throw InputError(SourceLocation{file, 0, 0}, "", "", "the case file is empty",
                     "a map with at least name, dimension, geometry, materials and time");
  }
  CaseDescription description;
  description.file = file;
  const SourceLocation absent{file, 0, 0};
  description.initial.where = description.numerics.where = description.output.where = absent;
  ErrorList errors;
  Reading reading{description, errors};
  const YamlMap top(root);
  const KeyTable<CaseDescription>& keys = top_level_keys();
  errors.attempt([&] { top.allow_only(key_names(keys)); });
  try {
    for (const Key<CaseDescription>& key : keys) {
      if (key.name == "dimension") {
        key.read(top.require("dimension"), description, reading);  // not collected: ends reading
        add_built_in_groups(description);
        continue;
      }
      errors.attempt([&] {
        if (const YamlNode* value = top.find(key.name)) {
          key.read(*value, description, reading);
        } else if (key.required) {
          top.require(key.name);
        } else if (key.name == "pore_fluid" && description.model == ModelKind::SaturatedVpw) {
          top.require(key.name);  // required by the saturated model only
        }
      });
    }
  } catch (const InputError& error) {
    errors.add(error);
  }
  if (!errors.empty()) throw InputError::combine(errors.take());
  return description;
}

/// The whole text of the case file. A directory (which an ifstream opens and reads as empty on
/// Linux) and a file that cannot be read are named as such, with the system's reason.
std::string read_case_bytes(const std::string& path) {
  const SourceLocation where{path, 0, 0};
  std::error_code status_error;
  const auto status = std::filesystem::status(path, status_error);
  if (std::filesystem::is_directory(status)) {
    throw InputError(where, "", "", "this is a directory, not a case file",
                     "the path of a YAML case file, e.g. " +
                         (std::filesystem::path(path) / "case.yaml").string());
  }
  errno = 0;
  std::ifstream stream(path, std::ios::binary);
  if (!stream) {
    const int reason = errno != 0 ? errno : ENOENT;
    throw InputError(where, "", "",
                     fmt::format("cannot open the case file: {}", std::strerror(reason)),
                     "a readable YAML file");
  }
  std::ostringstream text;
  text << stream.rdbuf();
  if (stream.bad()) {
    throw InputError(where, "", "",
                     fmt::format("cannot read the case file: {}", std::strerror(errno)),
                     "a readable YAML file");
  }
  return text.str();
}

}  // namespace

const KeyTable<CaseDescription>& top_level_keys() {
  static const KeyTable<CaseDescription> keys = [] {
    KeyTable<CaseDescription> table = header_keys();
    for (Key<CaseDescription> section :
         {materials_section(), geometry_section(), groups_section(), boundary_conditions_section(),
          loads_section(), initial_conditions_section(), numerics_section(), pore_fluid_section(),
          time_section(), output_section(), probes_section()})
      table.push_back(std::move(section));
    return table;
  }();
  return keys;
}

CaseOverride parse_override(const std::string& text) {
  const SourceLocation where{"<--set>", 0, 0};
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos) {
    throw InputError(where, "", text, "an override needs the form key=value",
                     "e.g. --set numerics.courant=0.3");
  }
  CaseOverride result{text.substr(0, equals), text.substr(equals + 1)};
  const bool empty_component = result.key.empty() || result.key.front() == '.' ||
                               result.key.back() == '.' ||
                               result.key.find("..") != std::string::npos;
  if (empty_component || result.key.find_first_of(" \t") != std::string::npos) {
    throw InputError(where, result.key, text, "the key of an override is empty or malformed",
                     "a dotted path such as numerics.courant or boundary_conditions.0.group");
  }
  return result;
}

CaseDescription read_case_file(const std::string& path,
                               const std::vector<CaseOverride>& overrides) {
  return read_case_text(read_case_bytes(path), path, overrides);
}

CaseDescription read_case_text(const std::string& text, const std::string& file_name,
                               const std::vector<CaseOverride>& overrides) {
  YamlNode root = parse_yaml(text, file_name);
  for (const CaseOverride& override_entry : overrides) {
    apply_override(root, override_entry.key, override_entry.value);
  }
  return read_description(root, file_name);
}

std::string write_case_yaml(const CaseDescription& description) {
  YAML::Emitter out;
  out.SetIndent(2);
  out << YAML::BeginMap;
  emit_keys(out, top_level_keys(), description, description);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace rktsph
