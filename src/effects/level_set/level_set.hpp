#pragma once
// The level_set effect: phases separated by the zero levels of level sets (cell
// centres). With `level_set:` one level set, psi: psi > 0 is phase 1, the material named
// in `level_set.phase`; psi < 0 is the scene's `fluid` (NOTES.md erratum 4). With
// `level_sets:` each named entry NAME carries its own field psi_NAME and phase; where no
// level set is positive the material is the scene's `fluid`, and where they overlap the
// later entry wins (the blending's priority order, advect.cpp). One file per stage:
//   level_set.cpp  scene section, fields, initial shape + Fast Marching, summary
//   advect.cpp     Eq. (1) advection (Advection stage), Eq. (2)-(4) blending
//                  (Properties stage), volume and area diagnostics
//   volume.cpp     global volume correction (Corrections stage, after reinit)
#include "core/field_names.hpp"
#include "effects/effect.hpp"
#include "effects/level_set/geometry.hpp"
#include "effects/level_set/shape_compiler.hpp"
#include "kernels/advection.hpp"
#include "levelset/fast_marching.hpp"

namespace voigt {

// One level set and its bookkeeping.
struct LevelSetInstance {
  LevelSetInfo info; // name, field, phase, geometry (Published)
  double rho = 1, mu = 0;
  bool harmonicMu = false;       // viscosity_blend: harmonic
  bool fastMarching = true;
  bool solid = false;
  // surface_velocity: solid (a solid phase's default with navier_stokes): psi moves with the
  // solid's velocity extended across the smoothing zone's fluid half (kernels/surface_velocity.hpp);
  // flow: with the grid's velocity, Eq. (1) as printed.
  bool surfaceSolid = false;
  // Several level sets: the global cells (indices [b, e)) where psi > -reach, reach = band + 1
  // cells (the re-initialisation's band and its far bound's neighbours; the elastic stress band,
  // kappa + 3 cells by default, lies within); every kernel of this level set runs on this box
  // grown by 2 cells (State::activeBoxes: a step moves psi by less than a cell), and outside it
  // psi stays <= -reach, as it was (a far field).
  Range3 global{{0, 0, 0}, {0, 0, 0}};
  bool moving = false;           // level_sets[i].velocity given: the body's initial velocity
  double velocity[3] = {0, 0, 0};            // its phase has a shear modulus: fluids' level sets are extended under it
  bool globalCorrection = true;  // volume_correction: global (default) or none
  ShapeProgram shape;
  FastMarchingStats fm;
  double target = 0;             // volume the correction holds: V0 minus what left through open faces
  double shiftTotal = 0;         // sum of |shift| over the run (length)
  double movedTotal = 0;         // sum of |shift| x INT H' over the run (volume)
  double volume0 = 0, volume = 0, sharpVolume0 = 0, sharpVolume = 0, area = 0, driftMax = 0;
  // Time-series column suffix: "" for the single `level_set:`, "_NAME" for named ones.
  std::string suffix() const { return info.name.empty() ? "" : "_" + info.name; }
  nlohmann::json state() const;
  void loadState(const nlohmann::json& j);
};

class LevelSet : public Effect {
 public:
  std::string name() const override { return "level_set"; }
  // The density exists (navier_stokes) or the flow is given; reinit comes after.
  std::vector<std::string> setupAfter() const override { return {"navier_stokes", "prescribed_flow"}; }
  void publish(const Scene& s, Published& pub) const override;
  void configure(const Scene& s, const Published& pub) override;
  void declareFields(FieldStore& f) const override;
  void setup(State& st) override;
  void registerTasks(Pipeline& p) override;
  void summary(const State& st, nlohmann::json& j) const override;
  void saveState(nlohmann::json& j) const override;
  void loadState(const nlohmann::json& j) override;
  void restored(State& st) override {
    for (auto& l : ls_) refreshGhosts(st, st.fields.scalar(l.info.field));
    updateBoxes(st, true);
  }

  // Stages (public so tests can drive them).
  void advect(State& st);
  void blend(State& st);
  void diagnose(State& st);
  void correctVolume(State& st);

 private:
  void refreshGhosts(State& st, const Field& f) const;
  // The velocity l's surface moves with (surface_velocity: solid), in "surface_velocity".
  VecField surfaceVelocity(State& st, const LevelSetInstance& l);
  bool single() const { return ls_.size() == 1 && ls_[0].info.name.empty(); }
  void correctVolume(State& st, size_t i);
  // Several level sets: each fluid's psi extended under every solid body (kernels/multiphase.hpp),
  // and the part of a fluid's volume the later level sets leave uncovered.
  void hideUnderSolids(State& st);
  // The boxes (several level sets): from the previous box grown by 2 cells (a step moves psi by
  // less than a cell), or over all cells (setup, restart); published in State::activeBoxes.
  void updateBoxes(State& st, bool everywhere);
  const Range3* box(const State& st, const LevelSetInstance& l) const { return st.activeBox(l.info.field); }
  bool covered(size_t i) const { return !single() && !ls_[i].info.solid && i + 1 < ls_.size(); }
  Field cover(State& st, size_t i) const; // PROD_{j>i} (1 - H_j) in "level_set_cover"
  bool hides_ = false; // some fluid level set lies under a solid one

  const Scene* scene_ = nullptr;
  std::vector<LevelSetInstance> ls_;
  double rhoF_ = 1, muF_ = 0; // the scene's fluid, where no level set is positive
  Limiter limiter_ = Limiter::MinMod;
  IntList layer_;     // surface_velocity: the nodes of the zone's fluid half
  FluxScratch flux_; // face fluxes of the transport (kernels/advection_faces.hpp), shared
  bool open_[6] = {}; // faces through which a phase may leave (inflow/outflow)
};

} // namespace voigt
