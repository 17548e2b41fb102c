#pragma once
// Shared fixtures for the Poisson solver tests: grids, coefficient patterns,
// velocities, dense operators. Functions are inline so both test files link.
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


namespace voigt::ptest {
using namespace voigt;


constexpr double kPi = 3.14159265358979323846;

inline int rank() {
  int r;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

struct Case {
  Grid g;
  Case(std::array<int, 3> n, std::array<bool, 3> per = {false, false, false},
       std::array<double, 3> hi = {1, 1, 1}, MPI_Comm comm = MPI_COMM_WORLD)
      : g(makeGrid(comm, n, {0, 0, 0}, hi, per)) {}
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
  bool slip = false;           // walls prescribe the normal component only
};

// coef_d = 1/rho at free nodes, 0 on wall faces and in the obstacle. Filled
// analytically over the whole array (ghosts included), so no halo is needed.
inline VecField makeCoef(const Case& c, CoefSpec s) {
  VecField coef = c.vec("coef");
  GridGeom G(c.g);
  Kokkos::parallel_for(
      "coef", c.all().policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        const int l[3] = {i, j, k};
        int gi[3];
        bool wall = false, obs = true, wallD[3] = {false, false, false};
        for (int d = 0; d < 3; ++d) {
          gi[d] = G.glob(d, l[d]);
          if (G.per[d]) gi[d] = ((gi[d] % G.n[d]) + G.n[d]) % G.n[d];
          if (!G.per[d] && gi[d] == 0 && s.outflowFace != 2 * d) wallD[d] = true;
          if (!G.per[d] && gi[d] == G.n[d] && s.outflowFace != 2 * d + 1) wallD[d] = true;
          wall = wall || wallD[d];
          obs = obs && gi[d] >= s.obsLo && gi[d] <= s.obsHi;
        }
        const double x = gi[0] / double(G.n[0]), y = gi[1] / double(G.n[1]), z = gi[2] / double(G.n[2]);
        const double rho = s.variable ? 1 + 0.5 * std::sin(2 * kPi * x) * std::cos(2 * kPi * (y + z)) : 1.0;
        for (int d = 0; d < 3; ++d)
          coef.c[d](i, j, k) = ((s.slip ? wallD[d] : wall) || obs) ? 0.0 : (s.variable ? 1 + 0.2 * d : 1.0) / rho;
      });
  Kokkos::fence();
  return coef;
}

// Smooth u*, zero on non-periodic boundary faces (sin-products) and wherever
// coef_d = 0, so that rhs = -D u*/dt is orthogonal to every null mode.
inline VecField makeVelocity(const Case& c, const VecField& coef) {
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
inline Field randomCells(const Case& c, unsigned seed) {
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

inline double dot(const Case& c, const Field& a, const Field& b) {
  double s = 0;
  Kokkos::parallel_reduce(
      "dot", cellRange(c.g).policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& acc) { acc += a(i, j, k) * b(i, j, k); }, s);
  MPI_Allreduce(MPI_IN_PLACE, &s, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return s;
}

// max over owned cells of |a + alpha b|
inline double maxAbs(const Case& c, const Field& a, const Field& b = Field(), double alpha = 0) {
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

inline PoissonSettings cfgOf(PoissonSettings::Op op, double tol, const char* pc = "sgs") {
  PoissonSettings cfg;
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

inline Projection project(const Case& c, PoissonSolver& s, const VecField& coef, const VecField& ustar, double dt) {
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

inline const char* opName(PoissonSettings::Op op) { return op == PoissonSettings::Op::Exact ? "exact" : "approx"; }

// Dense A (global rows x global columns, lexicographic cell index), assembled
// column by column through apply(); identical on every rank.
inline std::vector<double> denseOperator(const Case& c, PoissonSolver& s) {
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
inline int nullity(std::vector<double> A, int N) {
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

} // namespace voigt::ptest
