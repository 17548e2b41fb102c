// Height-function curvature (surface_tension.curvature: height_function,
// kernels/height_function.hpp) on the static drops of test_surface_tension.cpp, and the case
// the level set's own curvature fails: an inertial drop (cases/rising_bubble/README.md, "A
// resting water drop in air").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "kernels/height_function.hpp"
#include "levelset/capillary_support.hpp"
#include "stability/support.hpp"

using namespace voigt;
using namespace voigt::capillary_test;

// The Laplace jump within 1 % at 16 cells per radius (the bound), ratio 1 and 1000.
TEST(HeightFunction, StaticCylinderLaplaceJump) {
  for (double rhoIn : {1.0, 1000.0}) {
    const Drop d = staticDrop(64, rhoIn, 1.0, "balanced", 40, "height_function");
    const std::string tag = rhoIn > 1 ? "ratio1000" : "ratio1";
    test::report("hf_laplace_jump_" + tag, d.jump);
    test::report("hf_capillary_number_" + tag, d.ca);
    EXPECT_NEAR(d.jump, 4.0, 0.04) << tag; // sigma / R = 4 Pa within 1 %
    EXPECT_LT(d.ca, 1e-4) << tag;          // the level set's bound in test_surface_tension.cpp
  }
}

// The octant of a sphere of R = 0.25 on 32^3 cells (16 per radius): 2 sigma / R = 8 Pa within
// 1 % (measured 7.992). The columns next to the symmetry planes read psi's mirrored ghosts.
// The currents after 20 steps are 18 times the level set's (Ca 2.4e-4 against 1.3e-5): in 3-D
// the 3 x 3 heights are least accurate where the normal is near a diagonal
// (SphereCurvatureOfADistance); asserted bounded only (Ca < 1e-3).
TEST(HeightFunction, StaticSphereLaplaceJump) {
  const std::string scene = "domain: {lo: [0,0,0], hi: [0.5,0.5,0.5], cells: [32,32,32]}\n"
                            "boundaries: {default: {type: no_slip}, x-: {type: slip}, y-: {type: slip}, z-: {type: slip}}\n"
                            "time: {end: 100, max_steps: 20}\n" +
                            materials(1.0, 1.0) +
                            "level_set: {phase: drop, shape: {type: sphere, center: [0, 0, 0], radius: 0.25}}\n"
                            "surface_tension: {sigma: 1, curvature: height_function}\n";
  auto sim = test::runScene(test::scene(scene));
  const Drop d = measure(*sim);
  test::report("hf_sphere_laplace_jump", d.jump);
  test::report("hf_sphere_capillary_number", d.ca);
  EXPECT_NEAR(d.jump, 8.0, 0.08);
  EXPECT_LT(d.ca, 1e-3);
}

// The viscous cylinder of CurrentsDecay (ratio 1, La = 50, 8 cells per radius, to t = 1): the
// currents decay as with the level set's curvature (measured: level set Ca peak 2.3e-4, late
// 1.7e-6; heights 7.3e-5, 5.8e-7). Asserted: bounded (< 1e-3) and late < peak / 20.
TEST(HeightFunction, CurrentsDecay) {
  Simulation sim(test::scene(cylinderScene(32, 1, 1, "balanced", 1000000, "height_function")), MPI_COMM_WORLD,
                 RunOptions{});
  double peak = 0, late = 0;
  sim.advanceTo(1.0, [&](const State& st) {
    const double ca = st.diag.at("max_velocity") * 0.1;
    peak = std::max(peak, ca);
    if (st.t > 0.9) late = std::max(late, ca);
  });
  test::report("hf_currents_peak", peak);
  test::report("hf_currents_late", late);
  EXPECT_LT(peak, 1e-3);
  EXPECT_LT(late, peak / 20);
}

// An inertial drop: a water cylinder (R = 5 mm, 8 cells) resting in air, ratio 1000, sigma
// 0.0728, La = 7e5, to t = 1.2 s (2400 steps of the capillary limit). With the level set's
// curvature the kinetic energy grows 1000x to 1e-3 of the surface energy and Ca = max|u|
// mu_water / sigma reaches 6.5e-4 (README, "A resting water drop in air"); with the heights
// measured 1.2e-5 and 3.4e-5. Asserted: 1e-4 for both, ten times below what the level set gives.
TEST(HeightFunction, InertialDropStaysQuiet) {
  const std::string scene =
      "domain: {lo: [0, 0, 0], hi: [0.02, 0.02, 0.00125], cells: [32, 32, 2], ranks: [0, 0, 1]}\n"
      "boundaries: {default: {type: no_slip}, z-: {type: periodic}, z+: {type: periodic}}\n"
      "time: {end: 1.2}\n"
      "output: {enabled: false}\n"
      "materials: {water: {density: 1000, viscosity: 1.0e-3}, air: {density: 1, viscosity: 1.8e-5}}\n"
      "fluid: air\n"
      "effects: [navier_stokes, level_set, reinit, surface_tension]\n"
      "level_set: {phase: water, shape: {type: cylinder, center: [0.0101, 0.0099, 0], axis: z, radius: 0.005}}\n"
      "surface_tension: {sigma: 0.0728, curvature: height_function}\n";
  Simulation sim(test::scene(scene), MPI_COMM_WORLD, RunOptions{});
  const double surface = 0.0728 * 2 * M_PI * 0.005 * 0.00125;
  double ke = 0, ca = 0;
  sim.advanceTo(1.2, [&](const State& st) {
    ke = std::max(ke, st.diag.at("kinetic_energy") / surface);
    ca = std::max(ca, st.diag.at("max_velocity") * 1e-3 / 0.0728);
  });
  test::report("hf_inertial_drop_energy", ke);
  test::report("hf_inertial_drop_capillary_number", ca);
  EXPECT_LT(ke, 1e-4);
  EXPECT_LT(ca, 1e-4);
}

// The heights' curvature of an exact distance to a sphere (psi = R - |x - c|, 2 / R exact) at
// 8 and 16 cells per radius, on one rank (the kernel alone; ghosts filled from the formula).
// Measured: mean relative error 8.6e-3 and 1.6e-3, max 0.165 and 0.042, with 14 and 0
// fallbacks among 1348 and 5339 interface cells. The largest errors sit where the normal is
// near (1, 1, 1) / sqrt 3: every axis then sees slopes near 1 both ways and the 3 x 3 heights
// span 4-5 cells (a 3 x 3 stencil's known weakness at 8 cells per radius; with 5-cell columns,
// which left those cells to their neighbours, the max was 0.027 with 17 % fallbacks). Asserted:
// mean below 1.5 % and 0.3 %, falling at least 3x (second order: 4x), max below 25 % and 6 %.
namespace {
struct CurvatureStats {
  double meanErr = 0, maxErr = 0, fallbacks = 0, cells = 0;
};
CurvatureStats sphereCurvature(int n, double R) {
  Grid g = makeGrid(MPI_COMM_SELF, {n, n, n}, {0, 0, 0}, {1, 1, 1}, {false, false, false});
  const Field psi("psi", g.ext[0], g.ext[1], g.ext[2]), kap("kap", g.ext[0], g.ext[1], g.ext[2]);
  const Field ok("ok", g.ext[0], g.ext[1], g.ext[2]);
  const double h = g.h[0], c0 = 0.5013, c1 = 0.4987, c2 = 0.5031;
  const int ng = g.ng;
  Kokkos::parallel_for(
      "sphere", Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}), KOKKOS_LAMBDA(int i, int j, int k) {
        const double x = (i - ng + 0.5) * h - c0, y = (j - ng + 0.5) * h - c1, z = (k - ng + 0.5) * h - c2;
        psi(i, j, k) = R - std::sqrt(x * x + y * y + z * z);
      });
  CurvatureStats s;
  const VecField rec{Field("rx", g.ext[0], g.ext[1], g.ext[2]), Field("ry", g.ext[0], g.ext[1], g.ext[2]),
                     Field("rz", g.ext[0], g.ext[1], g.ext[2])};
  curvature::columnCrossings(psi, rec, cellRange(g, 0));
  s.fallbacks = curvature::heightCurvature(g, psi, rec, kap, ok, cellRange(g, -2));
  auto hk = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), kap);
  auto ho = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), ok);
  const Range3 r = cellRange(g);
  for (int k = r.b[2]; k < r.e[2]; ++k)
    for (int j = r.b[1]; j < r.e[1]; ++j)
      for (int i = r.b[0]; i < r.e[0]; ++i)
        if (ho(i, j, k) > 0.5) {
          const double e = std::abs(hk(i, j, k) * R / 2 - 1);
          s.meanErr += e, s.maxErr = std::max(s.maxErr, e), s.cells += 1;
        }
  s.meanErr /= s.cells;
  freeGrid(g);
  return s;
}
} // namespace

TEST(HeightFunction, SphereCurvatureOfADistance) {
  CurvatureStats s[2];
  for (int q = 0; q < 2; ++q) {
    const int cells = 8 << q, n = 4 * cells;
    s[q] = sphereCurvature(n, cells * 1.0 / n);
    if (test::worldRank() == 0)
      std::printf("[ heights ] R = %d cells: kappa error mean %.2e, max %.2e over %.0f cells; %.0f fallbacks\n", cells,
                  s[q].meanErr, s[q].maxErr, s[q].cells, s[q].fallbacks);
    EXPECT_LT(s[q].maxErr, q == 0 ? 0.25 : 0.06);
  }
  EXPECT_LT(s[0].meanErr, 0.015);
  EXPECT_LT(s[1].meanErr, 0.003);
  EXPECT_LT(s[1].meanErr, s[0].meanErr / 3);
}
