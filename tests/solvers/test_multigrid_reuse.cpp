// projection.multigrid_reuse (MueLu "reuse: type") and projection.multigrid_refresh:
// after the coefficients change (a density jump moving through the box, as in a
// two-phase scene), a solver that keeps part of its multigrid set-up must still
// converge, to the same solution as a full rebuild ("none") within what the CG
// tolerance allows. Also when the zero pattern changes (a moving obstacle), where
// the solver rebuilds the hierarchy.
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "poisson_fixture.hpp"

namespace voigt::ptest {
namespace {

constexpr double kTol = 1e-8; // CG relative residual ||b - A x|| <= kTol ||b|| for every solver

// Two phases: rho = 100 in the slab |y - yc| <= 0.2 (the falling block's density),
// 1.2 elsewhere (air); coef_d = 1/rho at free nodes, 0 on the walls and, when
// obstacle >= 0, in the cube of nodes [obstacle, obstacle + 3]^3.
VecField twoPhaseCoef(const Case& c, double yc, int obstacle) {
  VecField coef = c.vec("coef");
  GridGeom G(c.g);
  Kokkos::parallel_for(
      "coef_two_phase", c.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        const int l[3] = {i, j, k};
        int gi[3];
        bool wall = false, obs = obstacle >= 0;
        for (int d = 0; d < 3; ++d) {
          gi[d] = G.glob(d, l[d]);
          wall = wall || gi[d] <= 0 || gi[d] >= G.n[d];
          obs = obs && gi[d] >= obstacle && gi[d] <= obstacle + 3;
        }
        const double y = gi[1] / double(G.n[1]);
        const double rho = std::fabs(y - yc) <= 0.2 ? 100.0 : 1.2;
        for (int d = 0; d < 3; ++d) coef.c[d](i, j, k) = (wall || obs) ? 0.0 : 1 / rho;
      });
  Kokkos::fence();
  return coef;
}

struct Run {
  std::string reuse;
  int refresh;
  std::string smoother;
  std::unique_ptr<PoissonSolver> solver;
  Field x;
  PoissonStats st;
};

void movingJump(PoissonSettings::Op op, int n, bool movingObstacle) {
  Case c({n, n, n});
  const double dt = 0.1;
  std::vector<Run> runs;
  for (const char* r : {"none", "S", "tP", "RP", "RAP"}) runs.push_back({r, 0, "sgs", nullptr, Field(), {}});
  runs.push_back({"RAP", 3, "sgs", nullptr, Field(), {}}); // full rebuild every 3rd update
  // Chebyshev (the paper scenes' smoother): tP must equal its own rebuild bit for bit
  // (the fine level's eigenvalue estimate is recomputed on every update), RAP converge.
  runs.push_back({"none", 0, "chebyshev", nullptr, Field(), {}});
  runs.push_back({"tP", 0, "chebyshev", nullptr, Field(), {}});
  runs.push_back({"RAP", 0, "chebyshev", nullptr, Field(), {}});
  for (auto& r : runs) {
    PoissonSettings cfg = cfgOf(op, kTol, "multigrid");
    cfg.multigridReuse = r.reuse;
    cfg.multigridRefresh = r.refresh;
    cfg.multigridSmoother = r.smoother;
    r.solver = makePoissonSolver(c.g, cfg);
    r.x = c.cell("x");
  }
  Field rhs = c.cell("rhs"), diff = c.cell("diff"), adiff = c.cell("adiff");
  for (int step = 0; step < 6; ++step) {
    // The slab moves 1/12 of the box a step (2 cells at 24^3); the obstacle 1 cell
    // every other step, so that reuse follows each rebuild on a changed pattern.
    const double yc = 0.25 + step / 12.0;
    auto coef = twoPhaseCoef(c, yc, movingObstacle ? 6 + step / 2 : -1);
    auto ustar = makeVelocity(c, coef); // zero where coef = 0: rhs orthogonal to null(A)
    divergence(c.g, ustar, rhs, cellRange(c.g));
    const double bn = std::sqrt(dot(c, rhs, rhs)) / dt;
    Kokkos::parallel_for(
        "rhs", cellRange(c.g).policy(), KOKKOS_LAMBDA(int i, int j, int k) { rhs(i, j, k) *= -1 / dt; });
    for (auto& r : runs) {
      r.solver->setCoefficients(coef);
      Kokkos::deep_copy(r.x, 0.0);
      const PoissonStats st = r.st = r.solver->solve(rhs, r.x);
      const std::string what = std::string(opName(op)) + " reuse " + r.reuse + " refresh " +
                               std::to_string(r.refresh) + " " + r.smoother + " step " + std::to_string(step);
      EXPECT_TRUE(st.converged) << what;
      EXPECT_EQ(st.breakdowns, 0) << what;
      // relResidual is the explicit ||b - A x|| / ||b||; Belos stops on its implicit
      // (recursively updated) residual, which may drift from it: 2x margin (the
      // Preconditioners test in test_poisson.cpp allows 10x).
      EXPECT_LE(st.relResidual, 2 * kTol) << what;
      // Against the full rebuild ("none", solved first): b - A x = r, b - A x_none = r_none,
      // so ||A (x - x_none)|| <= (||r|| + ||r_none||), both reported as relResidual ||b||.
      // Null modes are projected off both (and A ignores them). 1e-3 kTol ||b|| covers the
      // round-off of evaluating the residuals, far below kTol.
      const Field x0 = runs[0].x;
      const Field x = r.x;
      Kokkos::parallel_for(
          "diff", cellRange(c.g).policy(), KOKKOS_LAMBDA(int i, int j, int k) { diff(i, j, k) = x(i, j, k) - x0(i, j, k); });
      Kokkos::fence();
      r.solver->apply(diff, adiff);
      const double ad = std::sqrt(dot(c, adiff, adiff));
      EXPECT_LE(ad, (st.relResidual + runs[0].st.relResidual + 1e-3 * kTol) * bn) << what;
      // S and tP keep only what does not depend on the values: smoother set-up data,
      // aggregates (built from the graph: "aggregation: drop tol" 0) and tentative
      // prolongators (from the constant null space). Each update then gives the same
      // preconditioner as a rebuild, bit for bit. Restarts (which rebuild) stay
      // bit-identical with tP, the default (README "Checkpoint and restart").
      if (r.reuse == "S" || r.reuse == "tP") { // against the rebuild with the same smoother
        const Field xs = r.smoother == "sgs" ? runs[0].x : runs[6].x;
        Kokkos::parallel_for(
            "same", cellRange(c.g).policy(), KOKKOS_LAMBDA(int i, int j, int k) { diff(i, j, k) = x(i, j, k) - xs(i, j, k); });
        Kokkos::fence();
        EXPECT_EQ(maxAbs(c, diff), 0.0) << what;
      }
      if (rank() == 0)
        std::printf("[%s%s %-4s refresh %d %-9s] step %d: its %3d relres %.2e ||A(x - x_none)||/||b|| %.2e\n",
                    opName(op), movingObstacle ? " +obstacle" : "", r.reuse.c_str(), r.refresh, r.smoother.c_str(), step,
                    st.iterations, st.relResidual, ad / bn);
    }
  }
}

TEST(MultigridReuse, MovingDensityJumpApproximate) { movingJump(PoissonSettings::Op::Approximate, 24, false); }
// Multigrid on the 27-point exact operator needs hundreds of iterations (measured before the
// checkerboard near-null vector: 226-314 at 16^3, 657 at 24^3, against ~30 on the 7-point
// one; with it, 2026-12-03: 46-194 with none, S, tP and RP, but 559-1047 with RAP, whose kept
// coarse levels miss the moved jump): a small grid keeps this test short (16^3 still gives
// MueLu a coarse level, 12^3 would not).
TEST(MultigridReuse, MovingDensityJumpExact) { movingJump(PoissonSettings::Op::Exact, 16, false); }
TEST(MultigridReuse, MovingObstacleRebuilds) { movingJump(PoissonSettings::Op::Approximate, 24, true); }

// MueLu's "full" keeps the fine smoother's inverse diagonal while A changes in place:
// CG broke down at the first iteration after the slab moved. Not offered.
TEST(MultigridReuse, UnsafeTypesRejected) {
  Case c({8, 8, 8});
  for (const char* r : {"full", "emin", "tp"}) {
    PoissonSettings cfg = cfgOf(PoissonSettings::Op::Approximate, kTol, "multigrid");
    cfg.multigridReuse = r;
    EXPECT_THROW(makePoissonSolver(c.g, cfg), std::invalid_argument) << r;
  }
}

} // namespace
} // namespace voigt::ptest
