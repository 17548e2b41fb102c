// The stability matrix (issue 7, "Stability suite"): hard scenes on reduced
// grids, each run for a fixed number of steps, each asserting that
//  - the run completes its steps (Simulation::advance throws BlowUp on any
//    non-finite value in any field: completing is the finiteness check);
//  - energy stays bounded: E = kinetic + elastic;
//      unforced: max_t E(t) / E(0) - 1 <= tol;
//      gravity:  E_mech = E + potential energy (-sum rho g.x dV over cells)
//                must not grow: max_t (E_mech(t) - E_mech(0)) / E_scale <= tol,
//                E_scale = E(0) + |rho_1 - rho_2| g V_phase H (the most the
//                phase could release falling through the whole height H);
//      tol is computed per run from the known discrete error sources (volume
//      drift, the hypoelastic energy measure at the run's peak strain, 1e-3 for
//      solver and time integration; see runCase), never tuned;
//      forced (inflow, porous bed): no runaway, stated with the case;
//      rotation (kinematic): the stress amplitude, see Energy::Amplitude;
//  - the phase volume drift (level_set diag volume_drift) stays under a bound;
//  - the projection leaves the divergence at solver tolerance: the exact
//    operator's projected divergence is dt times the CG residual, so
//    max|div after| <= tol_CG ||b||_2 <= tol_CG sqrt(N) max|div before|
//    (diag max_divergence vs max_divergence_predicted), checked every step.
// VOIGT_STABILITY_FULL=1 selects the full matrix (finer grids, longer runs,
// the porous bed); scripts/stability-matrix runs it and prints the table. Each
// case prints one "[ matrix ] |...|" markdown row on rank 0:
//   case | grid | steps | max energy growth | allowed | max volume drift |
//   volume corrected (the global correction's moved volume, relative) |
//   max divergence after projection (1/s) | status | wall s | ranks | dt reasons
// Diagnosis: VOIGT_STABILITY_TRACE=1 prints ~25 rows of each run's series,
// VOIGT_STABILITY_SPLIT=1 the kinetic energy and max speed split into heavy /
// interface / light nodes every 10 steps (rank 0's part of the grid).
// VOIGT_STABILITY_SET="key=value ..." applies --set overrides to every case
// that has the key's section (matrix_runner.hpp), e.g. level_set.smoothing=1.
#include "stability/matrix_runner.hpp"


// ---------------------------------------------------------------------------
// Scenes. Unit cube (or as stated), no-slip walls unless stated, the defaults
// (adaptive dt at cfl 0.5, exact projection at its default tolerance).
namespace {

struct Grid3 {
  int nx, ny, nz;
};

// The defaults a user gets: adaptive dt, no projection section (issue 50).
std::string header(const char* name, double lx, double ly, double lz, Grid3 n, const std::string& bc) {
  return fmt("name: %s\n"
             "domain: {lo: [0, 0, 0], hi: [%g, %g, %g], cells: [%d, %d, %d]}\n"
             "boundaries: %s\n"
             "time: {end: 1.0e9}\n"
             "output: {enabled: false}\n",
             name, lx, ly, lz, n.nx, n.ny, n.nz, bc.c_str());
}

const char* kWalls = "{default: {type: no_slip}}";

// Ratio-1000 two-phase: a water drop falling through air, or an air bubble rising in water.
std::string twoPhase(bool heavyDrop, Grid3 n) {
  const double lx = 1, ly = 1, lz = 1, R = 0.2;
  std::string s = header(heavyDrop ? "drop" : "bubble", lx, ly, lz, n, kWalls);
  s += "materials: {water: {density: 1000, viscosity: 1.0e-3}, air: {density: 1, viscosity: 1.8e-5}}\n";
  s += heavyDrop ? "fluid: air\n" : "fluid: water\n";
  s += "gravity: [0, -9.81, 0]\n"
       "effects: [navier_stokes, gravity, level_set, reinit]\n";
  s += fmt("level_set: {phase: %s, shape: {type: sphere, center: [0.5, %g, 0.5], radius: %g}}\n",
           heavyDrop ? "water" : "air", heavyDrop ? 0.7 : 0.3, R);
  return s;
}

} // namespace

// Density ratio 1000. Energy: gravity (E_mech must not grow); volume drift and
// divergence as stated in the header.
TEST(StabilityMatrix, HeavyDropRatio1000) {
  const Grid3 n = full() ? Grid3{24, 24, 24} : Grid3{16, 16, 16};
  const long steps = full() ? 300 : 150;
  const double V = 4.0 / 3 * M_PI * 0.2 * 0.2 * 0.2;
  auto r = runCase("drop_ratio1000", cellsText(n.nx, n.ny, n.nz), twoPhase(true, n), steps, Energy::Gravity,
                   999 * V);
  expectStable(r, steps, 0.37); // measured 0.29 (radius 3.2 cells, splashes on the floor)
}

TEST(StabilityMatrix, LightBubbleRatio1000) {
  const Grid3 n = full() ? Grid3{24, 24, 24} : Grid3{16, 16, 16};
  const double V = 4.0 / 3 * M_PI * 0.2 * 0.2 * 0.2;
  // To t = 0.25 s, before the bubble (top at y = 0.5, rising ~1 m/s) meets the
  // lid and spreads into a film thinner than the smoothing.
  auto r = runCase("bubble_ratio1000", cellsText(n.nx, n.ny, n.nz), twoPhase(false, n), 100000, Energy::Gravity,
                   999 * V, 0.25);
  // With the velocity-form advection -[div(u u) - u div_h u] E_mech grew by
  // 0.66 E_scale here (0.20 at 24^3): the air's 25 m/s was carried into interface
  // nodes up to 1000x heavier. The conservative, rho-consistent advection
  // (kernels/advection.hpp addMomentumAdvection) removed it: growth 3.6e-3.
  // Drift measured 0.053 (16^3) and 0.037 (24^3); bound 0.053 + 25 % (header).
  // Energy growth 3.6e-3 (16^3) and 4.2e-3 (24^3), under the drift allowance.
  expectStable(r, r.steps, 0.066);
  EXPECT_TRUE(r.completed) << "did not reach t = 0.25";
}

namespace {

// An elastic solid (density rhoS, shear modulus mu) in water under gravity.
std::string solidScene(const char* name, Grid3 n, double lx, double ly, double lz, double rhoS, double mu,
                       double rhoF, double nuF, const std::string& shape) {
  std::string s = header(name, lx, ly, lz, n, kWalls);
  s += fmt("materials: {solid: {density: %g, shear_modulus: %g}, fluid: {density: %g, viscosity: %g}}\n", rhoS, mu,
           rhoF, nuF);
  s += "fluid: fluid\n"
       "gravity: [0, -9.81, 0]\n"
       "effects: [navier_stokes, gravity, level_set, reinit, elasticity]\n";
  s += "level_set: {phase: solid, shape: " + shape + "}\n";
  return s;
}

} // namespace

// Stiff solid: a block (0.4 x 0.3 x 0.4) of density 2000 falls 0.1 onto the floor
// of a water-filled box, mu_S = 1e2, 1e4, 1e6 Pa (shear-wave speed 0.22, 2.2, 22
// m/s) with the adaptive dt: dt must equal the elastic-wave limit cfl h / c
// whenever it is the smallest, and never exceed it: a step limited by another
// rule has a dt below the elastic one. At mu_S >= 1e4 the flow is slower than c
// and the elastic wave limits nearly every step (fast matrix: all 100; full
// matrix at 1e4: 197 of 200, the other 3 advective at the impact, max speed
// 0.94 m/s); at 1e2 the advective and gravity limits are the smaller ones.
class StiffSolid : public ::testing::TestWithParam<double> {};
TEST_P(StiffSolid, BlockFallsOntoFloor) {
  const double mu = GetParam();
  const int c = full() ? 24 : 16;
  const Grid3 n{c, c, c};
  const long steps = full() ? 200 : 100;
  const std::string shape = "{type: box, lo: [0.3, 0.1, 0.3], hi: [0.7, 0.4, 0.7]}";
  char nm[64];
  std::snprintf(nm, sizeof nm, "stiff_mu1e%d", int(std::lround(std::log10(mu))));
  auto r = runCase(nm, cellsText(c, c, c), solidScene(nm, n, 1, 1, 1, 2000, mu, 1000, 1e-3, shape), steps,
                   Energy::Gravity, 1000 * 0.4 * 0.3 * 0.4);
  EXPECT_EQ(r.steps, steps);
  const double dtElastic = 0.5 * (1.0 / c) / std::sqrt(mu / 2000);
  for (size_t k = 0; k < r.s.dt.size(); ++k) {
    EXPECT_LE(r.s.dt[k], dtElastic * (1 + 1e-12)) << "step " << k + 1;
    if (r.s.reason[k] == "elastic wave") EXPECT_NEAR(r.s.dt[k], dtElastic, 1e-12 * dtElastic);
    else EXPECT_LT(r.s.dt[k], dtElastic) << "step " << k + 1 << " (" << r.s.reason[k] << ")";
  }
  if (mu >= 1e4) EXPECT_GE(r.reasons["elastic wave"], steps * 9 / 10); // the flow is slower than c
  // Drift measured 0.34 / 0.044 / 0.022 (mu_S 1e2 / 1e4 / 1e6) + 25 %. At 1e2 Pa
  // the block's weight stress over its modulus is rho g H / mu_S = 59: it is a
  // very soft gel that slumps into a layer a cell or two thick on the floor,
  // where the level set loses volume; stiffer blocks keep their shape.
  expectStable(r, steps, mu < 1e3 ? 0.43 : mu < 1e5 ? 0.056 : 0.028);
}
INSTANTIATE_TEST_SUITE_P(Moduli, StiffSolid, ::testing::Values(1e2, 1e4, 1e6));

// Large rotation: the pre-stressed disk of tests/elasticity/test_objectivity.cpp
// carried by a prescribed rigid rotation through 450 degrees (fast, 32 cells) or
// 1170 (full, 64 cells). Cayley (default) must keep the elastic energy; the literal explicit
// half step grows by prod (1 + (omega dt)^2) per turn (4.7 % at 64 cells).
namespace {
// fluid_side: integrate (the paper's): the amplitude measure assumes every cell
// holds s(x) M tau0, which the extension (the default) does not keep on the
// fluid side (there the amplitude decays, -3e-5 over 450 degrees measured).
std::string rotationScene(int n, const std::string& rotation) {
  const std::string key = rotation.empty() ? "" : "rotation: " + rotation + ",";
  return fmt("name: rotation\n"
             "domain: {lo: [0, 0, 0], hi: [1, 1, %.17g], cells: [%d, %d, 2]}\n"
             "boundaries: {default: {type: slip}, z-: {type: periodic}, z+: {type: periodic}}\n"
             "time: {end: 1.0e9, cfl: 0.5}\n"
             "materials: {disk: {density: 1, shear_modulus: 1.0e-3}, air: {density: 1}}\n"
             "fluid: air\n"
             "effects: [prescribed_flow, level_set, elasticity]\n"
             "prescribed_flow: {type: rotation, center: [0.5, 0.5, 0], omega: [0, 0, %.17g]}\n"
             "level_set: {phase: disk, fast_marching: false,\n"
             "            shape: {type: cylinder, center: [0.5, 0.7, 0], radius: 0.2, axis: z}}\n"
             "elasticity: {fluid_side: integrate, %s initial_stress: {xx: 1, yy: -1, zz: 0.3, xy: 0.5, yz: 0.2, zx: "
             "-0.1}}\n"
             "output: {enabled: false}\n",
             2.0 / n, n, n, 2 * M_PI, key.c_str());
}
} // namespace

TEST(StabilityMatrix, LargeRotationCayley) {
  const int n = full() ? 64 : 32;
  const double turns = full() ? 3.25 : 1.25;
  auto r = runCase("rotation_cayley", cellsText(n, n, 2), rotationScene(n, ""), 100000, Energy::Amplitude, 0, turns);
  auto e = runCase("rotation_explicit", cellsText(n, n, 2), rotationScene(n, "explicit"), 100000, Energy::Amplitude,
                   0, turns, "grows, as expected (reference)");
  // Cayley: the amplitude at round-off (allowed 1e-9). Explicit: grows by
  // prod (1 + (omega dt)^2) - 1 per component pair, ~theta omega dt: at 32 cells
  // and cfl 0.5 about 26 % in energy after 450 degrees; required > 100x the
  // Cayley bound so the measure demonstrably sees the growth.
  printRow(r, 0.035);
  printRow(e, 0.035);
  EXPECT_LE(r.growth, r.allowed);
  EXPECT_GT(e.growth, 0.1);
  EXPECT_LE(r.maxDrift, 0.035); // measured 0.027 (no reinit; radius 6.4 cells) + 25 %
  EXPECT_EQ(r.maxDiv, 0.0);     // kinematic: no projection
}

// Thin solid: a plate 2.5 cells thick (0.5 x 2.5h x 0.5) of density 2000,
// mu_S = 1e4 Pa, falling flat through water: the drag bends its free edges.
TEST(StabilityMatrix, ThinPlateFalling) {
  const int c = full() ? 24 : 16;
  const double t = 2.5 / c;
  const long steps = full() ? 300 : 150;
  const std::string shape = fmt("{type: box, lo: [0.25, 0.6, 0.25], hi: [0.75, %g, 0.75]}", 0.6 + t);
  auto r = runCase("thin_plate", cellsText(c, c, c), solidScene("thin_plate", {c, c, c}, 1, 1, 1, 2000, 1e4, 1000,
                                                                  1e-3, shape),
                   steps, Energy::Gravity, 1000 * 0.25 * t);
  // Measured 0.070 (fast) / 0.106 (full: twice as long, the plate bends further;
  // it stays 2.5 cells thick) + 25 %.
  expectStable(r, steps, full() ? 0.13 : 0.09);
}

// A solid hitting the floor at speed: an elastic ball (density 1000, mu_S 1e5)
// falling 0.45 through air (ratio 830) reaches ~3 m/s and hits the no-slip floor.
TEST(StabilityMatrix, BallHitsFloor) {
  const Grid3 n = full() ? Grid3{24, 24, 24} : Grid3{16, 16, 16};
  const long steps = full() ? 300 : 150;
  const std::string shape = "{type: sphere, center: [0.5, 0.65, 0.5], radius: 0.2}";
  auto r = runCase("ball_hits_floor", cellsText(n.nx, n.ny, n.nz),
                   solidScene("ball_floor", n, 1, 1, 1, 1000, 1e5, 1.2, 1.8e-5, shape), steps, Energy::Gravity,
                   998.8 * 4.0 / 3 * M_PI * 0.008);
  expectStable(r, steps, 0.12); // measured 0.093 (radius 3.2 cells, squashed on the floor)
}

// A solid hitting an obstacle at speed: periodic in x and z, slip walls in y,
// everything starts at 2 m/s along x (initial: uniform); an elastic ball
// (density 3000, mu_S 1e4) is carried into a fixed cylinder (obstacles). No
// source: E(t) <= E(0).
TEST(StabilityMatrix, BallHitsObstacle) {
  const Grid3 n = full() ? Grid3{24, 24, 12} : Grid3{16, 16, 8};
  const long steps = full() ? 300 : 150;
  std::string s = header("ball_obstacle", 1, 1, 0.5, n,
                         "{default: {type: slip}, x-: {type: periodic}, x+: {type: periodic}, z-: {type: periodic}, "
                         "z+: {type: periodic}}");
  s += "materials: {solid: {density: 3000, shear_modulus: 1.0e4}, water: {density: 1000, viscosity: 1.0e-3}}\n"
       "fluid: water\n"
       "effects: [navier_stokes, obstacles, level_set, reinit, elasticity]\n"
       "obstacles:\n  - {type: cylinder, center: [0.65, 0.5, 0.25], radius: 0.12, axis: z}\n"
       "initial: {velocity: uniform, uniform: [2, 0, 0]}\n"
       "level_set: {phase: solid, shape: {type: sphere, center: [0.25, 0.5, 0.25], radius: 0.15}}\n";
  auto r = runCase("ball_hits_obstacle", cellsText(n.nx, n.ny, n.nz), s, steps, Energy::Unforced);
  expectStable(r, steps, 0.47); // measured 0.376 (radius 2.4 cells, wrapped round the cylinder)
}

// Long run: 10^4 steps of an elastic ball (density 2000, mu_S 1e3) settling in
// water on an 8^3 grid at the adaptive dt. Full matrix only: it
// takes ~100 s at 1 rank (10 ms a step: the step cost at 8^3 is overhead).
TEST(StabilityMatrix, LongRun) {
  if (!full()) GTEST_SKIP() << "full matrix only (VOIGT_STABILITY_FULL=1)";
  const int c = 8;
  const long steps = 10000;
  const std::string shape = "{type: sphere, center: [0.5, 0.55, 0.5], radius: 0.25}";
  auto r = runCase("long_run", cellsText(c, c, c),
                   solidScene("long_run", {c, c, c}, 1, 1, 1, 2000, 1e3, 1000, 1e-3, shape), steps, Energy::Gravity,
                   1000 * 4.0 / 3 * M_PI * 0.25 * 0.25 * 0.25);
  expectStable(r, steps, 0.7); // measured 0.56 at 8^3 (radius 2 cells: the smoothing is the ball)
}

// Fluids at rest: test_matrix_rest.cpp.

// High inflow through the porous bed at reduced size (full matrix only):
// cases/porous_bed/packing.csv (181 spheres, d = 2.5 cm, bonded into one elastic
// solid: density 1000, mu_S 1e4) in the 11 x 33 x 11 cm duct at 1 cm cells
// (2.5 cells per diameter), gas (air) in through y- at 1 m/s, out through y+;
// the bed is held, as the case README describes, by zero velocity within 1.1 cm
// of the side walls (four obstacle boxes over the bed's height); gravity on.
// Forced: energy enters with the gas. Bound (no runaway): the energy over the
// second half of the run stays below twice its maximum over the first half
// (the flow starts at the inflow velocity everywhere and is statistically
// steady after one pass through the duct, 0.33 s ~ the first half).
TEST(StabilityMatrix, PorousBedHighInflow) {
  if (!full()) GTEST_SKIP() << "full matrix only (VOIGT_STABILITY_FULL=1)";
  const Grid3 n{11, 33, 11};
  const long steps = 600;
  std::string s = header("porous_bed", 0.11, 0.33, 0.11, n,
                         "{default: {type: no_slip}, y-: {type: inflow, velocity: [0, 1, 0]}, "
                         "y+: {type: outflow, pressure: 0}}");
  s += "materials: {bed: {density: 1000, shear_modulus: 1.0e4}, air: {density: 1.2, viscosity: 1.8e-5}}\n"
       "fluid: air\n"
       "gravity: [0, -9.81, 0]\n"
       "effects: [navier_stokes, gravity, obstacles, level_set, reinit, elasticity]\n"
       "obstacles:\n"
       "  - {type: box, lo: [0, 0.05, 0], hi: [0.011, 0.31, 0.11]}\n"
       "  - {type: box, lo: [0.099, 0.05, 0], hi: [0.11, 0.31, 0.11]}\n"
       "  - {type: box, lo: [0, 0.05, 0], hi: [0.11, 0.31, 0.011]}\n"
       "  - {type: box, lo: [0, 0.05, 0.099], hi: [0.11, 0.31, 0.11]}\n"
       "initial: {velocity: uniform, uniform: [0, 1, 0]}\n";
  s += "level_set: {phase: bed, shape: {type: sphere_packing, file: " + std::string(VOIGT_SOURCE_DIR) +
       "/cases/porous_bed/packing.csv}}\n";
  auto r = runCase("porous_bed_1mps", cellsText(n.nx, n.ny, n.nz), s, steps, Energy::Forced);
  printRow(r, 0.44);
  EXPECT_EQ(r.steps, steps);
  const size_t half = r.s.E.size() / 2;
  const double first = *std::max_element(r.s.E.begin(), r.s.E.begin() + half);
  const double second = *std::max_element(r.s.E.begin() + half, r.s.E.end());
  test::report("porous_bed_energy_second_over_first_half", second / first);
  EXPECT_LE(second, 2 * first);
  // Measured 0.354 + 25 %: spheres 1.25 cells in radius, thinner than the
  // level set's smoothing, lose volume fast (tests/levelset: filaments thinner
  // than the smoothing width are not kept).
  EXPECT_LE(r.maxDrift, 0.44);
  EXPECT_LE(r.worstDivRatio, 1.0);
}
