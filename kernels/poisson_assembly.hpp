#pragma once
// Values of the pressure matrix A = D B G (kernels/projection_ops.hpp) from the node
// coefficients coef_d = 1/rho (NUMERICS.md, "Projection"), into a CSR matrix whose graph
// was built once: slot(r, o) is the index into vals of row r's entry for stencil offset o.
// exact: the 27-point D B G; else the 7-point approximation (face means of coef).
// Per row it also records the zero pattern (bit 3 corner + d set when coef_d(corner) != 0)
// in `pattern`, sets changed() = 1 when it differs from the last call, and marks rows with
// no entries as identity rows (p fixed to 0). Returns max_r sum_c |A_rc| on this rank.
#include "kernels/projection_ops.hpp"
#include "kernels/poisson_rows.hpp"

namespace voigt {

constexpr int kStencil = 27; // slot table width: offset o = (di+1) + 3 (dj+1) + 9 (dk+1)
constexpr int kCentre = 13;
using SlotView = Kokkos::View<int**, Kokkos::LayoutRight, MemSpace>;

// Row r's cell l and the 24 node coefficients around it, read once: cv[3 corner + d]. Records
// the row's zero pattern (bit 3 corner + d set when coef_d(corner) != 0) in pattern(r), sets
// changed() = 1 when it differs from the last call, and returns it.
KOKKOS_INLINE_FUNCTION int rowCorners(const VecField& coef, const CellRows& rw, int r, const RowFlags& pattern,
                                      const Kokkos::View<int, MemSpace>& changed, int l[3], double cv[24]) {
  rw.cell(r, l[0], l[1], l[2]);
  int mask = 0;
  VOIGT_UNROLL
  for (int cn = 0; cn < 8; ++cn)
    VOIGT_UNROLL
    for (int d = 0; d < 3; ++d) {
      const double v = coef.c[d](l[0] + (cn & 1), l[1] + ((cn >> 1) & 1), l[2] + ((cn >> 2) & 1));
      cv[3 * cn + d] = v;
      mask |= (v != 0) << (3 * cn + d);
    }
  if (pattern(r) != mask) changed() = 1; // benign race: every writer stores 1
  pattern(r) = mask;
  return mask;
}

// One row of poissonRowPattern (below): the zero pattern of cell l's 24 corner coefficients
// (as rowCorners; differs |= 1 when it changed), the identity flag, and the row's bound
// 8 A_rr (1 on identity rows); s[d] = 1 / (16 h_d^2).
KOKKOS_INLINE_FUNCTION double rowPatternBound(const VecField& coef, const GridGeom& G, const RowFlags& ident,
                                              const RowFlags& pattern, int& differs, int r, const int l[3],
                                              const double s[3]) {
  int mask = 0;
  double diag = 0;
  VOIGT_UNROLL
  for (int cn = 0; cn < 8; ++cn) {
    const int i = l[0] + (cn & 1), j = l[1] + ((cn >> 1) & 1), k = l[2] + ((cn >> 2) & 1);
    const double wi = G.nodeWeightInv(i, j, k);
    VOIGT_UNROLL
    for (int d = 0; d < 3; ++d) {
      const double v = coef.c[d](i, j, k);
      mask |= (v != 0) << (3 * cn + d);
      diag += v * wi * s[d];
    }
  }
  differs |= pattern(r) != mask;
  pattern(r) = mask;
  ident(r) = mask == 0 ? 1 : 0;
  return mask == 0 ? 1.0 : 8 * diag;
}

// What the exact operator needs of its rows when it is applied without a matrix
// (kernels/poisson_apply.hpp): the zero pattern and `changed` as assemblePoisson, identity
// rows (no free corner coefficient: the row would be empty), and a bound on ||A||_inf:
// row r's absolute sum is at most 8 A_rr (each corner term s_d(n) enters at most 8 entries,
// A_rr = sum over corners and d of s_d(n)), and at least A_rr. Returns max_r 8 A_rr (1 on
// identity rows), the round-off scale of PoissonSolver::solve and of the null-space test.
// Host backends walk x lines (one (j, k) a work item, rows consecutive): decoding each row's
// cell took three integer divisions, and 1/(16 h^2) is multiplied, not divided (the bound may
// differ from the divided form in its last bit; it is a scale, within 8x by construction).
inline double poissonRowPattern(const RowFlags& ident, const RowFlags& pattern, const GridGeom& G, const CellRows& rw,
                                const VecField& coef, int nrows, const Kokkos::View<int, MemSpace>& changed) {
  double amax = 0;
  const double s0 = 1 / (16 * G.h[0] * G.h[0]), s1 = 1 / (16 * G.h[1] * G.h[1]), s2 = 1 / (16 * G.h[2] * G.h[2]);
#if !(defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL))
  if (!kOnDevice) {
    const int n0 = rw.n0, n1 = rw.n1, ng = rw.ng, lines = n0 > 0 ? nrows / n0 : 0;
    Kokkos::parallel_reduce(
        "poisson_row_pattern", Kokkos::RangePolicy<ExecSpace>(0, lines), KOKKOS_LAMBDA(int q, double& rowMax) {
          const double s[3] = {s0, s1, s2};
          int l[3] = {ng, ng + q % n1, ng + q / n1}, differs = 0;
          for (int r = q * n0; l[0] < ng + n0; ++l[0], ++r) {
            const double bound = rowPatternBound(coef, G, ident, pattern, differs, r, l, s);
            rowMax = rowMax > bound ? rowMax : bound;
          }
          if (differs) changed() = 1; // benign race: every writer stores 1
        },
        Kokkos::Max<double>(amax));
    return amax;
  }
#endif
  Kokkos::parallel_reduce(
      "poisson_row_pattern", Kokkos::RangePolicy<ExecSpace>(0, nrows), KOKKOS_LAMBDA(int r, double& rowMax) {
        const double s[3] = {s0, s1, s2};
        int l[3];
        rw.cell(r, l[0], l[1], l[2]);
        int differs = 0;
        const double bound = rowPatternBound(coef, G, ident, pattern, differs, r, l, s);
        if (differs) changed() = 1; // benign race: every writer stores 1
        rowMax = rowMax > bound ? rowMax : bound;
      },
      Kokkos::Max<double>(amax));
  return amax;
}

template <class Values, class RowMap>
inline double assemblePoisson(const Values& vals, const RowMap& rowPtr, const SlotView& slot, const RowFlags& ident,
                       const RowFlags& pattern, const GridGeom& G, const CellRows& rw, bool exact,
                       const VecField& coef, int nrows, const Kokkos::View<int, MemSpace>& changed) {
  double amax = 0;
  const int centre = kCentre; // by value: nvcc refuses a namespace constexpr in device code
    Kokkos::parallel_reduce(
        "poisson_fill", Kokkos::RangePolicy<ExecSpace>(0, nrows), KOKKOS_LAMBDA(int r, double& rowMax) {
          int l[3];
          double cv[24];
          rowCorners(coef, rw, r, pattern, changed, l, cv);
          for (auto p = rowPtr(r); p < rowPtr(r + 1); ++p) vals(p) = 0;
          if (exact) {
            // A_{c,c'} = sum_{shared nodes n} sum_d coef_d(n)/w_n s_d(c,n) s_d(c',n) / (16 h_d^2)
            for (int cn = 0; cn < 8; ++cn) {
              const int a[3] = {cn & 1, (cn >> 1) & 1, (cn >> 2) & 1};
              const int n[3] = {l[0] + a[0], l[1] + a[1], l[2] + a[2]};
              const double w = G.nodeWeight(n[0], n[1], n[2]);
              double cf[3];
              for (int d = 0; d < 3; ++d)
                cf[d] = cv[3 * cn + d] / (w * 16 * G.h[d] * G.h[d]) * (a[d] ? 1 : -1);
              if (cf[0] == 0 && cf[1] == 0 && cf[2] == 0) continue;
              for (int cm = 0; cm < 8; ++cm) {
                const int b[3] = {cm & 1, (cm >> 1) & 1, (cm >> 2) & 1}; // 1: c' on the high side of n
                bool exists = true;
                for (int d = 0; d < 3; ++d) exists = exists && G.cellExists(d, n[d] - 1 + b[d]);
                if (!exists) continue;
                double v = 0;
                for (int d = 0; d < 3; ++d) v += cf[d] * (b[d] ? -1 : 1);
                const int o = (a[0] + b[0]) + 3 * (a[1] + b[1]) + 9 * (a[2] + b[2]);
                vals(slot(r, o)) += v;
              }
            }
          } else {
            VOIGT_UNROLL
            for (int d = 0; d < 3; ++d)
              VOIGT_UNROLL
              for (int s = 0; s < 2; ++s) {
                double beta = 0; // mean coef_d over the face's 4 nodes (corners in order)
                VOIGT_UNROLL
                for (int cn = 0; cn < 8; ++cn)
                  if (((cn >> d) & 1) == s) beta += 0.25 * cv[3 * cn + d];
                const double c = beta / (G.h[d] * G.h[d]);
                if (G.cellExists(d, l[d] + (s ? 1 : -1))) {
                  int o = centre + (s ? 1 : -1) * (d == 0 ? 1 : d == 1 ? 3 : 9);
                  vals(slot(r, o)) -= c;
                  vals(slot(r, centre)) += c;
                } else {
                  vals(slot(r, centre)) += 2 * c; // outflow: dp = 0 on the face; wall: beta = 0
                }
              }
          }
          bool empty = true;
          double sum = 0;
          for (auto p = rowPtr(r); p < rowPtr(r + 1); ++p) {
            empty = empty && vals(p) == 0;
            sum += vals(p) < 0 ? -vals(p) : vals(p);
          }
          ident(r) = empty ? 1 : 0;
          if (empty) vals(slot(r, centre)) = sum = 1; // all nodes prescribed: p is free, fix it to 0
          rowMax = rowMax > sum ? rowMax : sum;
        },
        Kokkos::Max<double>(amax));
  return amax;
}

} // namespace voigt
