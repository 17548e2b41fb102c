// Pressure Poisson solver (src/solvers/poisson.hpp): operator symmetry, null
// space, exactness of the projection, order of the compact operator, identity
// rows and preconditioners. Runs on 1 and 2 ranks; every assertion is on
// globally reduced values, so all ranks agree.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/halo.hpp"
#include "core/index_space.hpp"
#include "kernels/projection_ops.hpp"
#include "solvers/poisson.hpp"

using namespace voigt;

namespace {

constexpr double kPi = 3.14159265358979323846;

int rank() {
  int r;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

struct Case {
  Grid g;
  Case(std::array<int, 3> n, std::array<bool, 3> per = {false, false, false},
       std::array<double, 3> hi = {1, 1, 1})
      : g(makeGrid(MPI_COMM_WORLD, n, {0, 0, 0}, hi, per)) {}
  ~Case() { freeGrid(g); }
  Field cell(const char* name) const { return Field(std::string(name), g.ext[0], g.ext[1], g.ext[2]); }
  VecField vec(const char* name) const {
    VecField v;
    for (int d = 0; d < 3; ++d) v.c[d] = cell(name);
    return v;
  }
  Range3 all() const { return Range3{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}}; }
};

struct CoefSpec {
  int outflowFace = -1;        // face (2*axis + side) whose nodes stay free
  bool variable = false;       // smooth variable density, component-dependent
  int obsLo = -1, obsHi = -1;  // obstacle: global nodes in [obsLo, obsHi]^3 prescribed
};

// coef_d = 1/rho at free nodes, 0 on wall faces and in the obstacle. Filled
// analytically over the whole array (ghosts included), so no halo is needed.
VecField makeCoef(const Case& c, CoefSpec s) {
  VecField coef = c.vec("coef");
  GridGeom G(c.g);
  Kokkos::parallel_for(
      "coef", c.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        const int l[3] = {i, j, k};
        int gi[3];
        bool wall = false, obs = true;
        for (int d = 0; d < 3; ++d) {
          gi[d] = G.glob(d, l[d]);
          if (G.per[d]) gi[d] = ((gi[d] % G.n[d]) + G.n[d]) % G.n[d];
          if (!G.per[d] && gi[d] == 0 && s.outflowFace != 2 * d) wall = true;
          if (!G.per[d] && gi[d] == G.n[d] && s.outflowFace != 2 * d + 1) wall = true;
          obs = obs && gi[d] >= s.obsLo && gi[d] <= s.obsHi;
        }
        const double x = gi[0] / double(G.n[0]), y = gi[1] / double(G.n[1]), z = gi[2] / double(G.n[2]);
        const double rho = s.variable ? 1 + 0.5 * std::sin(2 * kPi * x) * std::cos(2 * kPi * (y + z)) : 1.0;
        for (int d = 0; d < 3; ++d)
          coef.c[d](i, j, k) = (wall || obs) ? 0.0 : (s.variable ? 1 + 0.2 * d : 1.0) / rho;
      });
  Kokkos::fence();
  return coef;
}

// Smooth u*, zero on non-periodic boundary faces (sin-products) and wherever
// coef_d = 0, so that rhs = -D u*/dt is orthogonal to every null mode.
VecField makeVelocity(const Case& c, const VecField& coef) {
  VecField u = c.vec("u");
  GridGeom G(c.g);
  Kokkos::parallel_for(
      "ustar", c.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        const int l[3] = {i, j, k};
        double x[3], s = 1;
        for (int d = 0; d < 3; ++d) {
          x[d] = G.glob(d, l[d]) / double(G.n[d]);
          if (!G.per[d]) s *= std::sin(kPi * x[d]);
        }
        const double f[3] = {1 + 0.5 * std::cos(2 * kPi * (x[1] + 2 * x[2])),
                             0.7 - 0.4 * std::sin(2 * kPi * (x[0] - x[2])),
                             -0.3 + 0.6 * std::cos(2 * kPi * (2 * x[0] + x[1]))};
        for (int d = 0; d < 3; ++d) u.c[d](i, j, k) = coef.c[d](i, j, k) == 0 ? 0.0 : s * f[d];
      });
  Kokkos::fence();
  return u;
}

// Rank-independent pseudo-random values in [-1, 1] on owned cells.
Field randomCells(const Case& c, unsigned seed) {
  Field f = c.cell("rand");
  GridGeom G(c.g);
  Kokkos::parallel_for(
      "rand", cellRange(c.g).policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        unsigned h = seed + 2654435761u * unsigned(G.glob(0, i) + G.n[0] * (G.glob(1, j) + G.n[1] * G.glob(2, k)));
        h ^= h >> 13; h *= 0x5bd1e995u; h ^= h >> 15;
        f(i, j, k) = (h % 2000001u) / 1000000.0 - 1.0;
      });
  Kokkos::fence();
  return f;
}

double dot(const Case& c, const Field& a, const Field& b) {
  double s = 0;
  Kokkos::parallel_reduce(
      "dot", cellRange(c.g).policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& acc) { acc += a(i, j, k) * b(i, j, k); }, s);
  MPI_Allreduce(MPI_IN_PLACE, &s, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return s;
}

// max over owned cells of |a + alpha b|
double maxAbs(const Case& c, const Field& a, const Field& b = Field(), double alpha = 0) {
  double m = 0;
  const bool hasB = b.size() > 0;
  Kokkos::parallel_reduce(
      "maxabs", cellRange(c.g).policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
        const double v = std::fabs(a(i, j, k) + (hasB ? alpha * b(i, j, k) : 0.0));
        acc = v > acc ? v : acc;
      },
      Kokkos::Max<double>(m));
  MPI_Allreduce(MPI_IN_PLACE, &m, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return m;
}

ProjectionCfg cfgOf(ProjectionCfg::Op op, double tol, const char* pc = "sgs") {
  ProjectionCfg cfg;
  cfg.op = op;
  cfg.tolerance = tol;
  cfg.maxIterations = 3000;
  cfg.preconditioner = pc;
  return cfg;
}

// Full projection: rhs = -D u*/dt, solve, u = u* - dt coef G dp.
struct Projection {
  Field rhs, dp, res, div; // res = rhs - A dp
  VecField u;
  PoissonStats st;
  double divStar = 0; // max |D u*|
};

Projection project(const Case& c, PoissonSolver& s, const VecField& coef, const VecField& ustar, double dt) {
  Projection p;
  p.rhs = c.cell("rhs");
  p.dp = c.cell("dp");
  p.res = c.cell("res");
  p.div = c.cell("div");
  divergence(c.g, ustar, p.div, cellRange(c.g));
  p.divStar = maxAbs(c, p.div);
  auto rhs = p.rhs, div = p.div;
  Kokkos::parallel_for(
      "rhs", cellRange(c.g).policy(), KOKKOS_LAMBDA(int i, int j, int k) { rhs(i, j, k) = -div(i, j, k) / dt; });
  s.setCoefficients(coef);
  p.st = s.solve(p.rhs, p.dp);
  s.apply(p.dp, p.res);
  auto res = p.res;
  Kokkos::parallel_for(
      "res", cellRange(c.g).policy(), KOKKOS_LAMBDA(int i, int j, int k) { res(i, j, k) = rhs(i, j, k) - res(i, j, k); });
  Halo halo(c.g);
  halo.exchange(p.dp);
  p.u = c.vec("u_new");
  for (int d = 0; d < 3; ++d) Kokkos::deep_copy(p.u.c[d], ustar.c[d]);
  subtractGradient(c.g, p.dp, coef, dt, p.u, nodeRange(c.g));
  halo.exchange(p.u); // corner nodes owned by the neighbour
  divergence(c.g, p.u, p.div, cellRange(c.g));
  return p;
}

const char* opName(ProjectionCfg::Op op) { return op == ProjectionCfg::Op::Exact ? "exact" : "approx"; }

// Dense A (global rows x global columns, lexicographic cell index), assembled
// column by column through apply(); identical on every rank.
std::vector<double> denseOperator(const Case& c, PoissonSolver& s) {
  const Grid& g = c.g;
  const int N = (int)g.cellsGlobal();
  std::vector<double> A((size_t)N * N, 0.0);
  Field x = c.cell("x"), y = c.cell("y");
  auto hx = Kokkos::create_mirror_view(x);
  auto hy = Kokkos::create_mirror_view(y);
  const Range3 r = cellRange(g);
  auto gidx = [&](int i, int j, int k) {
    return g.global(0, i) + g.n[0] * (g.global(1, j) + g.n[1] * g.global(2, k));
  };
  for (int col = 0; col < N; ++col) {
    Kokkos::deep_copy(hx, 0.0);
    for (int k = r.b[2]; k < r.e[2]; ++k)
      for (int j = r.b[1]; j < r.e[1]; ++j)
        for (int i = r.b[0]; i < r.e[0]; ++i)
          if (gidx(i, j, k) == col) hx(i, j, k) = 1;
    Kokkos::deep_copy(x, hx);
    s.apply(x, y);
    Kokkos::deep_copy(hy, y);
    for (int k = r.b[2]; k < r.e[2]; ++k)
      for (int j = r.b[1]; j < r.e[1]; ++j)
        for (int i = r.b[0]; i < r.e[0]; ++i) A[(size_t)gidx(i, j, k) * N + col] = hy(i, j, k);
  }
  MPI_Allreduce(MPI_IN_PLACE, A.data(), N * N, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return A;
}

// dim null(A) of a symmetric positive semidefinite A by diagonally pivoted
// Cholesky: stop when the largest Schur-complement diagonal is below 1e-10 max.
int nullity(std::vector<double> A, int N) {
  std::vector<char> done(N, 0);
  double d0 = 0;
  for (int i = 0; i < N; ++i) d0 = std::max(d0, A[(size_t)i * N + i]);
  int rank = 0;
  for (; rank < N; ++rank) {
    int p = -1;
    for (int i = 0; i < N; ++i)
      if (!done[i] && (p < 0 || A[(size_t)i * N + i] > A[(size_t)p * N + p])) p = i;
    const double piv = A[(size_t)p * N + p];
    if (piv <= 1e-10 * d0) break;
    done[p] = 1;
    for (int i = 0; i < N; ++i) {
      if (done[i]) continue;
      const double f = A[(size_t)i * N + p] / piv;
      if (f == 0) continue;
      for (int j = 0; j < N; ++j)
        if (!done[j]) A[(size_t)i * N + j] -= f * A[(size_t)p * N + j];
    }
  }
  return N - rank;
}

} // namespace

// (a) <Ax, y> == <x, Ay>, with variable coefficients, a periodic axis, an outflow face and an obstacle.
// The second grid has 2 cells on a periodic axis, where offsets -1 and +1 alias (merged entries).
TEST(Poisson, Symmetric) {
  for (auto op : {ProjectionCfg::Op::Exact, ProjectionCfg::Op::Approximate})
  for (int grid = 0; grid < 2; ++grid) {
    Case c(grid ? std::array<int, 3>{6, 2, 5} : std::array<int, 3>{8, 6, 7},
           grid ? std::array<bool, 3>{true, true, false} : std::array<bool, 3>{false, true, false}, {1, 0.8, 1.3});
    auto coef = makeCoef(c, grid ? CoefSpec{5, true} : CoefSpec{1, true, 2, 4});
    auto s = makePoissonSolver(c.g, cfgOf(op, 1e-8));
    s->setCoefficients(coef);
    Field x = randomCells(c, 1), y = randomCells(c, 2), Ax = c.cell("Ax"), Ay = c.cell("Ay");
    s->apply(x, Ax);
    s->apply(y, Ay);
    const double lhs = dot(c, Ax, y), rhs = dot(c, x, Ay);
    const double scale = std::sqrt(dot(c, Ax, Ax) * dot(c, y, y));
    EXPECT_LE(std::fabs(lhs - rhs), 1e-12 * scale) << opName(op) << " grid " << grid;
    EXPECT_GT(s->globalNonzeros(), 0);
  }
}

// (b) Null modes, decided numerically (src/solvers/null_space.hpp).
TEST(Poisson, NullModes) {
  const auto E = ProjectionCfg::Op::Exact, P = ProjectionCfg::Op::Approximate;
  struct Row { std::array<int, 3> n; bool periodic; int outflow; ProjectionCfg::Op op; int expected; };
  // Walls or fully periodic (even n): the constant and the modulated modes
  // (-1)^(i_a+i_b)[i_c == q], n_x + n_y + n_z - 1 independent ones (the three
  // families share (-1)^(i+j+k)). Outflow face x+: the n_x modes (-1)^(j+k)[i == q]
  // (their G vanishes even with the outside cell missing). Odd periodic n breaks the
  // alternation. The 7-point operator only has the constant (none with outflow).
  const Row rows[] = {{{8, 8, 8}, false, -1, E, 23}, {{8, 8, 8}, true, -1, E, 23},
                      {{8, 8, 8}, false, 1, E, 8},   {{9, 9, 9}, true, -1, E, 1},
                      {{6, 2, 6}, true, -1, E, 13},  {{8, 8, 8}, false, -1, P, 1},
                      {{8, 8, 8}, false, 1, P, 0}};
  for (const Row& r : rows) {
    Case c(r.n, {r.periodic, r.periodic, r.periodic});
    auto s = makePoissonSolver(c.g, cfgOf(r.op, 1e-8));
    s->setCoefficients(makeCoef(c, {r.outflow}));
    EXPECT_EQ(s->nullModeCount(), r.expected)
        << opName(r.op) << " n=" << r.n[0] << " periodic=" << r.periodic << " outflow=" << r.outflow;
  }
}

// (b2) The solver's null-space dimension equals dim null(A) measured on the
// dense operator. All walls 8^3: 23 = 3 n - 1 (not the 5 global modes); outflow
// x+: 8; periodic 6x2x6: 13; walls + obstacle (8 identity rows): 23.
TEST(Poisson, NullSpaceDimension) {
  struct Row { std::array<int, 3> n; bool periodic; CoefSpec spec; int expected; };
  const Row rows[] = {{{8, 8, 8}, false, {-1, true}, 23},
                      {{8, 8, 8}, false, {1, true}, 8},
                      {{6, 2, 6}, true, {-1, true}, 13},
                      {{8, 8, 8}, false, {-1, false, 3, 5}, 23}};
  for (const Row& r : rows) {
    Case c(r.n, {r.periodic, r.periodic, r.periodic});
    auto s = makePoissonSolver(c.g, cfgOf(ProjectionCfg::Op::Exact, 1e-8));
    s->setCoefficients(makeCoef(c, r.spec));
    const int N = (int)c.g.cellsGlobal();
    const int measured = nullity(denseOperator(c, *s), N);
    EXPECT_EQ(measured, r.expected) << "n0=" << r.n[0] << " outflow=" << r.spec.outflowFace;
    EXPECT_EQ(s->nullModeCount(), measured) << "n0=" << r.n[0] << " outflow=" << r.spec.outflowFace;
  }
}

// (c) Exact operator: D u = -dt (rhs - A dp) to round-off, hence max|D u| <= dt ||rhs - A dp||_2.
// Case 1 adds an outflow face (free boundary nodes, where w_n = 1/2 matters) and a periodic axis.
TEST(Poisson, ExactProjection) {
  for (int cs = 0; cs < 2; ++cs) {
    Case c({16, 12, 14}, {false, false, cs == 1}, {1, 0.9, 1.2});
    auto coef = makeCoef(c, {cs == 1 ? 3 : -1, true});
    auto ustar = makeVelocity(c, coef);
    auto s = makePoissonSolver(c.g, cfgOf(ProjectionCfg::Op::Exact, 1e-10));
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
    auto s = makePoissonSolver(c.g, cfgOf(ProjectionCfg::Op::Exact, 1e-10, row.pc));
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
  auto s = makePoissonSolver(c.g, cfgOf(ProjectionCfg::Op::Exact, 1e-10));
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
  auto cfg = cfgOf(ProjectionCfg::Op::Exact, 1e-18);
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
    auto s = makePoissonSolver(c.g, cfgOf(ProjectionCfg::Op::Approximate, 1e-12));
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
  for (auto op : {ProjectionCfg::Op::Exact, ProjectionCfg::Op::Approximate})
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
    if (op == ProjectionCfg::Op::Exact) {
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
  for (auto op : {ProjectionCfg::Op::Exact, ProjectionCfg::Op::Approximate})
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
  EXPECT_THROW(makePoissonSolver(c.g, cfgOf(ProjectionCfg::Op::Exact, 1e-8, "ilu")), std::invalid_argument);
}

// Cost of the two operators at 32^3, SGS-CG to 1e-8 (reported, and must converge).
TEST(Poisson, Cost32) {
  Case c({32, 32, 32});
  auto coef = makeCoef(c, {});
  auto ustar = makeVelocity(c, coef);
  for (auto op : {ProjectionCfg::Op::Exact, ProjectionCfg::Op::Approximate}) {
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
