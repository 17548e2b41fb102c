#pragma once
// An effect is one piece of physics a scene can list under `effects:`. It
// declares its fields, reads its own scene section, registers tasks into the
// pipeline's stages and may limit the time step. The core knows none of them.
#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/pipeline.hpp"
#include "core/state.hpp"
#include "levelset/params.hpp"
#include "scene/load.hpp"
#include "scene/reader.hpp"

namespace voigt {

// One level set as its owner (level_set) resolved it: `level_set:` gives one with name ""
// and field "psi"; each `level_sets:` entry gives one named NAME with field "psi_NAME".
struct LevelSetInfo {
  std::string name;  // "" for the single `level_set:` section
  std::string field; // its cell field in the FieldStore (and outputs, checkpoints)
  std::string phase; // the material where psi > 0
  bool solid = false; // its phase has a shear modulus (an elastic body, not a fluid)
  LevelSetGeometry geometry; // smoothing half-width and re-initialisation band of Eq. (4), in cells
  std::string label() const { return name.empty() ? "level_set" : name; } // for messages
};

// What an effect resolves from its own scene section and shares with the others:
// the owner fills it in publish(), before any effect's configure(), and the others
// read it there, never by parsing a section they do not own.
struct Published {
  std::vector<LevelSetInfo> levelSets; // in the scene's order (the blending's priority order)

  // The level sets an effect acts on, from its section's key `level_set`: a name, or a list of
  // names where `list` allows several. Absent: the only level set; with several, all of them
  // if `allByDefault`, else an error asking for the key. Unknown or repeated names, a list
  // where one is expected, or a scene without level sets are errors at that key.
  std::vector<LevelSetInfo> select(const Section& sec, bool list, bool allByDefault = false) const;
  LevelSetInfo one(const Section& sec) const { return select(sec, false).front(); }
  // Does any level set's phase differ in density from the scene's fluid?
  bool varyingDensity(const Scene& s) const;
};

class Effect {
 public:
  virtual ~Effect() = default;
  virtual std::string name() const = 0;
  virtual std::vector<std::string> dependsOn() const { return {}; }
  // Effects (by name) whose setup, and so whose tasks within a stage, come before this
  // one's when the scene has them: navier_stokes builds the masks obstacles extend, the
  // level set exists before the elastic stress. The default: after every effect that
  // owns fields or masks others read. Ties keep the scene's order (makeEffects).
  virtual std::vector<std::string> setupAfter() const {
    return {"navier_stokes", "prescribed_flow", "level_set", "obstacles", "elasticity"};
  }
  // Validates and resolves what others read (Published); runs for every effect first.
  virtual void publish(const Scene&, Published&) const {}
  // Reads the effect's own section (rejecting unknown keys) and what others published.
  virtual void configure(const Scene&, const Published&) {}
  virtual void declareFields(FieldStore&) const {}
  virtual void setup(State&) {}
  virtual void registerTasks(Pipeline&) = 0;
  virtual DtLimit dtLimit(const State&) const { return {}; }
  virtual void summary(const State&, nlohmann::json&) const {}
  // Checkpoint and restart (io/checkpoint.hpp): state an effect carries from
  // step to step outside the field store (flags, reference values, counters).
  virtual void saveState(nlohmann::json&) const {}
  virtual void loadState(const nlohmann::json&) {}
  // Called on restart after the fields' owned points are loaded and their
  // halos exchanged: refill the ghost layers a normal step leaves filled
  // (boundary reflections), so the continued run is bit-identical.
  virtual void restored(State&) {}
};

struct EffectInfo {
  std::string name, description;
  std::string section; // top-level scene key this effect owns ("" for none)
  std::function<std::unique_ptr<Effect>()> make;
};

// All built-in effects (effects/registry.cpp: one line per effect).
const std::vector<EffectInfo>& effectRegistry();
std::set<std::string> knownEffectNames();
std::set<std::string> effectSections();
// Instantiates the scene's effects, checks `requires`, orders them by setupAfter().
std::vector<std::unique_ptr<Effect>> makeEffects(const Scene& scene);

// Loading a scene as `voigt run` does: every effect's name and section known to the
// loader, then the --set overrides in order. Throws SceneError (file, line, key).
// The one place that wires the loader to the registry (cli, tests, perf).
LoadOptions effectLoadOptions(std::vector<std::string> overrides = {});
Scene loadSceneWithEffects(const std::string& path, std::vector<std::string> overrides = {});
// `name` is used in messages only (test and perf scenes).
Scene loadSceneWithEffectsFromString(const std::string& yaml, const std::string& name,
                                     std::vector<std::string> overrides = {});

} // namespace voigt
