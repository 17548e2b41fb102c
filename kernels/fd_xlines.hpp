#pragma once
// The fast diagonalization's x lines (kernels/fast_diag.hpp has the passes and the method):
// the value types of the passes, the transform of one x line, the folds of one line, and on
// host backends the x transform with the folds around it as one pass over pairs of lines
// (fdLinePairs): the fold passes read and wrote the whole array each.
#include "core/field.hpp"
#include "core/index_space.hpp"

namespace voigt {

// The passes are templates on the value type: double, or float for the mixed-precision
// preconditioner (fast_diagonalization.hpp: half the bytes and twice the SIMD lanes).
template <class T>
using Grid3Of = Kokkos::View<T***, Kokkos::LayoutLeft, MemSpace>; // a whole grid, i fastest
template <class T>
using CGrid3Of = Kokkos::View<const T***, Kokkos::LayoutLeft, MemSpace>;
template <class T>
using DenseOf = Kokkos::View<T**, Kokkos::LayoutLeft, MemSpace>; // V_d(node-free index q, mode a)
template <class T>
struct FdSame { using type = T; }; // a non-deduced T: the input's type follows the output's
template <class T>
using CGrid3In = CGrid3Of<typename FdSame<T>::type>;
using Grid3 = Grid3Of<double>;
using CGrid3 = CGrid3Of<double>;
using Dense = DenseOf<double>;

namespace fd_detail {
// One x line (host backends use it): o[r] = sum_t W(r, t) x[t] within W's two blocks, as an
// axpy over contiguous outputs, four columns a pass (the point-wise form is a dot product,
// which the compiler may not reassociate). Block 0 (columns [0, nb)) fills rows [0, b1),
// block 1 (columns [nb, m)) rows [b1, e1): unpadded b1 = nb, e1 = m (lineTransform); padded,
// each block's rows rounded up to whole vectors (lineTransformPadded).
template <class T>
KOKKOS_INLINE_FUNCTION void lineTransformRows(const DenseOf<T>& W, const T* x, T* o, int m, int nb, int b1, int e1) {
#pragma GCC ivdep
  for (int r = 0; r < e1; ++r) o[r] = 0;
  for (int blk = 0; blk < 2; ++blk) {
    const int tb = blk ? nb : 0, te = blk ? m : nb; // W's columns of this block
    const int rb = blk ? b1 : 0, re = blk ? e1 : b1; // its rows
    int t = tb;
    for (; t + 3 < te; t += 4) {
      const T w0 = x[t], w1 = x[t + 1], w2 = x[t + 2], w3 = x[t + 3];
      const T *c0 = &W(0, t), *c1 = &W(0, t + 1), *c2 = &W(0, t + 2), *c3 = &W(0, t + 3);
#pragma GCC ivdep
      for (int r = rb; r < re; ++r) o[r] += (c0[r] * w0 + c1[r] * w1) + (c2[r] * w2 + c3[r] * w3);
    }
    for (; t < te; ++t) {
      const T w = x[t];
      const T* col = &W(0, t);
#pragma GCC ivdep
      for (int r = rb; r < re; ++r) o[r] += col[r] * w;
    }
  }
}
template <class T>
KOKKOS_INLINE_FUNCTION void lineTransform(const DenseOf<T>& W, const T* x, T* o, int m, int nb) {
  lineTransformRows(W, x, o, m, nb, nb, m);
}

// lineTransform with W's two row blocks each padded with zero rows to a multiple of kLanes
// (fdPadRows): the r loops then have no remainder to run scalar (the folded blocks of a
// 75-point axis are 38 and 37 rows: 4 vectors of 8 floats and 6 or 5 scalar iterations).
// o has p0 + p1 values: block 0 at [0, p0), block 1 at [p0, p0 + p1); the real rows get the
// same sums in the same order as lineTransform.
constexpr int kLanes = 8;
KOKKOS_INLINE_FUNCTION int padRows(int n) { return (n + kLanes - 1) / kLanes * kLanes; }
template <class T>
KOKKOS_INLINE_FUNCTION void lineTransformPadded(const DenseOf<T>& Wp, const T* x, T* o, int m, int nb) {
  const int p0 = padRows(nb);
  lineTransformRows(Wp, x, o, m, nb, p0, p0 + padRows(m - nb));
}
// The real rows of a padded result: out[r] for r < m.
template <class T>
KOKKOS_INLINE_FUNCTION void linePadded(const T* o, T* out, int m, int nb) {
  const int p0 = padRows(nb);
  for (int r = 0; r < nb; ++r) out[r] = o[r];
  for (int r = nb; r < m; ++r) out[r] = o[p0 + r - nb];
}

// fdFold and fdUnfold (kernels/fast_diag.hpp) of one line of m values: the same sums, so the
// same bits.
template <class T>
KOKKOS_INLINE_FUNCTION void lineFold(const T* in, T* out, int m) {
  const int h = (m + 1) / 2, lo = m / 2;
  for (int q = 0; q < lo; ++q) {
    out[q] = in[q] + in[m - 1 - q];
    out[h + q] = in[q] - in[m - 1 - q];
  }
  if (m & 1) out[lo] = in[lo] + T(0);
}
template <class T>
KOKKOS_INLINE_FUNCTION void lineUnfold(const T* in, T* out, int m) {
  const int h = (m + 1) / 2, lo = m / 2;
  for (int q = 0; q < lo; ++q) {
    out[q] = in[q] + in[h + q];
    out[m - 1 - q] = in[q] - in[h + q];
  }
  if (m & 1) out[lo] = in[lo] + T(0);
}
} // namespace fd_detail

// Wp = W with each of its row blocks [0, nb), [nb, m) padded with zero rows to a multiple of
// fd_detail::kLanes (fd_detail::lineTransformPadded reads it).
template <class T>
inline DenseOf<T> fdPadRows(const DenseOf<T>& W, int nb) {
  const int m = (int)W.extent(0), n = (int)W.extent(1);
  const int p0 = fd_detail::padRows(nb), p1 = fd_detail::padRows(m - nb);
  DenseOf<T> Wp("fd_W_padded", p0 + p1, n); // zero-initialised
  Kokkos::parallel_for(
      "fd_pad_rows", Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2>>({0, 0}, {m, n}),
      KOKKOS_LAMBDA(int r, int c) { Wp(r < nb ? r : p0 + r - nb, c) = W(r, c); });
  Kokkos::fence();
  return Wp;
}

// W(a, q) = V(q, a): the forward x transform's matrix (fdLinePairs reads rows of it).
template <class T>
inline DenseOf<T> fdTransposed(const DenseOf<T>& V) {
  const int m = (int)V.extent(0), n = (int)V.extent(1);
  DenseOf<T> W(Kokkos::view_alloc(Kokkos::WithoutInitializing, "fd_VT"), n, m);
  Kokkos::parallel_for(
      "fd_transpose", Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2>>({0, 0}, {m, n}),
      KOKKOS_LAMBDA(int q, int a) { W(a, q) = V(q, a); });
  Kokkos::fence();
  return W;
}

#if !(defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL))
constexpr int kFdLineMax = 1024; // fdLinePairs keeps four x lines of this many values on the stack

// Host backends: the x transform with the folds around it in one pass, each work item a
// pair of x lines mirrored along axis C (1 or 2), kept on the stack (the fold passes read and
// wrote the whole array each: ~20 % of the preconditioner at 75^3).
//   forward: [fdFold<0> if foldX], fdTransform<0> with W = V^T, [fdFold<C> if foldC]
//   back:    [fdUnfold<C> if foldC], fdTransform<0, true> with W = V, [fdUnfold<0> if foldX]
// The same sums in the same order as the separate passes: the same bits. n0 <= kFdLineMax;
// Wp: W = V^T (forward) or V (back) with padded row blocks (fdPadRows(W, nb0)).
template <int C, bool Back, class T>
inline void fdLinePairs(const CGrid3In<T>& in, const Grid3Of<T>& out, const DenseOf<T>& Wp, int nb0, bool foldX,
                        bool foldC) {
  const int n0 = (int)in.extent(0), mC = (int)in.extent(C), nO = (int)in.extent(C == 1 ? 2 : 1);
  const int hC = (mC + 1) / 2, loC = mC / 2, per = foldC ? hC : mC;
  Kokkos::parallel_for(
      "fd_line_pairs", Kokkos::RangePolicy<ExecSpace>(0, per * nO), KOKKOS_LAMBDA(int item) {
        T a[kFdLineMax], b[kFdLineMax], t[kFdLineMax + 2 * fd_detail::kLanes];
        const int p = item % per, r = item / per;
        auto src = [&](int pc) { return C == 1 ? &in(0, pc, r) : &in(0, r, pc); };
        auto dst = [&](int pc) { return C == 1 ? &out(0, pc, r) : &out(0, r, pc); };
        // One line through the x part: fold + transform (forward) or transform + unfold (back).
        T pad[kFdLineMax + 2 * fd_detail::kLanes];
        auto xPart = [&](const T* x, T* o) {
          if (Back) {
            fd_detail::lineTransformPadded(Wp, x, pad, n0, nb0);
            if (!foldX) return fd_detail::linePadded(pad, o, n0, nb0);
            fd_detail::linePadded(pad, t, n0, nb0);
            fd_detail::lineUnfold(t, o, n0);
          } else {
            const T* in = x;
            if (foldX) fd_detail::lineFold(x, t, n0), in = t;
            fd_detail::lineTransformPadded(Wp, in, pad, n0, nb0);
            fd_detail::linePadded(pad, o, n0, nb0);
          }
        };
        if (!foldC) return xPart(src(p), dst(p));
        const bool middle = p == loC; // odd mC: the line on the mirror plane
        if (!Back) {
          xPart(src(p), a);
          if (middle) {
            T* o = dst(p);
            for (int i = 0; i < n0; ++i) o[i] = a[i] + T(0);
            return;
          }
          xPart(src(mC - 1 - p), b);
          T *even = dst(p), *odd = dst(hC + p);
#pragma GCC ivdep
          for (int i = 0; i < n0; ++i) {
            even[i] = a[i] + b[i];
            odd[i] = a[i] - b[i];
          }
        } else {
          const T* e = src(p);
          if (middle) {
            for (int i = 0; i < n0; ++i) a[i] = e[i] + T(0);
            return xPart(a, dst(p));
          }
          const T* o = src(hC + p);
#pragma GCC ivdep
          for (int i = 0; i < n0; ++i) {
            a[i] = e[i] + o[i];
            b[i] = e[i] - o[i];
          }
          xPart(a, dst(p));
          xPart(b, dst(mC - 1 - p));
        }
      });
}
#endif

} // namespace voigt
