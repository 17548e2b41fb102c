// Pressure Poisson solves: exactness of the projection, compatibility,
// round-off, breakdown, order of the compact operator, identity rows and
// preconditioners. Runs on 1 and 2 ranks; every assertion is on globally
// reduced values, so all ranks agree.
#include <string>
#include "poisson_fixture.hpp"

using namespace voigt;
using namespace voigt::ptest;
// (c) Exact operator: D u = -dt (rhs - A dp) to round-off, hence max|D u| <= dt ||rhs - A dp||_2.
// Case 1 adds an outflow face (free boundary nodes, where w_n = 1/2 matters) and a periodic axis.
TEST(Poisson, ExactProjection) {
  for (int cs = 0; cs < 2; ++cs) {
    Case c({16, 12, 14}, {false, false, cs == 1}, {1, 0.9, 1.2});
    auto coef = makeCoef(c, {cs == 1 ? 3 : -1, true});
    auto ustar = makeVelocity(c, coef);
    auto s = makePoissonSolver(c.g, cfgOf(PoissonSettings::Op::Exact, 1e-10));
    const double dt = 0.05;
    auto p = project(c, *s, coef, ustar, dt);
    EXPECT_TRUE(p.st.converged);
    EXPECT_LE(p.st.relResidual, 1e-9);
    // Identity D u + dt (rhs - A dp) = 0: round-off of the divergence of O(1) velocities.
    EXPECT_LE(maxAbs(c, p.div, p.res, dt), 1e-12 * p.divStar) << "identity, case " << cs;
    // Bound: max|D u| = dt max|rhs - A dp| <= dt ||rhs - A dp||_2 = dt relRes ||rhs||_2.
    const double rnorm = p.st.relResidual * std::sqrt(dot(c, p.rhs, p.rhs));
    const double du = maxAbs(c, p.div); // collective: not inside the rank-0 branch
    EXPECT_LE(du, dt * rnorm + 1e-12 * p.divStar);
    EXPECT_LE(du, 1e-8 * p.divStar);
    if (rank() == 0)
      std::printf("[exact projection %d] %d null modes, its %d relres %.2e  max|Du*| %.3e -> max|Du| %.3e\n", cs,
                  p.st.nullModes, p.st.iterations, p.st.relResidual, p.divStar, du);
  }
}

// (c2) Cavity-like incompatible rhs: a moving face whose edge nodes stay at rest
// (a driven lid, buildFaceMask) puts part of D u* into null(A) for even n (the
// (-1)^(i+j) f(k) modes: their pairing with D u* telescopes to v(0) - v(n-1) along
// the lid). With only the 5 global modes removed, CG broke down. Now that part is
// removed and reported, and the rest solves to tolerance:
// rhs - A dp = P_N rhs + r with r in range(A), so ||rhs - A dp|| / ||rhs|| =
// sqrt(incompatibility^2 + (relResidual sqrt(1 - incompatibility^2))^2).
// The same lid with its edge nodes moving too ("leaky" lid), or an odd n, is
// compatible: the sum telescopes to 0 (rows 3-4 add the smooth interior u*,
// as a uniform leaky lid alone has D u* = 0).
TEST(Poisson, IncompatibleMovingFace) {
  struct Row { int n; bool leaky, smooth; const char* pc; bool incompatible; };
  const Row rows[] = {{16, false, false, "sgs", true}, {16, false, false, "multigrid", true},
                      {16, true, true, "sgs", false}, {15, false, true, "sgs", false}};
  for (const Row& row : rows) {
    Case c({row.n, row.n, row.n});
    auto coef = makeCoef(c, {});
    VecField ustar = row.smooth ? makeVelocity(c, coef) : c.vec("lid");
    GridGeom G(c.g);
    auto ux = ustar.c[0];
    const int e = row.leaky ? 0 : 1; // edge nodes: moving (leaky) or at rest
    Kokkos::parallel_for(
        "lid", c.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
          const int gi = G.glob(0, i), gj = G.glob(1, j), gk = G.glob(2, k);
          if (gj == G.n[1] && gi >= e && gi <= G.n[0] - e && gk >= e && gk <= G.n[2] - e) ux(i, j, k) = 1;
        });
    Kokkos::fence();
    auto s = makePoissonSolver(c.g, cfgOf(PoissonSettings::Op::Exact, 1e-10, row.pc));
    const double dt = 0.03;
    auto p = project(c, *s, coef, ustar, dt);
    const std::string what = std::to_string(row.n) + (row.leaky ? " leaky " : " ") + row.pc;
    EXPECT_TRUE(p.st.converged) << what;
    EXPECT_EQ(p.st.breakdowns, 0) << what;
    EXPECT_LE(p.st.relResidual, 1e-10) << what;
    if (row.incompatible) EXPECT_GT(p.st.incompatibility, 1e-2) << what;
    else EXPECT_LT(p.st.incompatibility, 1e-12) << what;
    const double inc = p.st.incompatibility, rel = p.st.relResidual;
    const double full = std::sqrt(dot(c, p.res, p.res) / dot(c, p.rhs, p.rhs));
    EXPECT_NEAR(full, std::sqrt(inc * inc + rel * rel * (1 - inc * inc)), 1e-9) << what;
    EXPECT_LE(maxAbs(c, p.div, p.res, dt), 1e-12 * p.divStar) << what; // D u = -dt (rhs - A dp)
    const double du = maxAbs(c, p.div);
    if (rank() == 0)
      std::printf("[lid %-19s] %2d null modes, incompatibility %.3e, its %3d relres %.2e, max|Du*| %.2e -> "
                  "max|Du| %.2e\n", what.c_str(), p.st.nullModes, inc, p.st.iterations, rel, p.divStar, du);
  }
}

// (c3) Round-off: the guess is x0 or 0, whichever has the smaller residual (x0 is
// usually the previous increment); an rhs below double precision is not solved.
TEST(Poisson, RoundoffRhs) {
  Case c({12, 12, 12});
  auto coef = makeCoef(c, {-1, true});
  auto ustar = makeVelocity(c, coef);
  auto s = makePoissonSolver(c.g, cfgOf(PoissonSettings::Op::Exact, 1e-10));
  auto p = project(c, *s, coef, ustar, 0.1); // dp = O(1) solution
  const double dpMax = maxAbs(c, p.dp);
  Field b = c.cell("b"), x = c.cell("x");
  auto rhs = p.rhs;
  // 1. rhs * 1e-20 from the O(1) guess dp: starts from 0, x = 1e-20 dp.
  Kokkos::parallel_for(
      "tiny", c.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) { b(i, j, k) = 1e-20 * rhs(i, j, k); });
  Kokkos::deep_copy(x, p.dp);
  PoissonStats st = s->solve(b, x);
  EXPECT_TRUE(st.converged);
  EXPECT_EQ(st.breakdowns, 0);
  EXPECT_LE(st.relResidual, 1e-9);
  EXPECT_LE(maxAbs(c, x, p.dp, -1e-20), 1e-6 * 1e-20 * dpMax);
  // 2. rhs entirely in null(A), (-1)^(i+j) on the plane k = 3: nothing to solve.
  GridGeom G(c.g);
  Kokkos::parallel_for(
      "mode", c.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        b(i, j, k) = G.glob(2, k) != 3 ? 0.0 : ((G.glob(0, i) + G.glob(1, j)) & 1) ? -1.0 : 1.0;
      });
  Kokkos::deep_copy(x, p.dp);
  st = s->solve(b, x);
  EXPECT_TRUE(st.converged);
  EXPECT_EQ(st.iterations, 0);
  EXPECT_NEAR(st.incompatibility, 1.0, 1e-12);
  EXPECT_EQ(maxAbs(c, x), 0.0); // the guess dp is worse than 0
  // 3. rhs = 0: x = 0, relative residual 0.
  Kokkos::deep_copy(b, 0.0);
  Kokkos::deep_copy(x, p.dp);
  st = s->solve(b, x);
  EXPECT_TRUE(st.converged);
  EXPECT_EQ(st.relResidual, 0.0);
  EXPECT_EQ(maxAbs(c, x), 0.0);
  // 4. The null mode of 2 plus 1e-12 noise: after one projection the null part left
  // by round-off (~1e-16 ||b||) exceeds tol ||b_range||; CG stagnated, then broke
  // down with relres ~1e3-1e8. The solver projects such a rhs twice.
  Field noise = randomCells(c, 7);
  Kokkos::parallel_for(
      "mode_noise", cellRange(c.g).policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        const double m = G.glob(2, k) != 3 ? 0.0 : ((G.glob(0, i) + G.glob(1, j)) & 1) ? -1.0 : 1.0;
        b(i, j, k) = m + 1e-12 * noise(i, j, k);
      });
  Kokkos::deep_copy(x, 0.0);
  st = s->solve(b, x);
  EXPECT_TRUE(st.converged);
  EXPECT_EQ(st.breakdowns, 0);
  EXPECT_LE(st.relResidual, 1e-10);
  EXPECT_GT(st.iterations, 0);
}

// (c4) A tolerance below what round-off allows: CG either breaks down
// (p^T A p <= 0) or stagnates to the iteration limit; neither throws, the true
// residual decides, iterations are counted. Measured at 12^3, SGS, tol 1e-18:
// breakdown after 204 its on 1 rank; on 2 ranks (with the null-space-projected
// preconditioner) no breakdown, the limit is reached.
TEST(Poisson, BreakdownIsReported) {
  Case c({12, 12, 12});
  auto coef = makeCoef(c, {-1, true});
  auto cfg = cfgOf(PoissonSettings::Op::Exact, 1e-18);
  cfg.maxIterations = 2000;
  auto s = makePoissonSolver(c.g, cfg);
  s->setCoefficients(coef);
  auto ustar = makeVelocity(c, coef);
  Field b = c.cell("b"), x = c.cell("x");
  divergence(c.g, ustar, b, cellRange(c.g));
  PoissonStats st;
  EXPECT_NO_THROW(st = s->solve(b, x));
  EXPECT_LE(st.breakdowns, 1);
  EXPECT_FALSE(st.converged);
  EXPECT_GT(st.iterations, 0);
  EXPECT_TRUE(st.breakdowns == 1 || st.iterations == cfg.maxIterations);
  EXPECT_LE(st.relResidual, 1e-5);
  EXPECT_TRUE(std::isfinite(maxAbs(c, x)));
}

// (d) Compact operator: D u = -dt (A_approx - A_exact) dp, a difference of two
// consistent second-order Laplacians applied to a smooth dp, so O(h^2). u* is
// zero on the walls: then both operators see the same homogeneous Neumann
// problem with a smooth solution; a wall flux would enter as an O(1/h) source
// that the two operators distribute differently, spoiling the order at the wall.
TEST(Poisson, ApproximateOrder) {
  double err[2];
  for (int m = 0; m < 2; ++m) {
    const int n = 16 << m;
    Case c({n, n, n});
    auto coef = makeCoef(c, {});
    auto ustar = makeVelocity(c, coef);
    auto s = makePoissonSolver(c.g, cfgOf(PoissonSettings::Op::Approximate, 1e-12));
    auto p = project(c, *s, coef, ustar, 0.1);
    EXPECT_TRUE(p.st.converged);
    err[m] = maxAbs(c, p.div) / p.divStar;
  }
  const double order = std::log2(err[0] / err[1]);
  if (rank() == 0)
    std::printf("[approx projection] max|Du|/max|Du*|: 16^3 %.3e, 32^3 %.3e, order %.2f\n", err[0], err[1], order);
  EXPECT_GT(order, 1.5);
}

// (e) Obstacle: cells with all 8 nodes prescribed become identity rows (p = 0 there).
TEST(Poisson, ObstacleIdentityRows) {
  for (auto op : {PoissonSettings::Op::Exact, PoissonSettings::Op::Approximate})
  for (const char* pc : {"sgs", "multigrid"}) {
    Case c({16, 16, 16});
    auto coef = makeCoef(c, {-1, false, 5, 10});
    auto ustar = makeVelocity(c, coef);
    auto s = makePoissonSolver(c.g, cfgOf(op, 1e-10, pc));
    auto p = project(c, *s, coef, ustar, 0.1);
    EXPECT_TRUE(p.st.converged) << opName(op) << " " << pc;
    const double xm = maxAbs(c, p.dp), dm = maxAbs(c, p.div);
    EXPECT_TRUE(std::isfinite(xm) && std::isfinite(dm)) << opName(op);
    // Inside the obstacle (cells 5..9 in every axis) the pressure is the identity row's 0.
    double inside = 0;
    GridGeom G(c.g);
    auto dp = p.dp;
    Kokkos::parallel_reduce(
        "inside", cellRange(c.g).policy(),
        KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
          const int gi = G.glob(0, i), gj = G.glob(1, j), gk = G.glob(2, k);
          if (gi >= 5 && gi <= 9 && gj >= 5 && gj <= 9 && gk >= 5 && gk <= 9) acc += std::fabs(dp(i, j, k));
        },
        inside);
    MPI_Allreduce(MPI_IN_PLACE, &inside, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    EXPECT_EQ(inside, 0.0) << opName(op) << " " << pc;
    if (op == PoissonSettings::Op::Exact) {
      EXPECT_EQ(s->nullModeCount(), 3 * 16 - 1); // modes zeroed on identity rows stay null
      EXPECT_LE(maxAbs(c, p.div, p.res, 0.1), 1e-12 * p.divStar) << "identity " << pc;
    }
  }
}

// (f) Every preconditioner converges at 16^3 (both operators); a warm start from
// the solution converges at once because the residual is scaled by ||rhs||.
TEST(Poisson, Preconditioners) {
  Case c({16, 16, 16});
  auto coef = makeCoef(c, {-1, true});
  auto coef2 = makeCoef(c, {});
  auto ustar = makeVelocity(c, coef);
  for (auto op : {PoissonSettings::Op::Exact, PoissonSettings::Op::Approximate})
    for (const char* pc : {"sgs", "jacobi", "none", "multigrid"}) {
      auto s = makePoissonSolver(c.g, cfgOf(op, 1e-8, pc));
      s->setCoefficients(coef2); // the second call exercises the refill / reuse path
      auto p = project(c, *s, coef, ustar, 0.1);
      EXPECT_TRUE(p.st.converged) << opName(op) << " " << pc;
      EXPECT_LE(p.st.relResidual, 1e-7) << opName(op) << " " << pc;
      const PoissonStats warm = s->solve(p.rhs, p.dp);
      EXPECT_TRUE(warm.converged);
      EXPECT_LE(warm.iterations, 1) << opName(op) << " " << pc;
      if (rank() == 0)
        std::printf("[16^3 %-6s %-9s] its %4d relres %.2e %.3f s (warm start: %d its)\n", opName(op), pc,
                    p.st.iterations, p.st.relResidual, p.st.seconds, warm.iterations);
    }
  EXPECT_THROW(makePoissonSolver(c.g, cfgOf(PoissonSettings::Op::Exact, 1e-8, "ilu")), std::invalid_argument);
}

// The dam break's water block on a closed 32^3 box: rho 1000 in the corner x < 1/4, y < 1/2,
// z < 1/2 (node coordinates), air rho 1 elsewhere, a sharp jump. Tests (g) and (h).
VecField waterBlockCoef(const Case& c) {
  auto coef = makeCoef(c, {});
  GridGeom G(c.g);
  Kokkos::parallel_for(
      "water_block", c.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        const double x = G.glob(0, i) / 32.0, y = G.glob(1, j) / 32.0, z = G.glob(2, k) / 32.0;
        const double rho = (x <= 0.25 && y <= 0.5 && z <= 0.5) ? 1000.0 : 1.0;
        for (int d = 0; d < 3; ++d) coef.c[d](i, j, k) /= rho;
      });
  Kokkos::fence();
  return coef;
}

// (g) Exact operator at density ratio 1000 (the dam break's water block, rho 1000 in the
// corner x < 1/4, y < 1/2, z < 1/2 of a closed 32^3 box, air rho 1 elsewhere, sharp jump):
// multigrid with the checkerboard near-null vector converges to 1e-8. Bound: measured 92 and
// 94 iterations at 1 and 2 ranks (2026-12-03); with MueLu's default near-null space (constant
// only) the same solve took 347 and 359 (SGS: 497, 660); 150 leaves room for platforms
// and still fails the old set-up.
TEST(Poisson, ExactMultigridDensityRatio1000) {
  Case c({32, 32, 32});
  auto coef = waterBlockCoef(c);
  auto ustar = makeVelocity(c, coef);
  for (const char* pc : {"multigrid", "sgs"}) {
    auto s = makePoissonSolver(c.g, cfgOf(PoissonSettings::Op::Exact, 1e-8, pc));
    auto p = project(c, *s, coef, ustar, 0.1);
    const double rnorm = p.st.relResidual * std::sqrt(dot(c, p.rhs, p.rhs));
    const double du = maxAbs(c, p.div); // collective: outside any rank-0 branch
    if (rank() == 0)
      std::printf("[32^3 exact %-9s ratio 1000] its %4d relres %.2e %.3f s, max|Du|/max|Du*| %.1e\n", pc,
                  p.st.iterations, p.st.relResidual, p.st.seconds, du / p.divStar);
    if (std::string(pc) == "multigrid") {
      EXPECT_TRUE(p.st.converged);
      EXPECT_LE(p.st.iterations, 150);
      // A projection to solver tolerance: max|D u| = dt max|rhs - A dp| <= dt relRes ||rhs||_2
      // (as test (a)), plus round-off of the O(1) velocities.
      EXPECT_LE(du, 0.1 * rnorm + 1e-12 * p.divStar);
      EXPECT_LE(du, 1e-6 * p.divStar); // and far below the approximate path's ~0.5 at a jump
    }
  }
}

// (h) Fast diagonalization (src/solvers/fast_diagonalization.hpp) is the exact inverse of the
// exact operator at one density in a box: CG then converges in one iteration (two allowed
// for round-off at tolerance 1e-10), on no-slip walls, on walls + an outflow face + a
// periodic axis with anisotropic h (test (c)'s cases), on slip walls and with odd extents,
// at 1 and 2 ranks (2 ranks: the slab transposes). In single precision (the default) A0^+ is
// exact to float round-off (~1e-7 relative), so CG needs a second iteration to reach 1e-10:
// measured 2 in every case, relres 6e-13 to 1.2e-12 (2026-12-05); 3 leaves room. At density
// ratio 1000 (test (g)'s sharp water block) it stays a preconditioner: measured 20 iterations
// at 1 and 2 ranks (2026-12-04; multigrid: 92, test (g)); 40 leaves room for platforms. It
// needs the exact operator.
TEST(Poisson, FastDiagonalization) {
  for (const bool single : {false, true})
    for (int cs = 0; cs < 4; ++cs) { // case 3: odd extents (the folds' middle row)
      Case c(cs == 3 ? std::array<int, 3>{15, 13, 11} : std::array<int, 3>{16, 12, 14}, {false, false, cs == 1},
             {1, 0.9, 1.2});
      CoefSpec spec{cs == 1 ? 3 : -1, false}; // one density
      spec.slip = cs == 2;
      auto coef = makeCoef(c, spec);
      auto ustar = makeVelocity(c, coef);
      auto cfg = cfgOf(PoissonSettings::Op::Exact, 1e-10, "fast_diagonalization");
      cfg.fdSingle = single;
      auto s = makePoissonSolver(c.g, cfg);
      const double dt = 0.05;
      auto p = project(c, *s, coef, ustar, dt);
      EXPECT_TRUE(p.st.converged);
      EXPECT_LE(p.st.iterations, single ? 3 : 2) << "case " << cs;
      const double du = maxAbs(c, p.div);
      EXPECT_LE(du, 1e-8 * p.divStar) << "case " << cs;
      if (rank() == 0)
        std::printf("[fast diagonalization %d, %s] its %d relres %.2e max|Du|/max|Du*| %.1e\n", cs,
                    single ? "single" : "double", p.st.iterations, p.st.relResidual, du / p.divStar);
    }
  for (const bool single : {false, true}) {
    Case c({32, 32, 32});
    auto coef = waterBlockCoef(c);
    auto ustar = makeVelocity(c, coef);
    auto cfg = cfgOf(PoissonSettings::Op::Exact, 1e-8, "fast_diagonalization");
    cfg.fdSingle = single;
    auto s = makePoissonSolver(c.g, cfg);
    auto p = project(c, *s, coef, ustar, 0.1);
    const double du = maxAbs(c, p.div);
    if (rank() == 0)
      std::printf("[32^3 exact fast_diagonalization %s ratio 1000] its %d relres %.2e %.3f s, max|Du|/max|Du*| %.1e\n",
                  single ? "single" : "double", p.st.iterations, p.st.relResidual, p.st.seconds, du / p.divStar);
    EXPECT_TRUE(p.st.converged);
    EXPECT_LE(p.st.iterations, 40);
    EXPECT_LE(du, 1e-6 * p.divStar);
    EXPECT_THROW(makePoissonSolver(c.g, cfgOf(PoissonSettings::Op::Approximate, 1e-8, "fast_diagonalization")),
                 std::invalid_argument);
  }
}

// Cost of the two operators at 32^3, SGS-CG to 1e-8 (reported, and must converge).
TEST(Poisson, Cost32) {
  Case c({32, 32, 32});
  auto coef = makeCoef(c, {});
  auto ustar = makeVelocity(c, coef);
  for (auto op : {PoissonSettings::Op::Exact, PoissonSettings::Op::Approximate}) {
    auto s = makePoissonSolver(c.g, cfgOf(op, 1e-8));
    auto p = project(c, *s, coef, ustar, 0.1);
    EXPECT_TRUE(p.st.converged) << opName(op);
    const double du = maxAbs(c, p.div) / p.divStar;
    if (rank() == 0)
      std::printf("[32^3 %-6s sgs] its %4d relres %.2e %.3f s, nnz %lld, max|Du|/max|Du*| %.2e\n", opName(op),
                  p.st.iterations, p.st.relResidual, p.st.seconds, s->globalNonzeros(), du);
  }
}

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rc = 0;
  {
    Kokkos::ScopeGuard kokkos(argc, argv);
    ::testing::InitGoogleTest(&argc, argv);
    if (rank() != 0) {
      auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
      delete listeners.Release(listeners.default_result_printer());
    }
    rc = RUN_ALL_TESTS();
  }
  MPI_Allreduce(MPI_IN_PLACE, &rc, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return rc;
}
