// Which program made a result: the version, the git commit it was built from and the build type,
// for --version, summary.json and run.log (set at configure time by CMakeLists.txt).
#pragma once

#include <string>

namespace rktsph {

/// The short git commit ("1a2b3c4"), with "-dirty" when tracked files were modified, or
/// "unknown" when the sources were not a git checkout.
const char* build_commit();
/// CMAKE_BUILD_TYPE: "Release", "Debug", "RelWithDebInfo", ...
const char* build_type();
/// "0.1.0 (commit 1a2b3c4, Release build)".
std::string version_text();

}  // namespace rktsph
