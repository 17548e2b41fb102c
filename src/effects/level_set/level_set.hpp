#pragma once
// The level_set effect: two phases separated by the zero level of psi (cell
// centres). psi > 0 is phase 1, the material named in `level_set.phase`;
// psi < 0 is the scene's `fluid` (NOTES.md erratum 4). One file per stage:
//   level_set.cpp  scene section, fields, initial shape + Fast Marching, summary
//   advect.cpp     Eq. (1) advection (Advection stage), Eq. (2)-(4) blending
//                  (Properties stage), volume and area diagnostics
#include "effects/effect.hpp"
#include "kernels/advection.hpp"
#include "levelset/fast_marching.hpp"
#include "levelset/params.hpp"
#include "levelset/shapes.hpp"

namespace voigt {

class LevelSet : public Effect {
 public:
  std::string name() const override { return "level_set"; }
  int setupOrder() const override { return 5; } // after navier_stokes (density exists), before reinit
  void configure(const Scene& s) override;
  void declareFields(FieldStore& f) const override;
  void setup(State& st) override;
  void registerTasks(Pipeline& p) override;
  void summary(const State& st, nlohmann::json& j) const override;
  void saveState(nlohmann::json& j) const override;
  void loadState(const nlohmann::json& j) override;
  void restored(State& st) override { refreshGhosts(st, st.fields.scalar("psi")); }

  // Stages (public so tests can drive them).
  void advect(State& st);
  void blend(State& st);
  void diagnose(State& st);

 private:
  void refreshGhosts(State& st, const Field& f) const;

  const Scene* scene_ = nullptr;
  LevelSetGeometry geo_;
  std::string phase_;
  double rho1_ = 1, mu1_ = 0, rho2_ = 1, mu2_ = 0;
  bool fastMarching_ = true;
  ShapeProgram shape_;
  Limiter limiter_ = Limiter::MinMod;
  FluxScratch flux_; // face fluxes of the transport (kernels/advection_faces.hpp)
  FastMarchingStats fm_;
  double volume0_ = 0, volume_ = 0, sharpVolume0_ = 0, sharpVolume_ = 0, area_ = 0, driftMax_ = 0;
};

} // namespace voigt
