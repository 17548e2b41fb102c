// Momentum predictor, Eq. (7):
//   du/dt = R(u) = -[div(u u) - u div_h u] + (1/rho) div(tau) + f/rho - (1/rho) G p^n
// integrated with SSP-RK2 (Heun):
//   u1 = u^n + dt R(u^n);   u* = (u^n + u1 + dt R(u1)) / 2
// Where the density varies (two phases) the advection is conservative: the node
// density r (r0 = rho^n) and m = r u advance together with one flux
// (kernels/advection.hpp), the other terms as forces r0 R_f:
//   r1 = r0 + dt Rr(r0, u^n),          u1 = r0 (u^n + dt R(u^n)) / r1
//   r* = (r0 + r1 + dt Rr(r1, u1))/2,  u* = (r0 u^n + r1 u1 + dt r0 R(u1)) / (2 r*)
// with R's advective part the momentum rate per r0.
// then prescribed components are re-imposed (oscillating walls: their values at
// t^{n+1}). tau comes from the Stress stage (viscous here; elasticity blends its
// own in, Eq. 9), f from the Forces stage.
// navier_stokes.viscous: semi_implicit makes each of the two Euler stages implicit-explicit
// in a scalar viscous operator K (kernels/viscous_implicit.hpp): stage 1 u1 += d1 with
// (M - dt K) d1 = dt K (u1 - u^n); stage 2 u* += d2 with (M - dt K) d2 = dt K (u* - (u^n + u1)/2).
#include <algorithm>

#include "core/boundary.hpp"
#include "core/field_names.hpp"
#include "effects/navier_stokes/navier_stokes.hpp"
#include "effects/navier_stokes/viscous_implicit.hpp"
#include "kernels/momentum.hpp"
#include "kernels/viscous_implicit.hpp"

namespace voigt {

namespace {
// u is the state's velocity (updated in place by the stages).
void refreshGhosts(State& st, const VecField& u) {
  exchangeVelocity(st);
  fillVelocityGhosts(st.grid, *st.scene, u);
}

// Semi-implicit viscosity (header): the stage increments and their corrections.
void implicitStage1(State& st, ImplicitViscosity& iv, const VecField& u, const VecField& u0, const VecField& q) {
  viscous::stageIncrement(u, u0, q, nodeRange(st.grid));
  iv.correct(st, q, u);
}
void keepStage(const VecField& u, const VecField& q) { // q = u1 for stage 2
  for (int d = 0; d < 3; ++d) Kokkos::deep_copy(q.c[d], u.c[d]);
}
void implicitStage2(State& st, ImplicitViscosity& iv, const VecField& u, const VecField& u0, const VecField& q) {
  viscous::secondStageIncrement(u, u0, q, nodeRange(st.grid));
  iv.correct(st, q, u);
}
} // namespace

void NavierStokes::evaluateRhs(State& st, Pipeline& p, const VecField& u, const VecField& rhs, const Field* rho) {
  const Grid& g = st.grid;
  const Range3 nodes = nodeRange(g);
  refreshGhosts(st, u);
  // The advection assigns rhs (no zeroing pass); the Stress stage writes tau only.
  if (rho)
    addMomentumAdvectionFaces(g, *rho, u, st.fields.scalar("momentum_density"),
                              st.fields.scalar("momentum_density_rhs"), rhs, nodes, limiter_, flux_, true);
  else
    addVelocityAdvectionFaces(g, u, rhs, nodes, limiter_, flux_, true);
  st.evalU = u;
  st.evalRhs = rhs;
  p.run(Stage::Stress, st);
  VecField coef = st.fields.vector("proj_coef");
  addStressMinusGradient(g, stressField(st.fields), st.fields.scalar(field::pressure), coef, 1.0, rhs, nodes);
  p.run(Stage::Forces, st);
}

// r0: the node density rho^n (mean of the cells around a node, as the
// projection's 1/rho), ghosts included for the MUSCL stencil.
void NavierStokes::nodeDensity(State& st) {
  const Grid& g = st.grid;
  Field rho = st.fields.scalar(field::density), r0 = st.fields.scalar("momentum_density");
  voigt::nodeDensity(g, rho, r0, nodeRange(g));
  exchangeWithVelocity(st, r0); // one message when the predictor's exchange of u is due too
  fillNodeGhostsEven(g, r0);
}

// Initial pressure: the pressure that makes the initial acceleration R(u^0)
// discretely divergence-free, D B G p0 = D R(u^0) (incflo's initial
// iterations). Without it the first RK stage sees p = 0, and near walls its
// viscous term leaves a non-gradient residue (7.8e-8 in hydrostatic rest).
void NavierStokes::initialPressure(State& st, Pipeline& p) {
  const Grid& g = st.grid;
  VecField u = st.fields.vector(field::velocity), acc = st.fields.vector("acceleration");
  IntField mask = st.fields.integer(field::fixMask);
  Field pr = st.fields.scalar(field::pressure), dp = st.fields.scalar("pressure_increment");
  Field rhs = st.fields.scalar("poisson_rhs"), div = st.fields.scalar("divergence");
  // Declared only with the conservative form.
  const Field r0 = conservative_ ? st.fields.scalar("momentum_density") : Field();
  const Field rr = conservative_ ? st.fields.scalar("momentum_density_rhs") : Field();
  if (conservative_) { // du/dt = (dm/dt - u dr/dt) / r0, r0 = rho^0 (Properties stage)
    evaluateRhs(st, p, u, acc, &r0);
  } else {
    evaluateRhs(st, p, u, acc);
  }
  initialVelocityRate(acc, u, rr, r0, conservative_, mask, nodeRange(g)); // and 0 where prescribed
  st.halo->exchange(acc);
  const Range3 cells = cellRange(g);
  divergence(g, acc, div, cells);
  poissonRhs(div, rhs, 1.0, cells); // -div
  Kokkos::deep_copy(dp, 0.0);
  const PoissonStats s = solver_->solve(rhs, dp, scene_->projection.volumeTolerance / (st.dt * st.dt));
  addTo(dp, pr, cells);
  Kokkos::deep_copy(dp, 0.0);
  st.halo->exchange(pr);
  if (split_) solver_->setCoefficients(st.fields.vector("proj_coef0")); // the steps solve with B0
  st.counters["initial_pressure_iterations"] = s.iterations;
}

void NavierStokes::momentum(State& st, Pipeline& p) {
  if (st.propertiesChanged) refreshCoefficients(st);
  if (!initialPressureDone_) {
    initialPressure(st, p);
    initialPressureDone_ = true;
  }
  const Grid& g = st.grid;
  const Range3 nodes = nodeRange(g);
  VecField u = st.fields.vector(field::velocity), u0 = st.fields.vector("velocity_old");
  VecField rhs = st.fields.vector("acceleration");
  IntField mask = st.fields.integer(field::fixMask);
  VecField val = st.fields.vector(field::fixValue);
  const double dt = st.dt;
  // Oscillating walls: prescribed values at t^{n+1}. Heun's stages sit at t^n
  // and t^{n+1}: u^n already holds the wall value at t^n, and both the stage-1
  // result u1 (the predictor at t^{n+1}, which stage 2 evaluates) and u* get
  // the value at t^{n+1}. Obstacles touching a wall keep their own velocity.
  if (hasOscillatingWalls(*scene_)) {
    refreshWallValues(g, *scene_, mask, val, st.t + dt);
    if (std::find(scene_->effects.begin(), scene_->effects.end(), "obstacles") != scene_->effects.end())
      addObstacleMask(g, scene_->obstacles, mask, val);
  }

  // Each stage update stores u^n (stage 1) and re-imposes the prescribed components
  // in its own pass (kernels/momentum.hpp).
  const VecField q = semiImplicit_ ? ImplicitViscosity::increment(st) : VecField();
  if (semiImplicit_) implicit_.prepare(st);
  if (!conservative_) {
    evaluateRhs(st, p, u, rhs);
    momentumStage1(u, u0, rhs, dt, mask, val, nodes);
    if (semiImplicit_) implicitStage1(st, implicit_, u, u0, q);
    st.velocityHalosCurrent = false;
    if (semiImplicit_) keepStage(u, q);
    evaluateRhs(st, p, u, rhs);
    momentumStage2(u, u0, rhs, dt, mask, val, nodes);
    if (semiImplicit_) implicitStage2(st, implicit_, u, u0, q);
    st.velocityHalosCurrent = false;
    return;
  }
  // Conservative form (header); r0 = rho^n from the Properties stage.
  Field r0 = st.fields.scalar("momentum_density"), r1 = st.fields.scalar("momentum_density_stage");
  Field rr = st.fields.scalar("momentum_density_rhs");
  evaluateRhs(st, p, u, rhs, &r0);
  momentumStage1Conservative(r0, rr, r1, u, u0, rhs, dt, mask, val, nodes);
  if (semiImplicit_) implicitStage1(st, implicit_, u, u0, q);
  st.velocityHalosCurrent = false;
  if (semiImplicit_) keepStage(u, q);
  exchangeWithVelocity(st, r1); // r1 and u1 in one message (refreshGhosts then skips u's)
  fillNodeGhostsEven(g, r1);
  evaluateRhs(st, p, u, rhs, &r1);
  momentumStage2Conservative(r0, r1, rr, u, u0, rhs, dt, mask, val, nodes);
  if (semiImplicit_) implicitStage2(st, implicit_, u, u0, q);
  st.velocityHalosCurrent = false;
}

} // namespace voigt
