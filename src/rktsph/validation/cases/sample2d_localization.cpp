// PLACEHOLDER, being written: until then this case reports that it is not implemented (and fails).
#include "rktsph/core/error.hpp"
#include "rktsph/validation/validation_cases.hpp"

namespace rktsph {

std::vector<CheckResult> validate_sample2d_localization(const ValidationContext&) {
  throw RunError("validation case 'sample2d-localization' is not implemented yet");
}

}  // namespace rktsph
