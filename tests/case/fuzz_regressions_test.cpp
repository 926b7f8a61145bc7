// Every input that ever made the case-file fuzzer (fuzz/case_reader_fuzzer.cpp) fail is kept in
// tests/data/fuzz-regressions/ once its fix is in. Each is a bad case, and checking it (reading it
// and building the Simulation, as `rktsph check` does) must end in an InputError that names the
// file, not in another exception, a crash or a sanitizer report. The fuzz build also runs the
// fuzz target itself over the folder, with its 1 s and 512 MB limits (CMakeLists.txt).
#include <gtest/gtest.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/core/error.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::fuzz_regressions_test {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> reproducers() {
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry :
       fs::directory_iterator(fs::path(RKTSPH_TEST_DATA_DIR) / "fuzz-regressions")) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

/// Empty if checking `file` ends in an InputError naming it; else what happened instead.
std::string wrong_outcome_of_checking(const fs::path& file) {
  try {
    const Simulation simulation(read_case_file(file.string()));
    return "accepted";
  } catch (const InputError& error) {
    const std::string message = error.what();
    if (message.rfind(file.string(), 0) == 0) return "";
    return "an InputError that does not start with the file name: " + message;
  } catch (const RunError& error) {
    return std::string("RunError: ") + error.what();
  } catch (const std::exception& error) {
    return std::string("exception: ") + error.what();
  }
}

TEST(FuzzRegressions, EveryReproducerIsRefusedWithAnInputErrorNamingTheFile) {
  for (const fs::path& file : reproducers()) {
    EXPECT_EQ(wrong_outcome_of_checking(file), "") << file;
  }
}

}  // namespace
}  // namespace rktsph::fuzz_regressions_test
