// Reads a material's parameters from its case-file block with located errors: a material asks
// for each key it knows (with its range) and, at the end, any key it did not ask for is an error.
// The mistakes of a block are collected, not thrown one at a time, so that one run reports all of
// them (as the case reader does for the other sections).
#pragma once

#include <set>
#include <string>
#include <vector>

#include "rktsph/case/case_description.hpp"

namespace rktsph {

class ParameterReader {
 public:
  explicit ParameterReader(const ParameterBlock& block) : block_(block) {}

  /// A required number in [min, max] (bounds inclusive unless `open_min`/`open_max`). A missing
  /// or out-of-range value is recorded and a value inside the range returned, so that the
  /// material's later parameters are still read and checked.
  double required(const std::string& key, double min, double max, bool open_min = false,
                  bool open_max = false);
  /// An optional number with a default.
  double optional(const std::string& key, double fallback, double min, double max,
                  bool open_min = false, bool open_max = false);
  /// An optional word that must be one of `allowed` (the case file's non-numeric values, e.g.
  /// "matching: plane_strain"), with a default; a mistake is recorded and the default returned.
  std::string optional_word(const std::string& key, const std::string& fallback,
                            const std::vector<std::string>& allowed);
  /// True if the block writes `key` (as a number or a word); does not count as asking for it.
  bool has(const std::string& key) const {
    return block_.values.count(key) > 0 || block_.words.count(key) > 0;
  }
  /// Records a mistake of the block as a whole (keys that exclude or require each other).
  void reject_block(const std::string& problem, const std::string& expected);
  /// Records an error for every key of the block that was not asked for, with the nearest
  /// known key as a suggestion ("yeild_stress": did you mean 'yield_stress'?).
  void reject_unknown_keys();
  /// The mistakes recorded so far, in the order they were found.
  const std::vector<InputError>& errors() const { return errors_; }

 private:
  double checked(const std::string& key, const Parameter& p, double min, double max, bool open_min,
                 bool open_max);
  /// Records an error if `key` holds a word where a number is wanted; true if it does.
  bool reject_word(const std::string& key, double min, double max, bool open_min, bool open_max);
  /// The key of the block that looks like a misspelling of `key`, or "".
  std::string misspelling_of(const std::string& key) const;
  const ParameterBlock& block_;
  std::set<std::string> asked_;
  std::vector<InputError> errors_;
};

}  // namespace rktsph
