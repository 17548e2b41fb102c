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
template <class V> // RowVector, or its const form
inline void rowsToField(const V& v, const Field& f, CellRows rw, Range3 cells) {
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

// The (j, k) lines of owned cells, j fastest (rows run i fastest, then j, then k).
using Lines = Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2, Kokkos::Iterate::Left, Kokkos::Iterate::Left>>;

// s = M^T v over the local rows (identity rows left out), one (j, k) line of owned cells
// at a time (rows are consecutive along i): the families of axes 1 and 2 are one basis
// column each along the line, with signs that alternate with i, so they take an
// alternating sum; the constant a plain one; the axis-0 family one column per i. No cell
// decoding (two divisions) per row: analyze + synthesize 8.1 -> 2.7 % of an exact-operator
// falling-block run (perf record, 75^3, 3 steps).
struct AnalyzeLines : ArraySum {
  NullBasis B;
  RowVector v;
  RowFlags ident;
  KOKKOS_INLINE_FUNCTION void operator()(int j, int k, value_type s) const {
    const CellRows& rw = B.rw;
    const int r0 = rw.n0 * (j + rw.n1 * k);
    const int gi = B.G.glob(0, rw.ng), g1 = B.G.glob(1, rw.ng + j), g2 = B.G.glob(2, rw.ng + k);
    const double s1 = ((g1 + g2) & 1) ? -1.0 : 1.0;
    double sum = 0, alt = 0; // alt: sum of (-1)^g0 x
    for (int i = 0; i < rw.n0; ++i) {
      const double x = ident(r0 + i) ? 0.0 : v(r0 + i);
      const int g0 = gi + i;
      sum += x;
      alt += (g0 & 1) ? -x : x;
      s[B.off0 + g0] += s1 * x;
    }
    s[0] += sum;
    s[B.off1 + g1] += (g2 & 1) ? -alt : alt; // sign (-1)^(g2 + g0)
    s[B.off2 + g2] += (g1 & 1) ? -alt : alt; // sign (-1)^(g0 + g1)
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
  using rows_detail::Lines; // nrows = n0 n1 n2 of B.rw
  rows_detail::AnalyzeLines f{{(unsigned)nb}, B, v, ident};
  Kokkos::parallel_reduce("nullspace_analyze", Lines({0, 0}, {B.rw.n1, nrows / (B.rw.n0 * B.rw.n1)}), f, s);
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
  // A (j, k) line at a time (see AnalyzeLines); the same arithmetic as the row form
  // c(0) + sg1 c(idx1) + sg2 c(idx2) + sg3 c(idx3), the signs split exactly.
  using rows_detail::Lines;
  const int n0 = B.rw.n0, n1 = B.rw.n1;
  Kokkos::parallel_for(
      "nullspace_synthesize", Lines({0, 0}, {n1, nrows / (n0 * n1)}), KOKKOS_LAMBDA(int j, int k) {
        const int r0 = n0 * (j + n1 * k);
        const int gi = B.G.glob(0, B.rw.ng), g1 = B.G.glob(1, B.rw.ng + j), g2 = B.G.glob(2, B.rw.ng + k);
        const double c0 = c(0);
        const double s1 = ((g1 + g2) & 1) ? -1.0 : 1.0;
        const double ca = ((g2 & 1) ? -1.0 : 1.0) * c(B.off1 + g1), cb = ((g1 & 1) ? -1.0 : 1.0) * c(B.off2 + g2);
        for (int i = 0; i < n0; ++i) {
          const double e = ((gi + i) & 1) ? -1.0 : 1.0;
          const double w = ident(r0 + i) ? 0.0 : c0 + s1 * c(B.off0 + gi + i) + e * ca + e * cb;
          v(r0 + i) = subtract ? v(r0 + i) - w : w;
        }
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
