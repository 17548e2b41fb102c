// Implicit-surface shapes: scene -> postfix program -> Kokkos kernel.
#include "effects/level_set/shape_compiler.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/host_access.hpp"

namespace voigt {

namespace {

struct Compiler {
  const Scene& scene;
  std::vector<ShapeOp> ops{};
  std::vector<std::array<double, 4>> spheres{};
  int depth = 0, maxDepth = 0;

  void push() { maxDepth = std::max(maxDepth, ++depth); }

  void loadPacking(const Section& s, ShapeOp& op) {
    if (!s.has("file")) s.fail("file", "is required (a CSV of sphere centres x,y,z and radii r)");
    std::string file = s.string("file", "");
    namespace fs = std::filesystem;
    fs::path p(file);
    if (p.is_relative() && !scene.path.empty()) p = fs::path(scene.path).parent_path() / p;
    std::ifstream in(p);
    if (!in) s.fail("file", "cannot open '" + p.string() + "'");
    const bool hasR = s.has("radius");
    const double rDef = s.number("radius", 0, Range::positive());
    op.n = int(spheres.size());
    std::string line;
    for (int ln = 1; std::getline(in, line); ++ln) {
      auto bad = [&](const std::string& m) { s.fail("file", p.string() + ":" + std::to_string(ln) + ": " + m); };
      if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t")] == '#')
        continue;
      for (char& c : line)
        if (c == ',' || c == ';' || c == '\t') c = ' ';
      std::istringstream is(line);
      std::vector<double> v;
      std::string tok;
      while (is >> tok) {
        char* end = nullptr;
        const double x = std::strtod(tok.c_str(), &end);
        if (*end != '\0' || !std::isfinite(x)) {
          if (ln == 1 && spheres.size() == size_t(op.n) && v.empty()) break; // header line
          bad("'" + tok + "' is not a finite number");
        }
        v.push_back(x);
      }
      if (v.empty()) continue;
      if (v.size() == 3 && hasR) v.push_back(rDef);
      if (v.size() != 4) bad("expected x, y, z, r (or x, y, z with 'radius' set), got " + std::to_string(v.size()) + " values");
      if (!(v[3] > 0)) bad("radius must be > 0");
      spheres.push_back({v[0], v[1], v[2], v[3]});
    }
    op.m = int(spheres.size()) - op.n;
    if (op.m == 0) s.fail("file", "'" + p.string() + "' holds no spheres");
  }

  // Compiles one shape map; returns its description.
  std::string compile(const Section& s, int level) {
    if (level > 16) s.fail("type", "shapes nest too deeply (more than 16 levels)");
    if (!s.has("type")) s.fail("type", "is required (sphere, box, plane, wave, cylinder, superquadric, sphere_packing, union, intersection, complement)");
    const std::string t = s.choice("type", "", {"sphere", "box", "plane", "wave", "cylinder", "superquadric", "sphere_packing",
                                                 "union", "intersection", "complement"});
    ShapeOp op;
    std::ostringstream d;
    auto vec = [&](const char* key, int at, Range r = {}) {
      if (!s.has(key)) s.fail(key, "is required for a " + t);
      auto v = s.vec3(key, {}, r);
      for (int c = 0; c < 3; ++c) op.a[at + c] = v[c];
    };
    if (t == "union" || t == "intersection") {
      op.kind = t == "union" ? ShapeKind::Union : ShapeKind::Intersection;
      auto list = s.list("of");
      if (list.size() < 2) s.fail("of", "needs a list of at least two shapes");
      d << t << "(";
      for (size_t i = 0; i < list.size(); ++i) d << (i ? ", " : "") << compile(list[i], level + 1);
      d << ")";
      op.n = int(list.size());
      depth -= op.n - 1;
    } else if (t == "complement") {
      op.kind = ShapeKind::Complement;
      if (!s.has("of")) s.fail("of", "is required: the shape to complement");
      d << "complement(" << compile(s.section("of"), level + 1) << ")";
    } else {
      push();
      if (t == "sphere") {
        op.kind = ShapeKind::Sphere;
        vec("center", 0);
        op.a[3] = s.requireNumber("radius", Range::positive());
      } else if (t == "box") {
        op.kind = ShapeKind::Box;
        vec("lo", 0);
        vec("hi", 3);
        for (int c = 0; c < 3; ++c) {
          if (!(op.a[3 + c] > op.a[c])) s.fail("hi", "must be greater than lo in every component");
          const double lo = op.a[c], hi = op.a[3 + c];
          op.a[c] = 0.5 * (lo + hi);
          op.a[3 + c] = 0.5 * (hi - lo);
        }
      } else if (t == "plane") {
        op.kind = ShapeKind::Plane;
        vec("point", 0);
        vec("normal", 3);
        const double nn = std::sqrt(op.a[3] * op.a[3] + op.a[4] * op.a[4] + op.a[5] * op.a[5]);
        if (!(nn > 0)) s.fail("normal", "must not be zero");
        for (int c = 3; c < 6; ++c) op.a[c] /= nn;
      } else if (t == "wave") {
        op.kind = ShapeKind::Wave;
        vec("point", 0);
        vec("normal", 3);
        vec("direction", 7);
        op.a[6] = s.requireNumber("amplitude");
        const double len = s.requireNumber("wavelength", Range::positive());
        double nn = 0, dd = 0, nd = 0;
        for (int c = 0; c < 3; ++c) nn += op.a[3 + c] * op.a[3 + c], dd += op.a[7 + c] * op.a[7 + c];
        if (!(nn > 0)) s.fail("normal", "must not be zero");
        if (!(dd > 0)) s.fail("direction", "must not be zero");
        for (int c = 0; c < 3; ++c) op.a[3 + c] /= std::sqrt(nn), op.a[7 + c] /= std::sqrt(dd);
        for (int c = 0; c < 3; ++c) nd += op.a[3 + c] * op.a[7 + c];
        if (std::fabs(nd) > 1e-12) s.fail("direction", "must be perpendicular to the normal");
        op.a[10] = 2 * M_PI / len;
      } else if (t == "cylinder") {
        op.kind = ShapeKind::Cylinder;
        vec("center", 0);
        op.a[3] = s.requireNumber("radius", Range::positive());
        op.a[4] = 0.5 * s.number("length", INFINITY, Range::positive());
        op.m = s.choice("axis", "z", {"x", "y", "z"})[0] - 'x';
      } else if (t == "superquadric") {
        op.kind = ShapeKind::Superquadric;
        vec("center", 0);
        vec("semi_axes", 3, Range::positive());
        op.a[6] = s.requireNumber("exponent", {1, 100, false, false});
      } else {
        op.kind = ShapeKind::Packing;
        loadPacking(s, op);
      }
      d << t;
    }
    s.finish();
    ops.push_back(op);
    return d.str();
  }
};

} // namespace

ShapeProgram compileShape(const Section& parent, const std::string& key, const Scene& scene) {
  if (!parent.has(key)) parent.fail(key, "is required: the initial shape of phase 1 (psi > 0)");
  Compiler c{scene};
  ShapeProgram p;
  p.text = c.compile(parent.section(key), 0);
  if (c.maxDepth > kShapeStack) parent.fail(key, "the shape needs too many simultaneous operands (max 32)");
  p.ops = Kokkos::View<ShapeOp*, MemSpace>("shape_ops", c.ops.size());
  auto ho = hostMirror(p.ops);
  for (size_t i = 0; i < c.ops.size(); ++i) ho(i) = c.ops[i];
  toDevice(p.ops, ho, "setup");
  p.spheres = Kokkos::View<double* [4], MemSpace>("shape_spheres", c.spheres.size());
  auto hs = hostMirror(p.spheres);
  for (size_t i = 0; i < c.spheres.size(); ++i)
    for (int q = 0; q < 4; ++q) hs(i, q) = c.spheres[i][q];
  toDevice(p.spheres, hs, "setup");
  p.sphereCount = (long long)c.spheres.size();
  auto exact = [](ShapeKind k) {
    return k == ShapeKind::Sphere || k == ShapeKind::Box || k == ShapeKind::Plane || k == ShapeKind::Cylinder;
  };
  p.exactDistance = (c.ops.size() == 1 && exact(c.ops[0].kind)) ||
                    (c.ops.size() == 2 && exact(c.ops[0].kind) && c.ops[1].kind == ShapeKind::Complement);
  return p;
}

} // namespace voigt
