// Errors that carry where they come from.
//
// InputError is for anything a user can fix in a case file or on the command line: it names the
// file, line and column, the key, the value found and what is allowed. The command line turns it
// into exit status 2. RunError is for a run that cannot go on (divergence, a failed solve); it
// names where, which field and which step, and maps to exit status 3.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace rktsph {

/// A position in a text file; line and column are 1-based, 0 means "unknown".
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;

  /// "file:line:column", "file:line" or "file", whichever is known.
  std::string to_string() const;
};

/// At most this many mistakes are listed in one report; the rest are counted ("and 3 more").
inline constexpr std::size_t kMaxReportedInputErrors = 20;

class InputError : public std::runtime_error {
 public:
  /// `key` is the dotted path of the offending key (e.g. "materials.soil.young_modulus"),
  /// `value` what was found (empty if the key is missing), `allowed` what would be accepted.
  InputError(SourceLocation location, std::string key, std::string value, std::string problem,
             std::string allowed);

  /// Several independent mistakes as one error, like a compiler's report: sorted into file order
  /// (case-file lines first, then the errors of --set arguments), each on its own line of
  /// what(), at most kMaxReportedInputErrors of them. location(), key() and the other accessors
  /// describe the first. Errors that are themselves combined are flattened; one error is returned
  /// as it is. `errors` must not be empty.
  static InputError combine(std::vector<InputError> errors);

  /// The mistakes this error reports, in file order: itself alone, or those it combines.
  std::vector<InputError> errors() const;

  const SourceLocation& location() const { return location_; }
  const std::string& key() const { return key_; }
  const std::string& value() const { return value_; }
  const std::string& problem() const { return problem_; }
  const std::string& allowed() const { return allowed_; }

 private:
  SourceLocation location_;
  std::string key_;
  std::string value_;
  std::string problem_;
  std::string allowed_;
  std::vector<InputError> combined_;  ///< empty unless made by combine()
};

class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rktsph
