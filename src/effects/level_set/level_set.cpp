// level_set: scene section, fields, the initial shape and its signed distance.
#include "effects/level_set/level_set.hpp"

#include <cmath>

#include "core/boundary.hpp"
#include "core/field_names.hpp"
#include "scene/reader.hpp"

namespace voigt {

std::unique_ptr<Effect> makeLevelSet() { return std::make_unique<LevelSet>(); }

// The phase and the band geometry, which navier_stokes, elasticity, reinit and
// solid_body read from Published.
void LevelSet::publish(const Scene& s, Published& pub) const {
  const Section ls = topSection(s, "level_set");
  if (!ls.has("phase")) ls.fail("phase", "is required: the material where psi > 0");
  pub.phase = ls.string("phase", "");
  if (!s.materials.count(pub.phase)) ls.fail("phase", "names no material in 'materials'");
  if (pub.phase == s.fluid) ls.fail("phase", "must differ from 'fluid' (" + s.fluid + "), the material where psi < 0");
  pub.levelSet = levelSetGeometry(s);
}

void LevelSet::configure(const Scene& s, const Published& pub) {
  scene_ = &s;
  geo_ = pub.levelSet;
  phase_ = pub.phase;
  const Section ls = topSection(s, "level_set");
  for (const char* k : {"smoothing", "band", "phase"}) ls.has(k); // validated in publish()
  rho1_ = s.materials.at(phase_).density;
  mu1_ = s.materials.at(phase_).viscosity;
  rho2_ = s.fluidMaterial().density;
  mu2_ = s.fluidMaterial().viscosity;
  shape_ = compileShape(ls, "shape", s);
  // Default: march unless the shape is already an exact distance.
  fastMarching_ = ls.boolean("fast_marching", !shape_.exactDistance);
  globalCorrection_ = ls.choice("volume_correction", "global", {"global", "none"}) == "global";
  // viscosity_blend: linear (the paper's Eq. 2) or harmonic, 1 / mu = H / mu1 + (1 - H) / mu2, the
  // series resistance of the two fluids to a shear across the zone (cases/rising_bubble/README.md).
  harmonicMu_ = ls.choice("viscosity_blend", "linear", {"linear", "harmonic"}) == "harmonic";
  if (harmonicMu_ && !(mu1_ > 0 && mu2_ > 0))
    ls.fail("viscosity_blend", "harmonic needs both phases' viscosity > 0");
  for (int f = 0; f < 6; ++f) open_[f] = s.bc[f].type == BcType::Inflow || s.bc[f].type == BcType::Outflow;
  ls.finish();
  limiter_ = limiterNamed(s.advection.limiter);
}

void LevelSet::declareFields(FieldStore& f) const {
  f.declare(field::psi, Centring::Cell, 1, name());
  f.declareDerived("psi_old", Centring::Cell, 1, name()); // the RK stage copy
}

void LevelSet::refreshGhosts(State& st, const Field& f) const {
  st.halo->exchange(f);
  fillCellGhostsEven(st.grid, f);
}

void LevelSet::setup(State& st) {
  Field psi = st.fields.scalar(field::psi);
  evaluateShape(st.grid, shape_, psi);
  if (fastMarching_) fm_ = fastMarching(st.grid, psi);
  refreshGhosts(st, psi);
  blend(st);
  diagnose(st);
  volume0_ = volume_;
  target_ = volume_;
  shiftTotal_ = movedTotal_ = 0;
  if (globalCorrection_) {
    st.diag["volume_shift_cells"] = 0;
    st.diag["volume_corrected"] = 0;
  }
  sharpVolume0_ = sharpVolume_;
  driftMax_ = 0;
  st.diag["volume_drift"] = 0;
}

void LevelSet::saveState(nlohmann::json& j) const {
  j = {{"volume0", volume0_}, {"volume", volume_}, {"sharp_volume0", sharpVolume0_}, {"sharp_volume", sharpVolume_},
       {"area", area_}, {"drift_max", driftMax_}, {"fm_initial_cells", fm_.initialCells},
       {"fm_accepted_cells", fm_.acceptedCells}, {"fm_seconds", fm_.seconds}, {"volume_target", target_},
       {"shift_total", shiftTotal_}, {"moved_total", movedTotal_}};
}

void LevelSet::loadState(const nlohmann::json& j) {
  volume0_ = j.at("volume0").get<double>();
  volume_ = j.at("volume").get<double>();
  sharpVolume0_ = j.at("sharp_volume0").get<double>();
  sharpVolume_ = j.at("sharp_volume").get<double>();
  area_ = j.at("area").get<double>();
  driftMax_ = j.at("drift_max").get<double>();
  target_ = j.value("volume_target", volume0_); // checkpoints from before the correction
  shiftTotal_ = j.value("shift_total", 0.0);
  movedTotal_ = j.value("moved_total", 0.0);
  fm_.initialCells = j.value("fm_initial_cells", fm_.initialCells);
  fm_.acceptedCells = j.value("fm_accepted_cells", fm_.acceptedCells);
  fm_.seconds = j.value("fm_seconds", fm_.seconds);
}

void LevelSet::registerTasks(Pipeline& p) {
  p.add(Stage::Properties, name(), "density and viscosity from H(psi), Eq. (2)-(4)", [this](State& st) { blend(st); });
  p.add(Stage::Advection, name(), "psi: SSP-RK2 + MUSCL/KT, Eq. (1)", [this](State& st) { advect(st); });
  if (globalCorrection_)
    p.add(Stage::Corrections, name(), "global volume correction: psi += s so that INT H(psi) = V0 - outflow",
          [this](State& st) { correctVolume(st); }, {"reinit"});
  p.add(Stage::Diagnostics, name(), "phase volumes, drift, interface area", [this](State& st) { diagnose(st); });
}

void LevelSet::summary(const State& st, nlohmann::json& j) const {
  double total = 1;
  VOIGT_UNROLL
  for (int d = 0; d < 3; ++d) total *= st.grid.hi[d] - st.grid.lo[d];
  j["volume_per_phase"] = {{phase_, volume_}, {scene_->fluid, total - volume_}};
  j["level_set"] = {{"phase", phase_},
                    {"smoothing_cells", geo_.kappaCells},
                    {"band_cells", geo_.bandCells},
                    {"shape", shape_.text},
                    {"volume_initial", volume0_},
                    {"volume", volume_},
                    {"volume_drift", volume0_ != 0 ? volume_ / volume0_ - 1 : volume_},
                    {"volume_drift_max_abs", driftMax_},
                    {"sharp_volume_initial", sharpVolume0_},
                    {"sharp_volume", sharpVolume_},
                    {"interface_area", area_},
                    {"volume_correction", globalCorrection_ ? "global" : "none"},
                    {"volume_target", target_},
                    {"shift_total", shiftTotal_},
                    {"volume_corrected", volume0_ != 0 ? movedTotal_ / volume0_ : 0.0},
                    {"viscosity_blend", harmonicMu_ ? "harmonic" : "linear"},
                    {"fast_marching",
                     {{"enabled", fastMarching_},
                      {"initial_cells", fm_.initialCells},
                      {"accepted_cells", fm_.acceptedCells},
                      {"seconds", fm_.seconds}}}};
}

} // namespace voigt
