// Shear wave in a periodic, fully elastic box: navier_stokes + level_set +
// elasticity (the whole pipeline: transport, H tau_S in the momentum stress,
// Benson update after the projection). Same scene as cases/shear_wave.
//
// Solid everywhere (a box shape far larger than the domain: H = 1 in every
// cell, the stress band covers the grid), rho_S = 1, mu_S = 1, c = 1; no
// viscosity. Initial u_x = U sin(k y), k = 2 pi / L, L = 1, U = 1e-3 (strain
// U k / omega = 1e-3: linear), tau_S = 0. Exact: u_x = U sin(k y) cos(omega t),
// omega = k c = 2 pi (period 1).
// Discrete prediction: velocity at nodes, stress at cell centres, so in y the
// scheme is the staggered wave equation, omega_h = (2 c / h) sin(k h / 2)
// (relative error -(k h)^2 / 24); momentum uses tau^n and the stress update
// u^{n+1} (symplectic Euler), so per step cos(theta) = 1 - (omega_h dt)^2 / 2,
// omega_d = theta / dt (+ (omega dt)^2 / 24); the amplitude is neutral.
// Measured: the modal amplitude a(t) = (2 / N) sum u_x sin(k y) over the nodes;
// the period from its zero crossings (linear interpolation, error O(dt^3))
// over 3 periods; the decay from its peaks (parabolic interpolation), fitted as
// exp(-alpha t): amplitude factor per period exp(-alpha T).
// Asserted: at 32 cells per wavelength the frequency is within 1% of omega
// (the requirement; the prediction is -0.12%), and at every resolution
// within 0.1% of omega_d (the zero-crossing interpolation and the O(U^2)
// transport terms are far below that); no amplitude growth beyond 1e-3 per
// period (the pair is neutrally stable). Decay reported; at U = 1e-3 it is
// below 2e-5 per period at every resolution: the time integration is neutral
// and the transport terms vanish for a transverse plane wave; a U = 0.05 run
// is reported as well.
// Half rotations: the scene default (elasticity.rotation: cayley). The
// assertions above do not depend on it (at U = 1e-3 the Jaumann terms are
// O(U^2)); at U = 0.05 the explicit half rotations (rotation: explicit) grew
// the amplitude by 3.7e-5 per period (their 1 + (w dt)^2 per step), the
// Cayley rotation by 1e-6: the large-amplitude run asserts < 1e-5.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "effects/elasticity/elasticity.hpp"
#include "support/flow.hpp"

using namespace voigt;

namespace {

constexpr double kK = 2 * M_PI, kOmega = 2 * M_PI; // c = 1, L = 1

std::string waveScene(int n, double periods) {
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "name: shear_wave\n"
                "domain: {lo: [0, 0, 0], hi: [%.17g, 1, %.17g], cells: [2, %d, 2], ranks: [1, 0, 1]}\n"
                "boundaries: {default: {type: periodic}}\n"
                "time: {end: %g, cfl: 0.5}\n"
                "materials: {solid: {density: 1, shear_modulus: 1}, void: {density: 1}}\n"
                "fluid: void\n"
                "effects: [navier_stokes, level_set, elasticity]\n"
                "level_set: {phase: solid, fast_marching: false,\n"
                "            shape: {type: box, lo: [-10, -10, -10], hi: [10, 10, 10]}}\n"
                "output: {enabled: false}\n",
                2.0 / n, 2.0 / n, n, periods);
  return buf;
}

// u_x = U sin(k y) at every node (owned and ghosts).
void setWave(State& st, double U) {
  const Grid& g = st.grid;
  VecField u = st.fields.vector("velocity");
  const double lo1 = g.lo[1], h1 = g.h[1];
  const int ng = g.ng, c01 = g.c0[1];
  auto ux = u.c[0];
  Kokkos::parallel_for(
      "wave", Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}), KOKKOS_LAMBDA(int i, int j, int k) {
        ux(i, j, k) = U * std::sin(kK * (lo1 + (j - ng + c01) * h1));
      });
}

double modalAmplitude(const State& st) {
  const Grid& g = st.grid;
  VecField u = st.fields.vector("velocity");
  const double lo1 = g.lo[1], h1 = g.h[1];
  const int ng = g.ng, c01 = g.c0[1];
  auto ux = u.c[0];
  const Range3 r = nodeRange(g);
  double s = 0;
  Kokkos::parallel_reduce(
      "modal", r.policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
        acc += ux(i, j, k) * std::sin(kK * (lo1 + (j - ng + c01) * h1));
      },
      s);
  double n = double(r.size());
  MPI_Allreduce(MPI_IN_PLACE, &s, 1, MPI_DOUBLE, MPI_SUM, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPI_DOUBLE, MPI_SUM, g.comm);
  return 2 * s / n;
}

struct Wave {
  double omega = 0, omegaDiscrete = 0, decayPerPeriod = 0, dt = 0;
  long steps = 0;
  double seconds = 0;
};

Wave run(int n, double periods, double U = 1e-3) {
  Simulation sim(test::scene(waveScene(n, periods)), MPI_COMM_WORLD, RunOptions{});
  sim.initialize();
  State& st = sim.state();
  setWave(st, U);
  auto* el = dynamic_cast<Elasticity*>(sim.effect("elasticity"));
  EXPECT_NE(el, nullptr);
  const double T = periods * 2 * M_PI / kOmega;
  std::vector<double> t{0}, a{modalAmplitude(st)};
  const double t0 = MPI_Wtime();
  Wave w;
  // Uniform steps of the elastic-wave limit (constant: material and h) until T is
  // passed, not clipped to land on it: the peak fit below assumes equal spacing.
  const DtLimit lim = sim.stableDt();
  EXPECT_EQ(lim.reason, "elastic wave");
  w.dt = lim.dt;
  long steps = 0;
  for (double tt = 0; tt < T * (1 - 1e-12); tt += w.dt) ++steps; // st.t's own sums
  sim.engine().advanceSteps(steps, w.dt, [&](const State& s) {
    t.push_back(s.t);
    a.push_back(modalAmplitude(st));
    EXPECT_EQ(s.diag.at("stress_cells"), double(s.grid.cellsGlobal()));
  });
  w.seconds = MPI_Wtime() - t0;
  w.steps = st.step;
  // Zero crossings.
  std::vector<double> zc;
  for (size_t q = 1; q < a.size(); ++q)
    if ((a[q - 1] > 0) != (a[q] > 0)) zc.push_back(t[q - 1] + (t[q] - t[q - 1]) * a[q - 1] / (a[q - 1] - a[q]));
  EXPECT_GE(zc.size(), 4u);
  if (zc.size() >= 2) w.omega = M_PI * double(zc.size() - 1) / (zc.back() - zc.front());
  // Peaks of |a| (parabolic through 3 samples), log-linear fit. Not t = 0:
  // with tau^0 = 0 the discrete mode peaks half a step later, above U.
  std::vector<double> pt, pa;
  for (size_t q = 1; q + 1 < a.size(); ++q) {
    const double y0 = std::abs(a[q - 1]), y1 = std::abs(a[q]), y2 = std::abs(a[q + 1]);
    if (y1 >= y0 && y1 > y2) {
      const double den = y0 - 2 * y1 + y2, d = den != 0 ? 0.5 * (y0 - y2) / den : 0;
      pt.push_back(t[q] + d * (t[q + 1] - t[q]));
      pa.push_back(std::log(y1 - 0.25 * (y0 - y2) * d));
    }
  }
  double st_ = 0, sa = 0, stt = 0, sta = 0;
  const double m = double(pt.size());
  for (size_t q = 0; q < pt.size(); ++q) st_ += pt[q], sa += pa[q], stt += pt[q] * pt[q], sta += pt[q] * pa[q];
  const double slope = (m * sta - st_ * sa) / (m * stt - st_ * st_);
  w.decayPerPeriod = std::exp(slope * 2 * M_PI / kOmega);
  const double h = 1.0 / n;
  const double omegaH = 2 / h * std::sin(kK * h / 2);
  w.omegaDiscrete = std::acos(1 - 0.5 * std::pow(omegaH * w.dt, 2)) / w.dt;
  return w;
}

} // namespace

TEST(ShearWave, FrequencyAndDecay) {
  for (int n : {16, 32, 64}) {
    const Wave w = run(n, 3);
    const std::string key = "n" + std::to_string(n);
    test::report(key + "_omega_over_exact_minus_1", w.omega / kOmega - 1);
    test::report(key + "_omega_discrete_prediction_over_exact_minus_1", w.omegaDiscrete / kOmega - 1);
    test::report(key + "_omega_over_discrete_prediction_minus_1", w.omega / w.omegaDiscrete - 1);
    test::report(key + "_amplitude_factor_per_period", w.decayPerPeriod);
    test::report(key + "_steps", double(w.steps));
    test::report(key + "_seconds", w.seconds);
    if (n == 32) EXPECT_LT(std::abs(w.omega / kOmega - 1), 0.01);
    EXPECT_LT(std::abs(w.omega / w.omegaDiscrete - 1), 1e-3);
    EXPECT_LT(w.decayPerPeriod, 1 + 1e-3);
  }
}

// A 50x larger amplitude (strain 5%, U / c = 0.05). In a transverse plane
// wave the transport terms vanish identically (u = u_x(y) moves along x, every
// field varies along y), so what changes is due to the Jaumann terms
// (O(strain): normal stresses, a frequency shift O(strain^2)). The Cayley half
// rotations keep the amplitude (growth < 1e-5 per period; the explicit ones
// gave 3.7e-5, header).
TEST(ShearWave, LargeAmplitudeReport) {
  const Wave w = run(32, 3, 0.05);
  test::report("n32_U0.05_omega_over_exact_minus_1", w.omega / kOmega - 1);
  test::report("n32_U0.05_amplitude_factor_per_period", w.decayPerPeriod);
  EXPECT_LT(w.decayPerPeriod, 1 + 1e-5);
}
