// PLACEHOLDER, being written: until then this case reports that it is not implemented (and fails).
#include "rktsph/core/error.hpp"
#include "rktsph/validation/validation_cases.hpp"

namespace rktsph {

std::vector<CheckResult> validate_vpw_localization(const ValidationContext&) {
  throw RunError("validation case 'vpw-localization' is not implemented yet");
}

}  // namespace rktsph
