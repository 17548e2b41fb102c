#include "scene/reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>

namespace voigt {

namespace {

std::string num(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

// What a node is, for "expected X, got Y" messages.
std::string kind(const YAML::Node& n) {
  if (n.IsMap()) return "a map";
  if (n.IsSequence()) return "a list";
  if (n.IsNull()) return "nothing";
  return "'" + n.Scalar() + "'";
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// True if `path` is `prefix` or lies inside it ("a.b[0]" is inside "a.b").
bool within(const std::string& path, const std::string& prefix) {
  if (path.compare(0, prefix.size(), prefix) != 0) return false;
  return path.size() == prefix.size() || path[prefix.size()] == '.' || path[prefix.size()] == '[';
}

template <class C>
std::string join(const C& s) {
  std::string out;
  for (auto& k : s) out += (out.empty() ? "" : ", ") + k;
  return out;
}

} // namespace

bool Range::contains(double v) const {
  return (loOpen ? v > lo : v >= lo) && (hiOpen ? v < hi : v <= hi);
}

std::string Range::describe() const {
  bool lowInf = std::isinf(lo), highInf = std::isinf(hi);
  if (lowInf && highInf) return "must be finite";
  if (highInf) return std::string("must be ") + (loOpen ? "> " : ">= ") + num(lo);
  if (lowInf) return std::string("must be ") + (hiOpen ? "< " : "<= ") + num(hi);
  return "must be in " + std::string(loOpen ? "(" : "[") + num(lo) + ", " + num(hi) + (hiOpen ? ")" : "]");
}

Section::Section(YAML::Node node, std::string path, std::shared_ptr<const SourceInfo> src)
    : path_(std::move(path)), src_(std::move(src)), read_(std::make_shared<std::set<std::string>>()) {
  // A zombie node (const operator[] on a missing key) throws on most calls: normalise to null.
  if (node.IsDefined()) node_.reset(node);
  fallback_ = node_.Mark();
}

std::string Section::keyPath(const std::string& key) const {
  if (key.empty()) return path_;
  return path_.empty() ? key : path_ + "." + key;
}

// Null for nodes made by --set or absent keys; failAt() resolves those.
YAML::Mark Section::markOf(const YAML::Node& n) const {
  return n.IsDefined() ? n.Mark() : YAML::Mark::null_mark();
}

void Section::failAt(const YAML::Mark& m, const std::string& kp, const std::string& msg) const {
  std::string where;
  if (src_) {
    // A value set (or inside a value set) by --set has no file position worth showing.
    for (auto it = src_->overrides.rbegin(); where.empty() && it != src_->overrides.rend(); ++it)
      if (within(kp, it->path)) where = "--set " + it->text;
    // A map created by --set to hold a new key (or a key missing from it): blame that --set.
    for (auto it = src_->overrides.rbegin(); where.empty() && m.is_null() && it != src_->overrides.rend(); ++it)
      if (within(it->path, kp) || within(it->path, path_)) where = "--set " + it->text;
  }
  if (where.empty()) {
    where = src_ ? src_->file : std::string("<scene>");
    const YAML::Mark& pos = m.is_null() ? fallback_ : m;
    if (!pos.is_null()) where += ":" + std::to_string(pos.line + 1) + ":" + std::to_string(pos.column + 1);
  }
  throw SceneError(where + ": key '" + kp + "': " + msg);
}

void Section::fail(const std::string& key, const std::string& msg) const {
  YAML::Node v;
  failAt(!key.empty() && lookup(key, v) ? markOf(v) : fallback_, keyPath(key), msg);
}

void Section::failItem(const std::string& key, size_t index, const std::string& msg) const {
  YAML::Node v;
  YAML::Mark m = fallback_;
  if (lookup(key, v)) m = v.IsSequence() && index < v.size() ? markOf(v[index]) : markOf(v);
  failAt(m, keyPath(key) + "[" + std::to_string(index) + "]", msg);
}

bool Section::lookup(const std::string& key, YAML::Node& out) const {
  read_->insert(key);
  if (!node_.IsMap()) return false;
  const YAML::Node& map = node_; // const access: a missing key must not be inserted
  YAML::Node v = map[key];
  if (!v.IsDefined()) return false;
  out.reset(v);
  return true;
}

bool Section::has(const std::string& key) const {
  YAML::Node v;
  return lookup(key, v);
}

void Section::allow(const std::string& key) const { read_->insert(key); }

// The scalar n parsed whole as T (an optional leading '+'), else failAt: "'s' tooLarge"
// when out of T's range, "expected <what>, got 's'" when not a T.
template <class T>
T Section::parseWhole(const YAML::Node& n, const std::string& kp, const char* what, const char* tooLarge) const {
  const std::string& s = n.Scalar();
  const char* b = s.data() + (!s.empty() && s[0] == '+' ? 1 : 0);
  const char* e = s.data() + s.size();
  T v = 0;
  auto res = std::from_chars(b, e, v);
  if (!s.empty() && res.ec == std::errc::result_out_of_range && res.ptr == e)
    failAt(markOf(n), kp, "'" + s + "' " + tooLarge);
  if (s.empty() || res.ec != std::errc() || res.ptr != e)
    failAt(markOf(n), kp, std::string("expected ") + what + ", got '" + s + "'");
  return v;
}

double Section::toNumber(const YAML::Node& n, const std::string& kp, Range r) const {
  if (!n.IsScalar()) failAt(markOf(n), kp, "expected a number, got " + kind(n));
  const std::string& s = n.Scalar();
  if (n.Tag() == "!") failAt(markOf(n), kp, "expected a number, got the quoted string '" + s + "'");
  std::string l = lower(s);
  if (l == ".inf" || l == "+.inf" || l == "-.inf" || l == ".nan")
    failAt(markOf(n), kp, "must be a finite number (got '" + s + "')");
  const double v = parseWhole<double>(n, kp, "a number", "is out of the range of a double (about 1e-308 to 1e308)");
  if (!std::isfinite(v)) failAt(markOf(n), kp, "must be a finite number (got '" + s + "')");
  if (!r.contains(v)) failAt(markOf(n), kp, r.describe() + " (got " + s + ")");
  return v;
}

long Section::toInteger(const YAML::Node& n, const std::string& kp, long lo, long hi) const {
  if (!n.IsScalar() || n.Tag() == "!") failAt(markOf(n), kp, "expected an integer, got " + kind(n));
  const std::string& s = n.Scalar();
  const long v = parseWhole<long>(n, kp, "an integer", "is too large");
  if (v < lo || v > hi) {
    std::string what = hi == std::numeric_limits<long>::max()
                           ? "must be >= " + std::to_string(lo)
                           : "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    failAt(markOf(n), kp, what + " (got " + s + ")");
  }
  return v;
}

std::string Section::toText(const YAML::Node& n, const std::string& kp) const {
  if (!n.IsScalar()) failAt(markOf(n), kp, "expected a string, got " + kind(n));
  return n.Scalar();
}

double Section::number(const std::string& key, double def, Range r) const {
  YAML::Node v;
  return lookup(key, v) ? toNumber(v, keyPath(key), r) : def;
}

double Section::requireNumber(const std::string& key, Range r) const {
  YAML::Node v;
  if (!lookup(key, v)) fail(key, "is required");
  return toNumber(v, keyPath(key), r);
}

long Section::integer(const std::string& key, long def, long lo, long hi) const {
  YAML::Node v;
  return lookup(key, v) ? toInteger(v, keyPath(key), lo, hi) : def;
}

bool Section::boolean(const std::string& key, bool def) const {
  YAML::Node v;
  if (!lookup(key, v)) return def;
  bool b = false;
  if (!v.IsScalar() || v.Tag() == "!" || !YAML::convert<bool>::decode(v, b))
    failAt(markOf(v), keyPath(key), "expected true or false, got " + kind(v));
  return b;
}

std::string Section::string(const std::string& key, const std::string& def) const {
  YAML::Node v;
  return lookup(key, v) ? toText(v, keyPath(key)) : def;
}

std::string Section::choice(const std::string& key, const std::string& def,
                            std::vector<std::string> allowed) const {
  YAML::Node v;
  if (!lookup(key, v)) return def;
  std::string s = toText(v, keyPath(key));
  if (std::find(allowed.begin(), allowed.end(), s) == allowed.end())
    failAt(markOf(v), keyPath(key),
           "must be one of " + join(allowed) + " (got '" + s + "')");
  return s;
}

std::array<double, 3> Section::vec3(const std::string& key, std::array<double, 3> def, Range r) const {
  YAML::Node v;
  if (!lookup(key, v)) return def;
  if (!v.IsSequence() || v.size() != 3)
    failAt(markOf(v), keyPath(key), "expected a list of 3 numbers, got " + kind(v));
  for (int i = 0; i < 3; ++i) def[i] = toNumber(v[i], keyPath(key) + "[" + std::to_string(i) + "]", r);
  return def;
}

std::array<int, 3> Section::ivec3(const std::string& key, std::array<int, 3> def, int lo, int hi) const {
  YAML::Node v;
  if (!lookup(key, v)) return def;
  if (!v.IsSequence() || v.size() != 3)
    failAt(markOf(v), keyPath(key), "expected a list of 3 integers, got " + kind(v));
  for (int i = 0; i < 3; ++i)
    def[i] = int(toInteger(v[i], keyPath(key) + "[" + std::to_string(i) + "]", lo, hi));
  return def;
}

std::vector<std::string> Section::strings(const std::string& key, std::vector<std::string> def) const {
  YAML::Node v;
  if (!lookup(key, v)) return def;
  if (!v.IsSequence()) failAt(markOf(v), keyPath(key), "expected a list of strings, got " + kind(v));
  std::vector<std::string> out;
  for (size_t i = 0; i < v.size(); ++i) {
    std::string kp = keyPath(key) + "[" + std::to_string(i) + "]";
    out.push_back(toText(v[i], kp));
    if (out.back().empty()) failAt(markOf(v[i]), kp, "must not be empty");
  }
  return out;
}

Section Section::section(const std::string& key) const {
  YAML::Node v;
  bool found = lookup(key, v);
  if (found && !v.IsNull() && !v.IsMap()) failAt(markOf(v), keyPath(key), "expected a map, got " + kind(v));
  Section s(found && v.IsMap() ? v : YAML::Node(), keyPath(key), src_);
  s.fallback_ = found ? markOf(v) : fallback_;
  return s;
}

std::vector<Section> Section::list(const std::string& key) const {
  YAML::Node v;
  if (!lookup(key, v) || v.IsNull()) return {};
  if (!v.IsSequence()) failAt(markOf(v), keyPath(key), "expected a list, got " + kind(v));
  std::vector<Section> out;
  for (size_t i = 0; i < v.size(); ++i) {
    std::string kp = keyPath(key) + "[" + std::to_string(i) + "]";
    YAML::Node item = v[i];
    if (!item.IsMap()) failAt(markOf(item), kp, "expected a map, got " + kind(item));
    out.emplace_back(item, kp, src_);
    out.back().fallback_ = markOf(item);
  }
  return out;
}

std::vector<std::string> Section::keys() const {
  std::vector<std::string> out;
  if (!node_.IsMap()) return out;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (!it->first.IsScalar()) failAt(markOf(it->first), path_, "keys must be plain names");
    out.push_back(it->first.Scalar());
    read_->insert(out.back());
  }
  return out;
}

void Section::finish() const {
  if (!node_.IsMap()) return;
  std::set<std::string> seen;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (!it->first.IsScalar()) failAt(markOf(it->first), path_, "keys must be plain names");
    const std::string& k = it->first.Scalar();
    if (!seen.insert(k).second) failAt(markOf(it->first), keyPath(k), "duplicate key");
    if (read_->count(k)) continue;
    std::string allowed = read_->empty() ? "none" : join(*read_);
    std::string where = path_.empty() ? "at top level" : "in '" + path_ + "'";
    failAt(markOf(it->first), keyPath(k), "unknown key '" + k + "' " + where + " (allowed: " + allowed + ")");
  }
}

Section topSection(const Scene& scene, const std::string& key) {
  return Section(scene.root, "", scene.source).section(key);
}

} // namespace voigt
