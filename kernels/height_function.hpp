#pragma once
// Height-function curvature of the zero level (surface_tension.curvature: height_function).
// Two passes. columnCrossings: every cell records, per axis, the zero of psi nearest to it
// along that axis within 2 cells (cubic interpolation through the 4 values around the sign
// change, quadratic at the window's ends) and psi's sign below it; the records are exchanged
// two layers deep. heightCurvature: in a cell next to the interface (a face neighbour of the
// other sign) the axis a of the largest |d psi / dx_a| is the height direction; on the 3 x 3
// columns along a around the cell (offsets in the two other axes b, c) each column's height is
// the record of the first of its cells at 0, -1, +1, -2, +2 along a that has one (so a column
// reaches 4 cells from the cell's plane with two ghost layers), giving y(p, q); then
// (Popinet 2009, Eq. 5)
//   kappa = -+ [y_bb (1 + y_c^2) + y_cc (1 + y_b^2) - 2 y_b y_c y_bc] / (1 + y_b^2 + y_c^2)^(3/2)
// with central differences; the sign makes a sphere with psi > 0 inside 2 / R. The heights are
// where the zero level is, not what psi's profile across it looks like, so a zone distorted
// by the flow (or left as advected by reinit.zone_curvature) does not change them.
// A column without a crossing in its window, or one whose sign order differs from the centre
// column's, makes the cell a fallback (ok = 0): it takes the mean of its neighbours' heights
// curvatures (Popinet 2009's first fallback, fallbackCurvature), else keeps its level-set one.
#include "core/field.hpp"
#include "core/index_space.hpp"
#include "kernels/reductions.hpp"

namespace voigt {
namespace curvature {

// The zero of the interpolant through v at positions lo..lo+n-1 (n = 3 or 4) between m and
// m + 1 (v[m], v[m + 1] of opposite signs): Newton from the linear estimate, kept in [m, m + 1].
KOKKOS_INLINE_FUNCTION double columnZero(const double* v, int lo, int n, int m) {
  const double a = v[m + 2], b = v[m + 3];
  double s = m + a / (a - b);
  VOIGT_UNROLL
  for (int it = 0; it < 4; ++it) {
    double f = 0, df = 0;
    for (int q = 0; q < n; ++q) { // Lagrange basis and its derivative at s
      const double xq = lo + q;
      double l = 1, dl = 0;
      for (int r = 0; r < n; ++r) {
        if (r == q) continue;
        const double xr = lo + r, w = 1 / (xq - xr);
        dl = dl * (s - xr) * w + l * w;
        l *= (s - xr) * w;
      }
      f += v[q + lo + 2] * l;
      df += v[q + lo + 2] * dl;
    }
    const double step = df != 0 ? f / df : 0.0;
    s -= step;
    s = s < m ? double(m) : s > m + 1 ? double(m + 1) : s;
  }
  return s;
}

// A crossing record: 0 for none, else o (10 + c), c in [-2, 2] the zero's position along the
// axis relative to the cell (cells), o = +1 where psi > 0 below it (on the lower side).
KOKKOS_INLINE_FUNCTION double crossingRecord(const double* v) {
  const int order[4] = {-1, 0, -2, 1}; // the sign change nearest the cell first
  int m = 99;
  VOIGT_UNROLL
  for (int t = 0; t < 4; ++t) {
    const int e = order[t];
    m = (m == 99 && ((v[e + 2] > 0) != (v[e + 3] > 0))) ? e : m;
  }
  if (m == 99) return 0.0;
  // Cubic through m-1..m+2 inside the window, else the quadratic at its end.
  const int lo = m <= -1 ? -2 : (m == 0 ? -1 : 0), n = (m == -1 || m == 0) ? 4 : 3;
  const double c = columnZero(v, lo, n, m);
  return (v[m + 2] > 0 ? 1.0 : -1.0) * (10 + c);
}

// rec.c[a] = the crossing record along axis a at the cells of r (psi fresh 2 layers beyond r).
inline void columnCrossings(const Field& psi, const VecField& rec, Range3 r) {
  const Field r0 = rec.c[0], r1 = rec.c[1], r2 = rec.c[2];
  for_each3("column_crossings", r, KOKKOS_LAMBDA(int i, int j, int k) {
    double vx[5], vy[5], vz[5];
    VOIGT_UNROLL
    for (int m = -2; m <= 2; ++m) {
      vx[m + 2] = psi(i + m, j, k);
      vy[m + 2] = psi(i, j + m, k);
      vz[m + 2] = psi(i, j, k + m);
    }
    r0(i, j, k) = crossingRecord(vx);
    r1(i, j, k) = crossingRecord(vy);
    r2(i, j, k) = crossingRecord(vz);
  });
}

// kap = the height-function curvature at the interface cells of r (psi fresh 1 layer and
// rec 2 layers beyond r) and ok = 1 there; fallbacks keep kap with ok = 0, other cells kap
// with ok = -1. Returns the number of fallbacks on this rank.
inline double heightCurvature(const Grid& g, const Field& psi, const VecField& rec, const Field& kap, const Field& ok,
                              Range3 r) {
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  const double kmax = 1 / minOf(h0, minOf(h1, h2));
  double fallbacks = 0;
  reduce_rows(
      "height_curvature", r,
      KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
        const double pc = psi(i, j, k);
        bool iface = false;
        VOIGT_UNROLL
        for (int f = 0; f < 6; ++f) {
          const int a = f >> 1, sg = (f & 1) ? 1 : -1;
          const double pn = psi(i + (a == 0 ? sg : 0), j + (a == 1 ? sg : 0), k + (a == 2 ? sg : 0));
          iface |= (pc > 0) != (pn > 0);
        }
        ok(i, j, k) = iface ? 1.0 : -1.0;
        if (!iface) return;
        const double gx = (psi(i + 1, j, k) - psi(i - 1, j, k)) / h0;
        const double gy = (psi(i, j + 1, k) - psi(i, j - 1, k)) / h1;
        const double gz = (psi(i, j, k + 1) - psi(i, j, k - 1)) / h2;
        const double ax = km::fabs(gx), ay = km::fabs(gy), az = km::fabs(gz);
        const int a = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2), b = (a + 1) % 3, c = (a + 2) % 3;
        const double ha = a == 0 ? h0 : a == 1 ? h1 : h2, hb = b == 0 ? h0 : b == 1 ? h1 : h2;
        const double hc = c == 0 ? h0 : c == 1 ? h1 : h2;
        const Field ra = rec.c[a];
        double y[3][3];
        int orient = 0;
        bool good = true;
        for (int p = -1; p <= 1; ++p)
          for (int q = -1; q <= 1; ++q) {
            const int order[5] = {0, -1, 1, -2, 2};
            double w = 0;
            int t0 = 0;
            for (int t = 0; t < 5 && w == 0; ++t) {
              int l[3] = {i, j, k};
              l[a] += order[t], l[b] += p, l[c] += q;
              w = ra(l[0], l[1], l[2]);
              t0 = order[t];
            }
            if (w == 0) {
              good = false;
              continue;
            }
            const int o = w > 0 ? 1 : -1;
            good &= orient == 0 || orient == o;
            orient = o;
            y[p + 1][q + 1] = (t0 + km::fabs(w) - 10) * ha;
          }
        if (!good) {
          ok(i, j, k) = 0;
          acc += 1;
          return;
        }
        const double yb = (y[2][1] - y[0][1]) / (2 * hb), yc = (y[1][2] - y[1][0]) / (2 * hc);
        const double ybb = (y[2][1] - 2 * y[1][1] + y[0][1]) / (hb * hb);
        const double ycc = (y[1][2] - 2 * y[1][1] + y[1][0]) / (hc * hc);
        const double ybc = (y[2][2] - y[2][0] - y[0][2] + y[0][0]) / (4 * hb * hc);
        const double den = 1 + yb * yb + yc * yc;
        const double num = ybb * (1 + yc * yc) + ycc * (1 + yb * yb) - 2 * yb * yc * ybc;
        const double kv = -orient * num / (den * km::sqrt(den));
        kap(i, j, k) = maxOf(-kmax, minOf(kmax, kv));
      },
      fallbacks);
  return fallbacks;
}

// At the fallback cells of r (ok = 0): out = the mean of kap over the 26 neighbours with
// ok = 1, if any; every other cell out = kap. kap and ok fresh one layer beyond r.
inline void fallbackCurvature(const Field& kap, const Field& ok, const Field& out, Range3 r) {
  for_each3("height_curvature_fallback", r, KOKKOS_LAMBDA(int i, int j, int k) {
    double s = 0, n = 0;
    VOIGT_UNROLL
    for (int dk = -1; dk <= 1; ++dk)
      VOIGT_UNROLL
      for (int dj = -1; dj <= 1; ++dj)
        VOIGT_UNROLL
        for (int di = -1; di <= 1; ++di) {
          const bool use = ok(i + di, j + dj, k + dk) > 0.5;
          s += use ? kap(i + di, j + dj, k + dk) : 0.0;
          n += use ? 1.0 : 0.0;
        }
    const bool fb = ok(i, j, k) == 0.0 && n > 0;
    out(i, j, k) = fb ? s / n : kap(i, j, k);
  });
}

} // namespace curvature
} // namespace voigt
