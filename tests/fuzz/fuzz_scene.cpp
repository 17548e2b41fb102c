// libFuzzer target for the scene loader (scripts/fuzz). The input is a scene
// file; lines starting with "#set " (YAML comments) are also applied as --set
// overrides, so the override parser is fuzzed too. A SceneError is the loader
// refusing politely; any other exception escaping, a crash, a sanitizer report,
// a hang or an out-of-memory is a finding.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "scene/load.hpp"
#include "scene/reader.hpp"

using namespace voigt;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 64 * 1024) return 0; // scenes are small; deep inputs only slow the search
  const std::string text(reinterpret_cast<const char*>(data), size);
  LoadOptions o;
  // As src/effects/registry.cpp and src/cli/main.cpp (kept here so the target needs no Trilinos).
  o.knownEffects = {"navier_stokes", "gravity", "obstacles", "level_set", "reinit", "prescribed_flow", "elasticity"};
  o.extraSections = {"level_set", "reinit", "prescribed_flow", "elasticity", "checkpoint"};
  std::istringstream lines(text);
  for (std::string l; std::getline(lines, l);)
    if (l.rfind("#set ", 0) == 0) o.overrides.push_back(l.substr(5));
  try {
    const Scene s = loadSceneFromString(text, "fuzz.yaml", o);
    // What effects do with their sections: generic reads through the reader, then finish().
    for (const char* sec : {"level_set", "reinit", "prescribed_flow", "elasticity", "checkpoint"}) {
      const Section x = topSection(s, sec);
      for (auto& k : x.keys()) {
        (void)k;
      }
      x.number("interval", 1, Range::positive());
      x.vec3("center", {0, 0, 0});
      x.string("type", "");
      x.section("shape").list("of");
      x.finish();
    }
  } catch (const SceneError&) {
  }
  return 0;
}
