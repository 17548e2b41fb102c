// Simulation: the record of the scene a run used (DIR/scene.yaml), and the comparison a restart
// makes between its scene and the one its checkpoint was written with.
#include "app/simulation.hpp"

#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

#include "scene/reader.hpp"

namespace voigt {

namespace {
// Same content whatever the style: maps without regard to key order or flow/block style,
// sequences element by element, scalars equal as text or as the same number (0.02 = 2e-2).
bool sameYaml(const YAML::Node& a, const YAML::Node& b) {
  if (a.Type() != b.Type()) return false;
  switch (a.Type()) {
    case YAML::NodeType::Scalar: {
      const std::string& x = a.Scalar();
      const std::string& y = b.Scalar();
      if (x == y) return true;
      char *ex = nullptr, *ey = nullptr;
      const double dx = std::strtod(x.c_str(), &ex), dy = std::strtod(y.c_str(), &ey);
      return !x.empty() && !y.empty() && *ex == '\0' && *ey == '\0' && dx == dy;
    }
    case YAML::NodeType::Sequence:
      if (a.size() != b.size()) return false;
      for (std::size_t i = 0; i < a.size(); ++i)
        if (!sameYaml(a[i], b[i])) return false;
      return true;
    case YAML::NodeType::Map: {
      if (a.size() != b.size()) return false;
      for (const auto& kv : a) {
        const YAML::Node other = b[kv.first.as<std::string>()];
        if (!other || !sameYaml(kv.second, other)) return false;
      }
      return true;
    }
    default:
      return true; // both null / undefined
  }
}
} // namespace

void Simulation::writeSceneRecord(const std::string& file, const std::string& note) const {
  const std::string path = opt_.outDir + "/" + file, tmp = path + ".tmp";
  std::ostringstream os;
  os << "# The scene this run segment used, as Voigt ran it (" << note << "):\n# "
     << (scene_.path.empty() ? std::string("built-in") : scene_.path) << "\n";
  if (scene_.source)
    for (const auto& o : scene_.source->overrides) os << "# --set " << o.text << "\n";
  if (opt_.endTime > 0) os << "# --end-time " << opt_.endTime << "\n";
  if (opt_.maxSteps >= 0) os << "# --steps " << opt_.maxSteps << "\n";
  YAML::Emitter e;
  e << scene_.root;
  os << e.c_str() << "\n";
  std::ofstream f(tmp, std::ios::trunc);
  f << os.str();
  f.close();
  if (!f) throw std::runtime_error("cannot write " + tmp);
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
}

void Simulation::compareScene(const nlohmann::json& meta) {
  restartSceneChanges_.clear();
  restartSceneCompared_ = false;
  if (!meta.contains("scene_yaml")) return; // written before checkpoints carried the scene
  YAML::Node was;
  try {
    was = YAML::Load(meta.at("scene_yaml").get<std::string>());
  } catch (const std::exception&) {
    return; // informational only: an unreadable record does not stop the restart
  }
  const YAML::Node& now = scene_.root;
  std::set<std::string> keys;
  for (const auto& kv : was) keys.insert(kv.first.as<std::string>());
  for (const auto& kv : now) keys.insert(kv.first.as<std::string>());
  for (const auto& k : keys) {
    const YAML::Node a = was[k], b = now[k];
    if (!a || !b || !sameYaml(a, b)) restartSceneChanges_.push_back(k);
  }
  restartSceneCompared_ = true;
}

// Rank 0, after a restart restored its checkpoint: keep the first segment's scene.yaml and add
// scene_segment<N>.yaml when this segment's scene differs (or cannot be compared). A failure
// here is reported, not thrown: the other ranks are already past any collective error check.
void Simulation::recordRestartScene() const {
  namespace fs = std::filesystem;
  try {
    std::error_code ec;
    if (!fs::exists(opt_.outDir + "/scene.yaml", ec))
      writeSceneRecord("scene.yaml", "first recorded at segment " + std::to_string(segments_));
    else if (!restartSceneCompared_ || !restartSceneChanges_.empty())
      writeSceneRecord("scene_segment" + std::to_string(segments_) + ".yaml",
                       "segment " + std::to_string(segments_) + ", restarted at step " + std::to_string(st_.step));
  } catch (const std::exception& e) {
    std::cerr << "warning: " << e.what() << " (the run goes on without that record)" << std::endl;
  }
}

} // namespace voigt
