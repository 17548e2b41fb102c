#pragma once
// Scene presets: `preset: fast | balanced | accurate` picks default values for the
// knobs that trade accuracy for time (CFL, limiter, projection operator, Poisson
// tolerance and preconditioner, re-initialisation interval and iterations, the
// level set's smoothing width). The
// values come from the measured Pareto fronts in perf/accuracy/README.md.
//
// applyPreset() runs after the --set overrides and before any section is read: it
// writes each preset value into the scene tree only where the key is absent, so a key
// written in the scene (or by --set) always wins. Re-initialisation and level-set knobs
// are set only when `reinit` / `level_set` is in the scene's effects.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "scene/reader.hpp"

namespace voigt {

struct PresetKnob {
  const char* section; // "time", "advection", "projection", "reinit", "level_set"
  const char* key;
  const char* value;   // YAML scalar
};

// Names, in order: fast, balanced, accurate.
const std::vector<std::string>& presetNames();
// The knobs preset `name` sets (empty for an unknown name).
const std::vector<PresetKnob>& presetKnobs(const std::string& name);

// Reads and validates top-level `preset` (a SceneError naming FILE:LINE:COL and key
// 'preset' if unknown), applies it to `root`, and returns one line per knob:
// "time.cfl = 0.5" or "projection.tolerance = 1e-10 (kept from the scene or --set; preset: 1e-06)".
// Returns {} and changes nothing when the scene has no preset. Returns the preset
// name through `name`.
std::vector<std::string> applyPreset(YAML::Node& root, const Section& top, std::string& name);

} // namespace voigt
