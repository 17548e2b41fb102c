#include "core/field.hpp"

#include <stdexcept>

#include "core/grid.hpp"
#include "core/host_access.hpp"

namespace voigt {

void FieldStore::declare(const std::string& name, Centring c, int components, const std::string& owner,
                         bool isInt) {
  auto it = decls_.find(name);
  if (it != decls_.end()) {
    if (it->second.centring != c || it->second.components != components || it->second.isInt != isInt)
      throw std::logic_error("field '" + name + "' declared twice with different shapes (" + owner +
                             ", " + it->second.owner + ")");
    it->second.derived = false; // state for this effect: state
    return;
  }
  decls_[name] = Decl{c, components, isInt, owner};
}

void FieldStore::declareDerived(const std::string& name, Centring c, int components, const std::string& owner) {
  const bool seen = declared(name);
  const bool wasDerived = seen && decls_.at(name).derived;
  declare(name, c, components, owner);
  decls_[name].derived = seen ? wasDerived : true;
}

long long FieldStore::bytes(const Grid& g) const {
  long long total = 0;
  for (auto& [name, d] : decls_)
    total += g.arrayPoints() * d.components * (d.isInt ? sizeof(int) : sizeof(double));
  return total;
}

void FieldStore::allocate(const Grid& g) {
  for (auto& [name, d] : decls_) {
    if (allocated(name)) continue;
    if (d.isInt) {
      ints_[name] = IntField(name, g.ext[0], g.ext[1], g.ext[2]);
    } else if (d.components == 1) {
      scalars_[name] = Field(name, g.ext[0], g.ext[1], g.ext[2]);
    } else {
      VecField v;
      for (int c = 0; c < 3; ++c)
        v.c[c] = Field(name + "_" + "xyz"[c], g.ext[0], g.ext[1], g.ext[2]);
      vectors_[name] = v;
    }
  }
  // Under the host-touch check every field's pages close outside kernels (host_access.hpp).
  for (auto& [n, f] : scalars_) guard(f);
  for (auto& [n, v] : vectors_)
    for (const Field& f : v.c) guard(f);
  for (auto& [n, f] : ints_) guard(f);
}

Field FieldStore::scalar(const std::string& name) const {
  auto it = scalars_.find(name);
  if (it == scalars_.end()) throw std::logic_error("scalar field '" + name + "' was never declared");
  return it->second;
}

VecField FieldStore::vector(const std::string& name) const {
  auto it = vectors_.find(name);
  if (it == vectors_.end()) throw std::logic_error("vector field '" + name + "' was never declared");
  return it->second;
}

IntField FieldStore::integer(const std::string& name) const {
  auto it = ints_.find(name);
  if (it == ints_.end()) throw std::logic_error("integer field '" + name + "' was never declared");
  return it->second;
}

bool FieldStore::allocated(const std::string& name) const {
  return scalars_.count(name) || vectors_.count(name) || ints_.count(name);
}

std::vector<std::string> FieldStore::allocatedNames() const {
  std::vector<std::string> out;
  for (auto& [n, f] : scalars_) out.push_back(n);
  for (auto& [n, f] : vectors_) out.push_back(n);
  for (auto& [n, f] : ints_) out.push_back(n);
  return out;
}

} // namespace voigt
