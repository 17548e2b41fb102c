// Taylor-Green vortex (cases/taylor_green): exact solution of Navier-Stokes,
//   u = A e^{-2 nu t} sin x cos y,  v = -A e^{-2 nu t} cos x sin y   (k = 1).
#include <gtest/gtest.h>

#include <cmath>

#include "support/flow.hpp"

using namespace voigt;

namespace {
std::string tgScene(int n, const std::string& op, const std::string& limiter, const std::string& tol = "1e-10") {
  return "name: tg\n"
         "domain: {lo: [0,0,0], hi: [6.283185307179586, 6.283185307179586, 1.5707963267948966],"
         " cells: [" + std::to_string(n) + "," + std::to_string(n) + ",4]}\n"
         "boundaries: {default: {type: periodic}}\n"
         "time: {end: 1.0, cfl: 0.4}\n"
         "materials: {fluid: {density: 1, viscosity: 0.05}}\n"
         "effects: [navier_stokes]\n"
         "initial: {velocity: taylor_green, amplitude: 1}\n"
         "advection: {limiter: " + limiter + "}\n"
         "projection: {operator: " + op + ", tolerance: " + tol + ", max_iterations: 5000}\n"
         "output: {enabled: false}\n";
}

double tgError(int n, const std::string& op, const std::string& limiter) {
  auto sim = test::runScene(test::scene(tgScene(n, op, limiter)));
  const double t = sim->state().t, nu = 0.05, decay = std::exp(-2 * nu * t);
  auto exact = [&](const Vec3& x, int c) {
    if (c == 0) return decay * std::sin(x[0]) * std::cos(x[1]);
    if (c == 1) return -decay * std::cos(x[0]) * std::sin(x[1]);
    return 0.0;
  };
  return test::nodeError(sim->state().grid, sim->state().fields.vector("velocity"), exact).l2;
}

double order(double eCoarse, double eFine) { return std::log2(eCoarse / eFine); }
} // namespace

// Decay: at 32^2 the RMS velocity error after t = 1 (amplitude 0.905) is below
// 1% of the amplitude; measured 2.6e-3 with minmod.
TEST(TaylorGreen, DecayMatchesExact) {
  const double e = tgError(32, "exact", "minmod");
  RecordProperty("l2_error_32", std::to_string(e));
  EXPECT_LT(e, 0.01 * std::exp(-0.1));
}

// Spatial convergence at fixed CFL over three grids. The scheme is second order
// (MUSCL, central gradients, SSP-RK2); MinMod clips smooth extrema, which costs
// a little order, so we assert the observed order on the finest pair > 1.8 and
// on each pair > 1.6.
TEST(TaylorGreen, SecondOrderConvergence) {
  for (std::string lim : {"minmod", "mc"}) {
    const double e16 = tgError(16, "exact", lim), e32 = tgError(32, "exact", lim), e64 = tgError(64, "exact", lim);
    const double p1 = order(e16, e32), p2 = order(e32, e64);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0)
      printf("taylor-green %s: L2 errors %.3e %.3e %.3e, orders %.2f %.2f\n", lim.c_str(), e16, e32, e64, p1, p2);
    EXPECT_GT(p1, 1.6) << lim;
    EXPECT_GT(p2, 1.8) << lim;
  }
}

// The approximate (7-point) projection converges at second order as well.
TEST(TaylorGreen, ApproximateProjectionConverges) {
  const double e16 = tgError(16, "approximate", "minmod"), e32 = tgError(32, "approximate", "minmod");
  EXPECT_GT(order(e16, e32), 1.6);
}
TEST(TaylorGreen, DISABLED_Explore) {
  const char* cfl = getenv("TG_CFL");
  for (int n : {16, 32, 64}) {
    std::string s = tgScene(n, getenv("TG_OP") ? getenv("TG_OP") : "exact", getenv("TG_LIM") ? getenv("TG_LIM") : "mc");
    if (cfl) s.replace(s.find("cfl: 0.4"), 8, std::string("cfl: ") + cfl);
    auto sim = test::runScene(test::scene(s));
    const double t = sim->state().t, decay = std::exp(-0.1 * t);
    auto exact = [&](const Vec3& x, int c) {
      return c == 0 ? decay * std::sin(x[0]) * std::cos(x[1]) : c == 1 ? -decay * std::cos(x[0]) * std::sin(x[1]) : 0.0;
    };
    auto e = test::nodeError(sim->state().grid, sim->state().fields.vector("velocity"), exact);
    printf("n=%d steps=%ld l2=%.4e linf=%.4e\n", n, sim->state().step, e.l2, e.linf);
  }
}
