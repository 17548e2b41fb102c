#pragma once
// Kernels of the solid_body effect (effects/solid_body.cpp): the solid's moments and
// gaps in one reduction with a combined sum + min reducer (the Kokkos 3.4 reducer
// concept, as Kokkos::Sum; both join forms, so Kokkos 4 finds its non-volatile one),
// the signed distance to an obstacle's surface or a domain face, and the bending of
// the mid-surface.
#include <mpi.h>

#include <Kokkos_Core.hpp>
#include <Kokkos_ScatterView.hpp>
#include <cmath>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/host_access.hpp"
#include "core/index_space.hpp"
#include "kernels/heaviside.hpp"
#include "kernels/reductions.hpp" // AccReducer

namespace voigt {

constexpr int kSolidSums = 13;    // w, w x (3), w v (3), w xx, yy, zz, xy, yz, zx
constexpr int kSolidTargets = 32; // obstacles + up to 6 domain faces

struct SolidAcc {
  double s[kSolidSums];
  double m[kSolidTargets];
  template <class D, class S>
  KOKKOS_INLINE_FUNCTION static void join(D& d, const S& s) {
    for (int q = 0; q < kSolidSums; ++q) d.s[q] += s.s[q];
    for (int q = 0; q < kSolidTargets; ++q) d.m[q] = s.m[q] < d.m[q] ? s.m[q] : d.m[q];
  }
  KOKKOS_INLINE_FUNCTION static void init(SolidAcc& v) {
    for (int q = 0; q < kSolidSums; ++q) v.s[q] = 0;
    for (int q = 0; q < kSolidTargets; ++q) v.m[q] = 1e300;
  }
};
using SolidReducer = AccReducer<SolidAcc>; // kernels/reductions.hpp

// A surface the solid may touch. kind: 0 sphere (center c, radius r), 1
// cylinder (infinite, as the obstacle mask), 2 box (lo, hi), 3 low face and
// 4 high face of the domain along `axis` at coordinate c[axis].
struct SolidTarget {
  int kind = 0, axis = 0;
  double c[3] = {0, 0, 0}, r = 0, lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
};
struct SolidTargets {
  SolidTarget t[kSolidTargets];
  int n = 0;
};

// Signed distance from x to the target's surface, > 0 in the fluid.
KOKKOS_INLINE_FUNCTION double targetDistance(const SolidTarget& t, const double x[3]) {
  if (t.kind == 0)
    return km::sqrt((x[0] - t.c[0]) * (x[0] - t.c[0]) + (x[1] - t.c[1]) * (x[1] - t.c[1]) +
                     (x[2] - t.c[2]) * (x[2] - t.c[2])) - t.r;
  if (t.kind == 1) {
    double r2 = 0;
    for (int d = 0; d < 3; ++d)
      if (d != t.axis) r2 += (x[d] - t.c[d]) * (x[d] - t.c[d]);
    return km::sqrt(r2) - t.r;
  }
  if (t.kind == 2) { // exact signed distance to a box
    double out = 0, in = -1e300;
    for (int d = 0; d < 3; ++d) {
      const double q = km::fabs(x[d] - 0.5 * (t.lo[d] + t.hi[d])) - 0.5 * (t.hi[d] - t.lo[d]);
      if (q > 0) out += q * q;
      in = q > in ? q : in;
    }
    return km::sqrt(out) + (in < 0 ? in : 0);
  }
  return t.kind == 3 ? x[t.axis] - t.c[t.axis] : t.c[t.axis] - x[t.axis];
}

KOKKOS_INLINE_FUNCTION double det3(const double m[3][3]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// Local sums of the solid's moments (SolidAcc::s: w, w x, w v, w x x about the domain
// centre, w = H(psi)) and the gap to each target (SolidAcc::m) over the owned cells, as
// effects/solid_body.cpp's header defines them; the caller reduces them over ranks.
// box: only there (several level sets: psi is far below -band outside it).
inline SolidAcc solidMoments(const Grid& g, const Field& psi, const VecField& u, double kappa, double band,
                             double hm, const SolidTargets& tg, const Range3* box = nullptr) {
  const int ng = g.ng, c0 = g.c0[0], c1 = g.c0[1], c2 = g.c0[2];
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  const double lo0 = g.lo[0], lo1 = g.lo[1], lo2 = g.lo[2];
  // Moments about the domain centre (conditioning of the second moments).
  const double r0 = 0.5 * (g.lo[0] + g.hi[0]), r1 = 0.5 * (g.lo[1] + g.hi[1]), r2 = 0.5 * (g.lo[2] + g.hi[2]);
  SolidAcc acc;
  reduce_rows(
      "solid_body_moments", within(box, 0, cellRange(g)),
      KOKKOS_LAMBDA(int i, int j, int k, SolidAcc& a) {
        const double p = psi(i, j, k);
        const double x[3] = {lo0 + (i - ng + c0 + 0.5) * h0, lo1 + (j - ng + c1 + 0.5) * h1,
                             lo2 + (k - ng + c2 + 0.5) * h2};
        if (tg.n > 0 && p > -band && p < hm) { // outside and the first layer in: deeper, psi has ridges
          // Fluid cells inside an obstacle are skipped: its fixed velocity leaves psi there
          // stale (not a distance), e.g. the fringe of a block resting on the cylinder.
          bool stale = false;
          for (int q = 0; q < tg.n; ++q)
            if (tg.t[q].kind <= 2 && p <= 0 && targetDistance(tg.t[q], x) < 0) stale = true;
          if (!stale)
            for (int q = 0; q < tg.n; ++q) a.m[q] = minOf(a.m[q], targetDistance(tg.t[q], x) - p);
        }
        const double w = smoothedHeaviside(p, kappa);
        if (w <= 0) return;
        double v[3] = {0, 0, 0};
        for (int d = 0; d < 3; ++d)
          for (int n = 0; n < 8; ++n) v[d] += 0.125 * u.c[d](i + (n & 1), j + ((n >> 1) & 1), k + (n >> 2));
        const double dx = x[0] - r0, dy = x[1] - r1, dz = x[2] - r2;
        a.s[0] += w, a.s[1] += w * dx, a.s[2] += w * dy, a.s[3] += w * dz;
        a.s[4] += w * v[0], a.s[5] += w * v[1], a.s[6] += w * v[2];
        a.s[7] += w * dx * dx, a.s[8] += w * dy * dy, a.s[9] += w * dz * dz;
        a.s[10] += w * dx * dy, a.s[11] += w * dy * dz, a.s[12] += w * dz * dx;
      },
      SolidReducer(acc));
  return acc;
}

// Mid-surface columns and their deviation from the best-fit plane (header comment).
inline double solidBending(const Grid& g, const Field& psi, double kappa, double hm, int R,
                           const Kokkos::View<double* [4], MemSpace>& bins, const double c[3], const double e[3][3]) {
  Kokkos::deep_copy(bins, 0.0);
  const int ng = g.ng, i0 = g.c0[0], j0 = g.c0[1], k0 = g.c0[2], nb = 2 * R + 1;
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  const double x0 = g.lo[0] - c[0], y0 = g.lo[1] - c[1], z0 = g.lo[2] - c[2];
  const double n0 = e[0][0], n1 = e[0][1], n2 = e[0][2], a0 = e[1][0], a1 = e[1][1], a2 = e[1][2];
  const double b0 = e[2][0], b1 = e[2][1], b2 = e[2][2];
  // Scatter-add through a ScatterView: plain adds on Serial (in the order the atomics
  // took), a copy per thread on OpenMP, atomics on a GPU; a plain parallel_for, never
  // for_each3's ivdep loop.
  auto sv = Kokkos::Experimental::create_scatter_view(bins);
  Kokkos::parallel_for("solid_body_columns", cellRange(g).policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        const double w = smoothedHeaviside(psi(i, j, k), kappa);
        if (w <= 0) return;
        const double dx = x0 + (i - ng + i0 + 0.5) * h0, dy = y0 + (j - ng + j0 + 0.5) * h1,
                     dz = z0 + (k - ng + k0 + 0.5) * h2;
        const double a = a0 * dx + a1 * dy + a2 * dz, b = b0 * dx + b1 * dy + b2 * dz, s = n0 * dx + n1 * dy + n2 * dz;
        // Bilinear (cloud-in-cell) share to the 4 nearest column centres: a cell
        // on a column boundary splits evenly, so no rounding tie moves it.
        const double fa = a / hm, fb = b / hm;
        const int ia = int(km::floor(fa)), ib = int(km::floor(fb));
        auto acc = sv.access();
        for (int n = 0; n < 4; ++n) {
          const int qa = ia + (n & 1) + R, qb = ib + (n >> 1) + R;
          if (qa < 0 || qa >= nb || qb < 0 || qb >= nb) continue;
          const double kw = w * ((n & 1) ? fa - ia : 1 - (fa - ia)) * ((n >> 1) ? fb - ib : 1 - (fb - ib));
          const int q = qa + nb * qb;
          acc(q, 0) += kw * a;
          acc(q, 1) += kw * b;
          acc(q, 2) += kw * s;
          acc(q, 3) += kw;
        }
      });
  auto sums = bins; // contribute takes a non-const view
  Kokkos::Experimental::contribute(sums, sv);
  auto hb = toHost(bins, "solid_body_columns");
  MPI_Allreduce(MPI_IN_PLACE, hb.data(), int(hb.size()), MPI_DOUBLE, MPI_SUM, g.comm);
  toDevice(bins, hb, "solid_body_columns");
  // Normal equations of the least-squares plane s = p0 + p1 a + p2 b over the columns.
  SolidAcc fit;
  const auto cols = Kokkos::RangePolicy<ExecSpace>(0, nb * nb);
  Kokkos::parallel_reduce(
      "solid_body_plane", cols,
      KOKKOS_LAMBDA(int q, SolidAcc& f) {
        const double W = bins(q, 3);
        if (W < 1) return; // at least one cell's worth of solid
        const double a = bins(q, 0) / W, b = bins(q, 1) / W, s = bins(q, 2) / W;
        f.s[0] += 1, f.s[1] += a, f.s[2] += b, f.s[3] += a * a, f.s[4] += a * b, f.s[5] += b * b;
        f.s[6] += s, f.s[7] += a * s, f.s[8] += b * s;
      },
      SolidReducer(fit));
  if (fit.s[0] < 3) return 0;
  const double A[3][3] = {{fit.s[0], fit.s[1], fit.s[2]}, {fit.s[1], fit.s[3], fit.s[4]}, {fit.s[2], fit.s[4], fit.s[5]}};
  const double rhs[3] = {fit.s[6], fit.s[7], fit.s[8]}, D = det3(A);
  if (!(km::fabs(D) > 0)) return 0;
  double p[3]; // Cramer's rule
  for (int col = 0; col < 3; ++col) {
    double M[3][3];
    for (int r = 0; r < 3; ++r)
      for (int cc = 0; cc < 3; ++cc) M[r][cc] = cc == col ? rhs[r] : A[r][cc];
    p[col] = det3(M) / D;
  }
  const double p0 = p[0], p1 = p[1], p2 = p[2];
  double dev = 0;
  Kokkos::parallel_reduce(
      "solid_body_bending", cols,
      KOKKOS_LAMBDA(int q, double& m) {
        const double W = bins(q, 3);
        if (W < 1) return;
        const double d = km::fabs(bins(q, 2) / W - p0 - p1 * bins(q, 0) / W - p2 * bins(q, 1) / W);
        if (d > m) m = d;
      },
      Kokkos::Max<double>(dev));
  return dev;
}

} // namespace voigt
