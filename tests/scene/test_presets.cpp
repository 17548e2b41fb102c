// Scene presets (src/scene/presets.hpp): `preset: fast | balanced | accurate` sets
// default knob values; keys written in the scene or given by --set win; an unknown
// preset is refused naming file, line and key.
#include <gtest/gtest.h>

#include <string>

#include "effects/effect.hpp"
#include "scene/load.hpp"
#include "scene/presets.hpp"
#include "scene/reader.hpp"

using namespace voigt;

namespace {

// As `voigt run` loads a scene: every effect of the registry known.
LoadOptions options(std::vector<std::string> overrides = {}) { return effectLoadOptions(std::move(overrides)); }

const std::string kBase = "name: p\n"
                          "domain: {lo: [0, 0, 0], hi: [1, 1, 1], cells: [8, 8, 8]}\n"
                          "effects: [navier_stokes]\n";

Scene load(const std::string& yaml, const LoadOptions& o = options()) {
  return loadSceneFromString(yaml, "presets.yaml", o);
}

std::string knob(const std::string& preset, const std::string& section, const std::string& key) {
  for (const auto& k : presetKnobs(preset))
    if (section == k.section && key == k.key) return k.value;
  return "";
}

} // namespace

TEST(Presets, EveryPresetSetsTheCoreKnobs) {
  for (const auto& name : presetNames()) {
    Scene s = load(kBase + "preset: " + name + "\n");
    EXPECT_EQ(s.preset, name);
    EXPECT_DOUBLE_EQ(s.time.cfl, std::stod(knob(name, "time", "cfl"))) << name;
    EXPECT_EQ(s.advection.limiter, knob(name, "advection", "limiter")) << name;
    EXPECT_DOUBLE_EQ(s.projection.tolerance, std::stod(knob(name, "projection", "tolerance"))) << name;
    EXPECT_EQ(s.projection.preconditioner, knob(name, "projection", "preconditioner")) << name;
    EXPECT_EQ(s.projection.op == ProjectionCfg::Op::Exact ? "exact" : "approximate",
              knob(name, "projection", "operator"))
        << name;
    // One note per knob set; reinit is not in the effects, so its knobs are left alone.
    EXPECT_FALSE(s.presetNotes.empty());
    for (const auto& n : s.presetNotes) EXPECT_EQ(n.find("reinit."), std::string::npos) << n;
    EXPECT_FALSE(s.root["reinit"].IsDefined()) << name;
  }
}

TEST(Presets, FastAndAccurateDiffer) {
  Scene f = load(kBase + "preset: fast\n"), a = load(kBase + "preset: accurate\n");
  EXPECT_GT(f.time.cfl, a.time.cfl);
  EXPECT_GT(f.projection.tolerance, a.projection.tolerance);
}

TEST(Presets, NoPresetChangesNothing) {
  Scene s = load(kBase), d = load(kBase + "time: {cfl: 0.5}\n");
  EXPECT_TRUE(s.preset.empty());
  EXPECT_TRUE(s.presetNotes.empty());
  EXPECT_DOUBLE_EQ(s.time.cfl, TimeCfg{}.cfl);
  EXPECT_DOUBLE_EQ(s.projection.tolerance, ProjectionCfg{}.tolerance);
  EXPECT_EQ(s.advection.limiter, AdvectionCfg{}.limiter);
  EXPECT_DOUBLE_EQ(d.time.cfl, 0.5);
}

TEST(Presets, ExplicitKeysWin) {
  Scene s = load(kBase + "preset: fast\n"
                         "time: {end: 2, cfl: 0.123}\n"
                         "projection: {tolerance: 1.0e-11}\n"
                         "advection:\n");
  EXPECT_DOUBLE_EQ(s.time.cfl, 0.123);
  EXPECT_DOUBLE_EQ(s.time.endTime, 2); // the rest of a section the preset writes into survives
  EXPECT_DOUBLE_EQ(s.projection.tolerance, 1e-11);
  EXPECT_EQ(s.projection.preconditioner, knob("fast", "projection", "preconditioner")); // preset fills the rest
  EXPECT_EQ(s.advection.limiter, knob("fast", "advection", "limiter"));                 // null section filled
  bool noted = false;
  for (const auto& n : s.presetNotes)
    if (n.rfind("time.cfl = 0.123 (kept from the scene", 0) == 0) noted = true;
  EXPECT_TRUE(noted) << "voigt check should say the scene kept its own time.cfl";
}

TEST(Presets, SetOverridesWinAndCanChooseThePreset) {
  Scene s = load(kBase + "preset: accurate\n", options({"time.cfl=0.2", "preset=fast"}));
  EXPECT_EQ(s.preset, "fast");
  EXPECT_DOUBLE_EQ(s.time.cfl, 0.2);
  EXPECT_DOUBLE_EQ(s.projection.tolerance, std::stod(knob("fast", "projection", "tolerance")));
}

TEST(Presets, ReinitKnobsOnlyWithTheReinitEffect) {
  const std::string ls = "name: z\n"
                         "domain: {lo: [0, 0, 0], hi: [1, 1, 1], cells: [8, 8, 8]}\n"
                         "effects: [prescribed_flow, level_set, reinit]\n"
                         "reinit: {iterations: 3}\n";
  Scene s = load(ls + "preset: fast\n");
  ASSERT_TRUE(s.root["reinit"].IsMap());
  EXPECT_EQ(s.root["reinit"]["iterations"].as<int>(), 3); // the scene's own value
  EXPECT_EQ(s.root["reinit"]["interval"].as<std::string>(), knob("fast", "reinit", "interval"));
}

// `accurate` narrows the level set's smoothing (kappa 1 cell); only where level_set runs,
// and a scene's own smoothing (the paper scenes pin 2) wins.
TEST(Presets, SmoothingOnlyWithTheLevelSet) {
  const std::string ls = "name: z\n"
                         "domain: {lo: [0, 0, 0], hi: [1, 1, 1], cells: [8, 8, 8]}\n"
                         "effects: [prescribed_flow, level_set]\n"
                         "level_set: {phase: a, shape: {type: sphere, center: [0.5, 0.5, 0.5], radius: 0.2}}\n";
  Scene s = load(ls + "preset: accurate\n");
  EXPECT_EQ(s.root["level_set"]["smoothing"].as<std::string>(), knob("accurate", "level_set", "smoothing"));
  Scene kept = load(ls + "preset: accurate\n", options({"level_set.smoothing=2"}));
  EXPECT_EQ(kept.root["level_set"]["smoothing"].as<double>(), 2.0);
  Scene fast = load(ls + "preset: fast\n");
  EXPECT_FALSE(fast.root["level_set"]["smoothing"].IsDefined()); // fast and balanced keep the default
  Scene none = load(kBase + "preset: accurate\n");
  EXPECT_FALSE(none.root["level_set"].IsDefined()); // no level set: no section written
}

TEST(Presets, UnknownPresetNamesFileLineAndKey) {
  try {
    load(kBase + "preset: fastest\n");
    FAIL() << "an unknown preset was accepted";
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("presets.yaml:4:"), std::string::npos) << m;
    EXPECT_NE(m.find("key 'preset'"), std::string::npos) << m;
    EXPECT_NE(m.find("fastest"), std::string::npos) << m;
    EXPECT_NE(m.find("balanced"), std::string::npos) << m; // lists the valid names
  }
  try {
    load(kBase, options({"preset=slow"}));
    FAIL() << "an unknown preset from --set was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("--set preset=slow"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load(kBase + "preset: [fast]\n"), SceneError);
}
