#include "rktsph/core/build_info.hpp"

#include <fmt/format.h>

// RKTSPH_COMMIT and RKTSPH_BUILD_TYPE, written by CMakeLists.txt at configure time.
#include "rktsph/build_commit.hpp"

namespace rktsph {

const char* build_commit() {
  return RKTSPH_COMMIT;
}

const char* build_type() {
  return RKTSPH_BUILD_TYPE;
}

std::string version_text() {
  return fmt::format("{} (commit {}, {} build)", RKTSPH_VERSION, build_commit(), build_type());
}

}  // namespace rktsph
