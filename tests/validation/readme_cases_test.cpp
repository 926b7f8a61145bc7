// The README's table of bundled cases is what users copy names from: every name in its first
// column must be a validation case `rktsph validate` accepts, every validation case must be listed,
// and every case folder must carry a README (docs: "each folder holds case.yaml and a README").
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>

#include "rktsph/validation/validation_case.hpp"

namespace rktsph::readme_cases_test {
namespace {

const std::filesystem::path kSource = RKTSPH_SOURCE_DIR;

std::set<std::string> readme_table_names() {
  std::ifstream readme(kSource / "README.md");
  std::set<std::string> names;
  std::string line;
  bool in_table = false;
  const std::regex row(R"(^\| `([a-z0-9-]+)` \|)");
  while (std::getline(readme, line)) {
    if (line.rfind("| validation name |", 0) == 0) in_table = true;
    if (!in_table) continue;
    if (line.empty()) break;
    std::smatch match;
    if (std::regex_search(line, match, row)) names.insert(match[1]);
  }
  return names;
}

TEST(ReadmeCases, TableNamesAreExactlyTheValidationCases) {
  const std::set<std::string> listed = readme_table_names();
  ASSERT_FALSE(listed.empty()) << "no '| validation name |' table in README.md";
  std::set<std::string> registered;
  for (const ValidationCase& validation : validation_cases())
    registered.insert(validation.name);
  for (const std::string& name : listed)
    EXPECT_TRUE(registered.count(name)) << "README lists '" << name << "', not a validation case";
  for (const std::string& name : registered)
    EXPECT_TRUE(listed.count(name)) << "validation case '" << name << "' missing from README";
}

TEST(ReadmeCases, EveryCaseFolderHasAReadme) {
  for (const auto& entry : std::filesystem::directory_iterator(kSource / "cases")) {
    if (!entry.is_directory() || !std::filesystem::exists(entry.path() / "case.yaml")) continue;
    EXPECT_TRUE(std::filesystem::exists(entry.path() / "README.md"))
        << entry.path().filename().string() << " has no README.md";
  }
}

}  // namespace
}  // namespace rktsph::readme_cases_test
