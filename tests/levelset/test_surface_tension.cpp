// Surface tension (issue 51; effects/surface_tension.cpp, kernels/curvature.hpp): a static
// drop, no gravity. The exact state is rest with the Laplace jump p_in - p_out = sigma / R
// (a cylinder: the scene is 2-D, 2 periodic cells along z). What is left of the velocity is
// the parasitic current, reported as the capillary number Ca = max|u| mu / sigma (Popinet 2009).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "levelset/capillary_support.hpp"

using namespace voigt;

using namespace voigt::capillary_test;


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

// The sphere: the octant x, y, z >= 0 of a drop of R = 0.25 centred at the origin (slip
// walls on the three symmetry planes), 32^3 cells of h = 1/64: 16 cells per radius. Laplace:
// p_in - p_out = 2 sigma / R = 8 Pa.
TEST(SurfaceTension, StaticSphereLaplaceJump) {
  for (double rhoIn : {1.0, 1000.0}) {
    Drop d[2];
    for (int f = 0; f < 2; ++f) {
      const std::string scene =
          "domain: {lo: [0,0,0], hi: [0.5,0.5,0.5], cells: [32,32,32]}\n"
          "boundaries: {default: {type: no_slip}, x-: {type: slip}, y-: {type: slip}, z-: {type: slip}}\n"
          "time: {end: 100, max_steps: 20}\n" + materials(rhoIn, 1.0) +
          "level_set: {phase: drop, shape: {type: sphere, center: [0, 0, 0], radius: 0.25}}\n"
          "surface_tension: {sigma: 1, form: " + std::string(f ? "csf" : "balanced") + "}\n";
      d[f] = measure(*test::runScene(test::scene(scene)));
    }
    const std::string tag = rhoIn > 1 ? "ratio1000" : "ratio1";
    test::report("sphere_laplace_jump_balanced_" + tag, d[0].jump);
    test::report("sphere_capillary_number_balanced_" + tag, d[0].ca);
    test::report("sphere_laplace_jump_csf_" + tag, d[1].jump);
    test::report("sphere_capillary_number_csf_" + tag, d[1].ca);
    EXPECT_NEAR(d[0].jump, 8.0, 0.08) << tag; // 2 sigma / R within 1 % (the bound)
    EXPECT_LT(d[0].ca, 0.1 * d[1].ca) << tag; // as the cylinder's
    EXPECT_LT(d[0].ca, 1e-4) << tag;
  }
}

// The currents over time (Popinet 2009's measure, Ca = max|u| mu / sigma): the cylinder at
// density ratio 1, 8 cells per radius, to t = 1 (0.4 of the viscous time rho D^2 / mu); three
// resolutions over 2.5 viscous times: cases/rising_bubble/README.md, "Static drop".
// They rise while the zone adjusts to the discrete balance and then decay: with
// reinit.zone_curvature (on with surface tension) the settled zone stops feeding them.
TEST(SurfaceTension, CurrentsDecay) {
  for (int n : {32}) {
    Simulation sim(test::scene(cylinderScene(n, 1, 1, "balanced", 1000000)), MPI_COMM_WORLD, RunOptions{});
    double peak = 0, late = 0;
    sim.advanceTo(1.0, [&](const State& st) {
      const double ca = st.diag.at("max_velocity") * 0.1;
      peak = std::max(peak, ca);
      if (st.t > 0.9) late = std::max(late, ca);
    });
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0)
      std::printf("cylinder %d cells per radius: Ca peak %.2e, max over t in (0.9, 1] %.2e\n", n / 4, peak, late);
    test::report("currents_peak_" + std::to_string(n), peak);
    test::report("currents_late_" + std::to_string(n), late);
    // Measured: peak 2.3e-4, late 1.7e-6 (16 cells per radius: 9.1e-5, 1.7e-6); without the
    // curved gate they stayed near 1.3e-4. Bounded: Ca < 1e-3; decaying: late < peak / 20.
    EXPECT_LT(peak, 1e-3);
    EXPECT_LT(late, peak / 20);
  }
}

// A capillary wave: y = a0 cos(k x), wavelength 1, a0 = 0.01, a liquid (density 1, viscosity
// 0.002) under a gas 1000 times lighter (viscosity 2e-6: the same kinematic viscosity), sigma =
// 1, no gravity, walls at y = -1 and 1 (k H = 2 pi: deep, tanh = 1 - 7e-6), 32 cells per
// wavelength. Linear theory (Lamb 1932, Sec. 267; Prosperetti 1981's inviscid limit): omega0^2 =
// sigma k^3 / (rho1 + rho2), period 0.39914 s; the viscous damping, about 2 nu k^2 = 0.16 /s,
// shifts the frequency by 1e-4. The period from the zero crossings of the amplitude at x = h/2.
TEST(SurfaceTension, CapillaryWavePeriod) {
  const int n = 32;
  const double h = 1.0 / n, k = 2 * M_PI, a0 = 0.01, nu = 0.002, rho1 = 1, rho2 = 0.001;
  const std::string scene =
      "domain: {lo: [0,-1,0], hi: [1,1," + std::to_string(2 * h) + "], cells: [" + std::to_string(n) + "," +
      std::to_string(2 * n) + ",2], ranks: [0,0,1]}\n"
      "boundaries: {default: {type: no_slip}, x-: {type: periodic}, x+: {type: periodic}, z-: {type: periodic}, "
      "z+: {type: periodic}}\n"
      "time: {end: 100}\n"
      "materials: {liquid: {density: 1, viscosity: 0.002}, gas: {density: 0.001, viscosity: 2.0e-6}}\n"
      "fluid: gas\n"
      "effects: [navier_stokes, level_set, reinit, surface_tension]\n"
      "level_set: {phase: liquid, shape: {type: wave, point: [0,0,0], normal: [0,1,0], direction: [1,0,0], "
      "amplitude: 0.01, wavelength: 1}}\n"
      "surface_tension: {sigma: 1}\n"
      "output: {enabled: false}\n";
  Simulation sim(test::scene(scene), MPI_COMM_WORLD, RunOptions{});
  const double period = 2 * M_PI / std::sqrt(k * k * k / (rho1 + rho2));
  std::vector<double> crossings; // times where the amplitude changes sign
  double prevT = 0, prevA = a0 * std::cos(k * h / 2), trough = 0;
  sim.advanceTo(2.1 * period, [&](const State& st) {
    // The interface height in the column at x = h/2: the sign change of psi along y.
    const Grid& g = st.grid;
    auto psi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.fields.scalar("psi"));
    double y = -1e300;
    const auto r = cellRange(g);
    if (g.c0[0] == 0)
      for (int j = r.b[1]; j < r.e[1]; ++j) {
        const double p0 = psi(r.b[0], j, r.b[2]), p1 = psi(r.b[0], j + 1, r.b[2]);
        if (p0 > 0 && p1 <= 0) y = g.lo[1] + (g.global(1, j) + 0.5 + p0 / (p0 - p1)) * g.h[1];
      }
    MPI_Allreduce(MPI_IN_PLACE, &y, 1, MPI_DOUBLE, MPI_MAX, g.comm);
    if (prevA * y < 0) crossings.push_back(prevT + (st.t - prevT) * prevA / (prevA - y));
    if (crossings.size() == 1) trough = std::min(trough, y); // between T/4 and 3T/4
    prevT = st.t, prevA = y;
  });
  ASSERT_GE(crossings.size(), 4u);
  const double measured = (crossings[3] - crossings[0]) / 1.5; // crossings T/2 apart
  const double decay = -trough / (a0 * std::cos(k * h / 2)), theory = std::exp(-2 * nu * k * k * period / 2);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0)
    std::printf("capillary wave, 32 cells per wavelength: period %.5f s, linear theory %.5f s (%+.2f %%); "
                "amplitude at T/2 %.3f of a0 (2 nu k^2: %.3f)\n",
                measured, period, 100 * (measured / period - 1), decay, theory);
  test::report("capillary_wave_period_error", measured / period - 1);
  test::report("capillary_wave_half_period_amplitude", decay);
  // Measured +2.1 % (64 cells: +0.49 %, second order). Allowed 3 %: the error at 32 cells of a
  // second-order scheme with the smoothing zone 4 cells wide (1/8 of the wavelength).
  EXPECT_NEAR(measured / period, 1.0, 0.03);
  // Damped, not amplified: the half-period amplitude (measured 0.976 against 0.969 from
  // 2 nu k^2) below 1 and not below the viscous decay less 10 %.
  EXPECT_LT(decay, 1.0);
  EXPECT_GT(decay, 0.9 * theory);
}
