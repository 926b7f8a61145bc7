// What tests that run bundled validation cases share: one OpenMP thread per run (ctest runs two
// tests at once on two cores, and a second thread per case would only wait at the barriers of
// loops too short to share on the quick lattices; the parallel paths have their own tests), the
// case by name, and a context for its quick variant in a folder of the test's own.
#pragma once

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "rktsph/validation/validation_case.hpp"

namespace rktsph::test {

/// One OpenMP thread while in scope.
class OneOpenMpThread {
 public:
  OneOpenMpThread() : saved_(omp_get_max_threads()) { omp_set_num_threads(1); }
  ~OneOpenMpThread() { omp_set_num_threads(saved_); }
  OneOpenMpThread(const OneOpenMpThread&) = delete;
  OneOpenMpThread& operator=(const OneOpenMpThread&) = delete;

 private:
  int saved_;
};

/// The bundled validation case `name`, or null.
inline const ValidationCase* bundled_validation(const std::string& name) {
  const auto& cases = validation_cases();
  const auto it = std::find_if(cases.begin(), cases.end(),
                               [&](const ValidationCase& c) { return c.name == name; });
  return it == cases.end() ? nullptr : &*it;
}

/// A context for the quick variants of the bundled cases, run into
/// <temp>/<folder_prefix><pid>.
inline ValidationContext quick_validation_context(const std::string& folder_prefix) {
  ValidationContext context;
  context.cases_directory = std::filesystem::path(RKTSPH_SOURCE_DIR) / "cases";
  context.output_directory =
      std::filesystem::temp_directory_path() / (folder_prefix + std::to_string(getpid()));
  context.quick = true;
  return context;
}

}  // namespace rktsph::test
