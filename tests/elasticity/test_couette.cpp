// Oscillatory Couette flow over an elastic layer (cases/elastic_couette): a gel
// layer 0 < y < a bonded to the fixed wall y = 0, water above it, the wall
// y = b moving as V sin(omega t). Started from the exact periodic state
// (tests/elasticity/couette_exact.hpp; derivation in the case README) and run
// for one period, the velocity profile must stay on the analytic one.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "effects/elasticity/elasticity.hpp"
#include "elasticity/couette_exact.hpp"
#include "kernels/reductions.hpp"
#include "support/flow.hpp"

using namespace voigt;

namespace {

// Parameters of cases/elastic_couette/elastic_couette.yaml: k_s a = 1.42 (the
// solid layer a little below its quarter-wave resonance: max |u| in the solid
// = 0.36 V), fluid |k_f| (b - a) = 2.7 (the Stokes layer reaches the
// interface), strain below 1e-3 (linear regime).
constexpr double kRho = 1000, kG = 100, kMu = 0.3, kA = 0.005, kB = 0.01, kV = 1e-4, kOmega = 90;
constexpr double kPeriod = 2 * M_PI / kOmega;

test::ElasticCouette exact() { return {kRho, kG, 0.0, kRho, kMu, kA, kB, kV, kOmega}; }

// ny cells across the gap; x and z are periodic, two cubic cells each (only y
// matters). Cubic cells: see test_kelvin_voigt.cpp on flat cells and the
// viscous dt limit.
std::string couetteScene(int ny, double periods) {
  char buf[1600];
  std::snprintf(buf, sizeof buf,
                "name: elastic_couette\n"
                "domain: {lo: [0, 0, 0], hi: [%.17g, %g, %.17g], cells: [2, %d, 2], ranks: [1, 0, 1]}\n"
                "boundaries:\n"
                "  default: {type: periodic}\n"
                "  y-: {type: no_slip}\n"
                "  y+: {type: no_slip, velocity: [%g, 0, 0], oscillation: {omega: %g}}\n"
                "materials:\n"
                "  water: {density: %g, viscosity: %g}\n"
                "  gel: {density: %g, shear_modulus: %g}\n"
                "fluid: water\n"
                "effects: [navier_stokes, level_set, elasticity]\n"
                "level_set: {phase: gel, shape: {type: plane, point: [0, %g, 0], normal: [0, 1, 0]}}\n"
                "time: {end: %.17g, cfl: 0.5, viscous_safety: 0.9}\n"
                "projection: {tolerance: 1e-6} # rhs: O(U^2) normal stresses only\n"
                "output: {enabled: false}\n",
                2 * kB / ny, kB, 2 * kB / ny, ny, kV, kOmega, kRho, kMu, kRho, kG, kA, periods * kPeriod);
  return buf;
}

// Velocity at the nodes and solid stress tau_S,xy at the cells from the exact
// periodic state at time t, over the whole arrays (ghosts included: the state
// depends on y only, so periodic and interior ghosts are consistent).
void setExactState(State& st, const test::ElasticCouette& ex, double t) {
  const Grid& g = st.grid;
  VecField u = st.fields.vector("velocity");
  SymTensorField tau = solidStressField(st.fields);
  auto hu = Kokkos::create_mirror_view(u.c[0]);
  auto ht = Kokkos::create_mirror_view(tau.c[3]);
  for (int k = 0; k < g.ext[2]; ++k)
    for (int j = 0; j < g.ext[1]; ++j)
      for (int i = 0; i < g.ext[0]; ++i) {
        const double y = g.lo[1] + g.global(1, j) * g.h[1];
        hu(i, j, k) = ex.velocity(y, t);
        ht(i, j, k) = ex.elasticStress(y + 0.5 * g.h[1], t);
      }
  Kokkos::deep_copy(u.c[0], hu);
  Kokkos::deep_copy(tau.c[3], ht);
  for (int c = 1; c < 3; ++c) Kokkos::deep_copy(u.c[c], 0.0);
  for (int c : {0, 1, 2, 4, 5}) Kokkos::deep_copy(tau.c[c], 0.0);
}

struct Result {
  test::ErrorNorms err;        // node velocity error / V
  test::ErrorNorms solid;      // same, nodes with y < a only
  double seconds = 0;
};

Result runCouette(int ny, double periods) {
  const auto ex = exact();
  Scene s = test::scene(couetteScene(ny, periods));
  RunOptions opt;
  opt.progress = false;
  Simulation sim(s, MPI_COMM_WORLD, opt);
  sim.initialize();
  setExactState(sim.state(), ex, 0.0);
  const auto t0 = std::chrono::steady_clock::now();
  sim.run();
  Result r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const State& st = sim.state();
  const double t = st.t;
  EXPECT_NEAR(t, periods * kPeriod, 1e-12);
  auto exactU = [&](const Vec3& x, int c) { return c == 0 ? ex.velocity(x[1], t) : 0.0; };
  VecField u = st.fields.vector("velocity");
  r.err = test::nodeError(st.grid, u, exactU);
  r.err.l2 /= kV;
  r.err.linf /= kV;
  // The same over the solid's nodes (y < a) only.
  {
    const Grid& g = st.grid;
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), u.c[0]);
    auto rg = nodeRange(g);
    double s2 = 0, m = 0;
    long long n = 0;
    for (int k = rg.b[2]; k < rg.e[2]; ++k)
      for (int j = rg.b[1]; j < rg.e[1]; ++j)
        for (int i = rg.b[0]; i < rg.e[0]; ++i) {
          const double y = test::nodePos(g, i, j, k)[1];
          if (y >= kA) continue;
          const double e = h(i, j, k) - ex.velocity(y, t);
          s2 += e * e;
          m = std::max(m, std::abs(e));
          ++n;
        }
    MPI_Allreduce(MPI_IN_PLACE, &s2, 1, MPI_DOUBLE, MPI_SUM, g.comm);
    MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPI_LONG_LONG, MPI_SUM, g.comm);
    MPI_Allreduce(MPI_IN_PLACE, &m, 1, MPI_DOUBLE, MPI_MAX, g.comm);
    r.solid.l2 = std::sqrt(s2 / n) / kV;
    r.solid.linf = m / kV;
  }
  // The other velocity components stay at round-off (the flow is a pure shear).
  double other = 0;
  for (int c = 1; c < 3; ++c) other = std::max(other, globalMaxAbs(st.grid, u.c[c], nodeRange(st.grid)));
  EXPECT_LT(other, 1e-9 * kV) << ny << " cells";

  // Profiles for cases/elastic_couette/couette.py --csv DIR (1 rank only).
  if (const char* dir = std::getenv("VOIGT_COUETTE_PROFILES"); dir && st.grid.size == 1) {
    const Grid& g = st.grid;
    std::ofstream f(std::string(dir) + "/profile_" + std::to_string(ny) + ".csv");
    f.precision(12);
    f << "# elastic Couette, t=" << t << " (" << periods << " periods), cells across " << ny << "\n";
    f << "# y,u_numerical,u_exact\n";
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), u.c[0]);
    auto rg = nodeRange(g);
    for (int j = rg.b[1]; j < rg.e[1]; ++j) {
      const double y = test::nodePos(g, g.ng, j, g.ng)[1];
      f << y << "," << h(g.ng, j, g.ng) << "," << ex.velocity(y, t) << "\n";
    }
  }
  return r;
}

} // namespace

// One period at 24 and 48 cells across the gap (12 and 24 per layer), errors
// relative to V. The interface is smoothed over kappa = 2 cells (Eq. 4): inside
// |y - a| < kappa the medium is the Kelvin-Voigt blend of Eq. (15), a layer of
// width 2 kappa whose compliance differs from the sharp interface's by
// O(kappa) = O(h). That smoothing error dominates: the periodic state of the
// smoothed 1-D problem (cases/elastic_couette/couette.py --smoothing 24 48, a
// fine-grid solve of i omega rho(y) U = (M(y) U')' with the blended rho and M)
// differs from the sharp solution at t = T by RMS/V 6.30e-3 and 4.06e-3 (max
// 1.26e-2 and 8.21e-3), order 0.64 between these two grids (0.83 and 0.91 at
// the next doublings: first order). Measured: RMS 6.09e-3 and 3.39e-3, max
// 1.22e-2 and 6.96e-3, order 0.84. Bounds: 1.5x the smoothing-model error at
// each grid, and an observed order in [0.5, 1.5] (first order, the model's
// pre-asymptotic 0.64 included).
TEST(ElasticCouette, ProfilesMatchTheAnalyticSolution) {
  const Result r24 = runCouette(24, 1), r48 = runCouette(48, 1);
  test::report("couette_l2_24", r24.err.l2);
  test::report("couette_max_24", r24.err.linf);
  test::report("couette_solid_l2_24", r24.solid.l2);
  test::report("couette_seconds_24", r24.seconds);
  test::report("couette_l2_48", r48.err.l2);
  test::report("couette_max_48", r48.err.linf);
  test::report("couette_solid_l2_48", r48.solid.l2);
  test::report("couette_seconds_48", r48.seconds);
  const double order = std::log2(r24.err.l2 / r48.err.l2);
  test::report("couette_order_l2", order);
  test::report("couette_order_max", std::log2(r24.err.linf / r48.err.linf));
  EXPECT_LT(r24.err.l2, 1.5 * 6.30e-3);
  EXPECT_LT(r24.err.linf, 1.5 * 1.26e-2);
  EXPECT_LT(r48.err.l2, 1.5 * 4.06e-3);
  EXPECT_LT(r48.err.linf, 1.5 * 8.21e-3);
  EXPECT_GT(order, 0.5);
  EXPECT_LT(order, 1.5);
}
