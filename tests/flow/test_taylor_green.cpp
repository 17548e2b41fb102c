// Taylor-Green vortex (cases/taylor_green): exact solution of Navier-Stokes,
//   u = A e^{-2 nu t} sin x cos y,  v = -A e^{-2 nu t} cos x sin y   (k = 1).
#include <gtest/gtest.h>

#include <cmath>

#include "support/flow.hpp"

using namespace voigt;

namespace {
// amp: velocity amplitude; dt > 0 fixes the step (else CFL 0.4).
std::string tgScene(int n, const std::string& op, const std::string& limiter, const std::string& tol = "1e-10",
                    double amp = 1, double dt = 0) {
  const std::string time = dt > 0 ? "dt: " + std::to_string(dt) : std::string("cfl: 0.4");
  return "name: tg\n"
         "domain: {lo: [0,0,0], hi: [6.283185307179586, 6.283185307179586, 1.5707963267948966],"
         " cells: [" + std::to_string(n) + "," + std::to_string(n) + ",4]}\n"
         "boundaries: {default: {type: periodic}}\n"
         "time: {end: 1.0, " + time + "}\n"
         "materials: {fluid: {density: 1, viscosity: 0.05}}\n"
         "effects: [navier_stokes]\n"
         "initial: {velocity: taylor_green, amplitude: " + std::to_string(amp) + "}\n"
         "advection: {limiter: " + limiter + "}\n"
         "projection: {operator: " + op + ", tolerance: " + tol + ", max_iterations: 5000}\n"
         "output: {enabled: false}\n";
}

double tgError(int n, const std::string& op, const std::string& limiter, double amp = 1, double dt = 0,
               const std::string& tol = "1e-10") {
  auto sim = test::runScene(test::scene(tgScene(n, op, limiter, tol, amp, dt)));
  const double t = sim->state().t, nu = 0.05, decay = amp * std::exp(-2 * nu * t);
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

// Spatial convergence at fixed CFL over three grids with the paper's scheme
// (MinMod MUSCL, central gradients, SSP-RK2): second order, measured 2.07 and
// 2.07. Asserted > 1.8 on the finest pair (theory: 2), > 1.6 on the coarse pair.
TEST(TaylorGreen, SecondOrderConvergence) {
  for (std::string lim : {"minmod"}) {
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
// Stokes regime (amplitude 1e-3, advection negligible): isolates the viscous
// stress path and the projection. Second order for both operators (measured
// 1.98, 1.99 with the approximate one); asserted > 1.9 on both pairs.
TEST(TaylorGreen, StokesRegimeSecondOrder) {
  for (std::string op : {"exact", "approximate"}) {
    double e[3];
    int i = 0;
    // Tolerance 1e-8: the solver error (relative to the O(1e-3) rhs) stays far
    // below the 2e-7 discretisation error at 64^2.
    for (int n : {16, 32, 64}) e[i++] = tgError(n, op, "minmod", 1e-3, 0.1 * 2 * M_PI / n, "1e-8");
    EXPECT_GT(order(e[0], e[1]), 1.9) << op;
    EXPECT_GT(order(e[1], e[2]), 1.9) << op;
  }
}
