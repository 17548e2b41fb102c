// Two fluids at rest under gravity, density ratio 1000 (water below air):
// the exact discrete hydrostatic state exists (p depends on y only, and the
// node coefficient 1/rho_n is the same in the momentum and the projection),
// so velocities must stay at solver round-off and the pressure must satisfy
//   (p_j - p_{j-1}) / h = -g rho_n(j),  rho_n(j) = (rho_{j-1} + rho_j) / 2.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/reductions.hpp"
#include "support/flow.hpp"

using namespace voigt;

namespace {
std::string restScene(const std::string& op, const std::string& heavyShape) {
  return "domain: {lo: [0,0,0], hi: [1,1,0.125], cells: [16,16,2], ranks: [0,0,1]}\n"
         "boundaries: {default: {type: no_slip}, z-: {type: periodic}, z+: {type: periodic}}\n"
         "time: {end: 1.0, cfl: 0.5}\n"
         "materials: {water: {density: 1000, viscosity: 1e-3}, air: {density: 1, viscosity: 1.8e-5}}\n"
         "fluid: air\n"
         "gravity: [0, -9.81, 0]\n"
         "effects: [navier_stokes, gravity, level_set, reinit]\n"
         "level_set: {phase: water, shape: " + heavyShape + "}\n"
         "projection: {operator: " + op + ", tolerance: 1e-12, max_iterations: 5000}\n"
         "output: {enabled: false}\n";
}
} // namespace

// Exact operator, tolerance 1e-12, 18 steps to t = 1: measured max|u| = 6.3e-13
// and hydrostatic residual 3.7e-15 (relative to rho_water g). Bounds: 1e-10 and
// 1e-12, two to three orders above round-off and far below any real flow.
TEST(TwoPhase, HeavyBelowLightStaysAtRest) {
  const double g = 9.81;
  auto sim = test::runScene(test::scene(
      restScene("exact", "{type: plane, point: [0.5, 0.4321, 0.06], normal: [0, 1, 0]}")));
  const State& st = sim->state();
  const Grid& G = st.grid;
  double umax = 0;
  for (int c = 0; c < 3; ++c) umax = std::max(umax, globalMaxAbs(G, st.fields.vector("velocity").c[c], nodeRange(G)));
  test::report("max_velocity", umax);
  EXPECT_LT(umax, 1e-10);
  // Hydrostatic pressure between every pair of owned cell rows.
  auto p = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.fields.scalar("pressure"));
  auto rho = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.fields.scalar("density"));
  const double h = G.h[1];
  double worst = 0;
  auto r = cellRange(G);
  for (int k = r.b[2]; k < r.e[2]; ++k)
    for (int j = r.b[1] + 1; j < r.e[1]; ++j)
      for (int i = r.b[0]; i < r.e[0]; ++i) {
        const double rn = 0.5 * (rho(i, j - 1, k) + rho(i, j, k));
        const double dp = (p(i, j, k) - p(i, j - 1, k)) / h;
        worst = std::max(worst, std::abs(dp + g * rn) / (g * 1000));
      }
  MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_DOUBLE, MPI_MAX, G.comm);
  test::report("hydrostatic_error", worst);
  EXPECT_LT(worst, 1e-12);
  // The level set does not move: volume drift at round-off.
  EXPECT_LT(std::abs(st.diag.at("volume_drift")), 1e-10);
}
