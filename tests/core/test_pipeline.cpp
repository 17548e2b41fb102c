// Pipeline task order: registration order, except that a task declared `after`
// some effects runs behind their tasks in its stage, whoever registered first,
// and the other tasks keep their order (the step's Corrections stage relies on
// it: reinit, then the level set's volume correction, then elasticity).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "core/pipeline.hpp"
#include "effects/effect.hpp"

using namespace voigt;

namespace {
std::vector<std::string> order(const Pipeline& p, Stage s) {
  std::vector<std::string> v;
  for (auto& t : p.tasks(s)) v.push_back(t.effect);
  return v;
}
void none(State&) {}
} // namespace

TEST(Pipeline, RegistrationOrderWithoutAfter) {
  Pipeline p;
  for (const char* e : {"a", "b", "c"}) p.add(Stage::Corrections, e, "t", none);
  EXPECT_EQ(order(p, Stage::Corrections), (std::vector<std::string>{"a", "b", "c"}));
}

TEST(Pipeline, AfterMovesOnlyTheDeclaringTask) {
  // The effects' real registration order: level_set, elasticity, reinit.
  Pipeline p;
  p.add(Stage::Corrections, "level_set", "correction", none, {"reinit"});
  p.add(Stage::Corrections, "elasticity", "jaumann", none, {"reinit", "level_set"});
  p.add(Stage::Corrections, "reinit", "eikonal", none);
  EXPECT_EQ(order(p, Stage::Corrections), (std::vector<std::string>{"reinit", "level_set", "elasticity"}));
  // Without the elasticity constraint, elasticity keeps its place before reinit.
  Pipeline q;
  q.add(Stage::Corrections, "level_set", "correction", none, {"reinit"});
  q.add(Stage::Corrections, "elasticity", "jaumann", none);
  q.add(Stage::Corrections, "reinit", "eikonal", none);
  EXPECT_EQ(order(q, Stage::Corrections), (std::vector<std::string>{"elasticity", "reinit", "level_set"}));
  // An absent effect is ignored; other stages are separate.
  Pipeline r;
  r.add(Stage::Corrections, "level_set", "correction", none, {"reinit"});
  r.add(Stage::Diagnostics, "reinit", "stats", none);
  r.add(Stage::Corrections, "elasticity", "jaumann", none);
  EXPECT_EQ(order(r, Stage::Corrections), (std::vector<std::string>{"level_set", "elasticity"}));
}

TEST(Pipeline, CycleIsAnError) {
  Pipeline p;
  p.add(Stage::Corrections, "a", "t", none, {"b"});
  EXPECT_THROW(p.add(Stage::Corrections, "b", "t", none, {"a"}), std::logic_error);
}

// Effects set up (and so register their tasks) in the order their setupAfter() declares;
// effects that declare nothing between them keep the scene's order.
TEST(EffectOrder, DeclaredSetupAfterThenSceneOrder) {
  const std::string yaml = R"(domain: {lo: [0, 0, 0], hi: [1, 1, 1], cells: [8, 8, 8]}
materials:
  water: {density: 1000, viscosity: 1e-3}
  gel: {density: 1100, viscosity: 0.1, shear_modulus: 1000}
fluid: water
gravity: [0, -9.81, 0]
effects: [gravity, reinit, elasticity, level_set, navier_stokes]
level_set:
  phase: gel
  shape: {type: sphere, center: [0.5, 0.5, 0.5], radius: 0.2}
)";
  std::vector<std::string> names;
  for (auto& e : makeEffects(loadSceneWithEffectsFromString(yaml, "order.yaml"))) names.push_back(e->name());
  EXPECT_EQ(names, (std::vector<std::string>{"navier_stokes", "level_set", "elasticity", "gravity", "reinit"}));
}
