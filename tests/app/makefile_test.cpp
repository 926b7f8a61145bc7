// The top-level Makefile as a user on a fresh machine meets it: a build that fails for a missing
// library says to run `make deps`, and `make test` installs what the report tools' tests need
// instead of skipping them.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "../support/shell.hpp"

namespace makefile_test {
namespace {

namespace fs = std::filesystem;

const std::string kMake = std::string("make --no-print-directory -C ") + RKTSPH_SOURCE_DIR;

TEST(Makefile, AConfigureWithoutEigenSaysToRunMakeDeps) {
  // A machine without Eigen3, as CMake sees it: the package may not be found.
  const fs::path build = rktsph::test::scratch_file("rktsph_makefile", "build-no-eigen");
  const rktsph::test::ShellResult result =
      rktsph::test::shell(kMake + " configure BUILD_DIR=" + build.string() +
                          " CMAKE_FLAGS=-DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=TRUE 2>&1");
  EXPECT_NE(result.status, 0) << result.output;
  EXPECT_NE(result.output.find("run 'make deps' first"), std::string::npos) << result.output;
  fs::remove_all(build);
}

TEST(Makefile, MakeTestInstallsWhatTheReportTestsNeed) {
  // -n: what `make test` would do, without doing it.
  const rktsph::test::ShellResult result =
      rktsph::test::shell(kMake + " -n test BUILD_DIR=/nonexistent/build 2>&1");
  EXPECT_EQ(result.status, 0) << result.output;
  EXPECT_NE(result.output.find("python3-matplotlib"), std::string::npos) << result.output;
  // The browser check of the report is skipped without chromium (issue 30: nothing skipped).
  EXPECT_NE(result.output.find("chromium"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace makefile_test
