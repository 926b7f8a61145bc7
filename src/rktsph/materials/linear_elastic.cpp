#include "rktsph/materials/linear_elastic.hpp"

#include <limits>

namespace rktsph {

ElasticParameters read_elastic_parameters(ParameterReader& reader) {
  constexpr double infinity = std::numeric_limits<double>::infinity();
  ElasticParameters p;
  p.density = reader.required("density", 0.0, infinity, true);
  p.elastic.young_modulus = reader.required("young_modulus", 0.0, infinity, true);
  // nu < 0.5: incompressible elasticity has no finite bulk modulus in this formulation.
  p.elastic.poisson_ratio = reader.required("poisson_ratio", -1.0, 0.5, true, true);
  return p;
}

std::unique_ptr<Material> LinearElastic::from_parameters(ParameterReader& reader) {
  const ElasticParameters p = read_elastic_parameters(reader);
  return std::make_unique<LinearElastic>(p.density, p.elastic);
}

}  // namespace rktsph
