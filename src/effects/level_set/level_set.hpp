#pragma once
// The level_set effect: two phases separated by the zero level of psi (cell
// centres). psi > 0 is phase 1, the material named in `level_set.phase`;
// psi < 0 is the scene's `fluid` (NOTES.md erratum 4). One file per stage:
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
  void restored(State& st) override { refreshGhosts(st, st.fields.scalar(field::psi)); }

  // Stages (public so tests can drive them).
  void advect(State& st);
  void blend(State& st);
  void diagnose(State& st);
  void correctVolume(State& st);

 private:
  void refreshGhosts(State& st, const Field& f) const;

  const Scene* scene_ = nullptr;
  LevelSetGeometry geo_;
  std::string phase_;
  double rho1_ = 1, mu1_ = 0, rho2_ = 1, mu2_ = 0;
  bool harmonicMu_ = false; // level_set.viscosity_blend: harmonic
  bool fastMarching_ = true;
  ShapeProgram shape_;
  Limiter limiter_ = Limiter::MinMod;
  FluxScratch flux_; // face fluxes of the transport (kernels/advection_faces.hpp)
  FastMarchingStats fm_;
  bool globalCorrection_ = true; // level_set.volume_correction: global (default) or none
  bool open_[6] = {};            // faces through which phase 1 may leave (inflow/outflow)
  double target_ = 0;            // volume the correction holds: V0 minus what left through open faces
  double shiftTotal_ = 0;        // sum of |shift| over the run (length)
  double movedTotal_ = 0;        // sum of |shift| x INT H' over the run (volume)
  double volume0_ = 0, volume_ = 0, sharpVolume0_ = 0, sharpVolume_ = 0, area_ = 0, driftMax_ = 0;
};

} // namespace voigt
