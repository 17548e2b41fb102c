// Re-initialisation, paper Eq. (17)-(21) (levelset/reinit.hpp): Eikonal
// convergence, zero-contour displacement, volume with and without the local
// constraint, thin filaments, the narrow band, fixed points, 1 vs 2 ranks.
// Measured numbers are printed on rank 0; each tolerance says what it allows.
// Measures run on the gathered global array, identically on every rank.
#include "levelset/reinit_fixture.hpp"

// 1. Eq. (17) makes |grad psi| = 1 in the band and keeps the zero contour.
// psi0 = (R - r) * distortion: the band (|psi0| < 6 cells) reaches 6 / 0.55 = 11
// cells of distance where psi0 is flattest; 60 steps of 0.5 cell carry the
// distance 30 cells out (the constraint slows convergence near the interface).
TEST(Reinit, DistortedSphereBecomesDistance) {
  const SphereRun d = runSphere(distortedSphere, "distorted sphere", 60, kDefault);
  const SphereRun plain = runSphere(distortedSphere, "distorted sphere", 60, kPlain);
  runSphere(distortedSphere, "distorted sphere", 60, kSubcell);
  runSphere(distortedSphere, "distorted sphere", 60, kSubcellOnly);
  EXPECT_GT(d.grad0[0], 0.5); // the start is far from a distance function
  // ||grad psi| - 1|, default: measured max 0.064, rms 0.008 (stats 0.074): the
  // constraint cancels the part of each step that changes INT H, so within kappa
  // of the interface the Eikonal converges slowly (0.10 after 40 steps, 0.04
  // after 80). Without it 0.053 (the max sits where the band is only 3.3 cells of
  // distance wide and the 5x5x5 selection touches the first-order band edge).
  // Allow 0.1 (stats 0.12) and 0.015 rms.
  EXPECT_LT(d.grad[0], 0.1);
  EXPECT_LT(d.grad[1], 0.015);
  EXPECT_LT(d.st.maxGradError, 0.12);
  EXPECT_LT(plain.grad[0], 0.1);
  // Zero contour: psi0's own linear-interpolation error is 0.0098 cells. The
  // default moves it by up to 0.10 cells (rms 0.014): INT H(psi0) of a distorted
  // psi0 is not INT H of the distance (the smoothing width scales with
  // 1/|grad psi0|), and the constraint keeps the former. Without the constraint
  // the upwind scheme drags it by up to 0.07 (rms 0.020); the subcell fix alone
  // keeps it at 0.009. Allow 0.15 and 0.03 rms.
  EXPECT_LT(d.contour[0], 0.15);
  EXPECT_LT(d.contour[1], 0.03);
  EXPECT_LT(plain.contour[0], 0.15);
}

// 2. The constraint, Eq. (18)-(21), keeps int H(psi) on the distorted sphere.
TEST(Reinit, ConstraintKeepsVolume) {
  const SphereRun d = runSphere(distortedSphere, "distorted sphere", 40, kDefault);
  const SphereRun plain = runSphere(distortedSphere, "distorted sphere", 40, kPlain);
  const SphereRun sub = runSphere(distortedSphere, "distorted sphere", 40, kSubcell);
  const SphereRun subOnly = runSphere(distortedSphere, "distorted sphere", 40, kSubcellOnly);
  if (rank0())
    printf("int H drift over 40 steps: %.2e with the constraint, %.2e without; with the subcell fix %.2e and "
           "%.2e\n",
           d.drift(), plain.drift(), sub.drift(), subOnly.drift());
  // Measured 5e-6 against 2.6e-3 without (the drift swings through -3e-4 on the
  // way: the constraint is exact only to the frozen H'(psi0), the per-cell
  // lambda and the 27-point quadrature). Allow 5e-4, a fifth of the drift without.
  EXPECT_LT(std::fabs(d.drift()), 5e-4);
  EXPECT_LT(std::fabs(d.drift()), 0.2 * std::fabs(plain.drift()));
  EXPECT_LT(std::fabs(sub.drift()), 0.2 * std::fabs(subOnly.drift()));
}

// 3. Thin filaments. The known weakness of Eq. (18)-(21) is that it moves mass
// around locally and grows bumps on filaments thinner than the smoothing width.
namespace {
struct FilamentRun {
  double volH0, volH, vol0, vol, thick0, thick; // int H, sharp volume, longest run [cells]
  double growth() const { return vol / vol0 - 1; }
};
// A sheet y = y0 (1.6 cells thick) or a thread along z (radius 0.9 cells), on 32^3
// with h = 1/32, periodic along the filament. Sharp volume and thickness from the
// interpolated crossings along y-lines (sheet) or x-lines (thread). psi is
// multiplied by `strain` (zero set unchanged) over |psi| < 5 cells before each of
// `calls` calls: a stand-in for an advection that keeps distorting |grad psi|.
FilamentRun runFilament(bool thread, const Variant& v, int iters, int calls, const Fn& strain) {
  Box c({32, 32, 32}, {0, 0, 0}, {1, 1, 1}, {!thread, false, true});
  const double h = c.hmin(), y0 = 16.2 * h, x0 = 16.35 * h;
  auto dist = [&](double x, double y, double) {
    return thread ? 0.9 * h - std::hypot(x - x0, y - y0) : 0.8 * h - std::fabs(y - y0);
  };
  c.fill(dist);
  const Global G0 = c.gather();
  Reinitializer re(c.g, paramsFor(c, iters, v));
  for (int call = 0; call < calls; ++call) {
    auto m = Kokkos::create_mirror(c.psi);
    Kokkos::deep_copy(m, c.psi);
    const Range3 r = cellRange(c.g);
    for (int k = r.b[2]; k < r.e[2]; ++k)
      for (int j = r.b[1]; j < r.e[1]; ++j)
        for (int i = r.b[0]; i < r.e[0]; ++i) {
          auto x = [&](int d, int l) { return c.g.lo[d] + (c.g.global(d, l) + 0.5) * h; };
          if (std::fabs(m(i, j, k)) < 5 * h) m(i, j, k) *= strain(x(0, i), x(1, j), x(2, k));
        }
    Kokkos::deep_copy(c.psi, m);
    re.run(c.halo, c.psi);
  }
  const Global G = c.gather();
  const int axis = thread ? 0 : 1;
  const auto r0 = G0.runs(axis), r = G.runs(axis);
  FilamentRun out{G0.volumeH(2 * h), G.volumeH(2 * h), r0[0], r[0], r0[1] / h, r[1] / h};
  if (rank0())
    printf("%s, %s, %d call(s) of %d steps: sharp volume %+.2e, int H %+.2e, max thickness %.3f -> %.3f cells\n",
           thread ? "thread r = 0.9 cells" : "sheet 1.6 cells", v.name, calls, iters, out.growth(),
           out.volH / out.volH0 - 1, out.thick0, out.thick);
  return out;
}
double unstrained(double, double, double) { return 1; }
} // namespace

TEST(Reinit, ThinFilamentDoesNotInflate) {
  // Repeated use, as in a run: 100 calls of the default 2 steps on a distance function.
  for (bool thread : {false, true}) {
    const FilamentRun d = runFilament(thread, kDefault, 2, 100, unstrained);
    const FilamentRun p = runFilament(thread, kPlain, 2, 100, unstrained);
    const FilamentRun s = runFilament(thread, kSubcell, 2, 100, unstrained);
    runFilament(thread, kSubcellOnly, 2, 100, unstrained);
    // The sheet is a fixed point (piecewise linear). The thread, default:
    // measured +1.0% volume, thickness 1.659 -> 1.716 cells. Without the
    // constraint the Eikonal erodes it away (-100%); with the subcell fix it
    // loses 33%, and the subcell fix alone inflates it (+65%, 2.0 cells).
    // Allow +-3% and +0.1 cell for the default; none may inflate but the last.
    EXPECT_LT(d.growth(), 0.03);
    EXPECT_GT(d.growth(), -0.03);
    EXPECT_LT(d.thick, d.thick0 + 0.1);
    EXPECT_LT(p.growth(), 0.03);
    EXPECT_LT(s.growth(), 0.03);
  }
  // One long call on a strongly distorted sheet (|grad psi0| 0.5 .. 2): the
  // constraint moves the interface where the Eikonal changes INT H by fixing
  // |grad psi| (reported, the known bump growth), and a persistent 2% strain per
  // call thickens the sheet whatever the variant.
  auto g = [](double x, double, double z) {
    return std::exp(0.5 * std::sin(2 * M_PI * x + 0.4) * std::cos(2 * M_PI * z) + 0.2 * std::sin(2 * M_PI * z));
  };
  auto strain = [](double x, double, double z) { return 1 + 0.02 * std::sin(2 * M_PI * x + 0.4) * std::cos(2 * M_PI * z); };
  for (const Variant* v : {&kDefault, &kPlain, &kSubcell, &kSubcellOnly}) {
    const FilamentRun a = runFilament(false, *v, 40, 1, g);
    const FilamentRun b = runFilament(false, *v, 2, 100, strain);
    if (v == &kDefault) {
      // Measured: +1.2% volume and 1.6 -> 1.83 cells (one call); +5% and 1.6 -> 2.33 (strain).
      EXPECT_LT(a.growth(), 0.03);
      EXPECT_LT(a.thick, 2.0);
      EXPECT_LT(b.growth(), 0.1);
    }
  }
}

// 4. The narrow band: cells with |psi0| >= band are bit-identical after the
// call, and stats.bandCells counts |psi0| < band (counted here independently).
TEST(Reinit, NarrowBandOnly) {
  Sphere c;
  c.fill(distortedSphere);
  const Global G0 = c.gather();
  const double band = 6 * c.hmin();
  Reinitializer re(c.g, paramsFor(c, 10, kDefault));
  const ReinitStats st = re.run(c.halo, c.psi);
  const Global G = c.gather();
  long long inBand = 0, changedOutside = 0, changedInside = 0;
  for (size_t q = 0; q < G.v.size(); ++q) {
    const bool in = std::fabs(G0.v[q]) < band;
    inBand += in;
    if (G.v[q] != G0.v[q]) ++(in ? changedInside : changedOutside);
  }
  if (rank0())
    printf("band: %lld cells (stats %lld) of %lld, %lld changed inside, %lld outside\n", inBand, st.bandCells,
           c.g.cellsGlobal(), changedInside, changedOutside);
  EXPECT_EQ(st.bandCells, inBand);
  EXPECT_EQ(changedOutside, 0);
  EXPECT_GT(changedInside, inBand / 2);
}

// 5. An exact signed distance is nearly a fixed point of the whole scheme.
TEST(Reinit, ExactDistanceIsNearlyFixed) {
  // Sphere: the discrete Eikonal of a curved distance has an O(h^2/R) residual
  // (O(h/R) at the band edge, first order there), so values drift to its own
  // steady state, more the farther out: measured max change 0.0017 cells within
  // 1 cell of the interface, 0.014 within 4, 0.091 in the last band layer.
  {
    Sphere c;
    c.fill(sphereDist);
    const Global G0 = c.gather();
    const ReinitStats st = Reinitializer(c.g, paramsFor(c, 40, kDefault)).run(c.halo, c.psi);
    const Global G = c.gather();
    double near = 0, mid = 0, all = 0;
    for (size_t q = 0; q < G.v.size(); ++q) {
      const double d = std::fabs(G.v[q] - G0.v[q]) / c.hmin(), a = std::fabs(G0.v[q]) / c.hmin();
      all = std::max(all, d);
      if (a < 4) mid = std::max(mid, d);
      if (a < 1) near = std::max(near, d);
    }
    const auto e = contourError(G, sphereDist), e0 = contourError(G0, sphereDist);
    if (rank0())
      printf("exact sphere, 40 steps: max change %.4f / %.4f / %.4f cells (|psi| < 1 / 4 / band), contour error "
             "%.4f -> %.4f cells, stats grad %.4f\n",
             near, mid, all, e0[0], e[0], st.maxGradError);
    EXPECT_LT(near, 0.005);
    EXPECT_LT(mid, 0.03);
    EXPECT_LT(all, 0.15);
    EXPECT_LT(e[0], e0[0] + 0.002); // measured: 0.0087 -> 0.0085
    EXPECT_LT(st.maxGradError, 0.03); // measured 0.012
  }
  // Tilted plane in a walled box: linear, so ENO2 and Godunov are exact and it is
  // a fixed point to round-off, except that the even-reflection ghosts at the
  // walls make it the distance to the plane and its mirror image there. That
  // change decays away from the walls: measured 1.6 cells at a wall, 3e-4 at 6
  // cells, 1.5e-13 at 12. Asserted at >= 12 cells: < 1e-11 cells.
  {
    Box c({32, 32, 32}, {0, 0, 0}, {1, 1, 1}, {false, false, false});
    const double n[3] = {0.48, 0.6, 0.64}; // |n| = 1
    const Fn plane = [&](double x, double y, double z) { return n[0] * x + n[1] * y + n[2] * z - 0.83; };
    c.fill(plane);
    const Global G0 = c.gather();
    Reinitializer(c.g, paramsFor(c, 40, kDefault)).run(c.halo, c.psi);
    const Global G = c.gather();
    double inner = 0, all = 0;
    long long innerBand = 0;
    G.cells([&](int i, int j, int k) {
      const double d = std::fabs(G(i, j, k) - G0(i, j, k)) / c.hmin();
      all = std::max(all, d);
      const int w = std::min({i, j, k, 31 - i, 31 - j, 31 - k}); // cells to the nearest wall
      if (w >= 12) {
        inner = std::max(inner, d);
        innerBand += std::fabs(G0(i, j, k)) < 6 * c.hmin();
      }
    });
    if (rank0())
      printf("tilted plane, 40 steps: max change %.2e cells >= 12 cells from walls (%lld band cells there), %.3f "
             "overall\n",
             inner, innerBand, all);
    EXPECT_GT(innerBand, 100);
    EXPECT_LT(inner, 1e-11);
  }
}

// 6. 2 ranks match 1 rank to round-off (every kernel is local; halos are exact copies).
TEST(Reinit, TwoRanksMatchOne) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size < 2) GTEST_SKIP() << "needs 2 ranks";
  Sphere par;
  par.fill(distortedSphere);
  const ReinitStats sp = Reinitializer(par.g, paramsFor(par, 10, kSubcell)).run(par.halo, par.psi);
  const Global a = par.gather();
  double diff = 0;
  long long bandSerial = 0;
  if (rank0()) {
    Sphere ser(MPI_COMM_SELF);
    ser.fill(distortedSphere);
    bandSerial = Reinitializer(ser.g, paramsFor(ser, 10, kSubcell)).run(ser.halo, ser.psi).bandCells;
    const Global b = ser.gather();
    for (size_t q = 0; q < a.v.size(); ++q) diff = std::max(diff, std::fabs(a.v[q] - b.v[q]));
    printf("2 ranks vs 1: max |psi difference| %.3e, band cells %lld vs %lld\n", diff, sp.bandCells, bandSerial);
  }
  MPI_Bcast(&diff, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  MPI_Bcast(&bandSerial, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  EXPECT_LT(diff, 1e-14);
  EXPECT_EQ(sp.bandCells, bandSerial);
}

// 7. The reinit effect in a run: its scene keys, the interval and the counters.
TEST(Reinit, EffectInARun) {
  const std::string base =
      "name: ri\ndomain: {lo: [0,0,0], hi: [1,1,0.0625], cells: [32,32,2], ranks: [0,0,1]}\n"
      "boundaries: {default: {type: slip}, z-: {type: periodic}, z+: {type: periodic}}\n"
      "time: {end: 10, cfl: 0.5, max_steps: 7}\n"
      "materials: {blob: {density: 1, viscosity: 0}, air: {density: 1, viscosity: 0}}\nfluid: air\n"
      "effects: [prescribed_flow, level_set, reinit]\n"
      "prescribed_flow: {type: rotation, center: [0.5, 0.5, 0], omega: [0, 0, 1]}\n"
      "level_set: {phase: blob, fast_marching: false,"
      " shape: {type: cylinder, center: [0.5, 0.7, 0], radius: 0.15, axis: z}}\n"
      "output: {enabled: false}\n";
  auto sim = test::runScene(test::scene(base + "reinit: {interval: 3, iterations: 4, dtau: 0.25}\n"));
  const State& st = sim->state();
  EXPECT_EQ(st.step, 7);
  EXPECT_EQ(st.counters.at("reinit_calls"), 2); // after steps 3 and 6
  EXPECT_GT(st.diag.at("reinit_band_cells"), 0);
  EXPECT_GT(st.counters.at("reinit_band_cells_total"), st.diag.at("reinit_band_cells"));
  // Keys are validated when the effect is configured.
  for (const char* bad : {"reinit: {intervall: 3}\n", "reinit: {interval: 0}\n", "reinit: {dtau: 0}\n",
                          "reinit: {iterations: 1001}\n", "reinit: {volume_constraint: 2}\n"})
    EXPECT_THROW(Simulation(test::scene(base + bad), MPI_COMM_WORLD), SceneError) << bad;
}
