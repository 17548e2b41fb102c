#pragma once
// Scene loading: parse YAML, apply --set overrides, validate everything the
// core owns, and leave effect-owned top-level sections in Scene::root.
#include <yaml-cpp/yaml.h>

#include <set>
#include <string>
#include <vector>

#include "scene/reader.hpp"
#include "scene/scene.hpp"

namespace voigt {

struct LoadOptions {
  std::vector<std::string> overrides;  // "a.b.c=value" from --set, applied in order
  std::set<std::string> knownEffects;  // names the effect registry knows
  std::set<std::string> extraSections; // top-level keys owned by effects (e.g. "level_set")
};

// Throws SceneError ("FILE:LINE:COL: key 'a.b': ...") on any problem.
Scene loadScene(const std::string& path, const LoadOptions& opts);
// `name` is used in messages only; Scene::path stays "" (built-in / test scenes).
Scene loadSceneFromString(const std::string& yaml, const std::string& name, const LoadOptions& opts);

// "a.b.c=value": list entries by index (obstacles.0.radius=0.1); value parsed as
// YAML ([1,2,3] works); missing map keys are created. Malformed -> SceneError naming the --set.
// Returns the canonical path it set, e.g. obstacles[0].radius.
std::string applyOverride(YAML::Node& root, const std::string& assignment);

} // namespace voigt
