// level_set: scene section(s), fields, the initial shapes and their signed distances.
#include "effects/level_set/level_set.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "core/boundary.hpp"
#include "core/field_names.hpp"
#include "effects/level_set/surface_velocity.hpp"
#include "kernels/multiphase.hpp"
#include "scene/reader.hpp"

namespace voigt {

std::unique_ptr<Effect> makeLevelSet() { return std::make_unique<LevelSet>(); }

namespace {
bool given(const Scene& s, const char* key) { return s.root[key].IsDefined() && !s.root[key].IsNull(); }

// The maps that define level sets: `level_set:` (one, unnamed) or the `level_sets:` list.
std::vector<Section> levelSetSections(const Scene& s) {
  const Section top(s.root, "", s.source);
  const bool one = given(s, "level_set"), many = given(s, "level_sets");
  if (one && many) top.fail("level_sets", "and 'level_set' both given: use one (level_set: one unnamed level set)");
  if (!many) return {topSection(s, "level_set")};
  std::vector<Section> out = top.list("level_sets");
  if (out.empty()) top.fail("level_sets", "must list at least one level set");
  return out;
}

LevelSetInfo readInfo(const Scene& s, const Section& ls, bool named) {
  LevelSetInfo info;
  if (named) {
    if (!ls.has("name")) ls.fail("name", "is required: each entry of 'level_sets' is named");
    info.name = ls.string("name", "");
    const bool ok = !info.name.empty() && std::all_of(info.name.begin(), info.name.end(), [](char c) {
      return std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_';
    });
    if (!ok) ls.fail("name", "must be lower-case letters, digits and '_' (it names the field psi_" + info.name + ")");
    info.field = std::string(field::psi) + "_" + info.name;
  } else {
    info.field = field::psi;
  }
  if (!ls.has("phase")) ls.fail("phase", "is required: the material where psi > 0");
  info.phase = ls.string("phase", "");
  if (!s.materials.count(info.phase)) ls.fail("phase", "names no material in 'materials'");
  if (info.phase == s.fluid)
    ls.fail("phase", "must differ from 'fluid' (" + s.fluid + "), the material where no level set is positive");
  info.solid = s.materials.at(info.phase).shearModulus > 0;
  info.geometry = levelSetGeometry(ls);
  return info;
}
} // namespace

// The phases and band geometries, which navier_stokes, elasticity, reinit, surface_tension
// and solid_body read from Published.
void LevelSet::publish(const Scene& s, Published& pub) const {
  const bool named = given(s, "level_sets");
  const std::vector<Section> secs = levelSetSections(s);
  for (const Section& ls : secs) {
    LevelSetInfo info = readInfo(s, ls, named);
    for (const LevelSetInfo& o : pub.levelSets)
      if (o.name == info.name) ls.fail("name", "'" + info.name + "' is used twice in 'level_sets'");
    pub.levelSets.push_back(info);
  }
  // Fluids before solids: the blend lays later level sets over earlier ones, and a fluid's psi
  // under a body is its extension (kernels/multiphase.hpp), which must not cover the body.
  bool solidSeen = false;
  for (size_t i = 0; i < secs.size(); ++i) {
    const bool solid = pub.levelSets[i].solid;
    if (!solid && solidSeen)
      secs[i].fail("phase", "is a fluid listed after a solid: list the fluids' level sets first (later ones are laid over earlier ones)");
    solidSeen |= solid;
  }
}

void LevelSet::configure(const Scene& s, const Published& pub) {
  scene_ = &s;
  rhoF_ = s.fluidMaterial().density;
  muF_ = s.fluidMaterial().viscosity;
  const std::vector<Section> secs = levelSetSections(s);
  ls_.clear();
  for (size_t i = 0; i < secs.size(); ++i) {
    const Section& ls = secs[i];
    LevelSetInstance l;
    l.info = pub.levelSets[i];
    for (const char* k : {"smoothing", "band", "phase"}) ls.has(k); // validated in publish()
    if (!l.info.name.empty()) ls.has("name");                        // only level_sets entries have one
    l.rho = s.materials.at(l.info.phase).density;
    l.mu = s.materials.at(l.info.phase).viscosity;
    l.shape = compileShape(ls, "shape", s);
    // Default: march unless the shape is already an exact distance.
    l.fastMarching = ls.boolean("fast_marching", !l.shape.exactDistance);
    l.globalCorrection = ls.choice("volume_correction", "global", {"global", "none"}) == "global";
    // velocity: a body's initial velocity, laid over the scene's initial field (multiphase.hpp).
    l.moving = ls.has("velocity");
    if (l.moving && std::find(s.effects.begin(), s.effects.end(), "navier_stokes") == s.effects.end())
      ls.fail("velocity", "needs navier_stokes (the initial velocity of a body in the flow)");
    const auto v = ls.vec3("velocity", {0, 0, 0});
    for (int d = 0; d < 3; ++d) l.velocity[d] = v[d];
    // viscosity_blend: linear (the paper's Eq. 2) or harmonic, 1 / mu = H / mu1 + (1 - H) / mu2, the
    // series resistance of the two fluids to a shear across the zone (cases/rising_bubble/README.md).
    l.harmonicMu = ls.choice("viscosity_blend", "linear", {"linear", "harmonic"}) == "harmonic";
    if (l.harmonicMu && !(l.mu > 0 && muF_ > 0)) ls.fail("viscosity_blend", "harmonic needs both phases' viscosity > 0");
    // surface_velocity (kernels/surface_velocity.hpp): a solid body's surface moves with the solid.
    const bool flowing = std::find(s.effects.begin(), s.effects.end(), "navier_stokes") != s.effects.end();
    l.surfaceSolid = ls.choice("surface_velocity", l.info.solid && flowing ? "solid" : "flow", {"solid", "flow"}) == "solid";
    if (l.surfaceSolid && !l.info.solid)
      ls.fail("surface_velocity", "solid needs a solid phase (a material with a shear modulus); '" + l.info.phase + "' is a fluid");
    if (l.surfaceSolid && !flowing) ls.fail("surface_velocity", "solid needs navier_stokes (a computed flow)");
    ls.finish();
    ls_.push_back(std::move(l));
  }
  hides_ = false;
  for (size_t i = 0; i + 1 < ls_.size(); ++i) hides_ |= !ls_[i].info.solid && ls_.back().info.solid;
  for (int f = 0; f < 6; ++f) open_[f] = s.bc[f].type == BcType::Inflow || s.bc[f].type == BcType::Outflow;
  limiter_ = limiterNamed(s.advection.limiter);
}

void LevelSet::declareFields(FieldStore& f) const {
  for (const auto& l : ls_) f.declare(l.info.field, Centring::Cell, 1, name());
  f.declareDerived("psi_old", Centring::Cell, 1, name()); // the RK stage copy, shared
  if (!single()) f.declareDerived("level_set_cover", Centring::Cell, 1, name());
  if (hides_)
    for (const char* n : {"level_set_known", "level_set_known_tmp"}) f.declareDerived(n, Centring::Cell, 1, name());
  if (std::any_of(ls_.begin(), ls_.end(), [](const LevelSetInstance& l) { return l.surfaceSolid; }))
    declareSurfaceVelocity(f, name());
}

void LevelSet::refreshGhosts(State& st, const Field& f) const {
  st.halo->exchange(f);
  fillCellGhostsEven(st.grid, f);
}

void LevelSet::setup(State& st) {
  for (auto& l : ls_) {
    Field psi = st.fields.scalar(l.info.field);
    evaluateShape(st.grid, l.shape, psi);
    if (l.fastMarching) l.fm = fastMarching(st.grid, psi);
    refreshGhosts(st, psi);
  }
  updateBoxes(st, true);
  hideUnderSolids(st);
  const Grid& g = st.grid;
  if (st.fields.allocated("surface_velocity")) layer_ = IntList("surface_velocity_layer", size_t(g.ext[0]) * g.ext[1] * g.ext[2]);
  for (auto& l : ls_)
    if (l.moving) {
      multiphase::setBodyVelocity(st.fields.scalar(l.info.field), l.info.geometry.kappa(st.grid), l.velocity[0],
                                  l.velocity[1], l.velocity[2], st.fields.vector(field::velocity), nodeRange(st.grid));
      st.velocityHalosCurrent = false; // written here
      exchangeVelocity(st);
    }
  blend(st);
  diagnose(st);
  for (auto& l : ls_) {
    l.volume0 = l.target = l.volume;
    l.shiftTotal = l.movedTotal = 0;
    if (l.globalCorrection) {
      st.diag["volume_shift_cells" + l.suffix()] = 0;
      st.diag["volume_corrected" + l.suffix()] = 0;
    }
    l.sharpVolume0 = l.sharpVolume;
    l.driftMax = 0;
    st.diag["volume_drift" + l.suffix()] = 0;
  }
}

nlohmann::json LevelSetInstance::state() const {
  return {{"volume0", volume0},         {"volume", volume},
          {"sharp_volume0", sharpVolume0}, {"sharp_volume", sharpVolume},
          {"area", area},               {"drift_max", driftMax},
          {"fm_initial_cells", fm.initialCells}, {"fm_accepted_cells", fm.acceptedCells},
          {"fm_seconds", fm.seconds},   {"volume_target", target},
          {"shift_total", shiftTotal},  {"moved_total", movedTotal}};
}

void LevelSetInstance::loadState(const nlohmann::json& j) {
  volume0 = j.at("volume0").get<double>();
  volume = j.at("volume").get<double>();
  sharpVolume0 = j.at("sharp_volume0").get<double>();
  sharpVolume = j.at("sharp_volume").get<double>();
  area = j.at("area").get<double>();
  driftMax = j.at("drift_max").get<double>();
  target = j.value("volume_target", volume0); // checkpoints from before the correction
  shiftTotal = j.value("shift_total", 0.0);
  movedTotal = j.value("moved_total", 0.0);
  fm.initialCells = j.value("fm_initial_cells", fm.initialCells);
  fm.acceptedCells = j.value("fm_accepted_cells", fm.acceptedCells);
  fm.seconds = j.value("fm_seconds", fm.seconds);
}

// One level set: its object as before; several: an object per name.
void LevelSet::saveState(nlohmann::json& j) const {
  if (single()) {
    j = ls_[0].state();
    return;
  }
  j = nlohmann::json::object();
  for (const auto& l : ls_) j[l.info.name] = l.state();
}

void LevelSet::loadState(const nlohmann::json& j) {
  if (single()) return ls_[0].loadState(j);
  for (auto& l : ls_) l.loadState(j.at(l.info.name));
}

void LevelSet::registerTasks(Pipeline& p) {
  p.add(Stage::Properties, name(), "density and viscosity from H(psi), Eq. (2)-(4)", [this](State& st) { blend(st); });
  const bool surface = std::any_of(ls_.begin(), ls_.end(), [](const LevelSetInstance& l) { return l.surfaceSolid; });
  p.add(Stage::Advection, name(),
        surface ? "psi: SSP-RK2 + MUSCL/KT, Eq. (1); a solid's surface with the solid's velocity (surface_velocity: solid)"
                : "psi: SSP-RK2 + MUSCL/KT, Eq. (1)",
        [this](State& st) { advect(st); });
  if (hides_)
    p.add(Stage::Corrections, name(), "fluids' psi extended under solid bodies (kernels/multiphase.hpp)",
          [this](State& st) { hideUnderSolids(st); }, {"reinit"});
  if (std::any_of(ls_.begin(), ls_.end(), [](const LevelSetInstance& l) { return l.globalCorrection; }))
    p.add(Stage::Corrections, name(), "global volume correction: psi += s so that INT H(psi) = V0 - outflow",
          [this](State& st) { correctVolume(st); }, {"reinit"});
  p.add(Stage::Diagnostics, name(), "phase volumes, drift, interface area and rms curvature", [this](State& st) { diagnose(st); });
}

void LevelSet::summary(const State& st, nlohmann::json& j) const {
  double total = 1;
  VOIGT_UNROLL
  for (int d = 0; d < 3; ++d) total *= st.grid.hi[d] - st.grid.lo[d];
  nlohmann::json perPhase = nlohmann::json::object(), each = nlohmann::json::object();
  double fluid = total;
  for (const auto& l : ls_) {
    perPhase[l.info.phase] = perPhase.value(l.info.phase, 0.0) + l.volume;
    fluid -= l.volume;
    each[l.info.name] = {{"phase", l.info.phase},
                         {"smoothing_cells", l.info.geometry.kappaCells},
                         {"band_cells", l.info.geometry.bandCells},
                         {"shape", l.shape.text},
                         {"volume_initial", l.volume0},
                         {"volume", l.volume},
                         {"volume_drift", l.volume0 != 0 ? l.volume / l.volume0 - 1 : l.volume},
                         {"volume_drift_max_abs", l.driftMax},
                         {"sharp_volume_initial", l.sharpVolume0},
                         {"sharp_volume", l.sharpVolume},
                         {"interface_area", l.area},
                         {"volume_correction", l.globalCorrection ? "global" : "none"},
                         {"volume_target", l.target},
                         {"shift_total", l.shiftTotal},
                         {"volume_corrected", l.volume0 != 0 ? l.movedTotal / l.volume0 : 0.0},
                         {"viscosity_blend", l.harmonicMu ? "harmonic" : "linear"},
                         {"surface_velocity", l.surfaceSolid ? "solid" : "flow"},
                         {"fast_marching",
                          {{"enabled", l.fastMarching},
                           {"initial_cells", l.fm.initialCells},
                           {"accepted_cells", l.fm.acceptedCells},
                           {"seconds", l.fm.seconds}}}};
  }
  perPhase[scene_->fluid] = fluid; // overlaps of level sets counted twice: see level_sets_overlap
  j["volume_per_phase"] = perPhase;
  if (single()) {
    j["level_set"] = each[""];
  } else {
    j["level_sets"] = each;
  }
}

} // namespace voigt
