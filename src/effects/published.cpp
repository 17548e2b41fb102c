// Published: the level sets an effect's section names (effect.hpp).
#include <algorithm>

#include "effects/effect.hpp"

namespace voigt {

std::vector<LevelSetInfo> Published::select(const Section& sec, bool list, bool allByDefault) const {
  const char* key = "level_set";
  if (levelSets.empty()) sec.fail(key, "needs a level set: the scene has neither 'level_set' nor 'level_sets'");
  const YAML::Node& n = sec.node();
  const bool given = n.IsMap() && n[key].IsDefined() && !n[key].IsNull();
  if (!given) {
    sec.has(key); // a null value counts as absent, not as an unknown key
    if (levelSets.size() == 1) return levelSets;
    if (allByDefault) return levelSets;
    sec.fail(key, "is required: the scene has " + std::to_string(levelSets.size()) +
                      " level sets; name the one" + std::string(list ? "s" : "") + " this section acts on");
  }
  std::vector<std::string> names;
  if (n[key].IsSequence()) {
    if (!list) sec.fail(key, "names one level set here, not a list");
    names = sec.strings(key, {});
    if (names.empty()) sec.fail(key, "must name at least one level set");
  } else {
    names = {sec.string(key, "")};
  }
  std::vector<LevelSetInfo> out;
  for (const std::string& nm : names) {
    auto it = std::find_if(levelSets.begin(), levelSets.end(), [&](const LevelSetInfo& l) { return l.name == nm; });
    if (it == levelSets.end()) {
      std::string known;
      for (const LevelSetInfo& l : levelSets) known += (known.empty() ? "" : ", ") + l.label();
      sec.fail(key, "names no level set '" + nm + "' (the scene's: " + known + ")");
    }
    if (std::any_of(out.begin(), out.end(), [&](const LevelSetInfo& l) { return l.name == nm; }))
      sec.fail(key, "names '" + nm + "' twice");
    out.push_back(*it);
  }
  return out;
}

bool Published::varyingDensity(const Scene& s) const {
  return std::any_of(levelSets.begin(), levelSets.end(), [&](const LevelSetInfo& l) {
    return s.materials.count(l.phase) && s.materials.at(l.phase).density != s.fluidMaterial().density;
  });
}

} // namespace voigt
