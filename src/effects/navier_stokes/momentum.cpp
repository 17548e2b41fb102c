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
#include <algorithm>

#include "core/boundary.hpp"
#include "effects/navier_stokes/navier_stokes.hpp"

namespace voigt {

namespace {
void refreshGhosts(State& st, const VecField& u) {
  st.halo->exchange(u);
  fillVelocityGhosts(st.grid, *st.scene, u);
}
} // namespace

void NavierStokes::evaluateRhs(State& st, Pipeline& p, const VecField& u, const VecField& rhs, const Field* rho) {
  const Grid& g = st.grid;
  const Range3 nodes = nodeRange(g);
  refreshGhosts(st, u);
  VOIGT_UNROLL
  for (int c = 0; c < 3; ++c) Kokkos::deep_copy(rhs.c[c], 0.0);
  if (rho)
    addMomentumAdvectionFaces(g, *rho, u, st.fields.scalar("momentum_density"),
                              st.fields.scalar("momentum_density_rhs"), rhs, nodes, limiter_, flux_);
  else
    addVelocityAdvectionFaces(g, u, rhs, nodes, limiter_, flux_);
  st.evalU = u;
  st.evalRhs = rhs;
  p.run(Stage::Stress, st);
  VecField coef = st.fields.vector("proj_coef");
  addStressDivergence(g, stressField(st.fields), coef, rhs, nodes);
  subtractGradient(g, st.fields.scalar("pressure"), coef, 1.0, rhs, nodes);
  p.run(Stage::Forces, st);
}

// r0: the node density rho^n (mean of the cells around a node, as the
// projection's 1/rho), ghosts included for the MUSCL stencil.
void NavierStokes::nodeDensity(State& st) {
  const Grid& g = st.grid;
  GridGeom G(g);
  Field rho = st.fields.scalar("density"), r0 = st.fields.scalar("momentum_density");
  for_each3("node_density", nodeRange(g), KOKKOS_LAMBDA(int i, int j, int k) { r0(i, j, k) = G.nodeMean(rho, i, j, k); });
  st.halo->exchange(r0);
  fillNodeGhostsEven(g, r0);
}

// Initial pressure: the pressure that makes the initial acceleration R(u^0)
// discretely divergence-free, D B G p0 = D R(u^0) (incflo's initial
// iterations). Without it the first RK stage sees p = 0, and near walls its
// viscous term leaves a non-gradient residue (7.8e-8 in hydrostatic rest).
void NavierStokes::initialPressure(State& st, Pipeline& p) {
  const Grid& g = st.grid;
  VecField u = st.fields.vector("velocity"), acc = st.fields.vector("acceleration");
  IntField mask = st.fields.integer("fix_mask");
  Field pr = st.fields.scalar("pressure"), dp = st.fields.scalar("pressure_increment");
  Field rhs = st.fields.scalar("poisson_rhs"), div = st.fields.scalar("divergence");
  if (conservative_) { // du/dt = (dm/dt - u dr/dt) / r0
    nodeDensity(st);
    Field r0 = st.fields.scalar("momentum_density"), rr = st.fields.scalar("momentum_density_rhs");
    evaluateRhs(st, p, u, acc, &r0);
    for_each3("velocity_rate", nodeRange(g), KOKKOS_LAMBDA(int i, int j, int k) {
          VOIGT_UNROLL
          for (int d = 0; d < 3; ++d) acc.c[d](i, j, k) -= u.c[d](i, j, k) * rr(i, j, k) / r0(i, j, k);
        });
  } else {
    evaluateRhs(st, p, u, acc);
  }
  for_each3("fixed_no_acceleration", nodeRange(g), KOKKOS_LAMBDA(int i, int j, int k) {
        const int m = mask(i, j, k);
        VOIGT_UNROLL
        for (int d = 0; d < 3; ++d)
          if ((m >> d) & 1) acc.c[d](i, j, k) = 0;
      });
  st.halo->exchange(acc);
  const Range3 cells = cellRange(g);
  divergence(g, acc, div, cells);
  for_each3("initial_pressure_rhs", cells, KOKKOS_LAMBDA(int i, int j, int k) { rhs(i, j, k) = -div(i, j, k); });
  Kokkos::deep_copy(dp, 0.0);
  const PoissonStats s = solver_->solve(rhs, dp);
  for_each3("initial_pressure", cells, KOKKOS_LAMBDA(int i, int j, int k) { pr(i, j, k) += dp(i, j, k); });
  Kokkos::deep_copy(dp, 0.0);
  st.halo->exchange(pr);
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
  VecField u = st.fields.vector("velocity"), u0 = st.fields.vector("velocity_old");
  VecField rhs = st.fields.vector("acceleration");
  IntField mask = st.fields.integer("fix_mask");
  VecField val = st.fields.vector("fix_value");
  const double dt = st.dt;
  VOIGT_UNROLL
  for (int c = 0; c < 3; ++c) Kokkos::deep_copy(u0.c[c], u.c[c]);
  // Oscillating walls: prescribed values at t^{n+1}. Heun's stages sit at t^n
  // and t^{n+1}: u^n already holds the wall value at t^n, and both the stage-1
  // result u1 (the predictor at t^{n+1}, which stage 2 evaluates) and u* get
  // the value at t^{n+1}. Obstacles touching a wall keep their own velocity.
  if (hasOscillatingWalls(*scene_)) {
    refreshWallValues(g, *scene_, mask, val, st.t + dt);
    if (std::find(scene_->effects.begin(), scene_->effects.end(), "obstacles") != scene_->effects.end())
      addObstacleMask(g, scene_->obstacles, mask, val);
  }

  if (!conservative_) {
    evaluateRhs(st, p, u, rhs);
    for_each3("rk2_stage1", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
          VOIGT_UNROLL
          for (int c = 0; c < 3; ++c) u.c[c](i, j, k) += dt * rhs.c[c](i, j, k);
        });
    applyFixed(mask, val, u, nodes);
    evaluateRhs(st, p, u, rhs);
    for_each3("rk2_stage2", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
          VOIGT_UNROLL
          for (int c = 0; c < 3; ++c)
            u.c[c](i, j, k) = 0.5 * (u0.c[c](i, j, k) + u.c[c](i, j, k) + dt * rhs.c[c](i, j, k));
        });
    applyFixed(mask, val, u, nodes);
    return;
  }
  // Conservative form (header). A prescribed node keeps its value, so its
  // momentum is r u with the prescribed u: no special case needed.
  nodeDensity(st);
  Field r0 = st.fields.scalar("momentum_density"), r1 = st.fields.scalar("momentum_density_stage");
  Field rr = st.fields.scalar("momentum_density_rhs");
  evaluateRhs(st, p, u, rhs, &r0);
  for_each3("rk2_stage1_conservative", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
        const double a = r0(i, j, k), b = a + dt * rr(i, j, k);
        r1(i, j, k) = b;
        VOIGT_UNROLL
        for (int c = 0; c < 3; ++c) u.c[c](i, j, k) = a * (u.c[c](i, j, k) + dt * rhs.c[c](i, j, k)) / b;
      });
  applyFixed(mask, val, u, nodes);
  st.halo->exchange(r1);
  fillNodeGhostsEven(g, r1);
  evaluateRhs(st, p, u, rhs, &r1);
  for_each3("rk2_stage2_conservative", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
        const double a = r0(i, j, k), b = r1(i, j, k), r = 0.5 * (a + b + dt * rr(i, j, k));
        VOIGT_UNROLL
        for (int c = 0; c < 3; ++c)
          u.c[c](i, j, k) = (a * u0.c[c](i, j, k) + b * u.c[c](i, j, k) + dt * a * rhs.c[c](i, j, k)) / (2 * r);
      });
  applyFixed(mask, val, u, nodes);
}

} // namespace voigt
