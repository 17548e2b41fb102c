// Conservative momentum advection (kernels/advection.hpp addMomentumAdvection,
// src/effects/navier_stokes/momentum.cpp): the properties that make it
// rho-consistent, checked exactly, not against a tuned number.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/advection.hpp"
#include "support/flow.hpp"

using namespace voigt;

namespace {

// Periodic 2 pi box, no viscosity; a heavy ball (1000x) in a light fluid.
std::string box(int n, const std::string& velocity, const std::string& form) {
  const std::string N = std::to_string(n);
  return "name: madv\n"
         "domain: {lo: [0,0,0], hi: [6.283185307179586, 6.283185307179586, 6.283185307179586], cells: [" + N + "," +
         N + "," + N + "]}\n"
         "boundaries: {default: {type: periodic}}\n"
         "materials: {light: {density: 1, viscosity: 0}, heavy: {density: 1000, viscosity: 0}}\n"
         "fluid: light\n"
         "effects: [navier_stokes, level_set]\n"
         "level_set: {phase: heavy, shape: {type: sphere, center: [2.0, 2.6, 3.0], radius: 1.2}}\n"
         "initial: {" + velocity + "}\n"
         "advection: {momentum: " + form + "}\n"
         "time: {end: 1, dt: 0.02, max_steps: 5}\n"
         "projection: {operator: exact, tolerance: 1e-12}\n"
         "output: {enabled: false}\n";
}

double globalSum(const Grid& g, double v) {
  MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_SUM, g.comm);
  return v;
}

} // namespace

// A uniform velocity through a moving density jump of 1000 stays uniform: F_m =
// u F_rho face by face, and the RK stages divide by the density they carried
// (r1, r*), not by a level-set density. Tolerance: round-off over 5 steps of
// |u| ~ 1 (the stage formulas hold exactly in real arithmetic).
TEST(MomentumAdvection, UniformVelocityStaysUniformAcrossDensityJump) {
  auto sim = test::runScene(test::scene(box(16, "velocity: uniform, uniform: [0.7, -0.3, 0.2]", "conservative")));
  const double U[3] = {0.7, -0.3, 0.2};
  const auto e = test::nodeError(sim->state().grid, sim->state().fields.vector("velocity"),
                                 [&](const Vec3&, int c) { return U[c]; });
  test::report("uniform_velocity_max_error", e.linf);
  EXPECT_LE(e.linf, 1e-12);
  EXPECT_EQ(sim->state().step, 5);
}

// Taylor-Green has div_h u = 0 at nodes exactly (central differences of
// sin/cos cancel for cubic cells), so the compression terms vanish and the
// flux form telescopes: total momentum sum(r rhs) and total mass sum(rhsRho)
// change by round-off only. The velocity form, sum(r du/dt), does not
// conserve momentum across the density jump: the test sees the difference.
TEST(MomentumAdvection, ConservesMomentumWhereVelocityFormDoesNot) {
  auto sim = std::make_unique<Simulation>(test::scene(box(24, "velocity: taylor_green, amplitude: 1", "conservative")),
                                          MPI_COMM_WORLD, RunOptions{});
  sim->initialize();
  State& st = sim->state();
  const Grid& g = st.grid;
  VecField u = st.fields.vector("velocity");
  st.halo->exchange(u);
  // A sharp heavy ball: the hardest case for consistency.
  Field r("r", g.ext[0], g.ext[1], g.ext[2]), rr("rr", g.ext[0], g.ext[1], g.ext[2]);
  VecField rhs, rhsV;
  for (int c = 0; c < 3; ++c) {
    rhs.c[c] = Field("rhs", g.ext[0], g.ext[1], g.ext[2]);
    rhsV.c[c] = Field("rhsV", g.ext[0], g.ext[1], g.ext[2]);
  }
  const double lo0 = g.lo[0], lo1 = g.lo[1], lo2 = g.lo[2], h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  const int ng = g.ng, c0 = g.c0[0], c1 = g.c0[1], c2 = g.c0[2];
  Kokkos::parallel_for(
      "ball", Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}), KOKKOS_LAMBDA(int i, int j, int k) {
        const double x = lo0 + (i - ng + c0) * h0 - 2.0, y = lo1 + (j - ng + c1) * h1 - 2.6,
                     z = lo2 + (k - ng + c2) * h2 - 3.0;
        r(i, j, k) = x * x + y * y + z * z < 1.44 ? 1000.0 : 1.0;
      });
  st.halo->exchange(r);
  const Range3 nodes = nodeRange(g);
  addMomentumAdvection(g, r, u, r, rr, rhs, nodes, Limiter::MinMod);
  for (int c = 0; c < 3; ++c) addNodeAdvection(g, u.c[c], u, rhsV.c[c], nodes, Limiter::MinMod);
  double mass = 0, massAbs = 0;
  double mom[3] = {0, 0, 0}, momAbs[3] = {0, 0, 0}, momV[3] = {0, 0, 0};
  Kokkos::parallel_reduce(
      "sums", nodes.policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& m, double& ma) {
        m += rr(i, j, k);
        ma += std::abs(rr(i, j, k));
      },
      mass, massAbs);
  for (int c = 0; c < 3; ++c) {
    auto q = rhs.c[c], qv = rhsV.c[c];
    Kokkos::parallel_reduce(
        "momentum", nodes.policy(),
        KOKKOS_LAMBDA(int i, int j, int k, double& m, double& ma, double& mv) {
          m += r(i, j, k) * q(i, j, k);
          ma += std::abs(r(i, j, k) * q(i, j, k));
          mv += r(i, j, k) * qv(i, j, k);
        },
        mom[c], momAbs[c], momV[c]);
    mom[c] = globalSum(g, mom[c]);
    momAbs[c] = globalSum(g, momAbs[c]);
    momV[c] = globalSum(g, momV[c]);
  }
  mass = globalSum(g, mass);
  massAbs = globalSum(g, massAbs);
  test::report("mass_rate_relative", std::abs(mass) / massAbs);
  EXPECT_LE(std::abs(mass), 1e-12 * massAbs); // round-off of a telescoping sum
  for (int c = 0; c < 2; ++c) { // Taylor-Green moves x and y
    test::report("momentum_rate_relative_" + std::to_string(c), std::abs(mom[c]) / momAbs[c]);
    test::report("velocity_form_momentum_rate_relative_" + std::to_string(c), std::abs(momV[c]) / momAbs[c]);
    EXPECT_LE(std::abs(mom[c]), 1e-12 * momAbs[c]);
    EXPECT_GE(std::abs(momV[c]), 1e-3 * momAbs[c]); // the velocity form's error is O(1), not round-off
  }
}
