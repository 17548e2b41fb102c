// The step engine (core/step_engine.hpp) on a pipeline of plain tasks, no physics:
// the dt rule (fixed, max_dt, the smallest stable limit, nothing moves), landing
// exactly on targets without a sliver step, advanceTo's step count, the finite
// check that names the field and the global cell on any decomposition, and the
// stop request. Expected values are exact: the rule is arithmetic, not numerics.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "core/step_engine.hpp"

using namespace voigt;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Rig {
  State st;
  Pipeline p;
  int stepsRun = 0; // Stage::Momentum tasks run
  Rig() {
    st.grid = makeGrid(MPI_COMM_WORLD, {8, 6, 4}, {0, 0, 0}, {1, 1, 1}, {false, false, false});
    st.fields.declare("phi", Centring::Cell, 1, "test");
    st.fields.declare("u", Centring::Node, 3, "test");
    st.fields.declareDerived("scratch", Centring::Cell, 1, "test");
    st.fields.allocate(st.grid);
    p.add(Stage::Momentum, "test", "count", [this](State&) { ++stepsRun; });
  }
  ~Rig() { freeGrid(st.grid); }
};

StepEngine::Limit limit(double dt, const char* why) {
  return [dt, why](const State&) { return DtLimit{dt, why}; };
}

} // namespace

// chooseDt(10) with the limits 0.3 and 0.2 under the time section tc: {dt, reason}.
static DtLimit chosen(const TimeCfg& tc) {
  Rig r;
  StepEngine e(r.st, r.p, tc);
  EXPECT_EQ(e.stableDt().reason, "none");
  e.addLimit(limit(0.3, "advective CFL"));
  e.addLimit(limit(0.2, "elastic wave"));
  const double dt = e.chooseDt(10);
  return {dt, r.st.dtReason};
}

TEST(StepEngine, SmallestLimitMaxDtFixed) {
  TimeCfg tc;
  const DtLimit a = chosen(tc);
  EXPECT_EQ(a.dt, 0.2);
  EXPECT_EQ(a.reason, "elastic wave");
  tc.maxDt = 0.1;
  const DtLimit b = chosen(tc);
  EXPECT_EQ(b.dt, 0.1);
  EXPECT_EQ(b.reason, "max_dt");
  tc.dt = 0.05; // a fixed step ignores the limits and max_dt
  const DtLimit c = chosen(tc);
  EXPECT_EQ(c.dt, 0.05);
  EXPECT_EQ(c.reason, "fixed");
}

TEST(StepEngine, NothingMovesTakesMaxDtOrTheTimeLeft) {
  Rig r;
  TimeCfg tc;
  StepEngine e(r.st, r.p, tc);
  e.addLimit(limit(kInf, "advective CFL"));
  r.st.t = 0.25;
  EXPECT_EQ(e.chooseDt(1.0), 0.75);
  EXPECT_EQ(r.st.dtReason, "nothing moves (clipped to output/end)");
  EXPECT_EQ(e.rule({kInf, "x"}, 2.0).dt, 2.0);
  tc.maxDt = 0.1;
  StepEngine m(r.st, r.p, tc);
  EXPECT_EQ(m.rule({kInf, "x"}, 2.0).dt, 0.1);
}

TEST(StepEngine, LandsOnTargetsWithoutASliver) {
  Rig r;
  StepEngine e(r.st, r.p, TimeCfg{});
  e.addLimit(limit(0.3, "advective CFL"));
  r.st.t = 0.0;
  EXPECT_EQ(e.chooseDt(10, 0.2), 0.2); // the output time first
  EXPECT_EQ(StepEngine::unclipped(r.st.dtReason), "advective CFL");
  // A step within 1e-9 (relative) of the target lands on it instead of leaving a sliver.
  EXPECT_EQ(e.chooseDt(0.3 * (1 + 0.5e-9)), 0.3 * (1 + 0.5e-9));
  EXPECT_EQ(e.chooseDt(0.3 * (1 + 2e-9)), 0.3);
  // A target behind t is not a target.
  r.st.t = 0.5;
  EXPECT_EQ(e.chooseDt(10, 0.2), 0.3);
  // A limit's own parenthesis survives unclipped().
  EXPECT_EQ(StepEngine::unclipped("advective CFL (prescribed flow) (clipped to output/end)"),
            "advective CFL (prescribed flow)");
}

TEST(StepEngine, AdvanceToLandsExactly) {
  Rig r;
  StepEngine e(r.st, r.p, TimeCfg{});
  e.addLimit(limit(0.3, "advective CFL"));
  int hooks = 0, seen = 0;
  e.addAfterStep([&](State&) { ++hooks; });
  // 0.3, 0.6, 0.9, then 0.1 to land on 1.0.
  EXPECT_EQ(e.advanceTo(1.0, [&](const State&) { ++seen; }), 4);
  EXPECT_EQ(r.st.t, 1.0);
  EXPECT_EQ(r.st.step, 4);
  EXPECT_EQ(r.stepsRun, 4);
  EXPECT_EQ(hooks, 4);
  EXPECT_EQ(seen, 4);
  EXPECT_EQ(e.advanceTo(1.0), 0); // already there
  EXPECT_EQ(e.advanceTo(10, {}, 2), 2); // the step cap
  EXPECT_EQ(r.st.step, 6);
  e.advanceSteps(3, 0.01);
  EXPECT_EQ(r.st.step, 9);
}

// What one step's BlowUp says ("" if it did not throw).
static std::string blowUp(StepEngine& e) {
  try {
    e.advance(0.1);
  } catch (const BlowUp& b) {
    return b.what();
  }
  return "";
}

TEST(StepEngine, NonFiniteNamesFieldAndGlobalCell) {
  Rig r;
  StepEngine e(r.st, r.p, TimeCfg{});
  const Grid& g = r.st.grid;
  // A NaN in u.y at global node (5, 2, 3), written by whichever rank owns it.
  VecField u = r.st.fields.vector("u");
  const int gi = 5, gj = 2, gk = 3;
  const bool mine = gi >= g.c0[0] && gi < g.nodeHi(0) && gj >= g.c0[1] && gj < g.nodeHi(1) && gk >= g.c0[2] &&
                    gk < g.nodeHi(2);
  if (mine) {
    auto one = Kokkos::subview(u.c[1], g.local(0, gi), g.local(1, gj), g.local(2, gk));
    Kokkos::deep_copy(one, std::nan(""));
  }
  const std::string m = blowUp(e);
  EXPECT_NE(m.find("field 'u' component y"), std::string::npos) << m;
  EXPECT_NE(m.find("node (5, 2, 3)"), std::string::npos) << m;
  EXPECT_NE(m.find("after step 1"), std::string::npos) << m;
}

// A derived field (recomputed within each step) is left out of the per-step check and
// caught by the check of all fields that comes before any write (voigt run).
TEST(StepEngine, DerivedFieldsCheckedBeforeWritesOnly) {
  Rig r;
  StepEngine e(r.st, r.p, TimeCfg{});
  const Grid& g = r.st.grid;
  Field s = r.st.fields.scalar("scratch");
  const int gi = 1, gj = 1, gk = 1; // global cell (1, 1, 1)
  if (gi >= g.c0[0] && gi < g.c1[0] && gj >= g.c0[1] && gj < g.c1[1] &&
      gk >= g.c0[2] && gk < g.c1[2])
    Kokkos::deep_copy(Kokkos::subview(s, g.local(0, gi), g.local(1, gj), g.local(2, gk)), INFINITY);
  EXPECT_EQ(blowUp(e), "");
  EXPECT_EQ(e.fieldsWhere(true), std::vector<std::string>{"scratch"});
  EXPECT_EQ(e.fieldsWhere(false), (std::vector<std::string>{"phi", "u"}));
  EXPECT_EQ(e.nonFinite({"phi", "u"}), "");
  const std::string m = e.nonFinite(e.fieldsWhere(true));
  EXPECT_NE(m.find("field 'scratch' = inf at cell (1, 1, 1)"), std::string::npos) << m;
}

// Declared derived by one effect and as state by another: state (checked every step).
TEST(StepEngine, StateWinsOverDerived) {
  FieldStore f;
  f.declareDerived("a", Centring::Cell, 1, "one");
  f.declare("a", Centring::Cell, 1, "two");
  f.declareDerived("a", Centring::Cell, 1, "three");
  EXPECT_FALSE(f.decls().at("a").derived);
  f.declareDerived("b", Centring::Cell, 1, "one");
  f.declareDerived("b", Centring::Cell, 1, "two");
  EXPECT_TRUE(f.decls().at("b").derived);
}

TEST(StepEngine, StopRequestStops) {
  Rig r;
  r.p.add(Stage::Corrections, "test", "stop", [](State& st) { st.stopRequest = "contact"; });
  StepEngine e(r.st, r.p, TimeCfg{});
  EXPECT_EQ(blowUp(e), "stopped: contact");
}
