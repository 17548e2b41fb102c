#pragma once
// Two bodies on two level sets (level_sets:): the gap between their zero levels.
#include "core/field.hpp"
#include "core/index_space.hpp"

namespace voigt {

// min over cells with min(psi_a, psi_b) > -reach of -(psi_a + psi_b). For signed distances
// d_A(x) + d_B(x) >= gap(A, B) at every point, with equality on the segment joining the
// closest points, so this is the gap to the cells' sampling (exact where a cell centre lies
// on that segment); where the bodies overlap it is minus the overlap's depth along it.
// No such cell on this rank: +huge (the caller reduces over ranks).
inline double localBodyGap(const Field& a, const Field& b, double reach, Range3 cells) {
  double m = 1e300;
  Kokkos::parallel_reduce(
      "body_gap", cells.policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
        const double pa = a(i, j, k), pb = b(i, j, k);
        if (!(pa > -reach && pb > -reach)) return;
        const double gap = -(pa + pb);
        if (gap < acc) acc = gap;
      },
      Kokkos::Min<double>(m));
  return m;
}

} // namespace voigt

namespace voigt {

// out = max(out, a) over r: the union of bodies on several level sets (max of signed
// distances is the union's signed distance outside it and a lower bound inside).
inline void maxInto(const Field& out, const Field& a, Range3 r) {
  for_each3("max_into", r, KOKKOS_LAMBDA(int i, int j, int k) {
        if (a(i, j, k) > out(i, j, k)) out(i, j, k) = a(i, j, k);
      });
}

} // namespace voigt
