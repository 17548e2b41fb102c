// navier_stokes set-up: fields, boundary masks, initial velocity and pressure.
#include <cstdio>
#include <algorithm>
#include <cmath>

#include "core/boundary.hpp"
#include "core/field_names.hpp"
#include "effects/navier_stokes/navier_stokes.hpp"
#include "kernels/initial_flow.hpp"
#include "kernels/reductions.hpp"
#include "scene/reader.hpp"

namespace voigt {

std::unique_ptr<Effect> makeNavierStokes() { return std::make_unique<NavierStokes>(); }

SymTensorField stressField(const FieldStore& f) {
  const char* names[6] = {"tau_xx", "tau_yy", "tau_zz", "tau_xy", "tau_yz", "tau_zx"};
  SymTensorField t;
  VOIGT_UNROLL
  for (int c = 0; c < 6; ++c) t.c[c] = f.scalar(names[c]);
  return t;
}

void NavierStokes::configure(const Scene& s, const Published& pub) {
  scene_ = &s;
  limiter_ = limiterNamed(s.advection.limiter);
  // Conservative momentum advection where the density varies: two phases of
  // different density (velocity form at ratio 1000 creates energy). The phase is
  // level_set's (validated there; "" without it).
  const bool varying = pub.varyingDensity(s);
  conservative_ = s.advection.momentum == "conservative" || (s.advection.momentum == "auto" && varying);
  // Scene section navier_stokes: viscous (explicit, the default | semi_implicit: the viscous
  // limit on dt goes, kernels/viscous_implicit.hpp).
  const Section ns = topSection(s, "navier_stokes");
  semiImplicit_ = ns.choice("viscous", "explicit", {"explicit", "semi_implicit"}) == "semi_implicit";
  split_ = s.projection.variableDensity == "split";
  if (split_) { // B0 = 1/rho_min, and the split's gravity-wave limit (dtLimit), from the scene
    double lo = s.fluidMaterial().density, hi = lo;
    for (const auto& [name, m] : s.materials)
      if (m.density > 0) lo = std::min(lo, m.density), hi = std::max(hi, m.density);
    b0_ = 1 / lo;
    const double gn = std::sqrt(s.gravity[0] * s.gravity[0] + s.gravity[1] * s.gravity[1] + s.gravity[2] * s.gravity[2]);
    if (gn > 0 && lo < hi) splitWaveTime_ = s.time.cfl * 2 * std::sqrt(lo / hi) / std::sqrt(M_PI * gn);
  }
  ns.finish();
  bool haveOutflow = false;
  VOIGT_UNROLL
  for (int i = 0; i < 6; ++i) {
    const FaceBc& f = s.bc[i];
    if (f.type != BcType::Outflow) continue;
    if (haveOutflow && f.pressure != pRef_) { // blame this face if the scene names it
      const char* faces[6] = {"x-", "x+", "y-", "y+", "z-", "z+"};
      const Section b = topSection(s, "boundaries");
      const std::string msg = "all outflow faces must share one pressure";
      if (b.has(faces[i])) b.section(faces[i]).fail("pressure", msg);
      b.fail("", msg);
    }
    haveOutflow = true;
    pRef_ = f.pressure;
  }
}

void NavierStokes::declareFields(FieldStore& f) const {
  const std::string me = name();
  // State: u, p and dp (the next solve's initial guess); the rest is derived from them,
  // the scene or the level set within each step (FieldStore::Decl::derived).
  f.declare(field::velocity, Centring::Node, 3, me);
  f.declareDerived("velocity_old", Centring::Node, 3, me);
  f.declareDerived("acceleration", Centring::Node, 3, me);
  f.declareDerived("proj_coef", Centring::Node, 3, me);
  f.declareDerived(field::fixValue, Centring::Node, 3, me);
  f.declare(field::fixMask, Centring::Node, 1, me, true);
  if (conservative_)
    for (const char* n : {"momentum_density", "momentum_density_stage", "momentum_density_rhs"})
      f.declareDerived(n, Centring::Node, 1, me);
  for (const char* n : {"tau_xx", "tau_yy", "tau_zz", "tau_xy", "tau_yz", "tau_zx"})
    f.declareDerived(n, Centring::Cell, 1, me);
  for (const char* n : {field::pressure, "pressure_increment"}) f.declare(n, Centring::Cell, 1, me);
  if (scene_->projection.initialGuess == "extrapolate")
    for (const char* n : {"pressure_rate", "pressure_rate_old"}) {
      f.declare(n, Centring::Cell, 1, me);
      f.markOptionalOnRestart(n); // checkpoints from before them: rateHistory_ 0, rebuilt in two steps
    }
  if (split_) {
    f.declareDerived("proj_coef0", Centring::Node, 3, me);
    f.declareDerived("pressure_increment_hat", Centring::Cell, 1, me);
  }
  for (const char* n : {"poisson_rhs", "divergence", field::density, field::viscosity})
    f.declareDerived(n, Centring::Cell, 1, me);
  if (semiImplicit_) ImplicitViscosity::declareFields(f, me);
}

void NavierStokes::setup(State& st) {
  const Grid& g = st.grid;
  auto& F = st.fields;
  buildFaceMask(g, *scene_, F.integer(field::fixMask), F.vector(field::fixValue));
  Kokkos::deep_copy(F.scalar(field::density), scene_->fluidMaterial().density);
  Kokkos::deep_copy(F.scalar(field::viscosity), scene_->fluidMaterial().viscosity);
  initialVelocity(st);
  solver_ = makePoissonSolver(g, poissonSettings(scene_->projection));
  st.propertiesChanged = true;
}

void NavierStokes::initialVelocity(State& st) {
  const Grid& g = st.grid;
  const InitialCfg& ic = scene_->initial;
  VecField u = st.fields.vector(field::velocity);
  Field p = st.fields.scalar(field::pressure);
  InitialFlow f;
  f.mode = ic.velocity == "uniform" ? 1 : ic.velocity == "taylor_green" ? 2
         : ic.velocity == "couette" ? 3 : ic.velocity == "poiseuille" ? 4 : 0;
  f.A = ic.amplitude, f.rho = scene_->fluidMaterial().density, f.p0 = ic.pressure - pRef_;
  for (int d = 0; d < 3; ++d) f.U[d] = ic.uniform[d];
  f.wLo = scene_->bc[2].velocity[0], f.wHi = scene_->bc[3].velocity[0];
  fillInitialFlow(g, f, u, p);
  applyFixed(st.fields.integer(field::fixMask), st.fields.vector(field::fixValue), u,
             Range3{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}});
}

void NavierStokes::restored(State& st) {
  fillVelocityGhosts(st.grid, *scene_, st.fields.vector(field::velocity));
}

void NavierStokes::registerTasks(Pipeline& p) {
  pipeline_ = &p;
  p.add(Stage::Momentum, name(),
        std::string("SSP-RK2 predictor: MUSCL advection (") + (conservative_ ? "conservative rho u" : "velocity form") +
            ") + stress + forces - grad p^n",
        [this](State& st) { momentum(st, *pipeline_); },
        {"gravity", "surface_tension"}); // after the hydrostatic shift of p and the curvature
  if (conservative_)
    p.add(Stage::Properties, name(), "node density rho^n for the conservative momentum advection",
          [this](State& st) { nodeDensity(st); }, {"level_set"});
  p.add(Stage::Stress, name(), "viscous stress mu D at cells (Eq. 10)", [](State& st) {
    viscousStress(st.grid, st.evalU, st.fields.scalar(field::viscosity), stressField(st.fields),
                  cellRange(st.grid, 1));
  });
  p.add(Stage::Projection, name(), std::string("incremental pressure correction, ") +
        (scene_->projection.op != ProjectionCfg::Op::Exact ? "approximate 7-point Laplacian"
         : scene_->projection.matrixFree                   ? "exact D(1/rho)G, 27-point, without its matrix"
                                                           : "exact D(1/rho)G, 27-point CSR matrix") +
        ", CG + " + solverSummary(scene_->projection),
        [this](State& st) { project(st); });
}

PoissonSettings poissonSettings(const ProjectionCfg& P) {
  PoissonSettings s;
  s.op = P.op == ProjectionCfg::Op::Exact ? PoissonSettings::Op::Exact : PoissonSettings::Op::Approximate;
  s.tolerance = P.tolerance;
  s.maxIterations = P.maxIterations;
  s.preconditioner = P.preconditioner;
  s.damping = P.damping;
  s.sweeps = P.sweeps;
  s.multigridReuse = P.multigridReuse;
  s.multigridRefresh = P.multigridRefresh;
  s.multigridRebuildGrowth = P.multigridRebuildGrowth;
  s.multigridSmoother = P.multigridSmoother;
  s.chebyshevDegree = P.chebyshevDegree;
  s.coarseSweeps = P.coarseSweeps;
  s.fdSingle = P.fdPrecision == "single";
  s.matrixFree = P.matrixFree;
  return s;
}

// The solver settings as `voigt check` prints them: every knob that changes the cost.
std::string solverSummary(const ProjectionCfg& P) {
  std::string s = P.preconditioner;
  if (P.preconditioner == "multigrid") {
    char growth[32];
    std::snprintf(growth, sizeof growth, "%g", P.multigridRebuildGrowth);
    s += " (reuse " + P.multigridReuse + ", refresh " + std::to_string(P.multigridRefresh) + ", rebuild growth " +
         growth + ", smoother " + P.multigridSmoother;
    if (P.multigridSmoother == "chebyshev") s += " degree " + std::to_string(P.chebyshevDegree);
    s += ", coarse sweeps " + std::to_string(P.coarseSweeps);
    s += ")";
  } else if (P.preconditioner == "fast_diagonalization") {
    s += " (the one-density exact inverse, " + P.fdPrecision + " precision)";
  } else if (P.preconditioner != "none") {
    s += " (" + std::to_string(P.sweeps) + " sweep" + (P.sweeps > 1 ? "s" : "") + ")";
  }
  if (P.preconditionerAuto)
    s += P.op == ProjectionCfg::Op::Exact ? " [default with the exact operator]"
                                           : " [default: multigrid from 32^3 cells or with two densities, else sgs]";
  char tol[32];
  std::snprintf(tol, sizeof tol, "%g", P.tolerance);
  const char* tolWhy = "";
  if (P.toleranceAuto)
    tolWhy = P.tolerance == ProjectionCfg::kTwoPhaseExactTolerance ? " [default: exact operator, two densities]"
                                                                   : " [default]";
  return s + ", tolerance " + tol + tolWhy + ", at most " + std::to_string(P.maxIterations) + " iterations (then " +
         (P.onCap == "stop" ? "stop the run" : "warn and go on") + "), initial guess " + P.initialGuess +
         (P.initialGuessAuto ? " [default with this preconditioner]" : "") +
         (P.variableDensity == "split" ? "; variable density split (one-density solve, Dodd & Ferrante 2014)" : "");
}

DtLimit NavierStokes::dtLimit(const State& st) const {
  const Grid& g = st.grid;
  VecField u = st.fields.vector(field::velocity);
  DtLimit best;
  double m[3], mg[3]; // one Allreduce for the three components
  VOIGT_UNROLL
  for (int d = 0; d < 3; ++d) m[d] = localMaxAbs(u.c[d], nodeRange(g));
  MPI_Allreduce(m, mg, 3, MPI_DOUBLE, MPI_MAX, g.comm);
  double inv = 0;
  VOIGT_UNROLL
  for (int d = 0; d < 3; ++d) inv += mg[d] / g.h[d];
  if (inv > 0) best = {scene_->time.cfl / inv, "advective CFL"};
  // Explicit viscous limit dt <= 1 / (2 nu sum 1/h^2) (NUMERICS.md, = h^2/(6 nu)).
  Field mu = st.fields.scalar(field::viscosity), rho = st.fields.scalar(field::density);
  const double nuMax = maxKinematicViscosity(mu, rho, cellRange(g));
  double nuG = nuMax;
  MPI_Allreduce(&nuMax, &nuG, 1, MPI_DOUBLE, MPI_MAX, g.comm);
  if (nuG > 0 && !semiImplicit_) {
    // The full term div(mu (grad u + grad u^T)) reaches 8 nu / h_min^2 on some
    // modes (the projection removes them in a fluid, a solid's stress keeps
    // them): flattened cells with elasticity blew up at 0.69x the plain limit
    // (tests/elasticity/test_kelvin_voigt.cpp). Same as before for cubes.
    double s = 0, hmin = g.h[0];
    VOIGT_UNROLL
    for (int d = 0; d < 3; ++d) s += 1 / (g.h[d] * g.h[d]), hmin = std::min(hmin, g.h[d]);
    s = std::max(s, 2 / (hmin * hmin));
    const double dv = scene_->time.viscousSafety / (2 * nuG * s);
    if (dv < best.dt) best = {dv, "viscous"};
  }
  // projection.variable_density: split. The lagged (B - B0) G dp_hat destabilises gravity
  // waves above dt_c = K sqrt(rho_min / rho_max) sqrt(h / (pi |g|)): a water column at rest grew
  // exponentially from round-off above K ~ 2-2.5 (16^3 and 32^3 at ratio 1000, 32^3 at 100)
  // and drifted only linearly below (perf/README.md, "The one-density split"). K = 2 times the
  // scene's cfl (0.5: half the measured threshold); splitWaveTime_ is dt_c / sqrt(h) (configure).
  if (splitWaveTime_ > 0) {
    const double ds = splitWaveTime_ * std::sqrt(std::min({g.h[0], g.h[1], g.h[2]}));
    if (ds < best.dt) best = {ds, "split (gravity waves)"};
  }
  return best;
}

void NavierStokes::summary(const State& st, nlohmann::json& j) const {
  auto& c = st.counters;
  auto get = [&](const char* k) { auto it = c.find(k); return it == c.end() ? 0.0 : it->second; };
  const double n = get("poisson_solves");
  j["poisson"] = {{"solves", n},
                  {"iterations_mean", n > 0 ? get("poisson_iterations") / n : 0},
                  {"iterations_max", get("poisson_iterations_max")},
                  {"unconverged", get("poisson_unconverged")},
                  {"breakdowns", get("poisson_breakdowns")},
                  {"incompatibility_max", get("poisson_incompatibility_max")},
                  {"null_modes", solver_ ? solver_->nullModeCount() : 0},
                  {"matrix_nonzeros", solver_ ? solver_->globalNonzeros() : 0},
                  {"operator", scene_->projection.op == ProjectionCfg::Op::Exact ? "exact" : "approximate"}};
  if (solver_ && solver_->fdRankGrid()[0] > 0) j["poisson"]["fast_diagonalization_ranks"] = solver_->fdRankGrid();
  if (semiImplicit_) {
    const double v = get("viscous_solves");
    j["viscous"] = {{"step", "semi_implicit"},
                    {"solves", v},
                    {"iterations_mean", v > 0 ? get("viscous_iterations") / v : 0},
                    {"iterations_max", get("viscous_iterations_max")},
                    {"unconverged", get("viscous_unconverged")}};
  }
}

} // namespace voigt
