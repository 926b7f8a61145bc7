// Isotropic linear elasticity: no source term (docs/theory.md §1.2).
#pragma once

#include "rktsph/materials/material.hpp"
#include "rktsph/materials/parameter_reader.hpp"

namespace rktsph {

class LinearElastic final : public Material {
 public:
  LinearElastic(double density, ElasticConstants elastic) : Material(density, elastic) {}
  static std::unique_ptr<Material> from_parameters(ParameterReader& reader);
  std::string model_name() const override { return "linear_elastic"; }
  bool has_flowed(std::span<const double> /*internal*/) const override { return false; }
};

/// Reads density, young_modulus and poisson_ratio (shared by every material).
struct ElasticParameters {
  double density;
  ElasticConstants elastic;
};
ElasticParameters read_elastic_parameters(ParameterReader& reader);

}  // namespace rktsph
