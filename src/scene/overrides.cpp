// --set KEY=VALUE on the parsed scene tree, before validation (scene/load.hpp).
#include "scene/load.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>
#include <string>
#include <vector>

namespace voigt {

// Applies one --set; returns the canonical path ("obstacles[0].radius") it set.
std::string applyOverride(YAML::Node& root, const std::string& a) {
  auto bad = [&](const std::string& key, const std::string& msg) {
    return SceneError("--set " + a + ": " + (key.empty() ? "" : "key '" + key + "': ") + msg);
  };
  size_t eq = a.find('=');
  if (eq == std::string::npos || eq == 0) throw bad("", "expected KEY=VALUE, e.g. time.end=2");
  std::string lhs = a.substr(0, eq), rhs = a.substr(eq + 1);
  std::vector<std::string> parts;
  std::stringstream ss(lhs);
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
  if (lhs.back() == '.' || std::find(parts.begin(), parts.end(), "") != parts.end())
    throw bad("", "empty key component in '" + lhs + "'");
  if (rhs.find_first_not_of(" \t") == std::string::npos) throw bad(lhs, "missing value");
  YAML::Node value, cur;
  try {
    value.reset(YAML::Load(rhs));
  } catch (const YAML::Exception& e) {
    throw bad(lhs, "value is not valid YAML: " + e.msg);
  }
  if (!root.IsDefined() || root.IsNull()) root.reset(YAML::Node(YAML::NodeType::Map));
  cur.reset(root);
  std::string path;
  for (size_t i = 0; i < parts.size(); ++i) {
    const std::string& k = parts[i];
    YAML::Node next; // a handle into the tree: assigning to it edits the tree
    if (cur.IsSequence()) {
      if (k.size() > 9 || !std::all_of(k.begin(), k.end(), [](unsigned char c) { return std::isdigit(c); }))
        throw bad(path, "is a list: index it with a number, not '" + k + "'");
      if (std::stoul(k) >= cur.size())
        throw bad(path, "index " + k + " is out of range (the list has " + std::to_string(cur.size()) + " entries)");
      path += "[" + k + "]";
      next.reset(cur[std::stoul(k)]);
    } else if (cur.IsMap() || cur.IsNull()) {
      path += (path.empty() ? "" : ".") + k;
      next.reset(cur[k]);
      if (i + 1 < parts.size() && (!next.IsDefined() || next.IsNull())) next = YAML::Node(YAML::NodeType::Map);
    } else {
      throw bad(path, "is the value '" + cur.Scalar() + "', not a map or list");
    }
    if (i + 1 == parts.size()) next = value;
    else cur.reset(next);
  }
  return path;
}

} // namespace voigt
