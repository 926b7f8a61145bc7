// Reading a case file (YAML, schema in docs/input-reference.md) into a validated CaseDescription.
//
// Every problem a user can fix is thrown as an InputError located at the file, line and column of
// the offending key or value. Values given with --set are located at "<--set key=value>", and an
// override whose path is not part of the schema at "<--set>".
#pragma once

#include <string>
#include <vector>

#include "rktsph/case/case_description.hpp"

namespace rktsph {

/// One "--set key=value" override: dotted path into the YAML tree (sequence items by index, e.g.
/// "boundary_conditions.0.group"), value parsed as YAML scalar/flow text ("[0, -9.81]" allowed).
struct CaseOverride {
  std::string key;
  std::string value;
};

/// Splits "a.b=c" at the first '='. InputError if there is no '=' or the key is empty or has an
/// empty component ("a..b").
CaseOverride parse_override(const std::string& text);

/// Reads and validates the case file at `path`, after applying `overrides` in order.
CaseDescription read_case_file(const std::string& path,
                               const std::vector<CaseOverride>& overrides = {});

/// As read_case_file, for text already in memory; `file_name` is used in locations and stored in
/// CaseDescription::file.
CaseDescription read_case_text(const std::string& text, const std::string& file_name,
                               const std::vector<CaseOverride>& overrides = {});

/// Emits the fully resolved case (all defaults filled in) as YAML text, re-readable by
/// read_case_text. Built-in groups are not written (they may not be redefined).
std::string write_case_yaml(const CaseDescription& description);

}  // namespace rktsph
