// Rayleigh-Taylor instability, density ratio 3 (Atwood A = 0.5), equal
// kinematic viscosities: the set-up of He, Chen & Zhang (1999), J. Comput.
// Phys. 152, 642 (cases/rayleigh_taylor/README.md has the sources and the
// full numbers). Units: H = g = 1 (H the wavelength), so t here is He's
// t* = t sqrt(g/H); Tryggvason's time is t_T = t sqrt(A g/H) = t / sqrt(2).
//   heavy (rho 3) above light (rho 1), nu = sqrt(g H) H / Re, Re = 256;
//   interface y = 2H + a0 cos(2 pi x / H), half a wavelength 0 <= x <= H/2
//   with slip sides (mirror symmetry = the periodic problem), no-slip
//   top and bottom; 2 cells in z, periodic, never split over ranks; x is
//   not split either (ranks [1,0,1]): MPI_Dims_create would split the
//   16-32 cells across before the 128-256 along y, 3x slower at 2 ranks.
// The bubble (light fluid rising) is on the axis x = 0, the spike (heavy
// fluid falling) on x = H/2.
//
// 1. Linear growth (a0 = 0.001 H): the growth rate of the interface's
//    cos(kx) mode against the viscous linear theory (linear_theory.py in the
//    case folder: Chandrasekhar's two-fluid problem with equal nu, solved
//    exactly, and the same problem with our smoothed density profile).
// 2. Nonlinear stage (a0 = 0.1 H): bubble and spike tip heights at
//    t_T = 1.0, 1.5, 2.0 against He et al.'s published curves.
//
// The two-fluid rest test is in test_two_phase.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

#include "support/flow.hpp"

using namespace voigt;

namespace {

constexpr double kRe = 256;           // He et al. (1999): Re = sqrt(g H) H / nu
constexpr double kNu = 1.0 / kRe;     // H = g = 1
constexpr double kK = 2 * M_PI;       // wavenumber of the mode (wavelength H)
constexpr double kSqrtA = 0.70710678118654752; // t_T = t * sqrt(A), A = 0.5

bool longRuns() {
  const char* v = std::getenv("VOIGT_LONG");
  return v && std::string(v) == "1";
}

int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

// Half a wavelength, n cells across it (h = 1 / (2n)), `height` tall with the
// interface at mid height. The scene's `wave` shape puts the same zero level
// there; the nonlinear test replaces psi by a closed-form distance anyway.
std::string rtScene(int n, double height, double amp, const std::string& op, const std::string& tol = "1e-8") {
  const double h = 0.5 / n;
  const int ny = int(std::lround(height / h));
  return "name: rt\n"
         "domain: {lo: [0,0,0], hi: [0.5, " + std::to_string(height) + ", " + std::to_string(2 * h) +
         "], cells: [" + std::to_string(n) + "," + std::to_string(ny) + ",2], ranks: [1,0,1]}\n"
         "boundaries: {default: {type: no_slip}, x-: {type: slip}, x+: {type: slip},"
         " z-: {type: periodic}, z+: {type: periodic}}\n"
         "time: {end: 10, cfl: 0.5}\n"
         "materials: {heavy: {density: 3, viscosity: " + std::to_string(3 * kNu) +
         "}, light: {density: 1, viscosity: " + std::to_string(kNu) + "}}\n"
         "fluid: light\n"
         "gravity: [0, -1, 0]\n"
         "effects: [navier_stokes, gravity, level_set, reinit]\n"
         // normal -y: heavy (psi > 0) above; the plane moves by -amplitude
         // cos along -y, i.e. y = height/2 + amp cos(2 pi x).
         "level_set: {phase: heavy, shape: {type: wave, point: [0, " + std::to_string(height / 2) +
         ", 0], normal: [0,-1,0], direction: [1,0,0], amplitude: " + std::to_string(-amp) +
         ", wavelength: 1}}\n"
         "projection: {operator: " + op + ", preconditioner: multigrid, tolerance: " + tol +
         ", max_iterations: 5000}\n"
         "output: {enabled: false}\n";
}

// psi = (y - eta(x)) / sqrt(1 + eta'(x)^2), eta = y0 + a cos(k x): the signed
// distance to first order in the local curvature, on every local cell
// (ghosts included), so the first step starts from an exact-enough distance
// whatever Fast Marching does with the `wave` shape.
void setCosineInterface(Simulation& sim, double y0, double a) {
  State& st = sim.state();
  const Grid& g = st.grid;
  Field psi = st.fields.scalar("psi");
  const double lo0 = g.lo[0], lo1 = g.lo[1], h0 = g.h[0], h1 = g.h[1], k = kK;
  const int ng = g.ng, c00 = g.c0[0], c01 = g.c0[1];
  Kokkos::parallel_for(
      "rt_psi", Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}), KOKKOS_LAMBDA(int i, int j, int kk) {
        const double x = lo0 + (i - ng + c00 + 0.5) * h0, y = lo1 + (j - ng + c01 + 0.5) * h1;
        const double eta = y0 + a * std::cos(k * x), slope = -a * k * std::sin(k * x);
        psi(i, j, kk) = (y - eta) / std::sqrt(1 + slope * slope);
      });
  Kokkos::fence();
  st.propertiesChanged = true; // the Properties stage re-blends rho, mu from psi
}

// Heights where psi changes sign in owned column (global) ic: every crossing
// between owned cell j and cell j+1 (j+1 may be a ghost: psi's ghosts are
// fresh after each step), linear interpolation between centres.
std::vector<double> crossings(const Grid& g, const Kokkos::View<double***, Kokkos::LayoutLeft, Kokkos::HostSpace>& psi,
                              int ic) {
  std::vector<double> ys;
  if (ic < g.c0[0] || ic >= g.c1[0]) return ys;
  const int i = g.local(0, ic), k = g.ng;
  const Range3 r = cellRange(g);
  for (int j = r.b[1]; j < r.e[1]; ++j) {
    if (g.global(1, j) + 1 >= g.n[1]) break;
    const double a = psi(i, j, k), b = psi(i, j + 1, k);
    if ((a > 0) == (b > 0)) continue;
    const double yc = g.lo[1] + (g.global(1, j) + 0.5) * g.h[1];
    ys.push_back(yc + g.h[1] * a / (a - b));
  }
  return ys;
}

auto hostPsi(State& st) {
  Field psi = st.fields.scalar("psi");
  st.halo->exchange(psi);
  return Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), psi);
}

// Tip heights on the axes. The cell centres nearest the axes sit h/2 and
// 3h/2 off them; the interface is even about each axis, y = y0 + c x^2 + ...,
// so y(axis) = (9 y(h/2) - y(3h/2)) / 8 to O(h^4) of the shape.
struct Tips {
  double bubble = 0, spike = 0;
};
Tips tips(State& st) {
  const Grid& g = st.grid;
  auto psi = hostPsi(st);
  const int n = g.n[0];
  const double inf = std::numeric_limits<double>::infinity();
  double b[2] = {-inf, -inf}, s[2] = {inf, inf}; // highest light / lowest heavy crossing
  for (int c = 0; c < 2; ++c) {
    for (double y : crossings(g, psi, c)) b[c] = std::max(b[c], y);
    for (double y : crossings(g, psi, n - 1 - c)) s[c] = std::min(s[c], y);
  }
  MPI_Allreduce(MPI_IN_PLACE, b, 2, MPI_DOUBLE, MPI_MAX, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, s, 2, MPI_DOUBLE, MPI_MIN, g.comm);
  return {(9 * b[0] - b[1]) / 8, (9 * s[0] - s[1]) / 8};
}

// Amplitude of the cos(kx) mode of the interface height eta(x) (one crossing
// per column in the linear stage): a = (2/n) sum_i eta_i cos(k x_i), exact for
// the midpoint columns over half a wavelength; the mean height drops out.
double modeAmplitude(State& st) {
  const Grid& g = st.grid;
  auto psi = hostPsi(st);
  std::vector<double> eta(g.n[0], 0.0), count(g.n[0], 0.0);
  for (int ic = g.c0[0]; ic < g.c1[0]; ++ic)
    for (double y : crossings(g, psi, ic)) eta[ic] += y, count[ic] += 1;
  MPI_Allreduce(MPI_IN_PLACE, eta.data(), g.n[0], MPI_DOUBLE, MPI_SUM, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, count.data(), g.n[0], MPI_DOUBLE, MPI_SUM, g.comm);
  double a = 0;
  for (int ic = 0; ic < g.n[0]; ++ic) {
    if (count[ic] != 1) return std::numeric_limits<double>::quiet_NaN(); // not a single-valued interface
    a += eta[ic] * std::cos(kK * (g.lo[0] + (ic + 0.5) * g.h[0]));
  }
  return 2 * a / g.n[0];
}

// ---------------------------------------------------------------------------
// 1. Linear growth rate.
// ---------------------------------------------------------------------------
// Theory (cases/rayleigh_taylor/linear_theory.py, k = 2 pi, A = 0.5, nu = 1/256):
//   inviscid sqrt(A g k)                                1.7725
//   sharp interface, viscous, exact (Chandrasekhar)     1.4928
//   sqrt(A g k + nu^2 k^4) - nu k^2 (irrotational approx.) 1.6249  (8.9% above
//       the exact rate: it misses the vortical layer at the interface that
//       carries the jump of the inviscid tangential velocity, O(sqrt(nu)))
//   smoothed interface, kappa = 2h, h = 1/64            1.4804  (-0.8%)
//                                   h = 1/32            1.4578  (-2.3%)
// The smoothing of Eq. (4) spreads the density jump over 2 kappa = 4h and
// lowers the rate by 0.8% at h = 1/64 (k kappa = 0.20).
//
// Measurement: a 2H-tall box (walls H from the interface, as in the theory:
// they change the rate by ~e^{-2kH} = 4e-6), a0 = 0.001 H (k a <= 0.12
// throughout), interface height from
// the psi zero crossing in every column, its cos(kx) Fourier amplitude a(t)
// sampled every 0.1, and sigma from a least-squares fit of
//   a(t) = C1 e^{sigma t} + C2 e^{-sigma t}      over t in [1.0, 2.4]
// (relative residuals; the second term is the decaying partner that a start
// from rest excites, a0 cosh(sigma t) in the inviscid limit; a plain
// log-slope over the window [1.2, 2.4] reads 1% low because of it).
struct Growth {
  double sigma = 0, fitResidual = 0, a0 = 0, aEnd = 0;
  long steps = 0;
  double seconds = 0;
};

// Best sigma in [lo, hi] of the two-exponential model: for each sigma the
// weighted linear least squares in (C1, C2) is a 2x2 solve; sigma is scanned
// at 1e-4 resolution (the fit is cheap, the scan robust).
std::pair<double, double> fitTwoExponentials(const std::vector<double>& t, const std::vector<double>& a, double lo,
                                             double hi) {
  double best = std::numeric_limits<double>::infinity(), bestS = 0;
  for (double s = lo; s <= hi; s += 1e-4) {
    double m11 = 0, m12 = 0, m22 = 0, r1 = 0, r2 = 0;
    for (size_t i = 0; i < t.size(); ++i) {
      const double e1 = std::exp(s * t[i]) / a[i], e2 = std::exp(-s * t[i]) / a[i];
      m11 += e1 * e1, m12 += e1 * e2, m22 += e2 * e2, r1 += e1, r2 += e2;
    }
    const double det = m11 * m22 - m12 * m12;
    const double c1 = (r1 * m22 - r2 * m12) / det, c2 = (m11 * r2 - m12 * r1) / det;
    double res = 0;
    for (size_t i = 0; i < t.size(); ++i) {
      const double e = (c1 * std::exp(s * t[i]) + c2 * std::exp(-s * t[i])) / a[i] - 1;
      res += e * e;
    }
    if (res < best) best = res, bestS = s;
  }
  return {bestS, std::sqrt(best / t.size())};
}

Growth measureGrowth(int n, const std::string& op, double a0 = 0.001) {
  const double height = 2;
  Simulation sim(test::scene(rtScene(n, height, a0, op)), MPI_COMM_WORLD);
  sim.initialize();
  setCosineInterface(sim, height / 2, a0);
  const double w0 = MPI_Wtime();
  std::vector<double> ts, as;
  Growth out;
  out.a0 = modeAmplitude(sim.state());
  // Sample at fixed times so every resolution and rank count fits the same points.
  for (int s = 1; s <= 24; ++s) {
    const double t = 0.1 * s;
    sim.advanceTo(t);
    const double a = modeAmplitude(sim.state());
    if (std::getenv("VOIGT_RT_TRACE") && rank() == 0) // a(t) trace
      printf("rt trace n=%d t = %.2f a = %.6e\n", n, t, a);
    if (t >= 1.0 - 1e-9) ts.push_back(t), as.push_back(a);
    out.aEnd = a;
  }
  std::tie(out.sigma, out.fitResidual) = fitTwoExponentials(ts, as, 1.0, 2.0);
  out.steps = sim.state().step;
  out.seconds = MPI_Wtime() - w0;
  return out;
}

// Theory at h = 1/64 (smoothed profile) and for the sharp interface.
constexpr double kSigmaSmoothed64 = 1.4804, kSigmaSharp = 1.4928;

void printGrowth(const char* label, int n, const std::string& op, const Growth& g) {
  if (rank() == 0)
    printf("rt linear %s n=%d (h=1/%d) %s: sigma = %.4f (fit rms %.1e), a %.3e -> %.3e; %ld steps, %.1f s\n", label, n,
           2 * n, op.c_str(), g.sigma, g.fitResidual, g.a0, g.aEnd, g.steps, g.seconds);
}

} // namespace

// Approximate (7-point) projection: in this test it gives the same a(t) as the
// exact operator to 1e-6 relative, at a fifth of the cost (the exact operator
// needs 100-1400 CG iterations a step here; case README).
// Measured (h = 1/32, 1/64, 1/128): sigma = 1.4194, 1.4686, 1.4844, i.e.
// -2.6%, -0.8%, -0.26% against the smoothed-profile theory of each grid
// (1.4578, 1.4804, 1.4883): convergence at order 1.6-1.7, and the Richardson
// extrapolation of the two finest, 1.4926, is the sharp-interface 1.4928.
// Tolerances: 2% of the smoothed theory (2.5x the measured discretisation
// error at h = 1/64, which also moved by 0.5% with changes to reinit during
// development) and 3% of the sharp one (adds the 0.8% smoothing effect). The
// alternatives are far outside: irrotational approximation 1.6249 (+9.8%),
// inviscid 1.7725; a0 = 0.0005 instead of 0.001 changes sigma by 0.07%.
TEST(RayleighTaylor, LinearGrowthRateMatchesViscousTheory) {
  const Growth g = measureGrowth(32, "approximate");
  printGrowth("", 32, "approximate", g);
  RecordProperty("sigma", std::to_string(g.sigma));
  EXPECT_NEAR(g.sigma / kSigmaSmoothed64, 1.0, 0.02);
  EXPECT_NEAR(g.sigma / kSigmaSharp, 1.0, 0.03);
  EXPECT_LT(g.sigma, 1.58); // not the irrotational approximation
  EXPECT_LT(g.fitResidual, 2e-3); // the two-exponential model describes a(t)
}

// ---------------------------------------------------------------------------
// 2. Nonlinear stage: tip heights against He, Chen & Zhang (1999), their
// curves of the bubble and spike positions, digitised by the Lethe project
// (examples/multiphysics/rayleigh-taylor-instability/ref_He_et_al_data.txt,
// y / 4H against t*), interpolated to t_T = 1.0, 1.5, 2.0 and written as
// displacements from y = 2H, units of H.
// ---------------------------------------------------------------------------
namespace {

struct Reference {
  double tT, bubble, spike;
};
const Reference kHe1999[] = {{1.0, 0.274, -0.348}, {1.5, 0.419, -0.602}, {2.0, 0.546, -0.873}};

struct TipRun {
  std::vector<Tips> at;
  long steps = 0;
  double seconds = 0;
};

TipRun runTips(int n, const std::string& op) {
  const double height = 4, a0 = 0.1;
  Simulation sim(test::scene(rtScene(n, height, a0, op)), MPI_COMM_WORLD);
  sim.initialize();
  setCosineInterface(sim, height / 2, a0);
  TipRun out;
  const double w0 = MPI_Wtime();
  for (const Reference& r : kHe1999) {
    sim.advanceTo(r.tT / kSqrtA);
    Tips t = tips(sim.state());
    t.bubble -= 2, t.spike -= 2;
    out.at.push_back(t);
  }
  out.steps = sim.state().step;
  out.seconds = MPI_Wtime() - w0;
  return out;
}

void printTips(int n, const std::string& op, const TipRun& r) {
  if (rank() != 0) return;
  for (size_t i = 0; i < r.at.size(); ++i)
    printf("rt tips n=%d (h=1/%d) %s t_T=%.1f: bubble %+.4f (He %+.3f), spike %+.4f (He %+.3f)\n", n, 2 * n,
           op.c_str(), kHe1999[i].tT, r.at[i].bubble, kHe1999[i].bubble, r.at[i].spike, kHe1999[i].spike);
  printf("rt tips n=%d %s: %ld steps, %.1f s\n", n, op.c_str(), r.steps, r.seconds);
}

} // namespace

// Two grids, h = 1/32 and 1/64, approximate projection (the exact one gives
// the same tips to 4 digits at 4.5 times the cost). On each tip and time:
//   |y(1/64) - He| <= 0.03 H + |y(1/64) - y(1/32)|
// 0.03 H is the published uncertainty: the digitised curves start 0.01 H off
// the exact initial heights, and two codes (He et al. 1999, Re 256; Fakhari
// et al. 2017, Re 3000 with weak surface tension) differ by up to 0.02 H at
// these times. |y(1/64) - y(1/32)| bounds our grid error at h = 1/64 when the
// tips converge at first order or better (measured: order 1.1-1.5 for the
// spike over h = 1/32, 1/64, 1/128; the spike, a thin finger 4h-smoothed,
// converges slowest). And the spike must approach He et al. as h shrinks.
TEST(RayleighTaylor, TipPositionsMatchHe1999) {
  const TipRun coarse = runTips(16, "approximate"), fine = runTips(32, "approximate");
  printTips(16, "approximate", coarse);
  printTips(32, "approximate", fine);
  for (size_t i = 0; i < fine.at.size(); ++i) {
    const Reference& ref = kHe1999[i];
    const Tips& c = coarse.at[i];
    const Tips& f = fine.at[i];
    EXPECT_LE(std::abs(f.bubble - ref.bubble), 0.03 + std::abs(f.bubble - c.bubble)) << "bubble, t_T = " << ref.tT;
    EXPECT_LE(std::abs(f.spike - ref.spike), 0.03 + std::abs(f.spike - c.spike)) << "spike, t_T = " << ref.tT;
    EXPECT_LT(std::abs(f.spike - ref.spike), std::abs(c.spike - ref.spike)) << "spike, t_T = " << ref.tT;
    RecordProperty("spike_tT" + std::to_string(int(10 * ref.tT)), std::to_string(f.spike));
  }
}

// VOIGT_LONG=1: grid convergence and the exact projection, for the case
// README. Run one at a time with --gtest_filter=RayleighTaylor.Long*.
TEST(RayleighTaylor, LongLinearConvergence) {
  if (!longRuns()) GTEST_SKIP() << "set VOIGT_LONG=1";
  for (int n : {16, 64}) printGrowth("", n, "approximate", measureGrowth(n, "approximate"));
  printGrowth("a0=0.0005", 32, "approximate", measureGrowth(32, "approximate", 0.0005));
}

TEST(RayleighTaylor, LongTipsFine) {
  if (!longRuns()) GTEST_SKIP() << "set VOIGT_LONG=1";
  printTips(64, "approximate", runTips(64, "approximate"));
}

TEST(RayleighTaylor, LongExactProjection) {
  if (!longRuns()) GTEST_SKIP() << "set VOIGT_LONG=1";
  printGrowth("", 32, "exact", measureGrowth(32, "exact"));
  printTips(16, "exact", runTips(16, "exact"));
  printTips(32, "exact", runTips(32, "exact"));
}
