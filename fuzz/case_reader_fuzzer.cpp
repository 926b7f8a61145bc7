// libFuzzer target: the fuzz input is the text of a case file, and the target does what
// `rktsph check` does with it (app/main.cpp, command_check): read and validate the case, then
// build the Simulation (nodes, materials, groups, boundary conditions, operators).
//
// An InputError or RunError is the expected answer to a bad case. Anything else is a finding:
// another exception (std::bad_alloc included: a case must be refused before it is built too large)
// escapes and aborts, and ASan/UBSan reports, timeouts and out-of-memory are caught by libFuzzer.
// How to run it: README.md, "Fuzzing".
#include <omp.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/core/error.hpp"
#include "rktsph/output/run_observers.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace {

// A valid case of more lattice points than this is only read, not built. Building takes 1-3 ms
// per node under the sanitizers (measured on the bundled cases, 2 shared cores), so a legitimate
// case of a few thousand nodes would exceed the 1 s allowed per input, which is not a defect.
// Cases far larger than any real run are the reader's to refuse (its node-count limit).
constexpr double kMaxBuiltLatticePoints = 300.0;

// Points of the lattice that build_node_sets lays over the bounding box of all shapes (or the
// nodes of a triangle mesh at that spacing).
double lattice_points(const rktsph::CaseDescription& description) {
  const rktsph::GeometrySpec& geometry = description.geometry;
  double points = 1.0;
  for (int axis = 0; axis < description.dimension; ++axis) {
    double low = std::numeric_limits<double>::infinity();
    double high = -low;
    for (const rktsph::ShapeSpec& shape : geometry.shapes) {
      for (const rktsph::Vec3& vertex : shape.vertices) {
        low = std::min(low, vertex[axis]);
        high = std::max(high, vertex[axis]);
      }
    }
    if (!(high >= low)) return 0.0;
    points *= (high - low) / geometry.spacing + 1.0;
  }
  // A triangle mesh holds about 2.5 times the nodes of the lattice at the same spacing
  // (docs/theory.md §3.6).
  if (geometry.cells == rktsph::CellLayout::Triangles) points *= 2.5;
  return points;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  // One thread: the 1 s per input limit is then about the work, not about the machine's load.
  omp_set_num_threads(1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const rktsph::CaseDescription description = rktsph::read_case_text(text, "fuzz-case.yaml");
    if (!(lattice_points(description) <= kMaxBuiltLatticePoints)) return 0;
    const rktsph::Simulation simulation(description);
    rktsph::check_run_observers(simulation);  // output fields, probe groups and fields, as check
    // What `check` prints; reading them must not fail either.
    static_cast<void>(simulation.time_step());
    static_cast<void>(simulation.total_steps());
  } catch (const rktsph::InputError&) {
  } catch (const rktsph::RunError&) {
  }
  return 0;
}
