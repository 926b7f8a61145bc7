#include "rktsph/core/build_info.hpp"

#include <fmt/format.h>

// Only this file gets the commit as a definition, so a new commit recompiles one file, not all.
#ifndef RKTSPH_COMMIT
#define RKTSPH_COMMIT "unknown"
#endif
#ifndef RKTSPH_BUILD_TYPE
#define RKTSPH_BUILD_TYPE "unknown"
#endif

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
