// Wall ghosts of a cell field (core/boundary.hpp): the restricted fill,
// fillCellGhostsEven(g, f, reads), which the extension sweeps and the
// re-initialisation's iterations use, must give exactly the full fill's values
// at every cell of `reads` (ghosts, edges and corners included), leave the
// owned cells alone and write no ghost far from `reads`. Exact equality: both
// are copies. At 1 and 2 ranks (the split axis has no wall ghosts inside).
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <array>

#include "core/boundary.hpp"
#include "core/grid.hpp"

using namespace voigt;

namespace {

constexpr double kGarbage = -7.25; // what a ghost holds before any fill

// f = a distinct value per owned cell (global index), kGarbage in the ghosts.
void initField(const Grid& g, const Field& f) {
  const int ng = g.ng, c0 = g.c0[0], c1 = g.c0[1], c2 = g.c0[2];
  const int l0 = g.ln[0], l1 = g.ln[1], l2 = g.ln[2];
  Kokkos::parallel_for(
      "ghost_init", Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}), KOKKOS_LAMBDA(int i, int j, int k) {
        const bool own = i >= ng && i < ng + l0 && j >= ng && j < ng + l1 && k >= ng && k < ng + l2;
        f(i, j, k) = own ? 1 + (i - ng + c0) + 100.0 * (j - ng + c1) + 1e4 * (k - ng + c2) : kGarbage;
      });
}

// Cells of `reads` (clipped to the array) where the two fields differ.
int mismatches(const Grid& g, const Field& a, const Field& b, const Range3& reads) {
  auto ha = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), a);
  auto hb = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b);
  int bad = 0;
  for (int k = std::max(0, reads.b[2]); k < std::min(g.ext[2], reads.e[2]); ++k)
    for (int j = std::max(0, reads.b[1]); j < std::min(g.ext[1], reads.e[1]); ++j)
      for (int i = std::max(0, reads.b[0]); i < std::min(g.ext[0], reads.e[0]); ++i) bad += ha(i, j, k) != hb(i, j, k);
  return bad;
}

void checkBox(const Grid& g, const Range3& reads) {
  Field full("full", g.ext[0], g.ext[1], g.ext[2]), part("part", g.ext[0], g.ext[1], g.ext[2]);
  initField(g, full);
  initField(g, part);
  fillCellGhostsEven(g, full);
  fillCellGhostsEven(g, part, reads);
  EXPECT_EQ(mismatches(g, full, part, reads), 0);
  // Owned cells are never written.
  Field fresh("fresh", g.ext[0], g.ext[1], g.ext[2]);
  initField(g, fresh);
  EXPECT_EQ(mismatches(g, fresh, part, cellRange(g)), 0);
}

Grid walledGrid() {
  std::array<bool, 3> per{false, false, false};
  return makeGrid(MPI_COMM_WORLD, {12, 10, 8}, {0, 0, 0}, {1.2, 1.0, 0.8}, per, {0, 0, 0});
}

} // namespace

TEST(CellGhosts, RestrictedFillEqualsFullFillInsideReads) {
  const Grid g = walledGrid();
  const int ng = g.ng;
  // A box at the low x wall and the high z wall (an edge), grown by 2 as reinit does.
  checkBox(g, Range3{{ng - 2, ng + 2, g.ext[2] - ng - 4}, {ng + 4, ng + 6, g.ext[2]}});
  // A low corner of three walls, grown by 1 as the extension does.
  checkBox(g, Range3{{ng - 1, ng - 1, ng - 1}, {ng + 3, ng + 3, ng + 3}});
  // Everything.
  checkBox(g, Range3{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}});
}

TEST(CellGhosts, InteriorBoxWritesNoGhost) {
  const Grid g = walledGrid();
  const int ng = g.ng;
  const Range3 inner{{ng + 3, ng + 3, ng + 2}, {ng + 6, ng + 5, ng + 4}};
  Field f("f", g.ext[0], g.ext[1], g.ext[2]), fresh("fresh", g.ext[0], g.ext[1], g.ext[2]);
  initField(g, f);
  initField(g, fresh);
  fillCellGhostsEven(g, f, inner);
  // Nothing changed anywhere: a box away from every wall reads no wall ghost.
  EXPECT_EQ(mismatches(g, fresh, f, Range3{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}}), 0);
}
