#pragma once
// The navier_stokes effect: incompressible momentum on the semi-staggered grid,
// Eq. (5)/(7)-(8). One file per stage: setup.cpp (fields, initial state),
// momentum.cpp (predictor), projection.cpp (pressure correction).
#include <memory>

#include "effects/effect.hpp"
#include "effects/navier_stokes/viscous_implicit.hpp"
#include "kernels/advection.hpp"
#include "kernels/advection_faces.hpp"
#include "kernels/stress.hpp"
#include "solvers/poisson.hpp"

namespace voigt {

class NavierStokes : public Effect {
 public:
  std::string name() const override { return "navier_stokes"; }
  std::vector<std::string> setupAfter() const override { return {}; } // first: the masks others extend
  void configure(const Scene& s, const Published& pub) override;
  void declareFields(FieldStore& f) const override;
  void setup(State& st) override;
  void registerTasks(Pipeline& p) override;
  DtLimit dtLimit(const State& st) const override;
  void summary(const State& st, nlohmann::json& j) const override;
  void saveState(nlohmann::json& j) const override {
    j["initial_pressure_done"] = initialPressureDone_;
    j["pressure_reference"] = pRef_;
    j["pressure_rate_history"] = rateHistory_;
  }
  void loadState(const nlohmann::json& j) override {
    initialPressureDone_ = j.value("initial_pressure_done", initialPressureDone_);
    pRef_ = j.value("pressure_reference", pRef_);
    rateHistory_ = j.value("pressure_rate_history", 0); // absent: a checkpoint from before the rates
  }
  void restored(State& st) override;

  // Stages (public so tests can drive them one at a time).
  void momentum(State& st, Pipeline& p);
  void project(State& st);
  void reportCap(State& st, const PoissonStats& s);
  void refreshCoefficients(State& st);

 private:
  // rho: the node density the momentum advection transports (conservative form).
  void evaluateRhs(State& st, Pipeline& p, const VecField& u, const VecField& rhs, const Field* rho = nullptr);
  void nodeDensity(State& st);
  void initialVelocity(State& st);
  void initialPressure(State& st, Pipeline& p);

  const Scene* scene_ = nullptr;
  Limiter limiter_ = Limiter::MinMod;
  bool conservative_ = false; // momentum advection in conservative form
  bool semiImplicit_ = false; // navier_stokes.viscous: semi_implicit
  ImplicitViscosity implicit_;
  std::unique_ptr<PoissonSolver> solver_;
  FluxScratch flux_; // face fluxes of the momentum advection
  Pipeline* pipeline_ = nullptr;
  double pRef_ = 0; // outflow pressure: stored p is relative to it
  bool initialPressureDone_ = false;
  int rateHistory_ = 0; // pressure rates stored (0-2), for initial_guess: extrapolate
  // projection.variable_density: split (projection.cpp): B0 = 1/rho_min of the materials, and
  // its gravity-wave dt limit over sqrt(h) (0: none); both from the scene (configure).
  bool split_ = false;
  double b0_ = 0, splitWaveTime_ = 0;
  void splitPredictor(State& st, const Field& rate, const Field& dp);
};

SymTensorField stressField(const FieldStore& f);
std::string solverSummary(const ProjectionCfg& P);
// The scene's projection section as the solver layer's settings (src/solvers/solver_settings.hpp).
PoissonSettings poissonSettings(const ProjectionCfg& P);

} // namespace voigt
