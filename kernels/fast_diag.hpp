#pragma once
// Fast diagonalization (Lynch, Rice & Thomas 1964) of the exact projection operator at
// one density. With no-slip walls, inflow, outflow or periodic faces the 27-point
// A0 = D B0 D^T (B0 = 1/w, kernels/projection_ops.hpp) is the tensor sum
//   A0 = sum_d (1/h_d^2) K_d (x) M_e (x) M_f,   K = D1^T W^-1 D1, M = A1^T W^-1 A1
// of 1-D node-to-cell differences D1 and means A1, and M = E - K/4 with E diagonal; so
// the 1-D generalised eigenvectors K V = E V Lambda (V^T E V = I) diagonalise every
// factor at once: V^T M V = I - Lambda/4, and
//   A0^+ r = V (Lambda3^+ (V^T r)),  V = V_0 (x) V_1 (x) V_2  (src/solvers/fast_diagonalization.hpp).
// These are its passes over a whole-grid array (global cells, i fastest): one 1-D
// transform along an axis (a small dense matrix applied to every grid line) and the
// eigenvalue scaling. 2 n_axis flops a cell a transform.
#include "kernels/fd_xlines.hpp"

namespace voigt {

namespace fd_detail {
template <int Axis, class T>
KOKKOS_INLINE_FUNCTION T at(const CGrid3Of<T>& v, int i, int j, int k, int q) {
  return Axis == 0 ? v(q, j, k) : Axis == 1 ? v(i, q, k) : v(i, j, q);
}
} // namespace fd_detail

// Forward (coefficients): out(.., a, ..) = sum_q V(q, a) in(.., q, ..) along Axis.
// Back (values):          out(.., q, ..) = sum_a V(q, a) in(.., a, ..).
// V may be block diagonal, blocks [0, nb) and [nb, m) (a mirror-symmetric axis after
// fdFold: even modes, then odd): the sums run over the output's block only, half the flops.
// Host backends, Axis 1 and 2: one slab (a j or a k) at a time, out(:, a) += w in(:, q) over
// whole x lines: the slab is reused from cache n times and the x loop vectorises (the
// point-wise form walked to a new slab for every output line: 1.3 GFLOP/s along z at 64^3,
// perf_kernels FastDiagTransform); Axis 0 as an axpy per x line. Device backends: one output
// per thread.
template <int Axis, bool Back, class T>
inline void fdTransform(const CGrid3In<T>& in, const Grid3Of<T>& out, const DenseOf<T>& V, int nb) {
  const int n0 = (int)in.extent(0), n1 = (int)in.extent(1), n2 = (int)in.extent(2);
  const int m = (int)V.extent(0);
#if !(defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL))
  if (Axis != 0 && !kOnDevice) { // host backends only: not compiled as device code
    const int slabs = Axis == 1 ? n2 : n1;
    Kokkos::parallel_for(
        "fd_transform_slab", Kokkos::RangePolicy<ExecSpace>(0, slabs), KOKKOS_LAMBDA(int s) {
          for (int a = 0; a < m; ++a) {
            T* o = Axis == 1 ? &out(0, a, s) : &out(0, s, a);
#pragma GCC ivdep
            for (int i = 0; i < n0; ++i) o[i] = 0;
            const int qb = a < nb ? 0 : nb, qe = a < nb ? nb : m;
            // Four input rows a pass: o is loaded and stored once per four (the axpy form
            // is bound by o's traffic through L1; perf/README.md, "The exact operator
            // without its matrix").
            int q = qb;
            for (; q + 3 < qe; q += 4) {
              const T w0 = Back ? V(a, q) : V(q, a), w1 = Back ? V(a, q + 1) : V(q + 1, a);
              const T w2 = Back ? V(a, q + 2) : V(q + 2, a), w3 = Back ? V(a, q + 3) : V(q + 3, a);
              const T* x0 = Axis == 1 ? &in(0, q, s) : &in(0, s, q);
              const T* x1 = Axis == 1 ? &in(0, q + 1, s) : &in(0, s, q + 1);
              const T* x2 = Axis == 1 ? &in(0, q + 2, s) : &in(0, s, q + 2);
              const T* x3 = Axis == 1 ? &in(0, q + 3, s) : &in(0, s, q + 3);
#pragma GCC ivdep
              for (int i = 0; i < n0; ++i) o[i] += (w0 * x0[i] + w1 * x1[i]) + (w2 * x2[i] + w3 * x3[i]);
            }
            for (; q < qe; ++q) {
              const T w = Back ? V(a, q) : V(q, a);
              const T* x = Axis == 1 ? &in(0, q, s) : &in(0, s, q);
#pragma GCC ivdep
              for (int i = 0; i < n0; ++i) o[i] += w * x[i];
            }
          }
        });
    return;
  }
  if (Axis == 0 && !kOnDevice) { // host backends, x lines: o(r) += W(r, t) x(t), an axpy
    // over contiguous outputs that vectorises (the point-wise form is a dot product, which
    // the compiler may not reassociate); same summation order, so the same bits.
    const DenseOf<T> W = Back ? V : fdTransposed(V); // back: column a of V; forward W(a, q) = V(q, a)
    Kokkos::parallel_for(
        "fd_transform_line", Kokkos::RangePolicy<ExecSpace>(0, n1 * n2), KOKKOS_LAMBDA(int l) {
          const int j = l % n1, k = l / n1;
          fd_detail::lineTransform(W, &in(0, j, k), &out(0, j, k), m, nb);
        });
    return;
  }
#endif
  const Range3 all{{0, 0, 0}, {n0, n1, n2}};
  for_each3("fd_transform", all, KOKKOS_LAMBDA(int i, int j, int k) {
    const int idx[3] = {i, j, k};
    const int a = idx[Axis];
    const int qb = a < nb ? 0 : nb, qe = a < nb ? nb : m;
    T s = 0;
    for (int q = qb; q < qe; ++q) s += (Back ? V(a, q) : V(q, a)) * fd_detail::at<Axis>(in, i, j, k, q);
    out(i, j, k) = s;
  });
}


// Mirror folding along Axis (m points, h = ceil(m/2)): out(q) = in(q) + in(m-1-q) and
// out(h+q) = in(q) - in(m-1-q) for q < m/2, out(h-1) = in(h-1) for odd m (the middle).
// On a mirror-symmetric axis the eigenvectors are even or odd, so after folding the
// transform is block diagonal (fdTransform's nb = h). fdUnfold is its inverse's transpose
// partner: out(q) = in(q) + in(h+q), out(m-1-q) = in(q) - in(h+q), the middle copied.
template <int Axis, class T>
inline void fdFold(const CGrid3In<T>& in, const Grid3Of<T>& out) {
  const int m = (int)in.extent(Axis), h = (m + 1) / 2, lo = m / 2;
  const Range3 all{{0, 0, 0}, {(int)in.extent(0), (int)in.extent(1), (int)in.extent(2)}};
  for_each3("fd_fold", all, KOKKOS_LAMBDA(int i, int j, int k) {
    const int idx[3] = {i, j, k};
    const int t = idx[Axis];
    const int q = t < lo ? t : t >= h ? t - h : t; // t = h - 1 = middle for odd m
    const T a = fd_detail::at<Axis>(in, i, j, k, q);
    const T b = (t < h && t >= lo) ? T(0) : fd_detail::at<Axis>(in, i, j, k, m - 1 - q);
    out(i, j, k) = t < h ? a + b : a - b;
  });
}

template <int Axis, class T>
inline void fdUnfold(const CGrid3In<T>& in, const Grid3Of<T>& out) {
  const int m = (int)in.extent(Axis), h = (m + 1) / 2, lo = m / 2;
  const Range3 all{{0, 0, 0}, {(int)in.extent(0), (int)in.extent(1), (int)in.extent(2)}};
  for_each3("fd_unfold", all, KOKKOS_LAMBDA(int i, int j, int k) {
    const int idx[3] = {i, j, k};
    const int t = idx[Axis];
    const bool middle = (m & 1) && t == lo;
    const int q = t < lo ? t : middle ? t : m - 1 - t;
    const T e = fd_detail::at<Axis>(in, i, j, k, q);
    const T o = middle ? T(0) : fd_detail::at<Axis>(in, i, j, k, h + q);
    out(i, j, k) = (t < lo || middle) ? e + o : e - o;
  });
}

// out = inv * in (inv: 1/eigenvalue of A0, 0 on its null modes).
template <class T>
inline void fdScale(const CGrid3In<T>& in, const CGrid3In<T>& inv, const Grid3Of<T>& out) {
  const Range3 all{{0, 0, 0}, {(int)in.extent(0), (int)in.extent(1), (int)in.extent(2)}};
  for_each3("fd_scale", all, KOKKOS_LAMBDA(int i, int j, int k) { out(i, j, k) = inv(i, j, k) * in(i, j, k); });
}

// out = in, converted (double <-> float at the ends of the mixed-precision passes).
template <class TI, class TO>
inline void fdConvert(const CGrid3Of<TI>& in, const Grid3Of<TO>& out) {
  const Range3 all{{0, 0, 0}, {(int)in.extent(0), (int)in.extent(1), (int)in.extent(2)}};
  for_each3("fd_convert", all, KOKKOS_LAMBDA(int i, int j, int k) { out(i, j, k) = TO(in(i, j, k)); });
}

// out(r) = in(r) converted over n rows (the preconditioner's input and output vectors).
template <class TI, class TO>
inline void fdConvertRows(const Kokkos::View<const TI*, Kokkos::LayoutLeft, MemSpace>& in,
                          const Kokkos::View<TO*, Kokkos::LayoutLeft, MemSpace>& out, size_t n) {
  Kokkos::parallel_for(
      "fd_convert_rows", Kokkos::RangePolicy<ExecSpace>(0, n), KOKKOS_LAMBDA(size_t r) { out(r) = TO(in(r)); });
}

// The preconditioner's ends (FastDiagPrec: Y = alpha Z A0^+ Z X + beta Y, Z zeroing the
// identity rows), each one pass: out(r) = in(r) in the passes' type, 0 where ident(r) != 0;
// and y(r) = alpha (0 where ident(r) != 0, else t(r)) + beta y(r) (beta = 0: y not read).
// The same arithmetic as the copy, zeroing, conversion and axpby they replace.
template <class TO>
inline void fdMaskIn(const Kokkos::View<const double*, Kokkos::LayoutLeft, MemSpace>& in,
                     const Kokkos::View<int*, MemSpace>& ident, const Kokkos::View<TO*, Kokkos::LayoutLeft, MemSpace>& out,
                     int n) {
  Kokkos::parallel_for(
      "fd_mask_in", Kokkos::RangePolicy<ExecSpace>(0, n),
      KOKKOS_LAMBDA(int r) { out(r) = ident(r) ? TO(0) : TO(in(r)); });
}

template <class TI>
inline void fdMaskOut(double alpha, const Kokkos::View<const TI*, Kokkos::LayoutLeft, MemSpace>& t,
                      const Kokkos::View<int*, MemSpace>& ident, double beta,
                      const Kokkos::View<double*, Kokkos::LayoutLeft, MemSpace>& y, int n) {
  Kokkos::parallel_for(
      "fd_mask_out", Kokkos::RangePolicy<ExecSpace>(0, n), KOKKOS_LAMBDA(int r) {
        const double v = ident(r) ? 0.0 : double(t(r));
        y(r) = alpha * v + (beta == 0 ? 0.0 : beta * y(r));
      });
  Kokkos::fence();
}

// dst = src converted (the eigenvectors in the passes' precision).
template <class T>
inline void fdConvertDense(const Dense& src, const DenseOf<T>& dst) {
  const int m = (int)src.extent(0), n = (int)src.extent(1);
  Kokkos::parallel_for(
      "fd_convert_V", Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2>>({0, 0}, {m, n}),
      KOKKOS_LAMBDA(int q, int a) { dst(q, a) = T(src(q, a)); });
}

// inv(a,b,c) = 1 / sum_d lambda_d/h_d^2 prod_{e != d} (1 - lambda_e/4) for the modes
// a + off0, b + off1, c (a z pencil of them), 0 where that sum is <= cut (A0's null modes).
inline void fdInverseEigenvalues(const Grid3& inv, const Kokkos::View<double* [3], MemSpace>& lam, double ih0,
                                 double ih1, double ih2, int off1, double cut, int off0 = 0) {
  const Range3 all{{0, 0, 0}, {(int)inv.extent(0), (int)inv.extent(1), (int)inv.extent(2)}};
  for_each3("fd_eigen", all, KOKKOS_LAMBDA(int a, int b, int c) {
    const double l0 = lam(a + off0, 0), l1 = lam(b + off1, 1), l2 = lam(c, 2);
    const double m0 = 1 - 0.25 * l0, m1 = 1 - 0.25 * l1, m2 = 1 - 0.25 * l2;
    const double d = ih0 * l0 * m1 * m2 + ih1 * m0 * l1 * m2 + ih2 * m0 * m1 * l2;
    inv(a, b, c) = d > cut ? 1.0 / d : 0.0;
  });
  Kokkos::fence();
}

// Largest coefficient of velocity component c over the nodes [b, e) of a face: > 0 when c
// is free there (fast_diagonalization.cpp reads the faces' kind off it).
inline double fdFaceMax(const VecField& coef, const int b[3], const int e[3], int c) {
  const Field f = coef.c[c];
  double m = 0;
  Kokkos::parallel_reduce(
      "fd_face_free", Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<3>>({b[0], b[1], b[2]}, {e[0], e[1], e[2]}),
      KOKKOS_LAMBDA(int i, int j, int k, double& mx) { mx = mx > f(i, j, k) ? mx : f(i, j, k); },
      Kokkos::Max<double>(m));
  return m;
}

// y = alpha t + beta y over n rows (beta = 0: y not read, as Tpetra's apply contract says).
template <class V, class CV>
inline void fdAxpby(double alpha, const CV& t, double beta, const V& y, int n) {
  Kokkos::parallel_for(
      "fd_prec_axpby", Kokkos::RangePolicy<ExecSpace>(0, n),
      KOKKOS_LAMBDA(int r) { y(r) = alpha * t(r) + (beta == 0 ? 0.0 : beta * y(r)); });
  Kokkos::fence();
}

} // namespace voigt
