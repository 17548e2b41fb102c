#include "scene/presets.hpp"

#include <map>

namespace voigt {

// Chosen from perf/accuracy (Taylor-Green, Zalesak): see perf/accuracy/README.md.
static const std::map<std::string, std::vector<PresetKnob>>& table() {
  // One knob at a time around the base (Taylor-Green 32^2, Zalesak 64^2), measured:
  // - limiter: MC cuts the Taylor-Green error 5.7x and the Zalesak shape error 18 % at the
  //   same cost as MinMod (which stays the default without a preset: the paper's, and the
  //   most dissipative near sharp density jumps, which these cases do not test);
  // - CFL: neither error moves by more than 13 % between 0.25 and 0.95, the time does (1/CFL);
  // - Poisson tolerance 1e-3..1e-10: the Taylor-Green error is unchanged, the time rises 2x;
  // - exact projection: same velocity error, divergence at the solver residual; on it SGS
  //   takes 2.5x the iterations of CG without preconditioner (Jacobi: as many as none, and
  //   it scales the rows of D(1/rho)G when density varies);
  // - reinit every 2 steps: shape error +1 %, area error 9.0 % instead of 7.7 %, ~20 % faster;
  // - level_set.smoothing (kappa, cells) 1 instead of 2: the elastic Couette error halves at
  //   the same cost (first order in kappa h), and the full stability matrix stays bounded
  //   at kappa 1 (the global correction puts back 1.4-4x the volume); `accurate` only.
  static const std::map<std::string, std::vector<PresetKnob>> t{
      {"fast",
       {{"time", "cfl", "0.9"},
        {"advection", "limiter", "mc"},
        {"projection", "operator", "approximate"},
        {"projection", "tolerance", "1e-4"},
        {"projection", "preconditioner", "sgs"},
        {"reinit", "interval", "2"},
        {"reinit", "iterations", "2"}}},
      {"balanced",
       {{"time", "cfl", "0.7"},
        {"advection", "limiter", "mc"},
        {"projection", "operator", "approximate"},
        {"projection", "tolerance", "1e-6"},
        {"projection", "preconditioner", "sgs"},
        {"reinit", "interval", "1"},
        {"reinit", "iterations", "2"}}},
      {"accurate",
       {{"time", "cfl", "0.4"},
        {"advection", "limiter", "mc"},
        {"projection", "operator", "exact"},
        {"projection", "tolerance", "1e-10"},
        {"projection", "preconditioner", "jacobi"},
        {"reinit", "interval", "1"},
        {"reinit", "iterations", "2"},
        {"level_set", "smoothing", "1"}}},
  };
  return t;
}

const std::vector<std::string>& presetNames() {
  static const std::vector<std::string> names{"fast", "balanced", "accurate"};
  return names;
}

const std::vector<PresetKnob>& presetKnobs(const std::string& name) {
  static const std::vector<PresetKnob> none;
  auto it = table().find(name);
  return it == table().end() ? none : it->second;
}

std::vector<std::string> applyPreset(YAML::Node& root, const Section& top, std::string& name) {
  name.clear();
  if (!top.has("preset")) return {};
  name = top.choice("preset", "", presetNames()); // unknown name: FILE:LINE:COL: key 'preset': ...

  // Effect-owned sections (reinit, level_set) only when the effect runs.
  const YAML::Node& croot = root;
  auto runs = [&](const std::string& effect) {
    if (croot["effects"].IsDefined() && croot["effects"].IsSequence())
      for (const auto& e : croot["effects"])
        if (e.IsScalar() && e.Scalar() == effect) return true;
    return false;
  };

  std::vector<std::string> notes;
  for (const PresetKnob& k : presetKnobs(name)) {
    const std::string sec0 = k.section, path = sec0 + "." + k.key;
    if ((sec0 == "reinit" || sec0 == "level_set") && !runs(sec0)) continue;
    if (sec0 == "level_set" && croot["level_sets"].IsDefined()) { // the named form sets its own
      notes.push_back(path + " = " + k.value + " not applied: set it in each level_sets entry");
      continue;
    }
    YAML::Node sec = croot[k.section].IsDefined() ? root[k.section] : YAML::Node();
    if (sec.IsDefined() && !sec.IsNull() && !sec.IsMap()) continue; // the section reader reports it
    const YAML::Node csec = sec;
    if (sec.IsDefined() && sec.IsMap() && csec[k.key].IsDefined()) {
      const YAML::Node v = csec[k.key];
      notes.push_back(path + " = " + (v.IsScalar() ? v.Scalar() : std::string("...")) + " (kept from the scene or --set; preset: " +
                      k.value + ")");
      continue;
    }
    if (!sec.IsDefined() || sec.IsNull()) {
      root[k.section] = YAML::Node(YAML::NodeType::Map);
      sec.reset(root[k.section]);
    }
    sec[k.key] = YAML::Load(k.value);
    notes.push_back(path + " = " + k.value);
  }
  return notes;
}

} // namespace voigt
