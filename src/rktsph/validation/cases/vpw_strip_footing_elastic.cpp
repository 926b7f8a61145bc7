// PLACEHOLDER, being written: until then this case reports that it is not implemented (and fails).
#include "rktsph/core/error.hpp"
#include "rktsph/validation/validation_cases.hpp"

namespace rktsph {

std::vector<CheckResult> validate_vpw_strip_footing_elastic(const ValidationContext&) {
  throw RunError("validation case 'vpw-strip-footing-elastic' is not implemented yet");
}

}  // namespace rktsph
