#pragma once
// Fast diagonalization with one axis left untransformed (kernels/fast_diag.hpp for A0 and the
// transforms). After the 1-D transforms along the two other axes (modes a, c), A0 is block
// diagonal with one symmetric tridiagonal block per line along the solve axis s:
//   T_ac = sigma M_s + tau K_s,  sigma = l_a m_c / h_a^2 + m_a l_c / h_c^2,  tau = m_a m_c / h_s^2,
// m = 1 - l/4, K_s and M_s = E_s - K_s/4 the 1-D factors of axis s in cells (tridiagonal on
// a bounded axis). So A0^+ r = (V_a (x) V_c) T^-1 (V_a^T (x) V_c^T) r: a Thomas solve, ~10
// flops a cell, replaces the two dense transforms along s (2 n_s flops a cell each way;
// issue 22: the porous bed's 150 cells along y were three quarters of the transforms' flops).
// Lines where T_ac is singular (A0's null modes: the constant and checkerboard modes)
// take the dense eigenvector form with the pseudo-inverse instead (fdDenseLines), as the
// fully transformed A0^+ does.
#include "kernels/fast_diag.hpp"

namespace voigt {

using Lines2 = Kokkos::View<int* [2], MemSpace>; // (i, o): a line of the slab along the solve axis
using Table = Kokkos::View<double*, MemSpace>;
using Table4 = Kokkos::View<double**, Kokkos::LayoutLeft, MemSpace>; // (q, {K diag, K up, M diag, M up})

namespace fd_detail {
// sigma and tau of line (a, c): mode a along x, mode c (global) along the other transformed axis.
KOKKOS_INLINE_FUNCTION void lineCoef(double la, double lc, double iha, double ihc, double ihs, double& sigma,
                                     double& tau) {
  const double ma = 1 - 0.25 * la, mc = 1 - 0.25 * lc;
  sigma = iha * la * mc + ihc * ma * lc;
  tau = ihs * ma * mc;
}
template <int Axis>
KOKKOS_INLINE_FUNCTION int lin(int i, int o, int q, int n0, int n1) { // (i, o, q along Axis) -> i + n0 (j + n1 k)
  return Axis == 1 ? i + n0 * (q + n1 * o) : i + n0 * (o + n1 * q);
}
} // namespace fd_detail

// out = T^-1 in on every line along Axis (1: lines (i, k) along y; 2: lines (i, j) along z) of a
// pencil (extents n0, n1, n2, i fastest); the other transformed axis' mode of index o is
// o + off, x's of index i is i + offA. In double whatever T (mixed precision: the solve is where round-off would grow,
// by up to cond(T) ~ n^2). cp, dp: double work arrays of the slab's extents. A singular
// line's output is not used (fdDenseLines overwrites it); its zero pivots are replaced by 1.
template <int Axis, class T>
inline void fdTridiagonal(const CGrid3In<T>& in, const Grid3Of<T>& out, const Grid3& cp, const Grid3& dp,
                          const Table4& tri, const Table& lamA, const Table& lamC, double iha, double ihc, double ihs,
                          int off, int offA = 0) {
  static_assert(Axis == 1 || Axis == 2, "the solve axis is y or z (lines vectorise along x)");
  const int n0 = (int)in.extent(0), n1 = (int)in.extent(1), n2 = (int)in.extent(2);
  const int m = Axis == 1 ? n1 : n2, nOther = Axis == 1 ? n2 : n1;
  const T* src = in.data();
  T* dst = out.data();
  double* c = cp.data();
  double* d = dp.data();
#if !(defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL))
  if (!kOnDevice) { // host backends: one slab (o) per iteration, the x loop vectorises
    Kokkos::parallel_for(
        "fd_tridiagonal_slab", Kokkos::RangePolicy<ExecSpace>(0, nOther), KOKKOS_LAMBDA(int o) {
          const double lc = lamC(o + off);
          // The ends apart (no branches in the x loops, which then vectorise).
          const int a0 = fd_detail::lin<Axis>(0, o, 0, n0, n1);
          const double ku0 = m > 1 ? tri(0, 1) : 0.0, mu0 = m > 1 ? tri(0, 3) : 0.0;
#pragma GCC ivdep
          for (int i = 0; i < n0; ++i) {
            double sigma, tau;
            fd_detail::lineCoef(lamA(i + offA), lc, iha, ihc, ihs, sigma, tau);
            double den = sigma * tri(0, 2) + tau * tri(0, 0);
            den = den != 0.0 ? den : 1.0;
            const double inv = 1.0 / den;
            c[a0 + i] = (sigma * mu0 + tau * ku0) * inv;
            d[a0 + i] = double(src[a0 + i]) * inv;
          }
          for (int q = 1; q < m; ++q) {
            const double kd = tri(q, 0), md = tri(q, 2);
            const double ku = q + 1 < m ? tri(q, 1) : 0.0, mu = q + 1 < m ? tri(q, 3) : 0.0;
            const double kl = tri(q - 1, 1), ml = tri(q - 1, 3);
            const int at = fd_detail::lin<Axis>(0, o, q, n0, n1), prev = fd_detail::lin<Axis>(0, o, q - 1, n0, n1);
#pragma GCC ivdep
            for (int i = 0; i < n0; ++i) {
              double sigma, tau;
              fd_detail::lineCoef(lamA(i + offA), lc, iha, ihc, ihs, sigma, tau);
              const double lo = sigma * ml + tau * kl;
              double den = sigma * md + tau * kd - lo * c[prev + i];
              den = den != 0.0 ? den : 1.0;
              const double inv = 1.0 / den;
              c[at + i] = (sigma * mu + tau * ku) * inv;
              d[at + i] = (double(src[at + i]) - lo * d[prev + i]) * inv;
            }
          }
          const int last = fd_detail::lin<Axis>(0, o, m - 1, n0, n1);
#pragma GCC ivdep
          for (int i = 0; i < n0; ++i) dst[last + i] = T(d[last + i]);
          for (int q = m - 2; q >= 0; --q) {
            const int at = fd_detail::lin<Axis>(0, o, q, n0, n1), next = fd_detail::lin<Axis>(0, o, q + 1, n0, n1);
#pragma GCC ivdep
            for (int i = 0; i < n0; ++i) {
              const double x = d[at + i] - c[at + i] * d[next + i];
              d[at + i] = x;
              dst[at + i] = T(x);
            }
          }
        });
    Kokkos::fence();
    return;
  }
#endif
  Kokkos::parallel_for( // device: one line per thread, neighbouring threads on neighbouring x
      "fd_tridiagonal_line", Kokkos::RangePolicy<ExecSpace>(0, n0 * nOther), KOKKOS_LAMBDA(int l) {
        const int i = l % n0, o = l / n0;
        double sigma, tau;
        fd_detail::lineCoef(lamA(i + offA), lamC(o + off), iha, ihc, ihs, sigma, tau);
        for (int q = 0; q < m; ++q) {
          const int at = fd_detail::lin<Axis>(i, o, q, n0, n1);
          const double lo = q > 0 ? sigma * tri(q - 1, 3) + tau * tri(q - 1, 1) : 0.0;
          const int prev = q > 0 ? fd_detail::lin<Axis>(i, o, q - 1, n0, n1) : at;
          double den = sigma * tri(q, 2) + tau * tri(q, 0) - (q > 0 ? lo * c[prev] : 0.0);
          den = den != 0.0 ? den : 1.0;
          c[at] = (q + 1 < m ? sigma * tri(q, 3) + tau * tri(q, 1) : 0.0) / den;
          d[at] = (double(src[at]) - (q > 0 ? lo * d[prev] : 0.0)) / den;
        }
        for (int q = m - 1; q >= 0; --q) {
          const int at = fd_detail::lin<Axis>(i, o, q, n0, n1);
          const double x = d[at] - (q + 1 < m ? c[at] * d[fd_detail::lin<Axis>(i, o, q + 1, n0, n1)] : 0.0);
          d[at] = x;
          dst[at] = T(x);
        }
      });
  Kokkos::fence();
}

// The singular lines: out = V diag(D^+) V^T in on each listed line (i, o) along Axis, with V
// the axis' 1-D eigenvectors (V(q, b), V^T E V = I, unfolded; VT its transpose, VT(b, q)),
// D_b = sigma m_b + tau l_b and D^+ = 1/D_b above cut, else 0 (A0's null modes; the fully
// transformed form's rule). Both products as sums of contiguous columns (they vectorise).
// work: (lines, 3 m) doubles.
template <int Axis, class T>
inline void fdDenseLines(const CGrid3In<T>& in, const Grid3Of<T>& out, const Lines2& lines, const Dense& V,
                         const Dense& VT, const Table& lamS, const Table& lamA, const Table& lamC, double iha,
                         double ihc, double ihs, int off, double cut,
                         const Kokkos::View<double**, Kokkos::LayoutRight, MemSpace>& work, int offA = 0) {
  const int n0 = (int)in.extent(0), n1 = (int)in.extent(1);
  const int m = Axis == 1 ? (int)in.extent(1) : (int)in.extent(2);
  const T* src = in.data();
  T* dst = out.data();
  Kokkos::parallel_for(
      "fd_dense_lines", Kokkos::RangePolicy<ExecSpace>(0, (int)lines.extent(0)), KOKKOS_LAMBDA(int l) {
        const int i = lines(l, 0), o = lines(l, 1);
        double sigma, tau;
        fd_detail::lineCoef(lamA(i + offA), lamC(o + off), iha, ihc, ihs, sigma, tau);
        double* w = &work(l, 0);
        double* t = w + m;
        double* y = t + m;
        for (int q = 0; q < m; ++q) w[q] = double(src[fd_detail::lin<Axis>(i, o, q, n0, n1)]), t[q] = 0, y[q] = 0;
        for (int q = 0; q < m; ++q) { // t = V^T w
          const double wq = w[q];
          const double* col = &VT(0, q);
#pragma GCC ivdep
          for (int b = 0; b < m; ++b) t[b] += col[b] * wq;
        }
        for (int b = 0; b < m; ++b) {
          const double dd = sigma * (1 - 0.25 * lamS(b)) + tau * lamS(b);
          t[b] = dd > cut ? t[b] / dd : 0.0;
        }
        for (int b = 0; b < m; ++b) { // y = V t
          const double tb = t[b];
          const double* col = &V(0, b);
#pragma GCC ivdep
          for (int q = 0; q < m; ++q) y[q] += col[q] * tb;
        }
        for (int q = 0; q < m; ++q) dst[fd_detail::lin<Axis>(i, o, q, n0, n1)] = T(y[q]);
      });
  Kokkos::fence();
}

// VT(b, q) = V(q, b) (fdDenseLines reads both).
inline void fdTransposeDense(const Dense& V, const Dense& VT) {
  const int m = (int)V.extent(0), n = (int)V.extent(1);
  Kokkos::parallel_for(
      "fd_transpose_dense", Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2>>({0, 0}, {m, n}),
      KOKKOS_LAMBDA(int q, int b) { VT(b, q) = V(q, b); });
  Kokkos::fence();
}

} // namespace voigt
