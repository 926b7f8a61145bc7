// The model registry and the case layer's model names agree: every name a case may select has
// one factory, and each factory makes a model of the dimension the case asks for.
#include <gtest/gtest.h>

#include "../support/elastic_block.hpp"
#include "rktsph/case/model_names.hpp"
#include "rktsph/models/model_registry.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::model_registry_test {
namespace {

TEST(ModelRegistry, EveryModelNameHasOneEntryInTheSameOrder) {
  ASSERT_EQ(registered_models().size(), model_names().size());
  for (std::size_t k = 0; k < model_names().size(); ++k) {
    EXPECT_EQ(registered_models()[k].kind, model_names()[k].kind) << model_names()[k].name;
    EXPECT_NE(registered_models()[k].create, nullptr) << model_names()[k].name;
    EXPECT_EQ(&registered_model(model_names()[k].kind), &registered_models()[k]);
  }
}

TEST(ModelRegistry, TheAssemblyTakesTheModelAndItsProjectionFromTheRegistry) {
  test::ElasticBlock block;
  Simulation dry(block.description());
  EXPECT_EQ(dry.model().pore_pressure_field(), -1);
  EXPECT_EQ(dry.pressure_projection(), nullptr);
  EXPECT_EQ(dry.assembly().registered_model().kind, ModelKind::DrySolid);
}

}  // namespace
}  // namespace rktsph::model_registry_test
