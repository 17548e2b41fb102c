// Poisson operator: symmetry and null space (src/solvers/poisson.hpp).
#include "effects/navier_stokes/navier_stokes.hpp" // poissonSettings()
#include "poisson_fixture.hpp"
#include "solvers/fast_diagonalization.hpp"

#include <cstring> // memcmp

using namespace voigt;
using namespace voigt::ptest;

// (a) <Ax, y> == <x, Ay>, with variable coefficients, a periodic axis, an outflow face and an obstacle.
// The second grid has 2 cells on a periodic axis, where offsets -1 and +1 alias (merged entries).
TEST(Poisson, Symmetric) {
  for (auto op : {PoissonSettings::Op::Exact, PoissonSettings::Op::Approximate})
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

// (a2) The matrix-free exact operator (kernels/poisson_apply.hpp) is the CSR matrix's: the same
// cases as (a) (identity rows of an obstacle, a periodic axis of 2 cells whose offsets alias),
// at 1 and 2 ranks. Tolerance: the two sum the same 27 x 8 products in different orders, so
// they differ by a few ulps of the largest partial sum; 1e-13 of max |A x| leaves 100x room.
TEST(Poisson, MatrixFreeMatchesMatrix) {
  for (int grid = 0; grid < 2; ++grid) {
    Case c(grid ? std::array<int, 3>{6, 2, 5} : std::array<int, 3>{8, 6, 7},
           grid ? std::array<bool, 3>{true, true, false} : std::array<bool, 3>{false, true, false}, {1, 0.8, 1.3});
    auto coef = makeCoef(c, grid ? CoefSpec{5, true} : CoefSpec{1, true, 2, 4});
    PoissonSettings mfCfg = cfgOf(PoissonSettings::Op::Exact, 1e-8), csrCfg = mfCfg;
    mfCfg.matrixFree = true;
    csrCfg.matrixFree = false;
    auto mf = makePoissonSolver(c.g, mfCfg), csr = makePoissonSolver(c.g, csrCfg);
    mf->setCoefficients(coef);
    csr->setCoefficients(coef);
    Field x = randomCells(c, 3), a = c.cell("Ax_mf"), b = c.cell("Ax_csr");
    mf->apply(x, a);
    csr->apply(x, b);
    const double scale = maxAbs(c, b);
    EXPECT_GT(scale, 0);
    EXPECT_LE(maxAbs(c, a, b, -1), 1e-13 * scale) << "grid " << grid;
  }
}

// (b) Null modes, decided numerically (src/solvers/null_space.hpp).
TEST(Poisson, NullModes) {
  const auto E = PoissonSettings::Op::Exact, P = PoissonSettings::Op::Approximate;
  struct Row { std::array<int, 3> n; bool periodic; int outflow; PoissonSettings::Op op; int expected; };
  // Walls or fully periodic (even n): the constant and the modulated modes
  // (-1)^(i_a+i_b)[i_c == q], n_x + n_y + n_z - 1 independent ones (the three
  // families share (-1)^(i+j+k)). Outflow face x+: the n_x modes (-1)^(j+k)[i == q]
  // (their G vanishes even with the outside cell missing). Odd periodic n breaks the
  // alternation. The 7-point operator only has the constant (none with outflow).
  const Row rows[] = {{{8, 8, 8}, false, -1, E, 23}, {{8, 8, 8}, true, -1, E, 23},
                      {{8, 8, 8}, false, 1, E, 8},   {{9, 9, 9}, true, -1, E, 1},
                      {{6, 2, 6}, true, -1, E, 13},  {{8, 8, 8}, false, -1, P, 1},
                      {{8, 8, 8}, false, 1, P, 0}};
  // Exact operator also without its matrix (fast diagonalization: the null-space test then
  // runs on the matrix-free product and the bound on ||A||, poissonRowPattern).
  for (const Row& r : rows)
    for (const char* pc : {"sgs", "fast_diagonalization"}) {
      if (r.op == P && std::string(pc) != "sgs") continue;
      Case c(r.n, {r.periodic, r.periodic, r.periodic});
      auto s = makePoissonSolver(c.g, cfgOf(r.op, 1e-8, pc));
      s->setCoefficients(makeCoef(c, {r.outflow}));
      EXPECT_EQ(s->nullModeCount(), r.expected)
          << opName(r.op) << " " << pc << " n=" << r.n[0] << " periodic=" << r.periodic << " outflow=" << r.outflow;
      if (std::string(pc) != "sgs") EXPECT_EQ(s->globalNonzeros(), 0); // no matrix
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
    auto s = makePoissonSolver(c.g, cfgOf(PoissonSettings::Op::Exact, 1e-8));
    s->setCoefficients(makeCoef(c, r.spec));
    const int N = (int)c.g.cellsGlobal();
    const int measured = nullity(denseOperator(c, *s), N);
    EXPECT_EQ(measured, r.expected) << "n0=" << r.n[0] << " outflow=" << r.spec.outflowFace;
    EXPECT_EQ(s->nullModeCount(), measured) << "n0=" << r.n[0] << " outflow=" << r.spec.outflowFace;
  }
}

// The scene's projection section reaches the solver unchanged: PoissonSettings has the
// defaults of ProjectionCfg, and poissonSettings() copies every knob the solver reads.
TEST(PoissonSettings, FromProjectionCfg) {
  const PoissonSettings d, fromDefault = poissonSettings(ProjectionCfg{});
  EXPECT_EQ(fromDefault.op, d.op);
  EXPECT_EQ(fromDefault.tolerance, d.tolerance);
  EXPECT_EQ(fromDefault.maxIterations, d.maxIterations);
  EXPECT_EQ(fromDefault.preconditioner, d.preconditioner);
  EXPECT_EQ(fromDefault.damping, d.damping);
  EXPECT_EQ(fromDefault.sweeps, d.sweeps);
  EXPECT_EQ(fromDefault.multigridReuse, d.multigridReuse);
  EXPECT_EQ(fromDefault.multigridRefresh, d.multigridRefresh);
  EXPECT_EQ(fromDefault.multigridSmoother, d.multigridSmoother);
  EXPECT_EQ(fromDefault.chebyshevDegree, d.chebyshevDegree);
  EXPECT_EQ(fromDefault.coarseSweeps, d.coarseSweeps);
  EXPECT_EQ(fromDefault.multigridRebuildGrowth, d.multigridRebuildGrowth);
  EXPECT_EQ(fromDefault.fdSingle, d.fdSingle);
  EXPECT_EQ(fromDefault.matrixFree, d.matrixFree);

  ProjectionCfg P;
  P.op = ProjectionCfg::Op::Approximate;
  P.tolerance = 3e-7;
  P.maxIterations = 17;
  P.preconditioner = "multigrid";
  P.damping = 0.7;
  P.sweeps = 3;
  P.multigridReuse = "RAP";
  P.multigridRefresh = 5;
  P.multigridSmoother = "chebyshev";
  P.chebyshevDegree = 4;
  P.coarseSweeps = 7;
  P.multigridRebuildGrowth = 0.5;
  P.fdPrecision = "double";
  P.matrixFree = false;
  const PoissonSettings s = poissonSettings(P);
  EXPECT_EQ(s.op, PoissonSettings::Op::Approximate);
  EXPECT_EQ(s.tolerance, 3e-7);
  EXPECT_EQ(s.maxIterations, 17);
  EXPECT_EQ(s.preconditioner, "multigrid");
  EXPECT_EQ(s.damping, 0.7);
  EXPECT_EQ(s.sweeps, 3);
  EXPECT_EQ(s.multigridReuse, "RAP");
  EXPECT_EQ(s.multigridRefresh, 5);
  EXPECT_EQ(s.multigridSmoother, "chebyshev");
  EXPECT_EQ(s.chebyshevDegree, 4);
  EXPECT_EQ(s.coarseSweeps, 7);
  EXPECT_EQ(s.multigridRebuildGrowth, 0.5);
  EXPECT_FALSE(s.fdSingle);
  EXPECT_FALSE(s.matrixFree);
}

// (e) Fast diagonalization with a solve axis (kernels/fd_tridiagonal.hpp: the longer bounded
// one of y and z is solved by lines, Thomas in double, singular lines by the dense form) is
// the operator of the fully transformed form: both are A0^+ on the same modes. On the
// cases of Poisson.FastDiagonalization (no-slip, outflow face + periodic z, slip, odd
// extents), one with y the longest and one with y and z periodic (no solve axis), at 1 and 2
// ranks (the outer and inner slabs of either axis), in double: they agree to round-off. The
// two sum in different orders through cond(A0) ~ (2n/pi)^2 ~ 1e2-1e3; 1e-11 of max |z|
// leaves 100x room over the 1e-13 seen.
TEST(Poisson, FastDiagonalizationSolveAxis) {
  struct Row { std::array<int, 3> n; std::array<bool, 3> per; CoefSpec spec; int axis; };
  CoefSpec slip{-1, false};
  slip.slip = true;
  const Row rows[] = {{{16, 12, 14}, {false, false, false}, {-1, false}, 2},
                      {{16, 12, 14}, {false, false, true}, {3, false}, 1},
                      {{16, 12, 14}, {false, false, false}, slip, 2},
                      {{15, 13, 11}, {false, false, false}, {-1, false}, 1},
                      {{10, 24, 9}, {false, false, false}, {3, false}, 1},   // outflow at y+: the porous bed's
                      {{10, 8, 6}, {false, true, true}, {-1, false}, -1}};
  int n = 0;
  for (const Row& row : rows) {
    Case c(row.n, row.per, {1, 0.9, 1.2});
    auto coef = makeCoef(c, row.spec);
    FastDiagonalization lines(c.g, MPI_COMM_WORLD, false, true), full(c.g, MPI_COMM_WORLD, false, false);
    EXPECT_EQ(lines.solveAxis(), row.axis) << "case " << n;
    EXPECT_EQ(full.solveAxis(), -1);
    lines.setup(coef);
    full.setup(coef);
    int singular = lines.singularLines();
    MPI_Allreduce(MPI_IN_PLACE, &singular, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    if (row.axis >= 0) EXPECT_GE(singular, 1) << "case " << n; // the constant mode at least: the dense form is used
    const long long m = c.g.cellsOwned();
    RowVector r("r", m), a("a", m), b("b", m);
    const int me = rank();
    Kokkos::parallel_for(
        "rand_rows", Kokkos::RangePolicy<ExecSpace>(0, m), KOKKOS_LAMBDA(long long q) {
          unsigned h = 2654435761u * unsigned(q + 7919 * me + 1);
          h ^= h >> 13, h *= 0x5bd1e995u, h ^= h >> 15;
          r(q) = (h % 2000001u) / 1000000.0 - 1.0;
        });
    lines.apply(r, a);
    full.apply(r, b);
    double big = 0, diff = 0;
    Kokkos::parallel_reduce(
        "fd_cmp", Kokkos::RangePolicy<ExecSpace>(0, m),
        KOKKOS_LAMBDA(long long q, double& mb, double& md) {
          const double vb = std::fabs(b(q)), vd = std::fabs(a(q) - b(q));
          mb = vb > mb ? vb : mb;
          md = vd > md ? vd : md;
        },
        Kokkos::Max<double>(big), Kokkos::Max<double>(diff));
    MPI_Allreduce(MPI_IN_PLACE, &big, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, &diff, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    EXPECT_GT(big, 0) << "case " << n;
    EXPECT_LE(diff, 1e-11 * big) << "case " << n;
    if (rank() == 0)
      std::printf("[fd solve axis %d, case %d] %d singular lines, max|a-b|/max|b| %.1e\n", row.axis, n, singular,
                  diff / big);
    ++n;
  }
}

#if !(defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL))
// (f) The host backends' fused x pass (kernels/fd_xlines.hpp, fdLinePairs) is the separate
// passes it replaces, bit for bit: forward [fdFold<0>] fdTransform<0> [fdFold<C>], back
// [fdUnfold<C>] fdTransform<0, true> [fdUnfold<0>], for C = 1 and 2, every fold on or off,
// odd and even extents (the middle lines), float and double. Equality, not a tolerance: the
// same sums in the same order.
template <class T>
void linePairsCase(int n0, int n1, int n2) {
  Grid3Of<T> in("in", n0, n1, n2), ref("ref", n0, n1, n2), tmp("tmp", n0, n1, n2), got("got", n0, n1, n2);
  auto h = Kokkos::create_mirror_view(in);
  unsigned s = 12345u + unsigned(n0 * 7 + n1 * 11 + n2 * 13);
  for (size_t q = 0; q < h.size(); ++q) s = s * 1664525u + 1013904223u, h.data()[q] = T(int(s >> 9) % 2001 - 1000) / T(317);
  Kokkos::deep_copy(in, h);
  DenseOf<T> V("V", n0, n0);
  auto vh = Kokkos::create_mirror_view(V);
  for (int q = 0; q < n0; ++q)
    for (int a = 0; a < n0; ++a) vh(q, a) = T(std::cos(0.37 * (q + 1) * (a + 2)));
  Kokkos::deep_copy(V, vh);
  auto same = [&](const char* what, int C, bool fx, bool fc) {
    auto a = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), ref);
    auto b = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), got);
    EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(T)))
        << what << " n " << n0 << "x" << n1 << "x" << n2 << " C " << C << " foldX " << fx << " foldC " << fc;
  };
  for (int C : {1, 2})
    for (bool fx : {false, true})
      for (bool fc : {false, true}) {
        const int nb = fx ? (n0 + 1) / 2 : n0;
        const DenseOf<T> fw = fdPadRows(fdTransposed(V), nb), bw = fdPadRows(V, nb);
        // forward
        Grid3Of<T> x = in;
        if (fx) fdFold<0>(x, tmp), x = tmp;
        Grid3Of<T> y("y", n0, n1, n2);
        fdTransform<0, false>(x, y, V, nb);
        if (fc) (C == 1 ? fdFold<1, T> : fdFold<2, T>)(y, ref);
        else Kokkos::deep_copy(ref, y);
        (C == 1 ? fdLinePairs<1, false, T> : fdLinePairs<2, false, T>)(in, got, fw, nb, fx, fc);
        Kokkos::fence();
        same("forward", C, fx, fc);
        // back
        x = in;
        if (fc) (C == 1 ? fdUnfold<1, T> : fdUnfold<2, T>)(x, tmp), x = tmp;
        fdTransform<0, true>(x, y, V, nb);
        if (fx) fdUnfold<0>(y, ref);
        else Kokkos::deep_copy(ref, y);
        (C == 1 ? fdLinePairs<1, true, T> : fdLinePairs<2, true, T>)(in, got, bw, nb, fx, fc);
        Kokkos::fence();
        same("back", C, fx, fc);
      }
}

TEST(Poisson, FastDiagLinePairs) {
  for (auto n : {std::array<int, 3>{9, 6, 7}, std::array<int, 3>{8, 7, 5}, std::array<int, 3>{17, 4, 4}}) {
    linePairsCase<float>(n[0], n[1], n[2]);
    linePairsCase<double>(n[0], n[1], n[2]);
  }
}
#endif
