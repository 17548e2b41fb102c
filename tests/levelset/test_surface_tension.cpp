// Surface tension (issue 51; effects/surface_tension.cpp, kernels/curvature.hpp): a static
// drop, no gravity. The exact state is rest with the Laplace jump p_in - p_out = sigma / R
// (a cylinder: the scene is 2-D, 2 periodic cells along z). What is left of the velocity is
// the parasitic current, reported as the capillary number Ca = max|u| mu / sigma (Popinet 2009).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "kernels/reductions.hpp"
#include "support/flow.hpp"

using namespace voigt;

namespace {
struct Drop {
  double jump, ca;
};

// R = 0.25 in the unit square on n^2 cells (n = 64: 16 cells per radius), sigma = 1, mu = 0.1
// in both phases, rho_in / rho_out as given; `steps` steps from rest.
Drop staticDrop(int n, double rhoIn, double rhoOut, const std::string& form, int steps) {
  const double h = 1.0 / n;
  const std::string scene =
      "domain: {lo: [0,0,0], hi: [1,1," + std::to_string(2 * h) + "], cells: [" + std::to_string(n) + "," +
      std::to_string(n) + ",2], ranks: [0,0,1]}\n"
      "boundaries: {default: {type: no_slip}, z-: {type: periodic}, z+: {type: periodic}}\n"
      "time: {end: 100, cfl: 0.5, max_steps: " + std::to_string(steps) + "}\n"
      "materials: {drop: {density: " + std::to_string(rhoIn) + ", viscosity: 0.1}, out: {density: " +
      std::to_string(rhoOut) + ", viscosity: 0.1}}\n"
      "fluid: out\n"
      "effects: [navier_stokes, level_set, reinit, surface_tension]\n"
      "level_set: {phase: drop, fast_marching: false, shape: {type: cylinder, center: [0.5, 0.5, 0], radius: 0.25, axis: z}}\n"
      "surface_tension: {sigma: 1, form: " + form + "}\n"
      "output: {enabled: false}\n";
  auto sim = test::runScene(test::scene(scene));
  const State& st = sim->state();
  const Grid& G = st.grid;
  auto p = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.fields.scalar("pressure"));
  auto psi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.fields.scalar("psi"));
  const double far = 4 * h; // beyond the smoothing zone (2 cells) on either side
  double s[4] = {0, 0, 0, 0}; // sum and count inside, outside
  auto r = cellRange(G);
  for (int k = r.b[2]; k < r.e[2]; ++k)
    for (int j = r.b[1]; j < r.e[1]; ++j)
      for (int i = r.b[0]; i < r.e[0]; ++i) {
        if (psi(i, j, k) > far) s[0] += p(i, j, k), s[1] += 1;
        if (psi(i, j, k) < -far) s[2] += p(i, j, k), s[3] += 1;
      }
  MPI_Allreduce(MPI_IN_PLACE, s, 4, MPI_DOUBLE, MPI_SUM, G.comm);
  double u = 0;
  for (int c = 0; c < 3; ++c) u = std::max(u, globalMaxAbs(G, st.fields.vector("velocity").c[c], nodeRange(G)));
  return {s[0] / s[1] - s[2] / s[3], u * 0.1 / 1.0};
}
} // namespace

// The Laplace jump within 1 % at 16 cells per radius (the bound), density ratio 1
// and 1000, with the balanced force; the plain CSF for comparison (reported).
TEST(SurfaceTension, StaticCylinderLaplaceJump) {
  for (double rhoIn : {1.0, 1000.0}) {
    const Drop b = staticDrop(64, rhoIn, 1.0, "balanced", 40);
    const Drop c = staticDrop(64, rhoIn, 1.0, "csf", 40);
    const std::string tag = rhoIn > 1 ? "ratio1000" : "ratio1";
    test::report("laplace_jump_balanced_" + tag, b.jump);
    test::report("capillary_number_balanced_" + tag, b.ca);
    test::report("laplace_jump_csf_" + tag, c.jump);
    test::report("capillary_number_csf_" + tag, c.ca);
    EXPECT_NEAR(b.jump, 4.0, 0.04) << tag; // sigma / R = 4 Pa, within 1 % (measured 0.13 %)
    // The balanced form's point: currents below the plain CSF's (measured 10.9x smaller at
    // ratio 1, 89x at 1000; Ca 5.4e-5 and 8.9e-7). Asserted: 10x, and Ca < 1e-4. (With
    // reinit.zone_tolerance 0.01, which settles this zone, 62x and 850x.)
    EXPECT_LT(b.ca, 0.1 * c.ca) << tag;
    EXPECT_LT(b.ca, 1e-4) << tag;
  }
}
