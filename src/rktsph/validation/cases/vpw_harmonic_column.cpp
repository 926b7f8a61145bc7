// PLACEHOLDER, being written: until then this case reports that it is not implemented (and fails).
#include "rktsph/core/error.hpp"
#include "rktsph/validation/validation_cases.hpp"

namespace rktsph {

std::vector<CheckResult> validate_vpw_harmonic_column(const ValidationContext&) {
  throw RunError("validation case 'vpw-harmonic-column' is not implemented yet");
}

}  // namespace rktsph
