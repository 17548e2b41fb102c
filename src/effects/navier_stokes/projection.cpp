// Incremental pressure correction (paper, "Numerical methodology"):
//   D B G dp = D u* / dt,  B = diag(1/rho) on free velocity components,
//   u^{n+1} = u* - dt B G dp,   p^{n+1} = p^n + dp.
// projection.variable_density: split (Dodd & Ferrante 2014), B0 = 1/rho_min, dp_hat = dt r^n:
//   u~ = u* - dt (B - B0) G dp_hat,   D B0 G dp = D u~ / dt,   u^{n+1} = u~ - dt B0 G dp.
// Exact operator: A = D B W^{-1} D^T (27-point), so D u^{n+1} equals dt times
// the solver residual; approximate: the compact 7-point Laplacian (NUMERICS.md).
#include <mpi.h>

#include <unistd.h>

#include <algorithm>
#include <iostream>
#include <sstream>

#include "core/boundary.hpp"
#include "core/field_names.hpp"
#include "effects/navier_stokes/navier_stokes.hpp"
#include "kernels/reductions.hpp"

namespace voigt {

// coef_d(n) = 0 where component d is prescribed, else 1/rho_n (mean of the
// existing cells around the node).
void NavierStokes::refreshCoefficients(State& st) {
  const Grid& g = st.grid;
  Field rho = st.fields.scalar(field::density);
  IntField mask = st.fields.integer(field::fixMask);
  VecField coef = st.fields.vector("proj_coef");
  st.halo->exchange(rho);
  fillCellGhostsEven(g, rho);
  projectionCoefficients(g, rho, mask, coef, nodeRange(g));
  st.halo->exchange(coef);
  if (split_) {
    // B0 = 1/rho_min of the scene's materials on the free components (B - B0 <= 0, as Dodd &
    // Ferrante require). The initial pressure is solved with B itself (initialPressure), every
    // step with B0.
    VecField coef0 = st.fields.vector("proj_coef0");
    splitCoefficients(coef, b0_, coef0, Range3{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}});
    solver_->setCoefficients(initialPressureDone_ ? coef0 : coef);
  } else {
    solver_->setCoefficients(coef);
  }
  st.propertiesChanged = false;
}

// A solve that stopped at its iteration cap: said on stderr as it happens (the
// first 10; all are counted), and the run stops if the scene asks for it.
void NavierStokes::reportCap(State& st, const PoissonStats& s) {
  const double n = st.counters["poisson_unconverged"] += 1;
  const ProjectionCfg& P = scene_->projection;
  std::ostringstream os;
  os << "Poisson solve at step " << st.step + 1 << " stopped at its iteration cap (" << s.iterations
     << " iterations, relative residual " << s.relResidual << " > tolerance " << P.tolerance << ")";
  if (P.onCap == "stop") {
    st.stopRequest = os.str() + " and projection.on_cap is stop";
    return;
  }
  if (st.grid.rank == 0 && n <= 10)
    std::cerr << (isatty(2) ? "\n" : "") << "warning: " << os.str() << (n == 10 ? "; further capped solves are counted, not printed" : "")
              << "\n";
}

// The split's u~ = u* - dt (B - B0) G dp_hat and the right-hand side from it. dp_hat = dt times
// the last pressure rate (rate: initial_guess extrapolate), or the last increment.
void NavierStokes::splitPredictor(State& st, const Field& rate, const Field& dp) {
  const Grid& g = st.grid;
  const Range3 cells = cellRange(g);
  VecField u = st.fields.vector(field::velocity), coef = st.fields.vector("proj_coef");
  Field dph = st.fields.scalar("pressure_increment_hat");
  Field rhs = st.fields.scalar("poisson_rhs"), div = st.fields.scalar("divergence");
  if (rate.size() > 0) {
    if (rateHistory_ > 0) extrapolateIncrement(rate, rate, dph, st.dt, false, cells); // dt r^n
    else Kokkos::deep_copy(dph, 0.0);
  } else {
    Kokkos::deep_copy(dph, dp);
  }
  st.halo->exchange(dph);
  subtractSplitGradient(g, dph, coef, b0_, st.dt, u, nodeRange(g));
  st.velocityHalosCurrent = false;
  exchangeVelocity(st);
  fillVelocityGhosts(g, *st.scene, u);
  divergence(g, u, div, cells);
  poissonRhs(div, rhs, st.dt, cells);
}

void NavierStokes::project(State& st) {
  const Grid& g = st.grid;
  const double dt = st.dt;
  VecField u = st.fields.vector(field::velocity), coef = st.fields.vector("proj_coef");
  Field p = st.fields.scalar(field::pressure), dp = st.fields.scalar("pressure_increment");
  Field rhs = st.fields.scalar("poisson_rhs"), div = st.fields.scalar("divergence");
  const Range3 cells = cellRange(g);

  exchangeVelocity(st);
  divergence(g, u, div, cells);
  st.diag["max_divergence_predicted"] = globalMaxAbs(g, div, cells);
  poissonRhs(div, rhs, dt, cells);
  // The initial guess: dp of the previous step, or (initial_guess: extrapolate) dt times the
  // pressure rate extrapolated from the last two steps.
  const bool extrapolate = scene_->projection.initialGuess == "extrapolate";
  Field f1, f2;
  if (extrapolate) {
    f1 = st.fields.scalar("pressure_rate");
    f2 = st.fields.scalar("pressure_rate_old");
    if (rateHistory_ > 0) extrapolateIncrement(f1, f2, dp, dt, rateHistory_ > 1, cells);
  }
  if (split_) splitPredictor(st, extrapolate ? f1 : Field(), dp);
  const PoissonStats s = solver_->solve(rhs, dp, scene_->projection.volumeTolerance / (dt * dt));
  if (extrapolate) {
    shiftPressureRates(f1, f2, dp, dt, cells);
    rateHistory_ = std::min(rateHistory_ + 1, 2);
  }
  addTo(dp, p, cells);
  st.halo->exchange(std::vector<Field>{dp, p}); // one exchange for both: subtractGradient reads dp's ghosts
  subtractGradient(g, dp, split_ ? st.fields.vector("proj_coef0") : coef, dt, u, nodeRange(g));
  st.velocityHalosCurrent = false;
  exchangeVelocity(st);
  fillVelocityGhosts(g, *st.scene, u);

  divergence(g, u, div, cells);
  st.diag["max_divergence"] = globalMaxAbs(g, div, cells);
  st.diag["mean_divergence"] = globalMeanAbs(g, div, cells);
  st.diag["poisson_iterations"] = s.iterations;
  st.diag["poisson_residual"] = s.relResidual;
  st.diag["poisson_incompatibility"] = s.incompatibility;
  st.diag["pressure_reference"] = pRef_;
  auto& c = st.counters;
  c["poisson_solves"] += 1;
  c["poisson_iterations"] += s.iterations;
  c["poisson_iterations_max"] = std::max(c["poisson_iterations_max"], double(s.iterations));
  c["poisson_seconds"] += s.seconds;
  c["poisson_setup_seconds"] += s.setupSeconds;
  if (!s.converged) reportCap(st, s);
  c["poisson_breakdowns"] += s.breakdowns;
  c["poisson_incompatibility_max"] = std::max(c["poisson_incompatibility_max"], s.incompatibility);
}

} // namespace voigt
