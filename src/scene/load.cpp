#include "scene/load.hpp"
#include "scene/presets.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

namespace voigt {

const char* toString(BcType t) {
  static const char* const names[] = {"no_slip", "slip", "periodic", "inflow", "outflow"};
  return names[int(t)];
}

namespace {

template <class... A>
std::string cat(const A&... a) {
  std::ostringstream o;
  (o << ... << a);
  return o.str();
}

std::string str(const Vec3& v) { return cat("[", v[0], ", ", v[1], ", ", v[2], "]"); }

template <class C>
std::string join(const C& c) {
  std::string out;
  for (auto& s : c) out += (out.empty() ? "" : ", ") + std::string(s);
  return out;
}

const char* const kFaces[6] = {"x-", "x+", "y-", "y+", "z-", "z+"};
const char* const kCoreKeys[] = {"name", "domain", "boundaries", "time", "materials", "fluid", "effects",
                                 "gravity", "obstacles", "initial", "projection", "advection", "output", "probes",
                                 "checkpoint"}; // checkpoint: validated by Simulation (app/simulation.cpp)

// Names end up in file names and CSV headers.
bool isName(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '-';
  });
}

Vec3 requireVec3(const Section& s, const std::string& key) {
  if (!s.has(key)) s.fail(key, "is required");
  return s.vec3(key, {});
}

// A required point that must lie in the (closed) domain box.
Vec3 requirePoint(const Section& s, const std::string& key, const Scene& sc) {
  Vec3 p = requireVec3(s, key);
  for (int a = 0; a < 3; ++a)
    if (p[a] < sc.lo[a] || p[a] > sc.hi[a])
      s.fail(key, "point " + str(p) + " lies outside the domain " + str(sc.lo) + " - " + str(sc.hi));
  return p;
}

void checkOrdered(const Section& s, const std::string& key, const Vec3& lo, const Vec3& hi) {
  for (int a = 0; a < 3; ++a)
    if (!(hi[a] > lo[a]))
      s.fail(key, cat("must be greater than lo in every component (", "xyz"[a], ": ", hi[a], " <= ", lo[a], ")"));
}

void readDomain(const Section& top, Scene& sc) {
  if (!top.has("domain")) top.fail("domain", "is required");
  Section d = top.section("domain");
  sc.lo = d.vec3("lo", sc.lo);
  sc.hi = d.vec3("hi", sc.hi);
  sc.cells = d.ivec3("cells", sc.cells, 1, 4096);
  sc.ranks = d.ivec3("ranks", sc.ranks, 0, 1 << 20);
  checkOrdered(d, "hi", sc.lo, sc.hi);
  for (int a = 0; a < 3; ++a) // finite bounds can still overflow: lo = -1e308, hi = 1e308
    if (!std::isfinite(sc.hi[a] - sc.lo[a]) || !std::isfinite((sc.hi[a] - sc.lo[a]) / sc.cells[a]) ||
        !((sc.hi[a] - sc.lo[a]) / sc.cells[a] > 0))
      d.fail("hi", cat("the domain size along ", "xyz"[a], " (hi - lo) must be a finite number with a nonzero cell size"));
  d.finish();
}

void readFace(const Section& f, FaceBc& bc) {
  static const std::vector<std::string> types{"no_slip", "slip", "periodic", "inflow", "outflow"};
  std::string t = f.choice("type", "no_slip", types);
  bc.type = BcType(std::find(types.begin(), types.end(), t) - types.begin());
  bool hasV = f.has("velocity"), hasP = f.has("pressure");
  bc.velocity = f.vec3("velocity", {0, 0, 0});
  bc.pressure = f.number("pressure", 0);
  if (hasV && bc.type != BcType::NoSlip && bc.type != BcType::Inflow)
    f.fail("velocity", "is only allowed on no_slip (moving wall) and inflow faces");
  if (hasP && bc.type != BcType::Outflow) f.fail("pressure", "is only allowed on outflow faces");
  if (!hasV && bc.type == BcType::Inflow) f.fail("velocity", "is required on an inflow face");
  if (f.has("oscillation")) { // velocity * sin(omega t + phase)
    if (bc.type != BcType::NoSlip) f.fail("oscillation", "is only allowed on no_slip (moving wall) faces");
    if (!hasV) f.fail("oscillation", "needs the wall 'velocity' (the amplitude)");
    Section o = f.section("oscillation");
    if (!o.has("omega")) o.fail("omega", "is required (angular frequency, rad per unit time)");
    bc.oscillating = true;
    bc.omega = o.number("omega", 0, Range::positive());
    bc.phase = o.number("phase", 0);
    o.finish();
  }
  f.finish();
}

void readBoundaries(const Section& top, Scene& sc) {
  Section b = top.section("boundaries");
  Section def = b.section("default");
  FaceBc defBc;
  readFace(def, defBc);
  std::vector<Section> from; // the section each face's settings came from, for errors
  bool given[6];
  for (int f = 0; f < 6; ++f) {
    given[f] = b.has(kFaces[f]);
    from.push_back(given[f] ? b.section(kFaces[f]) : def);
    sc.bc[f] = defBc;
    if (given[f]) readFace(from[f], sc.bc[f]);
  }
  b.finish();
  for (int f = 0; f < 6; ++f)
    if (sc.bc[f].type == BcType::NoSlip && sc.bc[f].velocity[f / 2] != 0)
      from[f].fail("velocity", cat("a wall moves tangentially: the ", "xyz"[f / 2], " component must be 0 on face ",
                                   kFaces[f]));
  for (int a = 0; a < 3; ++a) {
    int lo = 2 * a, hi = lo + 1;
    if ((sc.bc[lo].type == BcType::Periodic) == (sc.bc[hi].type == BcType::Periodic)) continue;
    int bad = sc.bc[lo].type == BcType::Periodic ? lo : hi;
    if (!given[bad]) bad = lo + hi - bad; // blame the face the user actually wrote
    from[bad].fail("type", cat("periodic must be set on both ", kFaces[lo], " and ", kFaces[hi], " or neither (",
                               kFaces[lo], " is ", toString(sc.bc[lo].type), ", ", kFaces[hi], " is ",
                               toString(sc.bc[hi].type), ")"));
  }
}

void readTime(const Section& top, TimeCfg& t) {
  Section s = top.section("time");
  t.endTime = s.number("end", t.endTime, Range::positive());
  t.dt = s.number("dt", t.dt, Range::nonNegative());
  t.cfl = s.number("cfl", t.cfl, {0, 1, true, false});
  t.viscousSafety = s.number("viscous_safety", t.viscousSafety, {0, 1, true, false});
  t.maxDt = s.number("max_dt", t.maxDt, Range::positive());
  t.minDt = s.number("min_dt", t.minDt, Range::nonNegative());
  t.maxSteps = s.integer("max_steps", t.maxSteps, 1, std::numeric_limits<long>::max());
  if (t.maxDt < t.minDt) s.fail("max_dt", cat("must be >= min_dt (", t.minDt, ")"));
  s.finish();
}

void readMaterials(const Section& top, Scene& sc) {
  Section m = top.section("materials");
  for (auto& name : m.keys()) {
    if (!isName(name)) m.fail(name, "material names may only use letters, digits, '_' and '-'");
    Section s = m.section(name);
    Material& mat = sc.materials[name] = Material{name};
    mat.density = s.number("density", mat.density, Range::positive());
    mat.viscosity = s.number("viscosity", mat.viscosity, Range::nonNegative());
    // Elastic moduli (elasticity effect): shear_modulus, or youngs_modulus + poisson_ratio.
    const bool hasG = s.has("shear_modulus"), hasE = s.has("youngs_modulus"), hasNu = s.has("poisson_ratio");
    if (hasG && (hasE || hasNu))
      s.fail(hasE ? "youngs_modulus" : "poisson_ratio",
             "give either shear_modulus or youngs_modulus + poisson_ratio, not both");
    if (hasG) mat.shearModulus = s.requireNumber("shear_modulus", Range::positive());
    if (hasE != hasNu) s.fail(hasE ? "poisson_ratio" : "youngs_modulus",
                              "is required with " + std::string(hasE ? "youngs_modulus" : "poisson_ratio"));
    if (hasE) {
      const double E = s.requireNumber("youngs_modulus", Range::positive());
      const double nu = s.requireNumber("poisson_ratio", {-1, 0.5, true, false}); // (-1, 0.5]
      mat.shearModulus = E / (2 * (1 + nu)); // Eq. (11)-(13): mu_S = E / (2 (1 + nu))
    }
    s.finish();
  }
  m.finish(); // duplicate names
  if (top.has("materials") && sc.materials.empty()) top.fail("materials", "must define at least one material");
  if (sc.materials.empty()) sc.materials["default"] = Material{"default"};
  std::vector<std::string> names;
  for (auto& kv : sc.materials) names.push_back(kv.first);
  if (!top.has("fluid") && names.size() > 1) top.fail("fluid", "is required when more than one material is defined");
  sc.fluid = top.string("fluid", names[0]);
  if (!sc.materials.count(sc.fluid)) top.fail("fluid", "names no material (defined: " + join(names) + ")");
}

void readEffects(const Section& top, Scene& sc, const LoadOptions& opts) {
  sc.effects = top.strings("effects", sc.effects);
  for (size_t i = 0; i < sc.effects.size(); ++i) {
    const std::string& e = sc.effects[i];
    if (!opts.knownEffects.count(e))
      top.failItem("effects", i, "unknown effect '" + e + "' (known: " + join(opts.knownEffects) + ")");
    if (std::find(sc.effects.begin(), sc.effects.begin() + i, e) != sc.effects.begin() + i)
      top.failItem("effects", i, "duplicate effect '" + e + "'");
  }
  sc.gravity = top.vec3("gravity", sc.gravity);
}

void readObstacles(const Section& top, Scene& sc) {
  auto list = top.list("obstacles");
  if (!list.empty() && std::find(sc.effects.begin(), sc.effects.end(), "obstacles") == sc.effects.end())
    top.fail("obstacles", "obstacles are given but 'obstacles' is not listed in effects");
  for (auto& o : list) {
    if (!o.has("type")) o.fail("type", "is required (cylinder, box or sphere)");
    std::string type = o.choice("type", "", {"cylinder", "box", "sphere"});
    Obstacle ob;
    ob.velocity = o.vec3("velocity", ob.velocity);
    if (type == "box") {
      ob.kind = Obstacle::Kind::Box;
      ob.lo = requireVec3(o, "lo");
      ob.hi = requireVec3(o, "hi");
      checkOrdered(o, "hi", ob.lo, ob.hi);
      for (int a = 0; a < 3; ++a) {
        ob.center[a] = 0.5 * (ob.lo[a] + ob.hi[a]);
        if (ob.hi[a] <= sc.lo[a] || ob.lo[a] >= sc.hi[a]) o.fail("lo", "the box lies entirely outside the domain");
      }
    } else {
      ob.kind = type == "cylinder" ? Obstacle::Kind::Cylinder : Obstacle::Kind::Sphere;
      ob.center = requirePoint(o, "center", sc);
      ob.radius = o.requireNumber("radius", Range::positive());
      if (type == "cylinder") ob.axis = o.choice("axis", "z", {"x", "y", "z"})[0] - 'x';
    }
    o.finish();
    sc.obstacles.push_back(ob);
  }
}

void readSettings(const Section& top, Scene& sc) {
  Section i = top.section("initial");
  auto& I = sc.initial;
  I.velocity = i.choice("velocity", I.velocity, {"zero", "uniform", "taylor_green", "couette", "poiseuille"});
  if (I.velocity == "uniform" && !i.has("uniform")) i.fail("uniform", "is required when velocity is 'uniform'");
  I.uniform = i.vec3("uniform", I.uniform);
  I.amplitude = i.number("amplitude", I.amplitude);
  I.pressure = i.number("pressure", I.pressure);
  i.finish();

  Section p = top.section("projection");
  auto& P = sc.projection;
  P.op = p.choice("operator", "exact", {"exact", "approximate"}) == "exact" ? ProjectionCfg::Op::Exact
                                                                          : ProjectionCfg::Op::Approximate;
  const long long cells = 1LL * sc.cells[0] * sc.cells[1] * sc.cells[2];
  bool twoPhase = false; // any level set's phase denser than the fluid?
  const bool ls = std::find(sc.effects.begin(), sc.effects.end(), "level_set") != sc.effects.end();
  const YAML::Node& root = sc.root, many = root["level_sets"];
  std::vector<YAML::Node> entries{root["level_set"]};
  for (size_t i = 0; many.IsDefined() && many.IsSequence() && i < many.size(); ++i) entries.push_back(many[i]);
  for (const YAML::Node& e : entries) {
    const YAML::Node phase = ls && e.IsDefined() && e.IsMap() ? e["phase"] : YAML::Node();
    if (phase && phase.IsScalar() && sc.materials.count(phase.Scalar()))
      twoPhase |= sc.materials.at(phase.Scalar()).density != sc.materials.at(sc.fluid).density;
  }
  // Exact operator, two densities: tolerance 1e-3, the divergence left relative to the
  // predictor's (D u = dt (rhs - A dp), poisson.hpp); dam break 64^3, ratio 1000: 50 its a step
  // against 236 at 1e-8, continuity error 4e-8 beside interFoam's 1e-8 to 1.3e-7 (perf/README.md,
  // "The exact projection at a tolerance"). One density (fast diagonalization is the inverse)
  // and the approximate operator (residual is not the divergence) keep 1e-8.
  const bool exact = P.op == ProjectionCfg::Op::Exact;
  P.toleranceAuto = !p.has("tolerance");
  P.tolerance = p.number("tolerance", exact && twoPhase ? ProjectionCfg::kTwoPhaseExactTolerance : P.tolerance,
                         {0, 1, true, true});
  P.maxIterations = int(p.integer("max_iterations", P.maxIterations, 1, 100000));
  P.preconditioner = p.choice("preconditioner", P.preconditioner, {"sgs", "jacobi", "none", "multigrid", "fast_diagonalization"});
  if (!p.has("preconditioner")) {
    // Exact operator: fast diagonalization, its own inverse at one density and the only
    // preconditioner measured to converge on both paper scenes. Approximate operator:
    // multigrid from 32^3 cells or two densities, else SGS (its set-up costs more than it
    // saves on small single-phase scenes). Measurements: perf/README.md, "Fast diagonalization".
    if (P.op == ProjectionCfg::Op::Exact) P.preconditioner = "fast_diagonalization";
    else P.preconditioner = (cells >= 32 * 32 * 32 || twoPhase) ? "multigrid" : "sgs";
    P.preconditionerAuto = true;
  }
  P.damping = p.number("damping", P.damping, {0, 2, true, true});
  P.sweeps = int(p.integer("sweeps", P.sweeps, 1, 100));
  P.multigridReuse = p.choice("multigrid_reuse", P.multigridReuse, {"none", "S", "tP", "RP", "RAP"});
  P.multigridRefresh = int(p.integer("multigrid_refresh", P.multigridRefresh, 0, 1000000));
  P.multigridRebuildGrowth = p.number("multigrid_rebuild_growth", P.multigridRebuildGrowth, Range::nonNegative());
  P.multigridSmoother = p.choice("multigrid_smoother", P.multigridSmoother, {"sgs", "chebyshev"});
  P.chebyshevDegree = int(p.integer("chebyshev_degree", P.chebyshevDegree, 1, 20));
  P.coarseSweeps = int(p.integer("multigrid_coarse_sweeps", P.coarseSweeps, 1, 1000));
  P.onCap = p.choice("on_cap", P.onCap, {"warn", "stop"});
  P.fdPrecision = p.choice("fd_precision", P.fdPrecision, {"single", "double"});
  P.initialGuessAuto = !p.has("initial_guess");
  const bool fd = P.op == ProjectionCfg::Op::Exact && P.preconditioner == "fast_diagonalization";
  P.initialGuess = p.choice("initial_guess", fd ? "extrapolate" : "previous",
                            {"previous", "extrapolate"});
  P.matrixFree = p.boolean("matrix_free", P.matrixFree);
  // Balanced gravity needs the exact operator: with the 7-point one a ratio-1000 column at rest
  // grew tenfold every ~80 steps at the gravity dt (16^3) (README, "Gravity and rest").
  P.hydrostatic = p.choice("hydrostatic", exact ? "balanced" : "none", {"balanced", "none"});
  P.volumeTolerance = p.number("volume_tolerance", P.volumeTolerance, {0, 1, false, true}); // 0: off
  P.variableDensity = p.choice("variable_density", P.variableDensity, {"solve", "split"});
  if (P.variableDensity == "split" && std::count(sc.effects.begin(), sc.effects.end(), "elasticity"))
    p.fail("variable_density", "split is for fluids: with elasticity the lagged pressure gradient is unstable "
                               "at the elastic time step (use solve)"); // perf/README.md, "The one-density split"
  p.finish();

  Section a = top.section("advection");
  sc.advection.limiter = a.choice("limiter", sc.advection.limiter, {"minmod", "van_leer", "mc", "none"});
  sc.advection.momentum = a.choice("momentum", sc.advection.momentum, {"auto", "conservative", "velocity"});
  a.finish();

  Section o = top.section("output");
  sc.output.interval = o.number("interval", sc.output.interval, Range::nonNegative());
  sc.output.fields = o.strings("fields", sc.output.fields);
  sc.output.enabled = o.boolean("enabled", sc.output.enabled);
  o.finish();
}

void readProbes(const Section& top, Scene& sc) {
  std::set<std::string> names;
  for (auto& p : top.list("probes")) {
    Probe pr;
    if (!p.has("name")) p.fail("name", "is required");
    pr.name = p.string("name", "");
    if (!isName(pr.name)) p.fail("name", "must match [A-Za-z0-9_-]+ (got '" + pr.name + "')");
    if (!names.insert(pr.name).second) p.fail("name", "duplicate probe name '" + pr.name + "'");
    bool point = p.has("point"), line = p.has("line");
    if (point == line) p.fail(point ? "line" : "point", "a probe needs exactly one of 'point' and 'line'");
    if (point) {
      pr.a = pr.b = requirePoint(p, "point", sc);
    } else {
      Section l = p.section("line");
      pr.kind = Probe::Kind::Line;
      pr.a = requirePoint(l, "from", sc);
      pr.b = requirePoint(l, "to", sc);
      if (!l.has("points")) l.fail("points", "is required");
      pr.points = int(l.integer("points", 0, 2, 100000));
      l.finish();
    }
    pr.fields = p.strings("fields", pr.fields);
    pr.interval = p.number("interval", pr.interval, Range::nonNegative());
    p.finish();
    sc.probes.push_back(pr);
  }
}

Scene build(YAML::Node root, const std::string& display, const std::string& path, const LoadOptions& opts) {
  auto src = std::make_shared<SourceInfo>();
  src->file = display;
  if (!root.IsDefined() || root.IsNull()) root.reset(YAML::Node(YAML::NodeType::Map)); // empty file
  if (!root.IsMap()) {
    YAML::Mark m = root.Mark();
    throw SceneError(cat(display, ":", m.line + 1, ":", m.column + 1, ": a scene must be a map of sections"));
  }
  for (auto& a : opts.overrides) src->overrides.push_back({applyOverride(root, a), a});

  Scene sc;
  sc.path = path;
  sc.root.reset(root);
  sc.source = src;
  const Section top(root, "", src);
  // Check top-level names first: a typo'd section is a better message than "domain is required".
  for (auto* k : kCoreKeys) top.allow(k);
  for (auto& k : opts.extraSections) top.allow(k); // effects validate these themselves
  sc.presetNotes = applyPreset(root, top, sc.preset); // defaults only: keys in the scene or --set win
  top.finish();

  std::string stem = display.substr(display.find_last_of('/') + 1);
  sc.name = top.string("name", stem.substr(0, stem.find('.')));
  if (top.has("name") && !isName(sc.name)) top.fail("name", "must match [A-Za-z0-9_-]+");
  readDomain(top, sc);
  readBoundaries(top, sc);
  readTime(top, sc.time);
  readMaterials(top, sc);
  readEffects(top, sc, opts);
  readObstacles(top, sc);
  readSettings(top, sc);
  readProbes(top, sc);
  return sc;
}

YAML::Node parse(const std::string& text, const std::string& display) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    std::string at = e.mark.is_null() ? "" : cat(":", e.mark.line + 1, ":", e.mark.column + 1);
    // yaml-cpp reports a tab in the indentation as a structural error: name the cause.
    std::string hint;
    if (!e.mark.is_null()) {
      std::istringstream in(text);
      std::string line;
      int i = 0;
      while (std::getline(in, line) && i < e.mark.line) ++i;
      if (i == e.mark.line && line.substr(0, line.find_first_not_of(" \t")).find('\t') != std::string::npos)
        hint = " (line " + std::to_string(e.mark.line + 1) + " is indented with a tab; YAML allows only spaces)";
    }
    throw SceneError(display + at + ": invalid YAML: " + e.msg + hint);
  }
}

} // namespace

Scene loadScene(const std::string& path, const LoadOptions& opts) {
  std::ifstream in(path);
  if (!in) throw SceneError("cannot open scene file '" + path + "'");
  std::stringstream text;
  text << in.rdbuf();
  return build(parse(text.str(), path), path, path, opts);
}

Scene loadSceneFromString(const std::string& yaml, const std::string& name, const LoadOptions& opts) {
  return build(parse(yaml, name), name, "", opts);
}

} // namespace voigt
