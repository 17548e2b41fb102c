// Level-set transport by a prescribed velocity (prescribed_flow + level_set,
// with and without reinit): Zalesak's slotted disk after one rotation and the
// LeVeque single vortex, deformed and reversed. 2-D problems on a z extent of
// 2 cubic cells (periodic z, `ranks: [0, 0, 1]`: MPI never splits z).
// Measured numbers are printed on rank 0 and recorded in the GoogleTest XML;
// cases/zalesak/README.md and cases/single_vortex/README.md hold the tables.
//
// Measures, all with the sharp Heaviside at cell centres:
//   area change  sharp_volume / sharp_volume_initial - 1 (level_set summary);
//                the smoothed H-volume change ("H-area") is reported alongside;
//   shape error  E = (1/L) sum |H(psi_exact) - H(psi)| dA, a length (also given
//                in cells, E/h); L is the exact perimeter, psi_exact the exact
//                shape at the cell centres (E = 0 at t = 0).
//   filament     at T/2 of the vortex (maximum stretching): the exact interface
//                is traced from the initial circle with RK4 markers; width =
//                2 area / length (a thin strip's mean width, length from the
//                diag interface_area) and max psi (the half width where psi is a
//                distance, i.e. in a filament thinner than the narrow band).
//
// Reinit runs use the reinit defaults (every step, 2 iterations, dtau 0.5 cells,
// no subcell fix) with volume_constraint true ("constrained") or false.
// Literature: the published tables (Enright et al. 2002; Sussman & Fatemi 1999)
// could not be read from the stored copies available here (only their opening
// pages), so no published numbers are quoted; see the case READMEs.
//
// Bounds: each is the measured value (Release; 1 and 2 ranks give the same
// numbers) times the factor stated next to it, so a regression of that size
// fails. They are not tuned to the literature. VOIGT_LONG=1 adds the finer
// grids and the full T = 8 vortex (README numbers).
#include "levelset/transport_cases.hpp"

// The exact geometry behind the shape error: perimeter 143.80, area 582.21 (the
// 582.2 quoted for this disk). The sharp area of the discrete initial shape at
// 128^2 is 1.5 % larger: each slot wall lies 0.2 cells inside a cell counted as
// disk (2 x 0.156 x 25 = 7.8 of the 8.6 area units).
TEST(Transport, ZalesakGeometry) {
  EXPECT_NEAR(zalesakPerimeter(), 143.80, 0.01);
  EXPECT_NEAR(zalesakArea(), 582.21, 0.01);
  Simulation sim(test::scene(zalesakScene(128, Mode::NoReinit)), MPI_COMM_WORLD, RunOptions{});
  sim.initialize();
  const Snapshot s = measure(sim, insideZalesak, zalesakPerimeter());
  EXPECT_EQ(s.shapeError, 0.0); // psi_exact is the initial shape at the same centres
  EXPECT_NEAR(s.sharpArea / zalesakArea(), 1.015, 2e-3);
  EXPECT_NEAR(s.length / zalesakPerimeter(), 1.0, 0.05); // smoothed-delta length; the corners cost a little
}

// One revolution of the slotted disk at 64^2 and 128^2 cells (h = 1.5625 and
// 0.78125 in the disk's units; 256^2 with VOIGT_LONG=1), re-initialised every
// step with the constraint, and without re-initialisation. Not 50^2 / 100^2: on
// a cell-centred grid of [0,100] those put cell centres exactly on the slot's
// top (n = 50) or walls (n = 100), where the sharp H is 1/2 and the shape error
// has a floor of half a cell per wall cell.
//
// Measured (Release):            area      H-area    E        E/h
//   64^2  constrained           +7.66 %   +0.24 %   1.443    0.92
//   128^2 constrained           -2.79 %   -1.04 %   0.293    0.37
//   64^2  no reinit             +2.25 %  -10.7 %    1.783    1.14
//   128^2 no reinit            +16.9 %   +15.9 %    1.129    1.45  (the slot fills in)
TEST(Transport, ZalesakOneRotation) {
  std::vector<int> grids = {64, 128};
  if (longRuns()) grids.push_back(256);
  std::vector<ZalesakResult> con, none;
  for (int n : grids) con.push_back(runZalesak(n, Mode::Constrained));
  for (int n : grids) none.push_back(runZalesak(n, Mode::NoReinit));
  if (longRuns())
    for (int n : grids) runZalesak(n, Mode::Unconstrained);
  // The shape error falls with resolution: 4.9x from 64^2 to 128^2 with reinit
  // (asserted > 3x), 1.6x without (asserted > 1.2x).
  EXPECT_GT(con[0].end.shapeError / con[1].end.shapeError, 3.0);
  EXPECT_GT(none[0].end.shapeError / none[1].end.shapeError, 1.2);
  // 128^2 with reinit: bounds 1.5x the measured values.
  EXPECT_LT(std::abs(con[1].end.sharpChange), 1.5 * 0.0279);
  EXPECT_LT(std::abs(con[1].end.hChange), 1.5 * 0.0104);
  EXPECT_LT(con[1].end.shapeError, 1.5 * 0.293);
  // Re-initialisation is what keeps the slot: at 128^2 the error without it is
  // 3.9x larger (asserted > 2x).
  EXPECT_GT(none[1].end.shapeError / con[1].end.shapeError, 2.0);
}

// Single vortex, T = 2, at 32^2, 64^2 and 128^2: the local volume constraint
// against plain re-initialisation (and, with VOIGT_LONG=1, no re-initialisation,
// reported only).
//
// Measured at t = T (area = sharp area change, E/h):
//              constrained              unconstrained            no reinit
//   32^2   +9.2 % (H +15.5 %) 0.56    -7.9 % (H -3.7 %) 0.66    -21.1 % 0.73
//   64^2   +3.9 % (H  +2.5 %) 0.35    -2.8 % (H -5.1 %) 0.43     +4.6 % 0.81
//   128^2  -0.34 % (H -0.02 %) 0.15   -2.8 % (H -2.5 %) 0.29     +1.7 % 0.46
// The constraint only pays off once the stretched circle (T/2 width measured 3.2, 5.3,
// 9.9 cells) is wider than the smoothing band 2 kappa = 4 cells: at 128^2 it
// cuts the area change 8x and the H-volume change 100x; at 32^2 and 64^2 it
// makes the sharp area change larger than without it (a finding, see
// cases/single_vortex/README.md), and those grids are only bounded here.
TEST(Transport, SingleVortexVolumeConstraint) {
  const double T = 2;
  std::vector<int> grids = {32, 64, 128};
  const Poly half = traceCircle(0.5 * T, T, 4000, 1000);
  if (rank0()) std::printf("exact interface at T/2 (T = 2): length %.5f (circle %.5f)\n", half.length(), 2 * M_PI * kVR);
  std::vector<VortexResult> con, unc;
  for (int n : grids) {
    con.push_back(runVortex(n, T, Mode::Constrained, half));
    unc.push_back(runVortex(n, T, Mode::Unconstrained, half));
    if (longRuns()) runVortex(n, T, Mode::NoReinit, half); // reported only (README)
  }
  const VortexResult &c128 = con[2], &u128 = unc[2];
  // Resolved (128^2): the constraint cuts the area change 8.3x (asserted > 4x)
  // and the H-volume change 107x (asserted > 20x).
  EXPECT_GT(std::abs(u128.end.sharpChange), 4 * std::abs(c128.end.sharpChange));
  EXPECT_GT(std::abs(u128.end.hChange), 20 * std::abs(c128.end.hChange));
  EXPECT_LT(std::abs(c128.end.sharpChange), 1.5 * 0.0034);
  // Under-resolved grids: regression bounds only (1.5x the measured change).
  EXPECT_LT(std::abs(con[0].end.sharpChange), 1.5 * 0.092);
  EXPECT_LT(std::abs(con[1].end.sharpChange), 1.5 * 0.039);
  for (size_t q = 0; q < grids.size(); ++q) {
    // The constraint never costs shape accuracy: E(constrained) / E(unconstrained)
    // = 0.85, 0.81, 0.51 at t = T; allowed up to 1.1.
    EXPECT_LT(con[q].end.shapeError, 1.1 * unc[q].end.shapeError) << grids[q];
    // Nor does it thicken the T/2 filament here: width ratio 1.03, 0.99, 1.00
    // (allowed up to 1.1).
    EXPECT_LT(con[q].half.width(), 1.1 * unc[q].half.width()) << grids[q];
  }
  // The error falls with resolution with the constraint: 3.2x and 4.7x per
  // halving of h (asserted > 2x).
  EXPECT_GT(con[0].end.shapeError, 2 * con[1].end.shapeError);
  EXPECT_GT(con[1].end.shapeError, 2 * con[2].end.shapeError);
}

// Thin filaments: the T = 8 vortex at 64^2, compared at T/2 (maximum stretching)
// where the spiral's arms are thinner than the smoothing band. The exact area is
// conserved; re-initialised level sets keep arms about 3 cells wide whatever
// their true width, so both runs gain area, and the constraint (which holds the
// H-volume, which for features thinner than 2 kappa depends on |grad psi|) gains
// more. Measured at T/2:
//                   area      width   max psi   E/h
//   constrained    +135 %    3.18 h   2.04 h    0.98
//   unconstrained  +105 %    2.98 h   1.92 h    0.91
// The constraint thickens the filament by 7 % in width and 6 % in max psi
// (allowed: 15 %), and its shape error is 7 % larger (allowed: 20 %). At 128^2
// (VOIGT_LONG=1): +50 % against +26 % area, width 4.11 h against 3.95 h.
TEST(Transport, FilamentT8) {
  const double T = 8;
  const Poly half = traceCircle(0.5 * T, T, 8000, 2000);
  if (rank0()) std::printf("exact interface at T/2 (T = 8): length %.5f\n", half.length());
  const VortexResult c = runVortex(64, T, Mode::Constrained, half, true);
  const VortexResult u = runVortex(64, T, Mode::Unconstrained, half, true);
  EXPECT_LT(c.half.width(), 1.15 * u.half.width());
  EXPECT_LT(c.half.maxPsi, 1.15 * u.half.maxPsi);
  EXPECT_LT(c.half.shapeError, 1.2 * u.half.shapeError);
  // Regression bound on the inflation itself (1.25x the measured +135 %).
  EXPECT_LT(c.half.sharpChange, 1.25 * 1.35);
}

// The README's T = 8 numbers at 128^2 (VOIGT_LONG=1 only; ~3 min, 1 rank).
// Measured (Release, 1 rank; cases/single_vortex/README.md), area at T/2 and T:
// global + constraint -0.5 %, +0.26 % (E/h 0.34, 2.68); constraint alone +50 %,
// +63 % (E/h 0.71, 6.14). Issue 21's bound: area within 5 % at T; the shape error
// at least 1.5x below the constraint alone's (2.1x and 2.3x measured).
TEST(Transport, SingleVortexT8Long) {
  if (!longRuns()) GTEST_SKIP() << "set VOIGT_LONG=1";
  const double T = 8;
  const Poly half = traceCircle(0.5 * T, T, 40000, 4000);
  if (rank0()) std::printf("exact interface at T/2 (T = 8): length %.5f\n", half.length());
  for (Mode m : {Mode::Unconstrained, Mode::NoReinit, Mode::GlobalUnconstrained}) runVortex(128, T, m, half);
  const VortexResult c = runVortex(128, T, Mode::Constrained, half);
  const VortexResult g = runVortex(128, T, Mode::GlobalConstrained, half);
  EXPECT_LT(std::abs(g.end.sharpChange), 0.05);
  EXPECT_LT(std::abs(g.half.sharpChange), 0.05);
  EXPECT_LT(g.half.shapeError, c.half.shapeError / 1.5);
  EXPECT_LT(g.end.shapeError, c.end.shapeError / 1.5);
}

// 256^2 (VOIGT_LONG=1 only; ~6 min, 1 rank): T = 8 and T = 2 with the global
// correction (the constraint alone at 256^2: `single_vortex.yaml` with
// `--set level_set.volume_correction=none`). Measured at T = 8: global + constraint -0.15 %,
// -0.04 % (E/h 0.39, 3.34). The 5 % bound as at 128^2; at T = 2 the area within
// 1 % (-0.34 % at 128^2) and E/h below 128^2's 0.149 (the error falls with h).
TEST(Transport, SingleVortexLong256) {
  if (!longRuns()) GTEST_SKIP() << "set VOIGT_LONG=1";
  const Poly half8 = traceCircle(4.0, 8.0, 40000, 4000);
  const VortexResult g = runVortex(256, 8.0, Mode::GlobalConstrained, half8);
  EXPECT_LT(std::abs(g.end.sharpChange), 0.05);
  EXPECT_LT(std::abs(g.half.sharpChange), 0.05);
  const Poly half2 = traceCircle(1.0, 2.0, 8000, 2000);
  const VortexResult g2 = runVortex(256, 2.0, Mode::GlobalConstrained, half2);
  EXPECT_LT(std::abs(g2.end.sharpChange), 0.01);
  EXPECT_LT(g2.end.shapeError / g2.h, 0.149);
}

// The decomposition does not matter: the constrained vortex at 32^2 on rank 0
// alone and on all ranks gives the same areas and errors (the local constraint
// has no global sums; only the diagnostics' summation order differs).
TEST(Transport, RankIndependent) {
  const double T = 2;
  const Poly half = traceCircle(0.5 * T, T, 1000, 500);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm solo;
  MPI_Comm_split(MPI_COMM_WORLD, rank == 0 ? 0 : MPI_UNDEFINED, 0, &solo);
  double a[4] = {0, 0, 0, 0};
  if (rank == 0) {
    const VortexResult r = runVortex(32, T, Mode::Constrained, half, false, solo, true);
    a[0] = r.half.sharpArea, a[1] = r.end.sharpArea, a[2] = r.end.shapeError, a[3] = r.end.hChange;
    MPI_Comm_free(&solo);
  }
  MPI_Bcast(a, 4, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  const VortexResult all = runVortex(32, T, Mode::Constrained, half, false, MPI_COMM_WORLD, true);
  EXPECT_NEAR(all.half.sharpArea, a[0], 1e-12 * a[0]);
  EXPECT_NEAR(all.end.sharpArea, a[1], 1e-12 * a[1]);
  EXPECT_NEAR(all.end.shapeError, a[2], 1e-12 * a[2]);
  EXPECT_NEAR(all.end.hChange, a[3], 1e-9);
}

// The global volume correction (level_set.volume_correction: global, the
// default; effects/level_set/volume.cpp) with the local constraint, against
// the constraint alone. Measured (Release, 1 rank):
//                          area       H-area    E/h at T/2   E/h at T
//   Zalesak 128^2, global   -1.76 %   2e-12                   0.353 (alone: -2.79 %, 0.37)
//   vortex T = 2, 128^2     -0.34 %   7e-11     0.034         0.149 (alone: -0.34 %, 0.15)
//   vortex T = 8, 64^2      +1.76 %   3e-11     0.41          3.47
//     constraint alone    +169 %     +162 %      0.98          8.16
//     global, no constraint  0.0 %   1e-8      0.49          4.58
// Holding INT H stops the thin arms' inflation (the re-initialisation widens
// them, the shift takes the gained volume back from the whole interface).
TEST(Transport, GlobalVolumeCorrection) {
  const ZalesakResult z = runZalesak(128, Mode::GlobalConstrained);
  const ZalesakResult z64 = runZalesak(64, Mode::GlobalConstrained);
  const Poly half2 = traceCircle(1.0, 2.0, 4000, 1000);
  const VortexResult v2 = runVortex(128, 2.0, Mode::GlobalConstrained, half2);
  const Poly half8 = traceCircle(4.0, 8.0, 8000, 2000);
  const VortexResult g8 = runVortex(64, 8.0, Mode::GlobalConstrained, half8);
  const VortexResult c8 = runVortex(64, 8.0, Mode::Constrained, half8);
  // The H-volume is held to the Newton step's residual (V'' s^2 / 2, ~1e-10
  // measured): 1e-8 allows 100x.
  for (double dh : {z.end.hChange, v2.half.hChange, v2.end.hChange, g8.half.hChange, g8.end.hChange})
    EXPECT_LT(std::abs(dh), 1e-8);
  // It costs no accuracy where the constraint already works: shape errors within
  // 10 % of the constraint alone (0.293 at Zalesak 128^2, 0.15 h at T = 2: the
  // README tables and the bounds of the tests above).
  EXPECT_LT(z.end.shapeError, 1.1 * 0.293);
  EXPECT_LT(std::abs(z.end.sharpChange), 0.0279); // the constraint alone: -2.79 %
  // 64^2: below the constraint alone's E (measured 1.392 against 1.443, with the default
  // reinit.zone_tolerance 1e-6 as with 0; 1.460 against 1.494 at 0.01).
  EXPECT_LT(z64.end.shapeError, runZalesak(64, Mode::Constrained).end.shapeError);
  EXPECT_LT(std::abs(z64.end.hChange), 1e-8);
  EXPECT_LT(v2.end.shapeError / v2.h, 1.1 * 0.15);
  // T = 8 (issue 21: area within 5 % at t = T): +1.8 % measured at 64^2.
  EXPECT_LT(std::abs(g8.end.sharpChange), 0.05);
  EXPECT_LT(std::abs(g8.half.sharpChange), 0.05);
  // And the shape is better than the constraint alone's: E ratio 0.42 at T/2
  // and at T (asserted < 0.6).
  EXPECT_LT(g8.half.shapeError, 0.6 * c8.half.shapeError);
  EXPECT_LT(g8.end.shapeError, 0.6 * c8.end.shapeError);
}

// The correction's target follows what leaves through open faces: a disk of
// radius 0.2 carried at u = 1 through an outflow face (x = 1), 64^2. Without the
// outflow term the correction would hold the initial volume and inflate what is
// left inside. Exact: the part of the disk with x < 1. Measured: within -1.7 %
// and +3.4 % of it while it leaves (the smoothed H against the sharp disk: +0.3 %
// at t = 0), and 0 once it has left (asserted: 5 % and 1e-6 of V0).
TEST(Transport, GlobalCorrectionFollowsOutflow) {
  const std::string yaml =
      "name: outflow\n"
      "domain: {lo: [0, 0, 0], hi: [1, 1, 0.03125], cells: [64, 64, 2], ranks: [0, 0, 1]}\n"
      "boundaries: {default: {type: slip}, x-: {type: inflow, velocity: [1, 0, 0]}, x+: {type: outflow, pressure: "
      "0},\n"
      "             z-: {type: periodic}, z+: {type: periodic}}\n"
      "time: {end: 0.7, cfl: 0.5}\n"
      "materials: {blob: {density: 1, viscosity: 0}, air: {density: 1, viscosity: 0}}\n"
      "fluid: air\n"
      "effects: [prescribed_flow, level_set, reinit]\n"
      "prescribed_flow: {type: uniform, velocity: [1, 0, 0]}\n"
      "level_set: {phase: blob, fast_marching: false, volume_correction: global,\n"
      "            shape: {type: cylinder, center: [0.7, 0.5, 0], radius: 0.2, axis: z}}\n"
      "output: {enabled: false}\n";
  Simulation sim(test::scene(yaml), MPI_COMM_WORLD, RunOptions{});
  sim.initialize();
  const double R = 0.2, lz = 0.03125, V0 = M_PI * R * R * lz;
  auto exactInside = [&](double t) { // disk centred at 0.7 + t, cut at x = 1
    const double d = 1 - (0.7 + t);
    if (d >= R) return V0;
    if (d <= -R) return 0.0;
    return V0 - (R * R * std::acos(d / R) - d * std::sqrt(R * R - d * d)) * lz;
  };
  for (double t : {0.2, 0.3, 0.4}) {
    sim.advanceTo(t);
    const double V = sim.state().diag.at("volume_blob");
    if (rank0()) std::printf("outflow t = %.1f: V / exact - 1 = %+.3e\n", t, V / exactInside(t) - 1);
    EXPECT_NEAR(V / exactInside(t), 1.0, 0.05) << "t = " << t;
  }
  sim.advanceTo(0.7);
  EXPECT_LT(sim.state().diag.at("volume_blob"), 1e-6 * V0);
}
