// Case text for step tests: linear-elastic soil (rho = 2000 kg/m3, E = 10 MPa, nu = 0.3) in plane
// strain (or stress), with its shapes, boundary conditions, loads and numerics given as YAML flow
// text.
#pragma once

#include <string>
#include <vector>

#include "rktsph/case/case_reader.hpp"

namespace rktsph::test {

struct ElasticBlock {
  double spacing = 1.0;
  std::string shapes = rectangle(12.0, 5.0);
  std::vector<std::string> conditions;  ///< e.g. "{group: xmin, fixed: true}"
  std::string loads;                    ///< e.g. "{damping: {coefficient: 20}}"; empty = none
  std::string groups;                   ///< e.g. "{load: {box: {...}}}"; empty = none
  std::string numerics = "{}";
  std::string plane = "strain";
  std::string cells = "lattice";  ///< geometry.cells: lattice or triangles

  static std::string rectangle(double width, double height) {
    return "[{rectangle: {min: [0, 0], max: [" + std::to_string(width) + ", " +
           std::to_string(height) + "]}, material: soil}]";
  }

  std::string text() const {
    std::string yaml = "name: block\ndimension: 2\nplane: " + plane +
                       "\ngeometry:\n  cells: " + cells +
                       "\n  spacing: " + std::to_string(spacing) + "\n  shapes: " + shapes +
                       "\nmaterials:\n  soil: {model: linear_elastic, density: 2000.0, "
                       "young_modulus: 1.0e7, poisson_ratio: 0.3}\n";
    if (!groups.empty()) yaml += "groups: " + groups + "\n";
    if (!conditions.empty()) {
      yaml += "boundary_conditions:\n";
      for (const std::string& condition : conditions)
        yaml += "  - " + condition + "\n";
    }
    if (!loads.empty()) yaml += "loads: " + loads + "\n";
    return yaml + "numerics: " + numerics + "\ntime: {end: 1.0}\n";
  }

  CaseDescription description() const { return read_case_text(text(), "block.yaml"); }
};

}  // namespace rktsph::test
