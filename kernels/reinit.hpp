#pragma once
// Re-initialisation kernel family (paper Eq. 17-21), narrow band.
//
// Eq. (17) dpsi/dtau = S(psi0)(1 - |grad psi|), S = psi0 / sqrt(psi0^2 + h^2)
//   (Sussman, Smereka & Osher 1994), |grad psi| by the Godunov upwind rule on
//   second-order ENO one-sided differences (Sussman et al. 1998), per-axis h.
//   Near the band edge, where the 5-point stencil would read a frozen cell, the
//   differences drop to first order: ENO2 there grows without bound (measured),
//   because frozen and updated values disagree by up to the band's distortion.
//   Time: Heun/SSP-RK2 in pseudo time (Sussman et al. 1998).
// Subcell fix (Russo & Smereka 2000), optional, in cells whose psi0 changes sign
//   across a face: dpsi/dtau = (D - psi)/h, D = psi0 / |grad psi0|_RS, with
//   |grad psi0|_RS from the largest of the central and one-sided differences per
//   axis. (They write -(sgn(psi0)|psi| - D)/h; equal while psi keeps the sign of
//   psi0, but with psi0 ~ 0 the constraint can push psi across zero and that form
//   then grows exponentially.) It pins the interface in one call: on a distorted
//   sphere the contour moves 0.009 instead of 0.065 cells without the constraint.
//   It is off by default: D is first order and biased where the curvature is
//   under-resolved, and repeated calls then drift thin threads (radius 1.5 cells,
//   100 calls of 2 steps: +46% volume alone, -5% with the constraint, +2% for the
//   constraint without it; test_reinit).
// Eq. (18)-(21) (Sussman & Fatemi 1999) per cell c, with psi~ the Eikonal result
//   of the pseudo step and psi^m the value before it:
//     psi^{m+1}_c = psi~_c + dtau lambda_c f_c,   f = H'(psi0)|grad psi0|,
//     lambda_c = -INT H'(psi0)(psi~ - psi^m)/dtau / INT H'(psi0) f,
//   so dtau lambda_c f_c = -coef_c SUM_n w_n H'_n (psi~_n - psi^m_n) with
//   coef_c = f_c / SUM_n w_n H'_n f_n, fixed for the call (psi0 is).
//   The integral over cell c uses the 27-point tensor product of the 1-D weights
//   (1, 22, 1)/24: the quadratic p through (-h,a), (0,b), (h,c) is
//   p = b + (c-a)x/2h + (a-2b+c)x^2/2h^2, and its mean over [-h/2, h/2] is
//   b + (a-2b+c)/24 (x^2 averages to h^2/12) = (a + 22b + c)/24.
// The constraint keeps INT H(psi), which for a thin feature (thinner than 2 kappa)
//   also depends on |grad psi|: where the Eikonal corrects |grad psi|, the
//   constraint moves the interface instead. This is the known way it grows bumps
//   on filaments; test_reinit measures it (a sheet 1.6 cells thick under a
//   persistent 2% gradient distortion per call thickens, with or without it).
//   cases/single_vortex at 128^2 (2 steps per time step), area change at t = T:
//   T = 2: -0.02% with the constraint, -2.5% without; T = 8, where the spiral
//   arms get thinner than the smoothing width: +63% with, +24% without.
// Only band cells move; the distance is exact where it is < band (frozen cells
//   hold |psi0| >= band and feed only such values in).
// Band cells are a packed list (local index i + e0 (j + e1 k)); every pseudo-time
// kernel is a 1-D RangePolicy over it. H'(psi0) = 0 outside the band when
// band >= kappa, so the lambda stencil needs no extra layer: cells outside the band
// contribute nothing to either integral (their psi does not move either).
#include <Kokkos_Core.hpp>

#include <algorithm>
#include <cmath>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/index_space.hpp"
#include "kernels/heaviside.hpp"
#include "kernels/reductions.hpp" // listCellsWhere
#include "kernels/lists.hpp"

namespace voigt {
namespace reinit {

using voigt::IntList;
using RealList = Kokkos::View<double*, MemSpace>;

// BandViews::flags bits. kEno << d: the 5-point ENO stencil along axis d lies in the band.
enum : int { kInterface = 1, kInterior = 2, kEno = 4 };

struct BandViews {
  IntList cell;   // packed local index
  IntList flags;  // kInterface: psi0 changes sign across a face (subcell fix);
                  // kInterior: not kInterface and all 6 face neighbours in the band
  RealList sgn;   // S(psi0)
  RealList dist;  // Russo-Smereka distance D (kInterface cells)
  RealList coef;  // f_c / INT H' f (0 without the constraint or where INT ~ 0)
  IntList runs;   // where the runs of consecutive cells start (listRuns: vectorised loops)
  int nRuns = 0;
  // The constrained cells (prepareBand): band cells with H'(psi0) > 0, the only ones whose
  // coef can be nonzero; where psi0 is all interface (a packed bed) most of the band, about
  // a third of it around one body. Their local index, band position q, coef, and runs.
  IntList con, conQ, conRuns;
  RealList conCoef;
  int nCon = 0, nConRuns = 0;
};

using voigt::Unpack; // core/index_space.hpp

KOKKOS_INLINE_FUNCTION double minmod(double a, double b) { // branch-free: this is the hot loop
  // std::copysign: Kokkos 3.4 has none (nvcc maps std::copysign to the device builtin).
  return (std::copysign(0.5, a) + std::copysign(0.5, b)) * minOf(km::fabs(a), km::fabs(b));
}

// Second-order ENO one-sided differences at p0 along one axis.
// eno = false: first-order differences (the stencil would reach a frozen cell).
KOKKOS_INLINE_FUNCTION void eno2(double pm2, double pm1, double p0, double pp1, double pp2, double h, bool eno,
                                 double& dm, double& dp) {
  const double d2m = pm2 - 2 * pm1 + p0, d20 = pm1 - 2 * p0 + pp1, d2p = p0 - 2 * pp1 + pp2;
  const double c = eno ? 0.5 : 0.0;
  dm = (p0 - pm1 + c * minmod(d2m, d20)) / h;
  dp = (pp1 - p0 - c * minmod(d20, d2p)) / h;
}

// Godunov's choice of the squared upwind derivative for the sign s of psi0:
// s > 0 takes max(D-, 0)^2 and min(D+, 0)^2, s < 0 the mirror image.
KOKKOS_INLINE_FUNCTION double godunov2(double s, double dm, double dp) {
  const double sg = s > 0 ? 1.0 : -1.0;
  const double a = maxOf(sg * dm, 0.0), b = maxOf(-sg * dp, 0.0);
  return maxOf(a * a, b * b);
}

// Settled smoothing-zone cell (issue 50): |psi0| < kappa and ||grad psi0| - 1| < tol
// (central differences; psi0 fresh one layer beyond (i, j, k)). Re-initialisation leaves
// it as advected: neither the Eikonal nor the constraint moves it, and it adds nothing to
// the Eq. (21) integrals. Why: the density is blended from psi in the zone, and
// re-initialising there resets it to a rigid profile around the zero level without any
// flow; the gravity force on the zone's nodes then does work that the zone's own motion
// never pays back. Where a no-slip obstacle shears the zone, that pumps energy into a
// resting tank (cases/rest_tank: tenfold every ~28 s at 32 cells per metre). A zone
// already within tol of a distance loses nothing by being left as advected; tol = 0
// re-initialises every band cell (the paper).
KOKKOS_INLINE_FUNCTION bool settledCell(const Field& psi0, int i, int j, int k, double ih0, double ih1, double ih2,
                                        double kappa, double tol, bool curved) {
  const double p0 = psi0(i, j, k);
  if (!(km::fabs(p0) < kappa)) return false;
  const double pe = psi0(i + 1, j, k), pw = psi0(i - 1, j, k), pn = psi0(i, j + 1, k), ps = psi0(i, j - 1, k);
  const double pt = psi0(i, j, k + 1), pb = psi0(i, j, k - 1);
  const double gx = (pe - pw) * ih0, gy = (pn - ps) * ih1, gz = (pt - pb) * ih2;
  // curved: a curved distance function is not one to the central differences: their
  // truncation error, (h^2 / 6) n . (psi_xxx, psi_yyy, psi_zzz), is -(h kappa)^2 nx^2 ny^2 on
  // a circle (at most (h kappa)^2 / 4) and -(h kappa)^2 (1 - sum n^4) / 8 on a sphere, kappa =
  // lap psi the mean curvature's sum. So the tolerance grows by (h kappa)^2 / 4 where the
  // curvature is resolved (h |kappa| <= 1/2: 2 cells per radius of a circle, 4 of a sphere);
  // an unresolved corner is re-initialised as before.
  if (!curved) return km::fabs(km::sqrt(gx * gx + gy * gy + gz * gz) - 1.0) < tol;
  const double h2 = 0.25 / minOf(ih0 * ih0, minOf(ih1 * ih1, ih2 * ih2)); // (largest h)^2
  const double lap = ((pe + pw - 2 * p0) * ih0 * ih0 + (pn + ps - 2 * p0) * ih1 * ih1 + (pt + pb - 2 * p0) * ih2 * ih2) * 4;
  const double hk2 = h2 * lap * lap;
  const double allow = hk2 <= 0.25 ? 0.25 * hk2 : 0.0;
  return km::fabs(km::sqrt(gx * gx + gy * gy + gz * gz) - 1.0) < tol + allow;
}

// The band's far side bounded by its neighbours (issue 51): out = sign(psi) max(kappa, min(|psi|,
// min over same-sign face neighbours n of |psi_n| + h_n)) on the cells with |psi| >= kappa; the
// smoothing zone is copied. A distance satisfies the bound already (1-Lipschitz), so it is left
// as it is; what the bound fixes is advected psi outside the band: where the flow converges on
// the interface (under a rising bubble) it steepens psi, |grad psi| reached 8, and a cell two
// cells from the interface kept |psi| = 15 h, outside the band, never re-initialised, with the
// curvature and the zone's neighbours read from it. No sign changes and no zone cell moves, so
// H(psi) and every phase volume are unchanged. One Jacobi pass a call; psi fresh one layer deep.
// box (here and below): only there (several level sets: core/index_space.hpp, within).
inline void boundFarField(const Grid& g, const Field& psi, const Field& out, double kappa, const Range3* box = nullptr) {
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  for_each3("reinit_bound_far", within(box, 0, cellRange(g)), KOKKOS_LAMBDA(int i, int j, int k) {
    const double p = psi(i, j, k), a = km::fabs(p);
    double m = a;
    if (a >= kappa) {
      const double nb[6] = {psi(i - 1, j, k), psi(i + 1, j, k), psi(i, j - 1, k),
                            psi(i, j + 1, k), psi(i, j, k - 1), psi(i, j, k + 1)};
      const double hs[3] = {h0, h1, h2};
      for (int q = 0; q < 6; ++q)
        if (nb[q] * p > 0) m = minOf(m, km::fabs(nb[q]) + hs[q / 2]);
      m = maxOf(m, kappa);
    }
    out(i, j, k) = p < 0 ? -m : m;
  });
}

// Compact list of owned cells with |psi0| < band that are not settled (tol > 0); returns
// the count. psi0 must be fresh one ghost layer deep.
inline int buildBandList(const Grid& g, const Field& psi0, double band, const IntList& cell, double kappa = 0,
                         double tol = 0, bool curved = false, const Range3* box = nullptr) {
  const double ih0 = 0.5 / g.h[0], ih1 = 0.5 / g.h[1], ih2 = 0.5 / g.h[2];
  return listCellsWhere("reinit_band_list", g, within(box, 0, cellRange(g)), cell, KOKKOS_LAMBDA(int i, int j, int k) {
    return km::fabs(psi0(i, j, k)) < band && !(tol > 0 && settledCell(psi0, i, j, k, ih0, ih1, ih2, kappa, tol, curved));
  });
}

// H' = 0 on the settled cells of the owned cells and one ghost layer (what the
// constraint's 27-point sums read): they take no correction and add none.
inline void unsettleDelta(const Grid& g, const Field& psi0, const Field& dH, double kappa, double tol,
                          bool curved = false, const Range3* box = nullptr) {
  const double ih0 = 0.5 / g.h[0], ih1 = 0.5 / g.h[1], ih2 = 0.5 / g.h[2];
  for_each3("reinit_settled", within(box, 1, cellRange(g, 1)), KOKKOS_LAMBDA(int i, int j, int k) {
    if (settledCell(psi0, i, j, k, ih0, ih1, ih2, kappa, tol, curved)) dH(i, j, k) = 0.0;
  });
}

// H'(psi0) of Eq. (4) over the whole array (ghosts included; psi0 must be fresh).
inline void deltaField(const Grid& g, const Field& psi0, const Field& dH, double kappa, const Range3* box = nullptr) {
  for_each3("reinit_delta", within(box, g.ng, Range3{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}}),
      KOKKOS_LAMBDA(int i, int j, int k) { dH(i, j, k) = smoothedDelta(psi0(i, j, k), kappa); });
}

// gm = |grad psi0| (central differences) where H'(psi0) > 0, else 0, on the owned
// cells and one ghost layer: the constraint's 27-point sums read it, instead of
// computing it again at every neighbour (27 times per cell). psi0 needs 2 fresh
// ghost layers.
inline void gradMagField(const Grid& g, const Field& psi0, const Field& dH, const Field& gm, const Range3* box = nullptr) {
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  for_each3("reinit_grad_mag", within(box, 1, cellRange(g, 1)), KOKKOS_LAMBDA(int i, int j, int k) {
    const double gx = (psi0(i + 1, j, k) - psi0(i - 1, j, k)) / (2 * h0);
    const double gy = (psi0(i, j + 1, k) - psi0(i, j - 1, k)) / (2 * h1);
    const double gz = (psi0(i, j, k + 1) - psi0(i, j, k - 1)) / (2 * h2);
    gm(i, j, k) = dH(i, j, k) > 0 ? km::sqrt(gx * gx + gy * gy + gz * gz) : 0.0;
  });
}

// The Eq. (21) integral over cell p's 27 neighbours o: SUM w_o term(w_o H'_o, H'_o, o), with w
// the tensor weights (1, 22, 1)/24 and H' = dH; branch-free, a neighbour with H' = 0 adds 0.0
// (H' >= 0, finite fields): the sums, in the order, of skipping it.
template <class Term>
KOKKOS_INLINE_FUNCTION double sumOverH(int p, int sj, int sk, const FlatField& fd, const Term& term) {
  const double w[3] = {1.0 / 24, 22.0 / 24, 1.0 / 24};
  double s = 0;
  VOIGT_UNROLL
  for (int c = -1; c <= 1; ++c)
    VOIGT_UNROLL
    for (int bb = -1; bb <= 1; ++bb)
      VOIGT_UNROLL
      for (int a = -1; a <= 1; ++a) {
        const int o = p + a + bb * sj + c * sk;
        const double dn = fd(o);
        s += dn > 0 ? term(w[a + 1] * w[bb + 1] * w[c + 1] * dn, dn, o) : 0.0;
      }
  return s;
}

// The band cells with H'(psi0) > 0 into b.con / b.conQ (allocated on first use, as large
// as the band list b.cell can be, so never again in a run) and their runs; sets b.nCon,
// b.nConRuns.
inline void listConstrained(BandViews& b, int n, const Field& dH) {
  if (b.con.extent(0) < size_t(n) || b.con.extent(0) == 0) {
    const size_t cap = std::max<size_t>({b.cell.extent(0), size_t(n), 1});
    b.con = IntList("reinit_con", cap), b.conQ = IntList("reinit_con_q", cap);
    b.conRuns = IntList("reinit_con_runs", cap), b.conCoef = RealList("reinit_con_coef", cap);
  }
  const FlatField fd = flat(dH);
  const IntList cell = b.cell, con = b.con, conQ = b.conQ;
  int count = 0;
  Kokkos::parallel_scan(
      "reinit_con_list", Kokkos::RangePolicy<ExecSpace>(0, n), KOKKOS_LAMBDA(int q, int& upd, bool final) {
        if (fd(cell(q)) > 0) {
          if (final) con(upd) = cell(q), conQ(upd) = q;
          ++upd;
        }
      },
      count);
  b.nCon = count;
  b.nConRuns = listRuns(b.con, count, b.conRuns);
}

// Per band cell, fixed for the call: flags, S(psi0), D, and the constraint's coef.
// psi0 and dH need 2 fresh ghost layers; gm: scratch for gradMagField.
inline void prepareBand(const Grid& g, BandViews& b, int n, const Field& psi0, const Field& dH,
                        const Field& gm, double band, bool constraint, const Range3* box = nullptr) {
  if (constraint) gradMagField(g, psi0, dH, gm, box);
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  const double hs = std::min({h0, h1, h2});
  const int sj = g.ext[0], sk = g.ext[0] * g.ext[1];
  const FlatField ps = flat(psi0), fd = flat(dH), fg = flat(gm);
  for_listed("reinit_prepare", b.cell, n, KOKKOS_LAMBDA(int q, int p) {
        const double p0 = ps(p);
        b.sgn(q) = p0 / km::sqrt(p0 * p0 + hs * hs);
        const double nb[3][2] = {{ps(p - 1), ps(p + 1)}, {ps(p - sj), ps(p + sj)}, {ps(p - sk), ps(p + sk)}};
        const double far[3][2] = {
            {ps(p - 2), ps(p + 2)}, {ps(p - 2 * sj), ps(p + 2 * sj)}, {ps(p - 2 * sk), ps(p + 2 * sk)}};
        const double hd[3] = {h0, h1, h2};
        bool iface = false, inside = true;
        int eno = 0;
        double g2 = 0;
        VOIGT_UNROLL
        for (int d = 0; d < 3; ++d) {
          const double m = nb[d][0], p = nb[d][1];
          iface = iface || p0 * m <= 0 || p0 * p <= 0;
          const bool in1 = km::fabs(m) < band && km::fabs(p) < band;
          inside = inside && in1;
          if (in1 && km::fabs(far[d][0]) < band && km::fabs(far[d][1]) < band) eno |= kEno << d;
          double del = km::fabs(p - m) * 0.5;
          del = maxOf(del, maxOf(km::fabs(p - p0), km::fabs(p0 - m)));
          g2 += (del / hd[d]) * (del / hd[d]);
        }
        b.flags(q) = (iface ? kInterface : 0) | (!iface && inside ? kInterior : 0) | eno;
        // Used only next to the interface, where it is ~ psi0; clamped for safety.
        const double D = g2 > 0 ? p0 / km::sqrt(g2) : p0;
        b.dist(q) = maxOf(-band, minOf(band, D));
        b.coef(q) = 0;
      });
  b.nCon = b.nConRuns = 0;
  if (!constraint) return;
  // coef on the cells with H'(psi0) > 0 (0 elsewhere), branch-free over their runs: a
  // neighbour with H' = 0 adds 0 (H' >= 0, finite fields), the sum and order of skipping it.
  listConstrained(b, n, dH);
  for_runs("reinit_con_coef", b.con, b.conRuns, b.nConRuns, b.nCon, KOKKOS_LAMBDA(int m, int p) {
        const double den = sumOverH(p, sj, sk, fd, [&](double wdn, double dn, int o) { return wdn * dn * fg(o); });
        const double f = fd(p) * fg(p);
        // den >= w_c^3 H'_c f_c, so den ~ 0 only where f_c ~ 0 too: lambda = 0 there.
        const double coef = den > 1e-300 ? f / den : 0.0;
        b.conCoef(m) = coef;
        b.coef(b.conQ(m)) = coef;
      });
}

// One RK stage of Eq. (17) on the band: out = alpha base + (1 - alpha)(in + dtau R(in)).
// Needs `in` on 2 fresh ghost layers; reads `base` and writes `out` only at the cell
// itself, so out may alias base (not in).
inline void eikonalStage(const Grid& g, const BandViews& b, int n, const Field& in, const Field& base,
                         const Field& out, double alpha, double dtau, bool subcell) {
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  const double hmin = std::min({h0, h1, h2});
  const int sj = g.ext[0], sk = g.ext[0] * g.ext[1];
  const FlatField fi = flat(in), fb = flat(base), fo = flat(out);
  if (n > 0 && b.nRuns == 0) throw std::logic_error("eikonalStage: the band's runs were not built (listRuns)");
  // Both rates computed, one selected: branch-free, so that a run of cells vectorises
  // (for_runs); the same operations on the same values as the branch it replaces.
  for_runs("reinit_stage", b.cell, b.runs, b.nRuns, n, KOKKOS_LAMBDA(int q, int p) {
        const double p0 = fi(p), s = b.sgn(q);
        const int fl = b.flags(q);
        const double interfaceRate = (b.dist(q) - p0) / hmin; // Russo-Smereka, relaxing for either sign
        double dm, dp, g2 = 0;
        eno2(fi(p - 2), fi(p - 1), p0, fi(p + 1), fi(p + 2), h0, fl & kEno, dm, dp);
        g2 += godunov2(s, dm, dp);
        eno2(fi(p - 2 * sj), fi(p - sj), p0, fi(p + sj), fi(p + 2 * sj), h1, fl & (kEno << 1), dm, dp);
        g2 += godunov2(s, dm, dp);
        eno2(fi(p - 2 * sk), fi(p - sk), p0, fi(p + sk), fi(p + 2 * sk), h2, fl & (kEno << 2), dm, dp);
        g2 += godunov2(s, dm, dp);
        const double rate = subcell && (fl & kInterface) ? interfaceRate : s * (1 - km::sqrt(g2));
        fo(p) = alpha * fb(p) + (1 - alpha) * (p0 + dtau * rate);
      });
}

// Eq. (19)-(21): out_c = psiT_c - coef_c SUM_27 w H'(psi0) (psiT - psiM).
// psiT (psi~) and psiM (psi^m) need 1 fresh ghost layer; out must alias neither.
// coef = 0 outside the constrained cells (prepareBand's list), so there out = psiT; on them
// the sum runs branch-free over their runs (a term with H' = 0 adds 0: the same sums in the
// same order as skipping it). Measured (kernel timer, 30 steps from a checkpoint, interleaved
// with the branching form): 2.3-2.5x faster on the porous bed, 1.7-2.2x on the falling block.
// The coefficients are read through `b` (b.conCoef): a separately captured copy of the view
// made GCC's loop 3.5x slower (measured), for reasons not pinned down.
inline void applyConstraint(const Grid& g, const BandViews& b, int n, const Field& psiT, const Field& psiM,
                            const Field& dH, const Field& out) {
  const int sj = g.ext[0], sk = g.ext[0] * g.ext[1];
  const FlatField ft = flat(psiT), fm = flat(psiM), fd = flat(dH), fo = flat(out);
  if (n > 0 && b.nRuns == 0) throw std::logic_error("applyConstraint: the band's runs were not built (listRuns)");
  for_runs("reinit_constraint_copy", b.cell, b.runs, b.nRuns, n, KOKKOS_LAMBDA(int, int p) { fo(p) = ft(p); });
  for_runs("reinit_constraint", b.con, b.conRuns, b.nConRuns, b.nCon, KOKKOS_LAMBDA(int m, int p) {
        const double num = sumOverH(p, sj, sk, fd, [&](double wdn, double, int o) { return wdn * (ft(o) - fm(o)); });
        fo(p) = ft(p) - b.conCoef(m) * num;
      });
}

inline void copyBand(const Grid& g, const BandViews& b, int n, const Field& src, const Field& dst) {
  const FlatField fs = flat(src), fd = flat(dst);
  for_listed("reinit_copy", b.cell, n, KOKKOS_LAMBDA(int, int p) {
        fd(p) = fs(p);
      });
}

// Local max ||grad psi| - 1| (central differences) over kInterior band cells
// with |psi| <= band - 2 hmin: frozen cells only feed values >= band into the
// band (they hold |psi0| >= band), so closer in psi is the distance to the
// interface, and the kinks where the two meet stay out of the measure.
// psi needs 1 fresh ghost layer.
inline double maxGradError(const Grid& g, const BandViews& b, int n, const Field& psi, double band) {
  const Unpack up{g.ext[0], g.ext[1]};
  const double i0 = 0.5 / g.h[0], i1 = 0.5 / g.h[1], i2 = 0.5 / g.h[2];
  const double lim = band - 2 * std::min({g.h[0], g.h[1], g.h[2]});
  double m = 0;
  Kokkos::parallel_reduce(
      "reinit_grad_error", Kokkos::RangePolicy<ExecSpace>(0, n),
      KOKKOS_LAMBDA(int q, double& acc) {
        if (!(b.flags(q) & kInterior)) return;
        int i, j, k;
        up(b.cell(q), i, j, k);
        if (km::fabs(psi(i, j, k)) > lim) return;
        const double gx = (psi(i + 1, j, k) - psi(i - 1, j, k)) * i0;
        const double gy = (psi(i, j + 1, k) - psi(i, j - 1, k)) * i1;
        const double gz = (psi(i, j, k + 1) - psi(i, j, k - 1)) * i2;
        const double e = km::fabs(km::sqrt(gx * gx + gy * gy + gz * gz) - 1);
        if (e > acc || e != e) acc = e;
      },
      Kokkos::Max<double>(m));
  return m > 0 ? m : 0.0; // the Max identity is -DBL_MAX when no cell qualifies
}

} // namespace reinit
} // namespace voigt
