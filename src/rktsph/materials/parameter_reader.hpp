// Reads a material's parameters from its case-file block with located errors: a material asks
// for each key it knows (with its range) and, at the end, any key it did not ask for is an error.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "rktsph/case/case_description.hpp"

namespace rktsph {

class ParameterReader {
 public:
  explicit ParameterReader(const ParameterBlock& block) : block_(block) {}

  /// A required number in [min, max] (bounds inclusive unless `open_min`/`open_max`).
  double required(const std::string& key, double min, double max, bool open_min = false,
                  bool open_max = false);
  /// An optional number with a default.
  double optional(const std::string& key, double fallback, double min, double max,
                  bool open_min = false, bool open_max = false);
  /// An optional word that must be one of `allowed` (the case file's non-numeric values, e.g.
  /// "matching: plane_strain"), with a default.
  std::string optional_word(const std::string& key, const std::string& fallback,
                            const std::vector<std::string>& allowed);
  /// Throws for every key of the block that was not asked for.
  void reject_unknown_keys() const;

 private:
  double checked(const std::string& key, const Parameter& p, double min, double max, bool open_min,
                 bool open_max) const;
  /// Throws if `key` holds a word where a number is wanted.
  void reject_word(const std::string& key, double min, double max, bool open_min,
                   bool open_max) const;
  const ParameterBlock& block_;
  std::set<std::string> asked_;
};

}  // namespace rktsph
