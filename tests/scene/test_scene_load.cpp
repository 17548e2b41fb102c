// Scene loader: a full scene round-trips, --set overrides apply, and every bad
// scene fails with a message naming the line and the key path.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scene/load.hpp"
#include "scene/reader.hpp"

using namespace voigt;

namespace {

LoadOptions options(std::vector<std::string> overrides = {}) {
  LoadOptions o;
  o.overrides = std::move(overrides);
  o.knownEffects = {"navier_stokes", "gravity", "obstacles", "level_set"};
  o.extraSections = {"level_set"};
  return o;
}

// The SceneError message, or "" if loading succeeded.
std::string errorOf(const std::string& yaml, const LoadOptions& o = options()) {
  try {
    loadSceneFromString(yaml, "test.yaml", o);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

const char* kFull = R"(name: cavity
domain: {lo: [0, 0, 0], hi: [1, 1, 0.25], cells: [32, 32, 8], ranks: [2, 1, 1]}
boundaries:
  default: {type: slip}
  y+: {type: no_slip, velocity: [1, 0, 0]}
  x-: {type: inflow, velocity: [0.1, 0, 0]}
  x+: {type: outflow, pressure: 0.5}
  z-: {type: periodic}
  z+: {type: periodic}
time: {end: 2.5, dt: 0, cfl: 0.4, viscous_safety: 0.8, max_dt: 0.01, min_dt: 1e-10, max_steps: 100}
materials:
  air: {density: 1.2, viscosity: 1.8e-5}
  water: {density: 1000, viscosity: 1e-3}
fluid: water
effects: [navier_stokes, gravity, obstacles]
gravity: [0, -9.81, 0]
obstacles:
  - {type: cylinder, center: [0.5, 0.5, 0.1], radius: 0.1, axis: x, velocity: [0, 0, 0.5]}
  - {type: box, lo: [0.1, 0.1, 0], hi: [0.2, 0.3, 0.25]}
  - {type: sphere, center: [0.7, 0.7, 0.1], radius: 0.05}
initial: {velocity: uniform, uniform: [1, 2, 3], amplitude: 2, pressure: 1}
projection: {operator: approximate, tolerance: 1e-6, max_iterations: 50, preconditioner: jacobi, damping: 0.8, sweeps: 3}
advection: {limiter: van_leer}
output: {interval: 0.1, fields: [velocity], enabled: false}
probes:
  - {name: centre, point: [0.5, 0.5, 0.125], fields: [velocity, pressure], interval: 0.01}
  - {name: mid-line, line: {from: [0.5, 0, 0.1], to: [0.5, 1, 0.1], points: 65}, fields: [velocity]}
level_set:
  thickness: 0.02
)";

TEST(SceneLoad, FullSceneRoundTrips) {
  Scene s = loadSceneFromString(kFull, "full.yaml", options());
  EXPECT_EQ(s.name, "cavity");
  EXPECT_EQ(s.path, "");
  EXPECT_EQ(s.hi, (Vec3{1, 1, 0.25}));
  EXPECT_EQ(s.cells, (std::array<int, 3>{32, 32, 8}));
  EXPECT_EQ(s.ranks, (std::array<int, 3>{2, 1, 1}));
  EXPECT_EQ(s.bc[0].type, BcType::Inflow);
  EXPECT_EQ(s.bc[0].velocity, (Vec3{0.1, 0, 0}));
  EXPECT_EQ(s.bc[1].type, BcType::Outflow);
  EXPECT_DOUBLE_EQ(s.bc[1].pressure, 0.5);
  EXPECT_EQ(s.bc[2].type, BcType::Slip); // from default
  EXPECT_EQ(s.bc[3].velocity, (Vec3{1, 0, 0}));
  EXPECT_TRUE(s.periodic(2));
  EXPECT_FALSE(s.periodic(0));
  EXPECT_DOUBLE_EQ(s.time.endTime, 2.5);
  EXPECT_DOUBLE_EQ(s.time.cfl, 0.4);
  EXPECT_DOUBLE_EQ(s.time.viscousSafety, 0.8);
  EXPECT_DOUBLE_EQ(s.time.maxDt, 0.01);
  EXPECT_DOUBLE_EQ(s.time.minDt, 1e-10);
  EXPECT_EQ(s.time.maxSteps, 100);
  EXPECT_EQ(s.fluid, "water");
  EXPECT_DOUBLE_EQ(s.fluidMaterial().density, 1000);
  EXPECT_DOUBLE_EQ(s.materials.at("air").viscosity, 1.8e-5);
  EXPECT_EQ(s.effects, (std::vector<std::string>{"navier_stokes", "gravity", "obstacles"}));
  EXPECT_EQ(s.gravity, (Vec3{0, -9.81, 0}));
  ASSERT_EQ(s.obstacles.size(), 3u);
  EXPECT_EQ(s.obstacles[0].kind, Obstacle::Kind::Cylinder);
  EXPECT_EQ(s.obstacles[0].axis, 0);
  EXPECT_EQ(s.obstacles[0].velocity, (Vec3{0, 0, 0.5}));
  EXPECT_EQ(s.obstacles[1].kind, Obstacle::Kind::Box);
  EXPECT_EQ(s.obstacles[1].hi, (Vec3{0.2, 0.3, 0.25}));
  EXPECT_EQ(s.obstacles[2].kind, Obstacle::Kind::Sphere);
  EXPECT_DOUBLE_EQ(s.obstacles[2].radius, 0.05);
  EXPECT_EQ(s.initial.velocity, "uniform");
  EXPECT_EQ(s.initial.uniform, (Vec3{1, 2, 3}));
  EXPECT_EQ(s.projection.op, ProjectionCfg::Op::Approximate);
  EXPECT_EQ(s.projection.maxIterations, 50);
  EXPECT_EQ(s.projection.preconditioner, "jacobi");
  EXPECT_EQ(s.projection.sweeps, 3);
  EXPECT_EQ(s.advection.limiter, "van_leer");
  EXPECT_FALSE(s.output.enabled);
  EXPECT_EQ(s.output.fields, (std::vector<std::string>{"velocity"}));
  ASSERT_EQ(s.probes.size(), 2u);
  EXPECT_EQ(s.probes[0].kind, Probe::Kind::Point);
  EXPECT_DOUBLE_EQ(s.probes[0].interval, 0.01);
  EXPECT_EQ(s.probes[1].kind, Probe::Kind::Line);
  EXPECT_EQ(s.probes[1].points, 65);
  EXPECT_EQ(s.probes[1].b, (Vec3{0.5, 1, 0.1}));
  // Effect-owned sections stay in the tree for the effect to read.
  EXPECT_DOUBLE_EQ(topSection(s, "level_set").number("thickness", 0), 0.02);
}

TEST(SceneLoad, DefaultsForAMinimalScene) {
  Scene s = loadSceneFromString("domain: {cells: [4, 4, 4]}\n", "dir/minimal.yaml", options());
  EXPECT_EQ(s.name, "minimal");
  EXPECT_EQ(s.fluid, "default");
  EXPECT_EQ(s.bc[5].type, BcType::NoSlip);
  EXPECT_TRUE(std::isinf(s.time.maxDt));
  EXPECT_EQ(s.time.maxSteps, -1);
  EXPECT_STREQ(toString(BcType::Outflow), "outflow");
}

// projection.preconditioner not given: fast_diagonalization with the exact operator (the
// default); with the approximate one multigrid from 32^3 cells or with two densities, else
// sgs (the rule and its measurements: src/scene/load.cpp, perf/README.md).
TEST(SceneLoad, DefaultPreconditionerBySizeAndPhases) {
  auto pc = [](const std::string& yaml, std::vector<std::string> sets = {}) {
    Scene s = loadSceneFromString(yaml, "pc.yaml", options(std::move(sets)));
    return s.projection.preconditioner + (s.projection.preconditionerAuto ? " auto" : "");
  };
  const std::string twoPhase = "domain: {cells: [8, 8, 8]}\n"
                               "materials: {air: {density: 1}, water: {density: 1000}}\nfluid: air\n"
                               "effects: [navier_stokes, level_set]\nlevel_set: {phase: water}\n";
  const std::string approx = "projection.operator=approximate";
  EXPECT_EQ(pc("domain: {cells: [4, 4, 4]}\n"), "fast_diagonalization auto");
  EXPECT_EQ(pc(twoPhase), "fast_diagonalization auto");
  EXPECT_EQ(pc("domain: {cells: [4, 4, 4]}\n", {approx}), "sgs auto");
  EXPECT_EQ(pc("domain: {cells: [32, 32, 31]}\n", {approx}), "sgs auto");
  EXPECT_EQ(pc("domain: {cells: [32, 32, 32]}\n", {approx}), "multigrid auto");
  EXPECT_EQ(pc(twoPhase, {approx}), "multigrid auto");
  EXPECT_EQ(pc(twoPhase, {approx, "materials.water.density=1"}), "sgs auto"); // same density: one phase
  EXPECT_EQ(pc(twoPhase, {"projection.preconditioner=sgs"}), "sgs");          // written: kept
  EXPECT_EQ(pc("domain: {cells: [32, 32, 32]}\nprojection: {preconditioner: jacobi}\n"), "jacobi");
}

// An oscillating wall: velocity * sin(omega t + phase); plain walls stay constant.
TEST(SceneLoad, OscillatingWall) {
  Scene s = loadSceneFromString("domain: {cells: [4, 4, 4]}\n"
                                "boundaries: {y+: {velocity: [2, 0, 0], oscillation: {omega: 3, phase: 0.5}},\n"
                                "             y-: {velocity: [1, 0, 0]}}\n",
                                "test.yaml", options());
  const FaceBc& top = s.bc[3];
  EXPECT_TRUE(top.oscillating);
  EXPECT_EQ(top.omega, 3);
  EXPECT_EQ(top.phase, 0.5);
  EXPECT_DOUBLE_EQ(top.velocityAt(0.7)[0], 2 * std::sin(3 * 0.7 + 0.5));
  EXPECT_EQ(top.velocityAt(0.7)[1], 0);
  EXPECT_FALSE(s.bc[2].oscillating);
  EXPECT_EQ(s.bc[2].velocityAt(0.7)[0], 1);
  // --set reaches the new keys through the same checks.
  Scene o = loadSceneFromString("domain: {cells: [4, 4, 4]}\nboundaries: {y+: {velocity: [2, 0, 0]}}\n", "test.yaml",
                                options({"boundaries.y+.oscillation.omega=5"}));
  EXPECT_TRUE(o.bc[3].oscillating);
  EXPECT_EQ(o.bc[3].omega, 5);
}

TEST(SceneLoad, OverridesApply) {
  Scene s = loadSceneFromString(kFull, "full.yaml",
                                options({"time.end=7", "domain.cells=[8, 16, 4]", "obstacles.2.radius=0.2",
                                         "boundaries.z-.type=slip", "boundaries.z+.type=slip"}));
  EXPECT_DOUBLE_EQ(s.time.endTime, 7);
  EXPECT_EQ(s.cells, (std::array<int, 3>{8, 16, 4}));
  EXPECT_DOUBLE_EQ(s.obstacles[2].radius, 0.2);
  EXPECT_FALSE(s.periodic(2));
  EXPECT_DOUBLE_EQ(s.root["time"]["end"].as<double>(), 7); // root holds the final tree
  // New nested keys are created, including whole sections.
  Scene m = loadSceneFromString("domain: {cells: [4, 4, 4]}\n", "m.yaml",
                                options({"projection.sweeps=5", "time.cfl=0.25"}));
  EXPECT_EQ(m.projection.sweeps, 5);
  EXPECT_DOUBLE_EQ(m.time.cfl, 0.25);
}

TEST(SceneLoad, ApplyOverrideOnATree) {
  YAML::Node root = YAML::Load("a: {b: [1, 2, {c: 3}]}");
  applyOverride(root, "a.b.2.c=[4, 5]");
  applyOverride(root, "a.new.deep=x");
  EXPECT_EQ(root["a"]["b"][2]["c"][1].as<int>(), 5);
  EXPECT_EQ(root["a"]["new"]["deep"].as<std::string>(), "x");
  EXPECT_EQ(root["a"]["b"][0].as<int>(), 1);
  EXPECT_THROW(applyOverride(root, "a.b.9=1"), SceneError);
  EXPECT_THROW(applyOverride(root, "a.b.0.x=1"), SceneError); // 1 is a scalar
}

TEST(SceneLoad, BadOverridesNameTheSet) {
  struct Case { std::string set, expect; };
  for (const Case& c : std::vector<Case>{
           {"time.cfl=2", "--set time.cfl=2: key 'time.cfl': must be in (0, 1]"},
           {"time.end", "--set time.end: expected KEY=VALUE"},
           {"time.end=", "--set time.end=: key 'time.end': missing value"},
           {"domain.cells=[1,2", "--set domain.cells=[1,2: key 'domain.cells'"},
           {"time.bogus=1", "--set time.bogus=1: key 'time.bogus': unknown key"},
           {"bogus.x=1", "--set bogus.x=1: key 'bogus': unknown key"},
           {"obstacles.9.radius=1", "--set obstacles.9.radius=1: key 'obstacles': index 9 is out of range"},
           {"domain.cells.1=x", "--set domain.cells.1=x: key 'domain.cells[1]': expected an integer"},
       }) {
    EXPECT_NE(errorOf(kFull, options({c.set})).find(c.expect), std::string::npos)
        << c.set << " -> " << errorOf(kFull, options({c.set}));
  }
  // A file error elsewhere still points into the file.
  std::string e = errorOf("domain: {cells: [4, 4, 4]}\ntime: {cfl: 3}\n", options({"time.end=2"}));
  EXPECT_EQ(e.rfind("test.yaml:2:", 0), 0u) << e;
}

struct BadScene {
  const char* label;
  const char* yaml;
  const char* line; // ":N:"
  const char* key;  // key path, or a fragment of the message when there is none
};

const BadScene kBad[] = {
    {"malformed_yaml", "domain: {cells: [4, 4, 4]}\ntime:\n  end: 1\n   cfl: 0.5\n", ":4:", "invalid YAML"},
    {"unclosed_flow", "domain: {cells: [4, 4, 4]\ntime: {end: 1}\n", ":2:", "invalid YAML"},
    {"not_a_map", "- 1\n- 2\n", ":1:", "must be a map"},
    {"missing_domain", "time: {end: 1}\n", ":1:", "'domain': is required"},
    {"unknown_top_level", "domain: {cells: [4, 4, 4]}\nboundary:\n  x-: {type: slip}\n", ":2:", "'boundary'"},
    {"unknown_nested", "domain: {cells: [4, 4, 4]}\ntime:\n  end: 1\n  ned: 2\n", ":4:", "'time.ned'"},
    {"unknown_face", "domain: {cells: [4, 4, 4]}\nboundaries:\n  x_: {type: slip}\n", ":3:", "'boundaries.x_'"},
    {"unknown_for_shape", "domain: {cells: [4, 4, 4]}\neffects: [obstacles]\nobstacles:\n"
                          "  - {type: box, lo: [0, 0, 0], hi: [1, 1, 1], radius: 1}\n", ":4:", "'obstacles[0].radius'"},
    {"duplicate_key", "domain: {cells: [4, 4, 4]}\ntime:\n  end: 1\n  end: 2\n", ":4:", "'time.end': duplicate"},
    {"map_for_number", "domain: {cells: [4, 4, 4]}\ntime:\n  end: {value: 1}\n", ":3:", "'time.end'"},
    {"number_for_vector", "domain:\n  cells: [4, 4, 4]\n  lo: 0\n", ":3:", "'domain.lo'"},
    {"string_for_list", "domain: {cells: [4, 4, 4]}\neffects: navier_stokes\n", ":2:", "'effects'"},
    {"non_numeric", "domain: {cells: [4, 4, 4]}\ntime:\n  cfl: fast\n", ":3:", "'time.cfl'"},
    {"quoted_number", "domain: {cells: [4, 4, 4]}\ntime:\n  cfl: \"0.5\"\n", ":3:", "'time.cfl'"},
    {"nan", "domain: {cells: [4, 4, 4]}\ntime: {end: .nan}\n", ":2:", "'time.end'"},
    {"inf", "domain: {cells: [4, 4, 4]}\ntime:\n  max_dt: .inf\n", ":3:", "'time.max_dt'"},
    {"cfl_above_one", "domain: {cells: [4, 4, 4]}\ntime:\n  cfl: 1.5\n", ":3:", "'time.cfl'"},
    {"negative_density", "domain: {cells: [4, 4, 4]}\nmaterials:\n  air: {density: -1.2}\n", ":3:",
     "'materials.air.density'"},
    {"zero_cells", "domain:\n  cells: [4, 0, 4]\n", ":2:", "'domain.cells[1]'"},
    {"fractional_cells", "domain:\n  cells: [4, 4.5, 4]\n", ":2:", "'domain.cells[1]'"},
    {"hi_not_above_lo", "domain:\n  lo: [0, 0, 0]\n  hi: [1, 0, 1]\n", ":3:", "'domain.hi'"},
    {"unknown_effect", "domain: {cells: [4, 4, 4]}\neffects: [navier_stokes, magic]\n", ":2:", "'effects[1]'"},
    {"duplicate_effect", "domain: {cells: [4, 4, 4]}\neffects:\n  - gravity\n  - gravity\n", ":4:", "'effects[1]'"},
    {"periodic_one_face", "domain: {cells: [4, 4, 4]}\nboundaries:\n  x-: {type: periodic}\n", ":3:",
     "'boundaries.x-.type'"},
    {"inflow_without_velocity", "domain: {cells: [4, 4, 4]}\nboundaries:\n  y-: {type: outflow}\n  x-: {type: inflow}\n",
     ":4:", "'boundaries.x-.velocity'"},
    {"wall_moving_through_itself", "domain: {cells: [4, 4, 4]}\nboundaries:\n  y+: {velocity: [0, 1, 0]}\n", ":3:",
     "'boundaries.y+.velocity'"},
    {"obstacles_without_effect", "domain: {cells: [4, 4, 4]}\neffects: [navier_stokes]\nobstacles:\n"
                                 "  - {type: sphere, center: [0.5, 0.5, 0.5], radius: 0.1}\n", ":4:", "'obstacles'"},
    {"bad_axis", "domain: {cells: [4, 4, 4]}\neffects: [obstacles]\nobstacles:\n"
                 "  - {type: cylinder, center: [0.5, 0.5, 0.5], radius: 0.1, axis: w}\n", ":4:", "'obstacles[0].axis'"},
    {"obstacle_outside", "domain: {cells: [4, 4, 4]}\neffects: [obstacles]\nobstacles:\n"
                         "  - type: sphere\n    radius: 0.1\n    center: [0.5, -1, 0.5]\n", ":6:", "'obstacles[0].center'"},
    {"probe_outside", "domain: {cells: [4, 4, 4]}\nprobes:\n  - {name: p, point: [2, 0.5, 0.5]}\n", ":3:",
     "'probes[0].point'"},
    {"probe_point_and_line", "domain: {cells: [4, 4, 4]}\nprobes:\n"
                             "  - {name: p, point: [0, 0, 0], line: {from: [0, 0, 0], to: [1, 1, 1], points: 3}}\n",
     ":3:", "'probes[0].line'"},
    {"probe_duplicate_name", "domain: {cells: [4, 4, 4]}\nprobes:\n  - {name: p, point: [0, 0, 0]}\n"
                             "  - {name: p, point: [1, 1, 1]}\n", ":4:", "'probes[1].name'"},
    {"probe_bad_name", "domain: {cells: [4, 4, 4]}\nprobes:\n  - {name: a b, point: [0, 0, 0]}\n", ":3:",
     "'probes[0].name'"},
    {"line_too_few_points", "domain: {cells: [4, 4, 4]}\nprobes:\n  - name: l\n    line:\n"
                            "      from: [0, 0, 0]\n      to: [1, 1, 1]\n      points: 1\n", ":7:",
     "'probes[0].line.points'"},
    {"fluid_missing_material", "domain: {cells: [4, 4, 4]}\nmaterials: {air: {density: 1.2}}\nfluid: water\n", ":3:",
     "'fluid'"},
    {"tolerance_one", "domain: {cells: [4, 4, 4]}\nprojection:\n  tolerance: 1\n", ":3:", "'projection.tolerance'"},
    {"damping_two", "domain: {cells: [4, 4, 4]}\nprojection: {damping: 2}\n", ":2:", "'projection.damping'"},
    {"bad_limiter", "domain: {cells: [4, 4, 4]}\nadvection:\n  limiter: superbee\n", ":3:", "'advection.limiter'"},
    {"oscillating_slip", "domain: {cells: [4, 4, 4]}\nboundaries:\n  y+: {type: slip, oscillation: {omega: 1}}\n", ":3:",
     "'boundaries.y+.oscillation'"},
    {"oscillation_without_velocity", "domain: {cells: [4, 4, 4]}\nboundaries:\n  y+: {oscillation: {omega: 1}}\n", ":3:",
     "'boundaries.y+.oscillation'"},
    {"oscillation_without_omega", "domain: {cells: [4, 4, 4]}\nboundaries:\n  y+:\n    velocity: [1, 0, 0]\n"
                                  "    oscillation: {phase: 1}\n", ":5:", "'boundaries.y+.oscillation.omega'"},
    {"oscillation_negative_omega", "domain: {cells: [4, 4, 4]}\nboundaries:\n  y+:\n    velocity: [1, 0, 0]\n"
                                   "    oscillation: {omega: -2}\n", ":5:", "'boundaries.y+.oscillation.omega'"},
    {"oscillation_unknown_key", "domain: {cells: [4, 4, 4]}\nboundaries:\n  y+:\n    velocity: [1, 0, 0]\n"
                                "    oscillation: {omega: 2, amplitude: 1}\n", ":5:", "'boundaries.y+.oscillation.amplitude'"},
};

class BadScenes : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadScenes, FailWithLineAndKey) {
  const BadScene& c = GetParam();
  std::string e = errorOf(c.yaml);
  ASSERT_FALSE(e.empty()) << "accepted:\n" << c.yaml;
  EXPECT_EQ(e.rfind("test.yaml" + std::string(c.line), 0), 0u) << e;
  EXPECT_NE(e.find(c.key), std::string::npos) << e;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadScenes, ::testing::ValuesIn(kBad),
                         [](const auto& info) { return std::string(info.param.label); });

TEST(SceneLoad, BadFilesOnDisk) {
  const std::string dir = VOIGT_SOURCE_DIR "/tests/scene/bad/";
  struct Case { const char* file; const char* where; const char* key; };
  for (const Case& c : std::vector<Case>{{"unknown_key.yaml", ":5:3:", "key 'time.viscosity'"},
                                         {"negative_viscosity.yaml", ":5:16:", "key 'materials.oil.viscosity'"},
                                         {"malformed.yaml", ":4:", "invalid YAML"},
                                         {"probe_outside.yaml", ":6:", "key 'probes[1].line.to'"}}) {
    try {
      loadScene(dir + c.file, options());
      ADD_FAILURE() << c.file << " was accepted";
    } catch (const SceneError& e) {
      std::string msg = e.what();
      EXPECT_EQ(msg.rfind(dir + c.file + c.where, 0), 0u) << msg;
      EXPECT_NE(msg.find(c.key), std::string::npos) << msg;
    }
  }
  try {
    loadScene(dir + "does_not_exist.yaml", options());
    ADD_FAILURE() << "missing file accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("does_not_exist.yaml"), std::string::npos);
  }
}

TEST(SceneLoad, EffectSectionsAreValidatedByTheirOwners) {
  const char* yaml = "domain: {cells: [4, 4, 4]}\nlevel_set:\n  thickness: -1\n  typo: 2\n";
  LoadOptions noExtra = options();
  noExtra.extraSections.clear();
  EXPECT_NE(errorOf(yaml, noExtra).find("test.yaml:2:1: key 'level_set': unknown key"), std::string::npos);
  Scene s = loadSceneFromString(yaml, "test.yaml", options());
  Section ls = topSection(s, "level_set");
  try {
    ls.number("thickness", 0.1, Range::positive());
    ADD_FAILURE();
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("test.yaml:3:14: key 'level_set.thickness': must be > 0", 0), 0u)
        << e.what();
  }
  try {
    ls.finish();
    ADD_FAILURE();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("test.yaml:4:3: key 'level_set.typo': unknown key 'typo' in 'level_set' "
                                         "(allowed: thickness)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(topSection(s, "absent").has("x")); // an absent section reads as empty
}

} // namespace
