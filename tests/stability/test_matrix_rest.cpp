// The stability matrix, rest cases (issue 50): fluids at rest under gravity must stay at
// rest on the defaults a user gets - adaptive dt, no projection section (exact operator,
// fast diagonalization, tolerance 1e-3 at two densities), level set + reinit as given.
// Bound: max |u_d| <= 1e-8 m/s on every step of the fast runs (200-1000 steps) and
// 1e-9 m/s over 10^4 steps (VOIGT_STABILITY_FULL=1), the numbers.
// On d7c7ccf (rho^n in the momentum stage: the interface-gravity coupling was forward
// Euler, unstable at any dt) the column reached KE 5e-8 J (max |u| 5e-4 m/s) by step 100
// and the tank with the sphere 0.08 J (0.46 m/s) by step 200 (README, "Rest at rest").
#include "stability/matrix_runner.hpp"

namespace {

// A closed box of water (below y = level) under air of density rhoAir, on the defaults.
std::string restScene(const char* name, double lx, double ly, double lz, int nx, int ny, int nz, double level,
                      double rhoWater, double rhoAir, const std::string& extra = "") {
  std::string s = fmt("name: %s\n"
                      "domain: {lo: [0, 0, 0], hi: [%g, %g, %g], cells: [%d, %d, %d]}\n"
                      "boundaries: {default: {type: no_slip}}\n"
                      "time: {end: 1.0e9}\n"
                      "output: {enabled: false}\n",
                      name, lx, ly, lz, nx, ny, nz);
  s += fmt("materials: {water: {density: %g, viscosity: 1.0e-3}, air: {density: %g, viscosity: 1.8e-5}}\n", rhoWater,
           rhoAir);
  s += "fluid: air\n"
       "gravity: [0, -9.81, 0]\n";
  s += extra.empty() ? "effects: [navier_stokes, gravity, level_set, reinit]\n"
                     : "effects: [navier_stokes, gravity, obstacles, level_set, reinit]\n" + extra;
  s += fmt("level_set: {phase: water, shape: {type: box, lo: [-1, -1, -1], hi: [2, %g, 2]}}\n", level);
  return s;
}

void expectRest(Result& r, long steps, double bound) {
  printRow(r, 1e-6);
  if (test::worldRank() == 0)
    std::printf("[ rest ] %s: max |u_d| %.3e m/s over %ld steps (bound %.0e), dt %.4g (%s)\n", r.name.c_str(),
                r.maxSpeed, r.steps, bound, r.s.dt.empty() ? 0.0 : r.s.dt.back(),
                r.s.reason.empty() ? "" : r.s.reason.back().c_str());
  EXPECT_EQ(r.steps, steps);
  EXPECT_LE(r.maxSpeed, bound);
  EXPECT_LE(r.growth, r.allowed) << "energy grows";
  EXPECT_LE(r.maxDrift, 1e-6); // nothing moves: the volume stays (measured ~1e-15)
}

long restSteps() { return full() ? 10000 : 200; }
double restBound() { return full() ? 1e-9 : 1e-8; }

} // namespace

// The first scene: unit cube, 32^3, water below y = 0.5 (a cell face), ratio 1000.
// dt is the gravity limit on every step (0.0399 s).
TEST(StabilityRest, ColumnRatio1000) {
  const long steps = restSteps();
  auto r = runCase("rest_column_ratio1000", cellsText(32, 32, 32),
                   restScene("rest_column", 1, 1, 1, 32, 32, 32, 0.5, 1000, 1), steps, Energy::Gravity, 999 * 0.5);
  r.worstDivRatio = 0; // u* is round-off: the ratio to it says nothing
  expectRest(r, steps, restBound());
  EXPECT_EQ(r.reasons["gravity"], steps); // the adaptive default, not a tightened dt
}

// The same column with navier_stokes.viscous: semi_implicit (an option): the implicit
// correction of a resting state is the solve of a round-off right-hand side and must leave
// it at rest. dt stays the gravity limit (the air's viscous limit, 4.5 s, is far above it).
TEST(StabilityRest, ColumnRatio1000SemiImplicitViscosity) {
  const long steps = restSteps();
  auto r = runCase("rest_column_ratio1000_semi_implicit", cellsText(32, 32, 32),
                   restScene("rest_column_si", 1, 1, 1, 32, 32, 32, 0.5, 1000, 1) +
                       "navier_stokes: {viscous: semi_implicit}\n",
                   steps, Energy::Gravity, 999 * 0.5);
  r.worstDivRatio = 0;
  expectRest(r, steps, restBound());
  EXPECT_EQ(r.reasons["gravity"], steps);
}

// The second scene: 1.5 x 1 x 0.75 (48 x 32 x 24), interface at y = 0.37 (off the
// faces), a fixed sphere of radius 0.15 half submerged (obstacles). Before reinit.zone_tolerance
// it grew from step ~4500 on, tenfold every ~700 steps (re-initialising the smoothing zone next
// to the sphere; cases/rest_tank/README.md); the 10^4 steps of the full matrix catch that.
TEST(StabilityRest, TankWithSphereRatio1000) {
  const long steps = restSteps();
  const std::string sphere = "obstacles: [{type: sphere, center: [0.75, 0.37, 0.375], radius: 0.15}]\n";
  auto r = runCase("rest_sphere_ratio1000", cellsText(48, 32, 24),
                   restScene("rest_sphere", 1.5, 1, 0.75, 48, 32, 24, 0.37, 1000, 1, sphere), steps, Energy::Gravity,
                   999 * 0.37 * 1.5 * 0.75);
  r.worstDivRatio = 0;
  expectRest(r, steps, restBound());
}

// Ratio 1.1e4: mercury (13 600) under air (1.2), interface at y = 0.4 (off the faces).
TEST(StabilityRest, ColumnRatio1e4) {
  const int c = full() ? 32 : 16;
  const long steps = full() ? 10000 : 1000;
  auto r = runCase("rest_column_ratio1e4", cellsText(c, c, c),
                   restScene("rest_mercury", 1, 1, 1, c, c, c, 0.4, 13600, 1.2), steps, Energy::Gravity,
                   13598.8 * 0.4);
  r.worstDivRatio = 0;
  expectRest(r, steps, 1e-9);
}

// The approximate (7-point) projection with multigrid, an option the paper scenes have run
// (issue 21), on the adaptive dt (d7c7ccf ran it at max_dt 0.002), with its default
// projection.hydrostatic: none. Its first solve (tolerance 1e-6) leaves ~2e-8 m/s, so the
// bound is issue 21's, 1e-6 m/s, and the speed must not grow: the largest over the last
// tenth of the run at most that over the first tenth (measured 2.2e-9 against 1.8e-8 over
// 3000 steps; with hydrostatic: balanced it grew tenfold every ~80 steps: README).
TEST(StabilityRest, ColumnRatio1000Approximate) {
  const int c = 16;
  const long steps = full() ? 10000 : 1000;
  std::string s = restScene("rest_approx", 1, 1, 1, c, c, c, 0.4, 1000, 1);
  s += "projection: {operator: approximate, preconditioner: multigrid, tolerance: 1.0e-6}\n";
  auto r = runCase("rest_column_ratio1000_approx", cellsText(c, c, c), s, steps, Energy::Gravity, 999 * 0.4);
  r.worstDivRatio = 0; // the CG bound is for the exact operator
  expectRest(r, steps, 1e-6);
  const size_t n = r.s.speed.size(), tenth = std::max<size_t>(1, n / 10);
  ASSERT_GE(n, tenth);
  const double first = *std::max_element(r.s.speed.begin(), r.s.speed.begin() + tenth);
  const double last = *std::max_element(r.s.speed.end() - tenth, r.s.speed.end());
  EXPECT_LE(last, first) << "the speed grows";
}

// Issue 51: a water drop resting in air (ratio 1000, sigma 0.0728, R = 5 mm = 8 cells of 32^3,
// no gravity), on the defaults (adaptive dt: the capillary limit on every step). The Laplace
// number sigma rho D / mu^2 is 7e5: too little viscosity to damp the currents that the level
// set's curvature errors drive, and they do not decay (a finding: cases/rising_bubble/README.md,
// "A resting water drop in air"). What is asserted is that they stay bounded and small: the
// kinetic energy below 1e-3 of the surface energy sigma 4 pi R^2 (measured 8e-8 at step 200,
// saturating at 5e-4 by step 1400 of the full run), Ca = max|u| mu_water / sigma below 1e-3
// (measured 4e-6 at step 200, 5.5e-4 at most over 2400 steps), and no volume lost.
// The drop's scene (`extra` appended) and its bounds, on `steps` steps all set by `reason`.
static void restingDrop(const char* name, long steps, const char* reason, const std::string& extra = "") {
  const std::string s = "name: rest_drop\n"
                        "domain: {lo: [0, 0, 0], hi: [0.02, 0.02, 0.02], cells: [32, 32, 32]}\n"
                        "boundaries: {default: {type: no_slip}}\n"
                        "time: {end: 1.0e9}\n"
                        "output: {enabled: false}\n"
                        "materials: {water: {density: 1000, viscosity: 1.0e-3}, air: {density: 1, viscosity: 1.8e-5}}\n"
                        "fluid: air\n"
                        "effects: [navier_stokes, level_set, reinit, surface_tension]\n"
                        "level_set: {phase: water, shape: {type: sphere, center: [0.0101, 0.0099, 0.0102], radius: 0.005}}\n"
                        "surface_tension: {sigma: 0.0728}\n" +
                        extra;
  auto r = runCase(name, cellsText(32, 32, 32), s, steps, Energy::Unforced);
  r.worstDivRatio = 0;
  printRow(r, 1e-6, false);
  const double surface = 0.0728 * 4 * M_PI * 0.005 * 0.005;
  const double keMax = *std::max_element(r.s.E.begin(), r.s.E.end());
  if (test::worldRank() == 0)
    std::printf("[ rest ] %s: max KE %.3e J (%.2e of the surface energy), max Ca %.2e over %ld steps\n", name, keMax,
                keMax / surface, r.maxSpeed * 1e-3 / 0.0728, r.steps);
  EXPECT_EQ(r.steps, steps);
  EXPECT_EQ(r.reasons[reason], steps); // the dt rule the scene gets, not a tightened one
  EXPECT_LT(keMax, 1e-3 * surface);
  EXPECT_LT(r.maxSpeed * 1e-3 / 0.0728, 1e-3);
  EXPECT_LE(r.maxDrift, 1e-6);
}

TEST(StabilityRest, DropRatio1000SurfaceTension) {
  restingDrop("rest_drop_ratio1000", full() ? 2400 : 200, "capillary");
}

// projection.variable_density: split (an option, Dodd & Ferrante 2014). At rest its extrapolated
// increment is round-off, and below its own dt limit (navier_stokes "split (gravity waves)",
// half the threshold measured on these columns) it must keep the rest the full solve keeps: the
// same bounds. At the gravity dt (40x the split's limit at ratio 1000) the column grew from
// round-off to 1.2 m/s in 123 steps. The column takes one CG iteration a step (fast
// diagonalization inverts the one-density operator); the sphere's fixed nodes leave CG a few.
// The split's steps are short (1/40 and 1/5 of the solve's): 5x the solve's step count.
static long splitSteps() { return full() ? 10000 : 1000; }

TEST(StabilityRest, ColumnRatio1000Split) {
  const long steps = splitSteps();
  auto r = runCase("rest_column_ratio1000_split", cellsText(32, 32, 32),
                   restScene("rest_column_split", 1, 1, 1, 32, 32, 32, 0.5, 1000, 1) +
                       "projection: {variable_density: split}\n",
                   steps, Energy::Gravity, 999 * 0.5);
  r.worstDivRatio = 0;
  expectRest(r, steps, restBound());
  EXPECT_EQ(r.reasons["split (gravity waves)"], steps);
}

TEST(StabilityRest, TankWithSphereRatio1000Split) {
  const long steps = splitSteps();
  const std::string sphere = "obstacles: [{type: sphere, center: [0.75, 0.37, 0.375], radius: 0.15}]\n"
                             "projection: {variable_density: split}\n";
  auto r = runCase("rest_sphere_ratio1000_split", cellsText(48, 32, 24),
                   restScene("rest_sphere_split", 1.5, 1, 0.75, 48, 32, 24, 0.37, 1000, 1, sphere), steps,
                   Energy::Gravity, 999 * 0.37 * 1.5 * 0.75);
  r.worstDivRatio = 0;
  expectRest(r, steps, restBound());
}

// The resting drop with the split: capillary waves feel its lag too (at the capillary dt the drop's
// kinetic energy grew 1000x in 400 steps), so the capillary limit is scaled for it
// ("capillary (split)", 0.19 of it at ratio 1000); under it the same bounds as the solve's.
TEST(StabilityRest, DropRatio1000SurfaceTensionSplit) {
  restingDrop("rest_drop_ratio1000_split", full() ? 12000 : 1000, "capillary (split)", // the solve's time
              "projection: {variable_density: split}\n");
}
