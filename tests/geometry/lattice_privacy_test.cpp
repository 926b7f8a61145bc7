// The lattice is one way to build cells (docs/theory.md §3.5): its indices stay inside the
// lattice builder, so that everything else works on any mesh. This reads the sources.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace rktsph::lattice_privacy_test {
namespace {

namespace fs = std::filesystem;

const std::regex kLatticeIndex(
    R"(\b(LatticeIndex|node_index|stress_point_index|node_lookup|lattice_size|node_at)\b)");

std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(LatticePrivacy, NoFileOutsideTheLatticeBuilderReadsALatticeIndex) {
  const fs::path source = fs::path(RKTSPH_SOURCE_DIR) / "src" / "rktsph";
  const fs::path builder = source / "geometry" / "node_sets.cpp";
  // The pattern finds the builder's own use, so that a renamed index is not silently missed.
  EXPECT_TRUE(std::regex_search(text_of(builder), kLatticeIndex));
  std::vector<std::string> readers;
  for (const auto& entry : fs::recursive_directory_iterator(source)) {
    const fs::path& path = entry.path();
    if (path == builder || (path.extension() != ".cpp" && path.extension() != ".hpp")) continue;
    if (std::regex_search(text_of(path), kLatticeIndex)) readers.push_back(path.string());
  }
  EXPECT_TRUE(readers.empty()) << "lattice indices read in " << ::testing::PrintToString(readers);
}

}  // namespace
}  // namespace rktsph::lattice_privacy_test
