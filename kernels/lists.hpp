#pragma once
// Packed cell lists (memory offsets, core/index_space.hpp flat()): the band kernels run
// over them instead of boxes. listCellsWhere builds one from a test, listRuns finds its
// stretches of consecutive cells (for_runs vectorises over them), listBox bounds it.
#include <climits>

#include "core/field.hpp"
#include "core/index_space.hpp"
#include "kernels/reductions.hpp" // AccReducer

namespace voigt {

// listBox's running bounds: one reduction decodes each cell once for all three axes.
struct ListBoxAcc {
  int lo[3], hi[3];
  template <class D, class S>
  KOKKOS_INLINE_FUNCTION static void join(D& d, const S& s) {
    for (int q = 0; q < 3; ++q) {
      d.lo[q] = s.lo[q] < d.lo[q] ? s.lo[q] : d.lo[q];
      d.hi[q] = s.hi[q] > d.hi[q] ? s.hi[q] : d.hi[q];
    }
  }
  KOKKOS_INLINE_FUNCTION static void init(ListBoxAcc& v) {
    for (int q = 0; q < 3; ++q) v.lo[q] = INT_MAX, v.hi[q] = INT_MIN;
  }
};

// Packed list (memory offsets, x fastest, as a scan over the cells would give) of the
// cells of r where keep(i, j, k) holds; returns the count. The scan runs over x rows,
// each counting its cells in a loop: no (i, j, k) decoding by division per cell, which
// cost more than the test (elastic_active_list, reinit_band_list).
template <class Keep>
inline int listCellsWhere(const char* name, const Grid& g, Range3 r, const IntList& cell, const Keep& keep) {
  const int b0 = r.b[0], e0r = r.e[0], b1 = r.b[1], b2 = r.b[2];
  const int l1 = r.e[1] - r.b[1], rows = l1 * (r.e[2] - r.b[2]);
  const int e0 = g.ext[0], e1 = g.ext[1];
  int count = 0;
  if (rows <= 0 || e0r <= b0) return 0;
  Kokkos::parallel_scan(
      name, Kokkos::RangePolicy<ExecSpace>(0, rows), KOKKOS_LAMBDA(int q, int& upd, bool final) {
        const int j = b1 + q % l1, k = b2 + q / l1, base = e0 * (j + e1 * k);
        if (final) {
          for (int i = b0; i < e0r; ++i)
            if (keep(i, j, k)) cell(upd++) = base + i;
        } else {
          int c = 0;
          for (int i = b0; i < e0r; ++i) c += keep(i, j, k) ? 1 : 0;
          upd += c;
        }
      },
      count);
  return count;
}

// Runs of a packed list: start(r) is the first q of the r-th stretch of consecutive
// cells (list(q + 1) == list(q) + 1, so within one x row); returns their count. start
// needs room for n entries.
inline int listRuns(const IntList& list, int n, const IntList& start) {
  int count = 0;
  Kokkos::parallel_scan(
      "list_runs", Kokkos::RangePolicy<ExecSpace>(0, n), KOKKOS_LAMBDA(int q, int& upd, bool final) {
        if (q == 0 || list(q) != list(q - 1) + 1) {
          if (final) start(upd) = q;
          ++upd;
        }
      },
      count);
  return count;
}

// Bounding box (local indices, [b, e)) of the first n listed cells; empty range if n == 0.
inline Range3 listBox(const Grid& g, const IntList& cell, int n) {
  Range3 box{{0, 0, 0}, {0, 0, 0}};
  if (n == 0) return box;
  const Unpack up{g.ext[0], g.ext[1]};
  ListBoxAcc acc;
  Kokkos::parallel_reduce(
      "list_box", Kokkos::RangePolicy<ExecSpace>(0, n),
      KOKKOS_LAMBDA(int p, ListBoxAcc& v) {
        int i, j, k;
        up(cell(p), i, j, k);
        ListBoxAcc::join(v, ListBoxAcc{{i, j, k}, {i, j, k}});
      },
      AccReducer<ListBoxAcc>(acc));
  for (int d = 0; d < 3; ++d) {
    box.b[d] = acc.lo[d];
    box.e[d] = acc.hi[d] + 1;
  }
  return box;
}

} // namespace voigt
