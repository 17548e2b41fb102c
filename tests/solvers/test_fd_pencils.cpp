// Fast diagonalization on pencils (src/solvers/fast_diagonalization.hpp): at any rank count
// and any rank grid p1 x p2 (slabs p1 = 1, pencils p1 > 1, the rank grid chosen or forced),
// z = A0^+ r is the one-rank result bit for bit: every grid line is transformed and solved
// alone, in the same order, whichever rank holds it. Run by CTest at 1, 2, 4 and 8 ranks
// (label oversubscribed above 2: `ctest -LE oversubscribed` skips them).
#include "poisson_fixture.hpp"
#include "core/mpi_traffic.hpp"
#include "solvers/fast_diagonalization.hpp"

#include <cstring> // memcmp
#include <vector>

using namespace voigt;
using namespace voigt::ptest;

namespace {

// The rows' values at their global cell index (i fastest over the whole grid), summed over
// the ranks: each index is written by one rank and is 0 elsewhere, so the sum is exact.
std::vector<double> gather(const Grid& g, const RowVector& z, MPI_Comm comm) {
  std::vector<double> all(g.cellsGlobal(), 0.0);
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), z);
  long long q = 0;
  for (int k = 0; k < g.ln[2]; ++k)
    for (int j = 0; j < g.ln[1]; ++j)
      for (int i = 0; i < g.ln[0]; ++i, ++q)
        all[(g.c0[0] + i) + 1LL * g.n[0] * ((g.c0[1] + j) + 1LL * g.n[1] * (g.c0[2] + k))] = h(q);
  MPI_Allreduce(MPI_IN_PLACE, all.data(), (int)all.size(), MPI_DOUBLE, MPI_SUM, comm);
  return all;
}

// r at global cell (I, J, K): a hash, the same on every rank and rank count.
RowVector rows(const Grid& g) {
  RowVector r("r", g.cellsOwned());
  auto h = Kokkos::create_mirror_view(r);
  long long q = 0;
  for (int k = 0; k < g.ln[2]; ++k)
    for (int j = 0; j < g.ln[1]; ++j)
      for (int i = 0; i < g.ln[0]; ++i, ++q) {
        unsigned v = 2654435761u * unsigned((g.c0[0] + i) + 131 * (g.c0[1] + j) + 17161 * (g.c0[2] + k) + 1);
        v ^= v >> 13, v *= 0x5bd1e995u, v ^= v >> 15;
        h(q) = (v % 2000001u) / 1000000.0 - 1.0;
      }
  Kokkos::deep_copy(r, h);
  return r;
}

std::vector<double> applyOn(const Case& c, const CoefSpec& spec, bool single, int p1, std::array<int, 2>* grid) {
  FastDiagonalization fd(c.g, c.g.comm, single, true, p1);
  fd.setup(makeCoef(c, spec));
  if (grid) *grid = fd.rankGrid();
  RowVector z("z", c.g.cellsOwned());
  fd.apply(rows(c.g), z);
  return gather(c.g, z, c.g.comm);
}

} // namespace

TEST(FastDiagonalization, PencilsAreTheOneRankResult) {
  struct Row { std::array<int, 3> n; std::array<bool, 3> per; CoefSpec spec; };
  CoefSpec slip{-1, false};
  slip.slip = true;
  const Row cases[] = {{{16, 12, 14}, {false, false, false}, {-1, false}},  // s = z, x and y folded
                       {{15, 13, 11}, {false, false, false}, slip},        // s = y, odd extents
                       {{10, 24, 9}, {false, false, false}, {3, false}},   // outflow at y+ (porous bed)
                       {{10, 8, 6}, {false, true, true}, {-1, false}},     // no solve axis
                       {{10, 4, 6}, {false, false, false}, {-1, false}},   // 4 planes of c: pencils above 4 ranks
                       {{12, 12, 6}, {false, false, false}, {-1, false}}}; // s = y, 6 planes of c: pencils above 6
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  int n = 0;
  for (const Row& row : cases) {
    for (bool single : {false, true}) {
      Case one(row.n, row.per, {1, 0.9, 1.2}, MPI_COMM_SELF), many(row.n, row.per, {1, 0.9, 1.2});
      const std::vector<double> ref = applyOn(one, row.spec, single, 0, nullptr);
      for (int p1 : {0, 1, 2, 4}) {
        if (p1 > 0 && size % p1 != 0) continue;
        std::array<int, 2> grid{};
        const std::vector<double> got = applyOn(many, row.spec, single, p1, &grid);
        EXPECT_EQ(0, std::memcmp(ref.data(), got.data(), ref.size() * sizeof(double)))
            << "case " << n << " single " << single << " ranks " << size << " grid " << grid[0] << "x" << grid[1];
        if (p1 == 0 && rank() == 0 && !single)
          std::printf("[fd pencils] case %d, %d ranks: rank grid %d x %d\n", n, size, grid[0], grid[1]);
      }
    }
    ++n;
  }
}

// The chosen rank grid: slabs while the ranks fit the planes (up to 8 ranks), then pencils
// near sqrt(size) x sqrt(size) with every rank working where the count factors, else the
// largest grid that fits.
TEST(FastDiagonalization, RankGrid) {
  const int n[3] = {10, 4, 6}; // s = z (2), c = y (1): min(n_s, n_c) = 4, min(n_x, n_c) = 4
  using A = std::array<int, 2>;
  EXPECT_EQ(FastDiagonalization::pencilGrid(1, n, 2, 1), (A{1, 1}));
  EXPECT_EQ(FastDiagonalization::pencilGrid(4, n, 2, 1), (A{1, 4}));
  EXPECT_EQ(FastDiagonalization::pencilGrid(8, n, 2, 1), (A{2, 4}));
  EXPECT_EQ(FastDiagonalization::pencilGrid(6, n, 2, 1), (A{2, 3}));
  EXPECT_EQ(FastDiagonalization::pencilGrid(16, n, 2, 1), (A{4, 4}));
  EXPECT_EQ(FastDiagonalization::pencilGrid(17, n, 2, 1), (A{4, 4})); // 17 is prime: 16 work
  EXPECT_EQ(FastDiagonalization::pencilGrid(40, n, 2, 1), (A{4, 4}));
  const int big[3] = {512, 512, 512}; // the user: 2,048 ranks on 512^3, none idle
  EXPECT_EQ(FastDiagonalization::pencilGrid(2048, big, 2, 1), (A{32, 64}));
  EXPECT_EQ(FastDiagonalization::pencilGrid(8, big, 2, 1), (A{1, 8}));    // a workstation: slabs
  EXPECT_EQ(FastDiagonalization::pencilGrid(64, big, 2, 1), (A{8, 8}));
  EXPECT_EQ(FastDiagonalization::pencilGrid(512, big, 2, 1), (A{16, 32}));
}

// What summary.json reports as MPI traffic (core/mpi_traffic.hpp: the PMPI wrappers) is what
// was sent: around one application, the wrappers' all-to-all count equals the moves' own
// (Redistribute::sent, from the boxes), and nothing goes point to point.
TEST(FastDiagonalization, TrafficCountedByTheWrappers) {
  Case c({10, 4, 6}, {false, false, false}, {1, 0.9, 1.2});
  for (bool single : {false, true}) {
    FastDiagonalization fd(c.g, c.g.comm, single);
    fd.setup(makeCoef(c, {-1, false}));
    RowVector r = rows(c.g), z("z", c.g.cellsOwned());
    const mpi_traffic::Counts before = mpi_traffic::now();
    fd.apply(r, z);
    const mpi_traffic::Counts d = mpi_traffic::now() - before;
    const auto t = fd.traffic();
    EXPECT_EQ(d.messages[mpi_traffic::AllToAll], t[0]);
    EXPECT_EQ(d.bytes[mpi_traffic::AllToAll], t[1]);
    EXPECT_EQ(d.messages[mpi_traffic::PointToPoint], 0);
    if (c.g.size > 1) EXPECT_GT(t[1], 0);
  }
}
