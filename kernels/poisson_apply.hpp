#pragma once
// The exact pressure operator applied without its matrix (kernels/poisson_assembly.hpp
// assembles the same A). With s_d(n) = coef_d(n) / (16 h_d^2 w_n),
//   A x = G^T S G x,  (G x)_d(n) = sum over the existing cells c' around node n of
//                                  (c' on the high side of n along d ? +1 : -1) x(c'),
// the 27-point D B G of NUMERICS.md ("Projection"). Two passes: node fluxes q = S G x on the
// corners of the owned cells (x needs one ghost layer), then y = G^T q on the owned cells.
// Traffic a cell ~100 B (x, s and q) against ~330 B of the CSR product (27 values and
// column indices a row); perf/README.md, "The exact operator without its matrix".
// Rows whose cell has no free corner coefficient are identity rows there (y = x).
#include "core/index_space.hpp"
#include "kernels/poisson_rows.hpp"
#include "kernels/projection_ops.hpp"

namespace voigt {

// s_d(n) = coef_d(n) / (16 h_d^2 w_n) at the given nodes (once per coefficient update).
inline void poissonNodeScale(const Grid& g, const VecField& coef, const VecField& s, Range3 nodes) {
  GridGeom G(g);
  for_each3("poisson_node_scale", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
    const double wi = G.nodeWeightInv(i, j, k);
    VOIGT_UNROLL
    for (int d = 0; d < 3; ++d) s.c[d](i, j, k) = coef.c[d](i, j, k) * wi / (16 * G.h[d] * G.h[d]);
  });
}

// q_d(n) = s_d(n) (G x)_d(n) at the given nodes. x: valid one layer into the ghosts next to
// neighbour ranks and periodic images, and 0 in the ghosts beyond a wall, so that a missing
// cell adds nothing without a test (MatrixFreeOperator never writes them).
inline void poissonNodeFlux(const Field& x, const VecField& s, const VecField& q, Range3 nodes) {
  for_each3("poisson_node_flux", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
    // The 8 cells around the node as differences and sums along x, then y: 17 adds, not 24.
    double dx[4], sx[4];
    VOIGT_UNROLL
    for (int c = 0; c < 4; ++c) {
      const int cj = j - 1 + (c & 1), ck = k - 1 + (c >> 1);
      const double hi = x(i, cj, ck), lo = x(i - 1, cj, ck);
      dx[c] = hi - lo;
      sx[c] = hi + lo;
    }
    const double gx = (dx[0] + dx[1]) + (dx[2] + dx[3]);
    const double gy = (sx[1] - sx[0]) + (sx[3] - sx[2]);
    const double gz = (sx[2] + sx[3]) - (sx[0] + sx[1]);
    q.c[0](i, j, k) = s.c[0](i, j, k) * gx;
    q.c[1](i, j, k) = s.c[1](i, j, k) * gy;
    q.c[2](i, j, k) = s.c[2](i, j, k) * gz;
  });
}

// y(r) = (G^T q)(cell r) on the owned cells, y(r) = x(r) on identity rows.
inline void poissonCellSum(const VecField& q, const Field& x, const RowVector& y, const RowFlags& ident, CellRows rw,
                           Range3 cells) {
  for_each3("poisson_cell_sum", cells, KOKKOS_LAMBDA(int i, int j, int k) {
    // G^T: minus the divergence of q over the cell's 8 corners, summed along x first.
    double sum = 0;
    VOIGT_UNROLL
    for (int c = 0; c < 4; ++c) {
      const int nj = j + (c & 1), nk = k + (c >> 1);
      sum += q.c[0](i, nj, nk) - q.c[0](i + 1, nj, nk);
      const double ty = q.c[1](i, nj, nk) + q.c[1](i + 1, nj, nk);
      const double tz = q.c[2](i, nj, nk) + q.c[2](i + 1, nj, nk);
      sum += ((c & 1) ? -ty : ty) + ((c >> 1) ? -tz : tz);
    }
    const int r = rw.row(i, j, k);
    const double xv = x(i, j, k); // unconditional load: vectorises
    y(r) = ident(r) ? xv : sum;
  });
  Kokkos::fence();
}

} // namespace voigt
