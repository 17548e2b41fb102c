#pragma once
// The pressure solver's row space: owned cells as the rows of a linear system (one row
// per owned cell, i fastest), the copies between cell fields and row vectors, and the
// passes over rows that the implicit null space (src/solvers/null_space.hpp) is made of.
// Every function here returns this rank's share; the MPI sums stay with the caller.
// No Trilinos: a Tpetra vector's local view is a RowVector.
#include "core/field.hpp"
#include "core/index_space.hpp"
#include "kernels/projection_ops.hpp"

namespace voigt {

// Owned cell (local i,j,k) <-> row r; rows in local lexicographic order, i fastest.
struct CellRows {
  int ng, n0, n1;
  KOKKOS_INLINE_FUNCTION int row(int i, int j, int k) const {
    return (i - ng) + n0 * ((j - ng) + n1 * (k - ng));
  }
  KOKKOS_INLINE_FUNCTION void cell(int r, int& i, int& j, int& k) const {
    i = ng + r % n0;
    j = ng + (r / n0) % n1;
    k = ng + r / (n0 * n1);
  }
};

using RowVector = Kokkos::View<double*, Kokkos::LayoutLeft, MemSpace>;
using RowFlags = Kokkos::View<int*, MemSpace>;

// v(row) = f on the owned cells; identity rows (ident(r) != 0) zeroed when ident is non-empty.
inline void fieldToRows(const Field& f, const RowVector& v, CellRows rw, Range3 cells, const RowFlags& ident) {
  const bool zero = ident.extent(0) > 0;
  for_each3("poisson_field_to_vec", cells, KOKKOS_LAMBDA(int i, int j, int k) {
    const int r = rw.row(i, j, k);
    v(r) = (zero && ident(r)) ? 0.0 : f(i, j, k);
  });
  Kokkos::fence();
}

// f = v(row) on the owned cells.
inline void rowsToField(const RowVector& v, const Field& f, CellRows rw, Range3 cells) {
  for_each3("poisson_vec_to_field", cells, KOKKOS_LAMBDA(int i, int j, int k) { f(i, j, k) = v(rw.row(i, j, k)); });
  Kokkos::fence();
}

// v(r) = 0 on the identity rows (a multigrid correction may leak into them).
inline void zeroIdentityRows(const RowVector& v, const RowFlags& ident, int nrows) {
  Kokkos::parallel_for(
      "poisson_zero_identity", Kokkos::RangePolicy<ExecSpace>(0, nrows), KOKKOS_LAMBDA(int r) {
        if (ident(r)) v(r) = 0;
      });
  Kokkos::fence();
}

// Basis memberships of one row for the null space: the constant and one plane mode per axis,
// m_{c,q} = (-1)^(i_a + i_b) [i_c == q] in global cell indices (null_space.hpp).
struct NullBasis {
  GridGeom G;
  CellRows rw;
  int off0, off1, off2;
  KOKKOS_INLINE_FUNCTION void at(int r, int idx[4], double sg[4]) const {
    int l[3];
    rw.cell(r, l[0], l[1], l[2]);
    const int g0 = G.glob(0, l[0]), g1 = G.glob(1, l[1]), g2 = G.glob(2, l[2]);
    idx[0] = 0;
    idx[1] = off0 + g0;
    idx[2] = off1 + g1;
    idx[3] = off2 + g2;
    sg[0] = 1;
    sg[1] = ((g1 + g2) & 1) ? -1.0 : 1.0;
    sg[2] = ((g2 + g0) & 1) ? -1.0 : 1.0;
    sg[3] = ((g0 + g1) & 1) ? -1.0 : 1.0;
  }
};

namespace rows_detail {
// Kokkos array-sum reduction: value_type, init and join shared by the functors (both join
// forms: Kokkos 3.4 calls the volatile one, Kokkos 4 the plain one).
struct ArraySum {
  using value_type = double[];
  using size_type = int;
  unsigned value_count;
  KOKKOS_INLINE_FUNCTION void init(value_type s) const {
    for (unsigned m = 0; m < value_count; ++m) s[m] = 0;
  }
  KOKKOS_INLINE_FUNCTION void join(value_type d, const value_type s) const {
    for (unsigned m = 0; m < value_count; ++m) d[m] += s[m];
  }
  KOKKOS_INLINE_FUNCTION void join(volatile value_type d, const volatile value_type s) const {
    for (unsigned m = 0; m < value_count; ++m) d[m] += s[m];
  }
};

// s = M^T v over the local rows (identity rows left out).
struct Analyze : ArraySum {
  NullBasis B;
  RowVector v;
  RowFlags ident;
  KOKKOS_INLINE_FUNCTION void operator()(int r, value_type s) const {
    if (ident(r)) return;
    int idx[4];
    double sg[4];
    B.at(r, idx, sg);
    const double x = v(r);
    for (int m = 0; m < 4; ++m) s[idx[m]] += sg[m] * x;
  }
};

// ps[q] = sum over plane q along `axis` of y^2.
struct PlaneSquares : ArraySum {
  GridGeom G;
  CellRows rw;
  int axis;
  RowVector y;
  KOKKOS_INLINE_FUNCTION void operator()(int r, value_type s) const {
    int l[3];
    rw.cell(r, l[0], l[1], l[2]);
    s[G.glob(axis, l[axis])] += y(r) * y(r);
  }
};
} // namespace rows_detail

// sum of v over the rows that are not identity rows (this rank's).
inline double rowSum(const RowVector& v, const RowFlags& ident, int nrows) {
  double sum = 0;
  Kokkos::parallel_reduce(
      "nullspace_sum", Kokkos::RangePolicy<ExecSpace>(0, nrows),
      KOKKOS_LAMBDA(int r, double& acc) { acc += ident(r) ? 0.0 : v(r); }, sum);
  return sum;
}

// s[0..nb) = M^T v over this rank's rows (s is host memory of nb doubles).
inline void nullAnalyze(const NullBasis& B, int nb, const RowVector& v, const RowFlags& ident, int nrows, double* s) {
  rows_detail::Analyze f{{(unsigned)nb}, B, v, ident};
  Kokkos::parallel_reduce("nullspace_analyze", Kokkos::RangePolicy<ExecSpace>(0, nrows), f, s);
}

// v = c0 (or v -= c0) on the rows that are not identity rows (0 there when assigning).
inline void nullSynthesizeConstant(double c0, const RowVector& v, const RowFlags& ident, int nrows, bool subtract) {
  Kokkos::parallel_for(
      "nullspace_synthesize_constant", Kokkos::RangePolicy<ExecSpace>(0, nrows), KOKKOS_LAMBDA(int r) {
        const double w = ident(r) ? 0.0 : c0;
        v(r) = subtract ? v(r) - w : w;
      });
  Kokkos::fence();
}

// v = M c (or v -= M c), c: the nb basis coefficients on the device.
inline void nullSynthesize(const NullBasis& B, const Kokkos::View<double*, MemSpace>& c, const RowVector& v,
                           const RowFlags& ident, int nrows, bool subtract) {
  Kokkos::parallel_for(
      "nullspace_synthesize", Kokkos::RangePolicy<ExecSpace>(0, nrows), KOKKOS_LAMBDA(int r) {
        int idx[4];
        double sg[4];
        B.at(r, idx, sg);
        const double w = ident(r) ? 0.0 : c(0) + sg[1] * c(idx[1]) + sg[2] * c(idx[2]) + sg[3] * c(idx[3]);
        v(r) = subtract ? v(r) - w : w;
      });
  Kokkos::fence();
}

// ps[q] = this rank's sum of y^2 over plane q along axis (ps: host memory of G.n[axis] doubles).
inline void planeSquares(const GridGeom& G, CellRows rw, int axis, const RowVector& y, int nrows, double* ps) {
  rows_detail::PlaneSquares f{{(unsigned)G.n[axis]}, G, rw, axis, y};
  Kokkos::parallel_reduce("nullspace_plane_norms", Kokkos::RangePolicy<ExecSpace>(0, nrows), f, ps);
}

// This rank's sum of v^2.
inline double rowSquares(const RowVector& v, int nrows) {
  double s = 0;
  Kokkos::parallel_reduce(
      "nullspace_norm", Kokkos::RangePolicy<ExecSpace>(0, nrows),
      KOKKOS_LAMBDA(int r, double& acc) { acc += v(r) * v(r); }, s);
  return s;
}

} // namespace voigt
