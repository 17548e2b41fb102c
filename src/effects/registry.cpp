#include <algorithm>
#include <stdexcept>

#include "effects/effect.hpp"
#include "scene/reader.hpp"

namespace voigt {

std::unique_ptr<Effect> makeNavierStokes();
std::unique_ptr<Effect> makeGravity();
std::unique_ptr<Effect> makeObstacles();
std::unique_ptr<Effect> makeLevelSet();
std::unique_ptr<Effect> makeReinit();
std::unique_ptr<Effect> makePrescribedFlow();
std::unique_ptr<Effect> makeElasticity();
std::unique_ptr<Effect> makeSolidBody();
std::unique_ptr<Effect> makeSurfaceTension();

const std::vector<EffectInfo>& effectRegistry() {
  static const std::vector<EffectInfo> reg = {
      {"navier_stokes", "incompressible momentum: MUSCL advection, viscous stress, projection", "navier_stokes",
       makeNavierStokes},
      {"gravity", "body force from the scene's gravity vector", "", makeGravity},
      {"obstacles", "fixed or moving rigid bodies: prescribed node velocities", "", makeObstacles},
      {"level_set", "phases: MUSCL advection of psi (Eq. 1; one, or several named), properties blended by H(psi) (Eq. 2-4)",
       "level_set", makeLevelSet},
      {"reinit", "Sussman re-initialisation of psi with the local volume constraint (Eq. 17-21)", "reinit",
       makeReinit},
      {"prescribed_flow", "kinematic velocity field given in closed form (rotation, vortex, ...)",
       "prescribed_flow", makePrescribedFlow},
      {"elasticity", "hypoelastic solid: Jaumann-rate stress (Eq. 13/16), transported, blended by H(psi) (Eq. 14)",
       "elasticity", makeElasticity},
      {"solid_body", "diagnostics of the psi > 0 body: centroid, velocity, orientation, bending, gaps, contacts",
       "solid_body", makeSolidBody},
      {"surface_tension", "capillary force sigma kappa grad H on the interface, balanced with the pressure (CSF)",
       "surface_tension", makeSurfaceTension},
  };
  return reg;
}

std::set<std::string> knownEffectNames() {
  std::set<std::string> s;
  for (auto& e : effectRegistry()) s.insert(e.name);
  return s;
}

std::set<std::string> effectSections() {
  std::set<std::string> s;
  for (auto& e : effectRegistry())
    if (!e.section.empty()) s.insert(e.section);
  s.insert("level_sets"); // level_set's named form (effects/level_set/level_set.hpp)
  return s;
}

// Kahn's order on setupAfter(): the next effect is the first, in the scene's order, whose
// predecessors present in the scene are all placed.
static std::vector<std::unique_ptr<Effect>> orderBySetupAfter(std::vector<std::unique_ptr<Effect>> in) {
  std::vector<std::unique_ptr<Effect>> out;
  auto placed = [&](const std::string& n) {
    const bool present = std::any_of(in.begin(), in.end(), [&](auto& e) { return e && e->name() == n; });
    return !present; // not in the scene, or already moved to out
  };
  for (size_t left = in.size(); left > 0; --left) {
    auto next = std::find_if(in.begin(), in.end(), [&](auto& e) {
      if (!e) return false;
      const auto after = e->setupAfter();
      return std::all_of(after.begin(), after.end(), [&](const std::string& n) { return n == e->name() || placed(n); });
    });
    if (next == in.end()) throw std::logic_error("effects: setupAfter() has a cycle");
    out.push_back(std::move(*next)); // leaves a null behind in `in`
  }
  return out;
}

std::vector<std::unique_ptr<Effect>> makeEffects(const Scene& scene) {
  std::vector<std::unique_ptr<Effect>> out;
  for (auto& name : scene.effects) {
    auto it = std::find_if(effectRegistry().begin(), effectRegistry().end(),
                           [&](const EffectInfo& e) { return e.name == name; });
    if (it == effectRegistry().end()) throw SceneError(scene.path + ": unknown effect '" + name + "'");
    out.push_back(it->make());
  }
  for (auto& e : out)
    for (auto& need : e->dependsOn())
      if (std::find(scene.effects.begin(), scene.effects.end(), need) == scene.effects.end()) {
        const std::string msg = "effect '" + e->name() + "' needs '" + need + "' in the effects list";
        if (!scene.source) throw SceneError(scene.path + ": key 'effects': " + msg); // a scene built in code
        const size_t i = std::find(scene.effects.begin(), scene.effects.end(), e->name()) - scene.effects.begin();
        Section(scene.root, "", scene.source).failItem("effects", i, msg); // FILE:LINE:COL of the entry
      }
  out = orderBySetupAfter(std::move(out));
  Published pub;
  for (auto& e : out) e->publish(scene, pub);
  for (auto& e : out) e->configure(scene, pub);
  return out;
}

LoadOptions effectLoadOptions(std::vector<std::string> overrides) {
  LoadOptions lo;
  lo.overrides = std::move(overrides);
  lo.knownEffects = knownEffectNames();
  lo.extraSections = effectSections();
  return lo;
}

Scene loadSceneWithEffects(const std::string& path, std::vector<std::string> overrides) {
  return loadScene(path, effectLoadOptions(std::move(overrides)));
}

Scene loadSceneWithEffectsFromString(const std::string& yaml, const std::string& name,
                                     std::vector<std::string> overrides) {
  return loadSceneFromString(yaml, name, effectLoadOptions(std::move(overrides)));
}

} // namespace voigt
