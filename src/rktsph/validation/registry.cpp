#include "rktsph/validation/validation_case.hpp"

namespace rktsph {

const std::vector<ValidationCase>& validation_cases() {
  static const std::vector<ValidationCase> cases = {};
  return cases;
}

}  // namespace rktsph
