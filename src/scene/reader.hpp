#pragma once
// Validating access to one YAML map of a scene. Every read is type- and
// range-checked, finish() rejects keys nobody read (typos), and every error
// points at FILE:LINE:COL, or at the --set assignment the value came from.
#include <yaml-cpp/yaml.h>

#include <array>
#include <limits>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace voigt {

struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool loOpen = false, hiOpen = false;

  static Range positive() { return {0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range nonNegative() { return {0, std::numeric_limits<double>::infinity(), false, false}; }
  static Range between(double a, double b) { return {a, b, false, false}; } // closed [a, b]
  bool contains(double v) const;
  std::string describe() const; // "must be > 0", "must be in (0, 2)"
};

// Where a scene tree came from, for error locations.
struct SourceInfo {
  struct Override {
    std::string path; // canonical key path, e.g. "obstacles[0].radius"
    std::string text; // the assignment as typed: "obstacles.0.radius=0.1"
  };
  std::string file;                 // name used in messages
  std::vector<Override> overrides;  // in application order
};

class Section { // a YAML map plus its dotted path, e.g. "time" or "obstacles[2]"
 public:
  Section(YAML::Node node, std::string path, std::shared_ptr<const SourceInfo> src);

  const std::string& path() const { return path_; }
  const YAML::Node& node() const { return node_; }

  bool has(const std::string& key) const; // also marks the key as known
  double number(const std::string& key, double def, Range r = {}) const;
  double requireNumber(const std::string& key, Range r = {}) const;
  long integer(const std::string& key, long def, long lo, long hi) const;
  bool boolean(const std::string& key, bool def) const;
  std::string string(const std::string& key, const std::string& def) const;
  std::string choice(const std::string& key, const std::string& def,
                     std::vector<std::string> allowed) const;
  std::array<double, 3> vec3(const std::string& key, std::array<double, 3> def, Range r = {}) const;
  std::array<int, 3> ivec3(const std::string& key, std::array<int, 3> def, int lo, int hi) const;
  std::vector<std::string> strings(const std::string& key, std::vector<std::string> def) const;
  Section section(const std::string& key) const;           // missing or null -> empty section
  std::vector<Section> list(const std::string& key) const;  // list of maps; missing -> {}
  std::vector<std::string> keys() const;      // all keys in file order (for name->map sections)
  void allow(const std::string& key) const;   // accept key unread (owned by someone else)

  [[noreturn]] void fail(const std::string& key, const std::string& msg) const;
  [[noreturn]] void failItem(const std::string& key, size_t index, const std::string& msg) const;
  void finish() const; // error on duplicate keys and keys that were never read

 private:
  bool lookup(const std::string& key, YAML::Node& out) const; // marks key as read
  std::string keyPath(const std::string& key) const;
  YAML::Mark markOf(const YAML::Node& n) const;
  template <class T>
  T parseWhole(const YAML::Node& n, const std::string& kp, const char* what, const char* tooLarge) const;
  [[noreturn]] void failAt(const YAML::Mark& m, const std::string& keyPath, const std::string& msg) const;
  double toNumber(const YAML::Node& n, const std::string& kp, Range r) const;
  long toInteger(const YAML::Node& n, const std::string& kp, long lo, long hi) const;
  std::string toText(const YAML::Node& n, const std::string& kp) const;

  YAML::Node node_;
  std::string path_;
  std::shared_ptr<const SourceInfo> src_;
  std::shared_ptr<std::set<std::string>> read_; // shared by copies: reads through any copy count
  YAML::Mark fallback_;                         // for errors about keys that are absent
};

// A top-level section of a loaded scene (e.g. an effect's "level_set"); empty if absent.
// Call finish() on it after reading so typos in the effect's keys are caught.
Section topSection(const Scene& scene, const std::string& key);

} // namespace voigt
