#pragma once
// Elastic-stress kernel family: the hypoelastic solid stress tau_S of
// Eq. (12)-(13) with the objective (Jaumann) rate, updated by Benson's
// half-step scheme, Eq. (16), as corrected in NOTES.md errata 1-2:
//   W = (L - L^T) / 2,  D = L + L^T,  L_ij = du_i/dx_j at the cell centre
//   (kernels/stress.hpp cellVelocityGradient; the paper's D has no 1/2, so
//   mu_S D is the usual 2 mu_S e);
//   d(tau)/dt = mu_S D + W tau - tau W                          (Eq. 13)
//   tau^{n+1/2} = tau^n + (dt/2)(W tau^n - tau^n W)
//   tau*        = tau^{n+1/2} + dt mu_S D                       (Eq. 16, with dt)
//   tau^{n+1}   = tau* + (dt/2)(W tau* - tau* W)
// (erratum 2 literally: rotation: explicit; the default applies the two half
// rotations as orthogonal Cayley rotations instead, see below).
// Sign of the spin term: for a rigid rotation x(t) = R(t) X, dR/dt = W R, the
// co-rotated stress R tau0 R^T has d/dt = W tau - tau W; tests/elasticity/
// test_objectivity checks this (and that the paper's W = L - L^T turns the
// stress twice as fast).
//
// Rotation of the half steps (scene key elasticity.rotation, default cayley).
// Eq. (16) as corrected by erratum 2 applies each half rotation explicitly,
//   tau -> tau + (dt/2)(W tau - tau W)                         (rotation: explicit)
// For a constant spin the two explicit half steps multiply the in-plane
// deviatoric amplitude, (xx - yy)/2 + i xy, by (1 + i w dt)^2 per step (exact:
// exp(2 i w dt); w the rotation rate): the phase is right to O((w dt)^3) but
// the modulus grows by 1 + (w dt)^2 per step, i.e. after an angle theta the
// amplitude is too large by exp(theta w dt) - 1, first order in dt. Measured in
// test_objectivity (pre-stressed disk in rigid rotation, 64 cells, cfl 0.5,
// 806 steps per turn): |tau| 4.7e-2 too large after 360 degrees, 9.7e-2 after
// 720 (max error vs R tau0 R^T 5.0e-2, 1.0e-1; half at cfl 0.25). A spinning
// pre-stressed solid gains elastic energy from nothing at that rate (~10% per
// turn); the issue 7 stability suite ("no growth without a source") would see it.
// The default keeps Eq. (16)'s structure (half rotation, elastic increment
// dt mu_S D, half rotation; same W from u^{n+1} in both halves) but rotates
// each half step by the Cayley transform of the half-step spin (Hughes &
// Winget 1980, Int. J. Numer. Meth. Eng. 15, 1862):
//   Q = (I - (dt/4) W)^{-1} (I + (dt/4) W),   tau -> Q tau Q^T   (rotation: cayley)
//   tau^{n+1/2} = Q tau^n Q^T;  tau* = tau^{n+1/2} + dt mu_S D;  tau^{n+1} = Q tau* Q^T.
// Q is orthogonal for antisymmetric W (and I - (dt/4) W is always invertible:
// det = 1 + (dt/4)^2 |w|^2 >= 1), so a pure rotation keeps |tau| (every
// invariant) exactly, to round-off. Q = I + (dt/2) W + O(dt^2) as the explicit
// half step; it turns by 2 atan(|w| dt / 4) per half step instead of |w| dt/2,
// so the phase error is -(w dt)^3 / 24 per step in the tensor phase (the same
// order as the explicit form), and the error after an angle theta is
// theta (w dt)^2 / 24 times the amplitude: second order, with no amplitude
// error. Measured (same scene): error vs R tau0 R^T 1.6e-5 after 360 degrees,
// 3.2e-5 after 720 (a quarter of that at cfl 0.25: observed order 2.00), |tau|
// kept to 7e-13; equal to the closed form R(theta_d) tau0 R(theta_d)^T,
// theta_d = sum 4 atan(w dt / 4), to 1e-12. Cost: one 3x3 cofactor inverse and
// two 3x3 triple products per cell-step: about 30 ns more than the explicit
// form on one host core (58-65 vs 33 ns per bensonUpdate, latency-bound
// micro-benchmark), against ~1.8 us per cell-step for the whole elasticity
// effect (cases/shear_wave/README.md).
// The explicit map is kept bit-for-bit (rotation: explicit) for comparison and
// for the replay tests that pin it.
//
// Band: every kernel here loops over a packed list of active cells (local
// index i + e0 (j + e1 k), as kernels/reinit.hpp), built from psi each step.
#include <Kokkos_Core.hpp>

#include <cmath>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/index_space.hpp"
#include "kernels/elastic_stretch.hpp"
#include "kernels/heaviside.hpp"
#include "kernels/projection_ops.hpp"
#include "kernels/reductions.hpp"
#include "kernels/lists.hpp"
#include "kernels/stress.hpp"

namespace voigt {
namespace elastic {

using voigt::IntList;

using voigt::Unpack; // core/index_space.hpp

// Symmetric tensor as a 3x3 array <-> the six stored components (xx, yy, zz, xy, yz, zx).
KOKKOS_INLINE_FUNCTION void unpackSym(const double s[6], double t[3][3]) {
  t[0][0] = s[0]; t[1][1] = s[1]; t[2][2] = s[2];
  t[0][1] = t[1][0] = s[3];
  t[1][2] = t[2][1] = s[4];
  t[2][0] = t[0][2] = s[5];
}

// s += a (W t - t W) for symmetric t and antisymmetric W (the result is symmetric).
KOKKOS_INLINE_FUNCTION void addSpin(const double W[3][3], const double s[6], double a, double out[6]) {
  double t[3][3];
  unpackSym(s, t);
  double c[3][3];
  VOIGT_UNROLL
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) {
      double v = 0;
      VOIGT_UNROLL
      for (int r = 0; r < 3; ++r) v += W[p][r] * t[r][q] - t[p][r] * W[r][q];
      c[p][q] = v;
    }
  out[0] = s[0] + a * c[0][0];
  out[1] = s[1] + a * c[1][1];
  out[2] = s[2] + a * c[2][2];
  out[3] = s[3] + a * c[0][1];
  out[4] = s[4] + a * c[1][2];
  out[5] = s[5] + a * c[2][0];
}

// How the half-step rotations of Eq. (16) are applied (header comment).
enum class Rotation : int { Cayley = 0, Explicit = 1 };

// Q = (I - a W)^{-1} (I + a W) for a 3x3 W: the Cayley transform (orthogonal
// when W is antisymmetric). Closed-form inverse by cofactors; det(I - a W) =
// 1 + a^2 |w|^2 for antisymmetric W, never zero.
KOKKOS_INLINE_FUNCTION void cayleyTransform(const double W[3][3], double a, double Q[3][3]) {
  double M[3][3], P[3][3];
  VOIGT_UNROLL
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) {
      const double d = p == q ? 1.0 : 0.0;
      M[p][q] = d - a * W[p][q];
      P[p][q] = d + a * W[p][q];
    }
  // Adjugate: inv = adj(M) / det(M), adj[p][q] = cofactor of M[q][p].
  double A[3][3];
  A[0][0] = M[1][1] * M[2][2] - M[1][2] * M[2][1];
  A[0][1] = M[0][2] * M[2][1] - M[0][1] * M[2][2];
  A[0][2] = M[0][1] * M[1][2] - M[0][2] * M[1][1];
  A[1][0] = M[1][2] * M[2][0] - M[1][0] * M[2][2];
  A[1][1] = M[0][0] * M[2][2] - M[0][2] * M[2][0];
  A[1][2] = M[0][2] * M[1][0] - M[0][0] * M[1][2];
  A[2][0] = M[1][0] * M[2][1] - M[1][1] * M[2][0];
  A[2][1] = M[0][1] * M[2][0] - M[0][0] * M[2][1];
  A[2][2] = M[0][0] * M[1][1] - M[0][1] * M[1][0];
  const double inv = 1.0 / (M[0][0] * A[0][0] + M[0][1] * A[1][0] + M[0][2] * A[2][0]);
  VOIGT_UNROLL
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) {
      double v = 0;
      VOIGT_UNROLL
      for (int r = 0; r < 3; ++r) v += A[p][r] * P[r][q];
      Q[p][q] = v * inv;
    }
}

// out = Q t Q^T for symmetric t (six components in, six out).
KOKKOS_INLINE_FUNCTION void rotateSym(const double Q[3][3], const double s[6], double out[6]) {
  double t[3][3];
  unpackSym(s, t);
  double B[3][3]; // t Q^T
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) B[p][q] = t[p][0] * Q[q][0] + t[p][1] * Q[q][1] + t[p][2] * Q[q][2];
  double c[3][3];
  VOIGT_UNROLL
  for (int p = 0; p < 3; ++p)
    for (int q = p; q < 3; ++q) c[p][q] = Q[p][0] * B[0][q] + Q[p][1] * B[1][q] + Q[p][2] * B[2][q];
  out[0] = c[0][0];
  out[1] = c[1][1];
  out[2] = c[2][2];
  out[3] = c[0][1];
  out[4] = c[1][2];
  out[5] = c[0][2];
}

// One Benson half-step update of Eq. (16) for one cell, given L (= grad u).
// spinScale multiplies (L - L^T): 0.5 is the standard spin (NOTES.md erratum 1);
// 1.0 is the paper's Eq. (13) as printed (kept for the test that shows it fails).
// rot: each half rotation by Q tau Q^T with Q the Cayley transform of (dt/2) W
// (default), or explicitly, tau + (dt/2)(W tau - tau W) (erratum 2 literally).
// neoHookean (elasticity.model: neo_hookean): the stretching terms of the upper-convected
// rate added to the middle increment (kernels/elastic_stretch.hpp).
KOKKOS_INLINE_FUNCTION void bensonUpdate(double tau[6], const double L[3][3], double mu, double dt,
                                         double spinScale = 0.5, Rotation rot = Rotation::Cayley,
                                         bool neoHookean = false) {
  double W[3][3];
  VOIGT_UNROLL
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) W[p][q] = spinScale * (L[p][q] - L[q][p]);
  double half[6];
  double Q[3][3];
  if (rot == Rotation::Cayley) {
    cayleyTransform(W, 0.25 * dt, Q);
    rotateSym(Q, tau, half); // tau^{n+1/2}
  } else {
    addSpin(W, tau, 0.5 * dt, half); // tau^{n+1/2}
  }
  if (neoHookean) addStretching(half, L, mu, dt); // kernels/elastic_stretch.hpp
  half[0] += dt * mu * 2 * L[0][0]; // tau* = tau^{n+1/2} + dt mu D, D = L + L^T
  half[1] += dt * mu * 2 * L[1][1];
  half[2] += dt * mu * 2 * L[2][2];
  half[3] += dt * mu * (L[0][1] + L[1][0]);
  half[4] += dt * mu * (L[1][2] + L[2][1]);
  half[5] += dt * mu * (L[2][0] + L[0][2]);
  if (rot == Rotation::Cayley)
    rotateSym(Q, half, tau); // tau^{n+1}
  else
    addSpin(W, half, 0.5 * dt, tau); // tau^{n+1}
}

// Packed list of the cells of range r with psi > threshold; returns the count. psi
// must be fresh on r.
inline int buildActiveList(const Grid& g, const Field& psi, double threshold, Range3 r, const IntList& cell) {
  return listCellsWhere("elastic_active_list", g, r, cell,
                        KOKKOS_LAMBDA(int i, int j, int k) { return psi(i, j, k) > threshold; });
}

// Packed list of the owned cells where any component of tau is non-zero (restart:
// the cells the last step's band left stress in); returns the count.
inline int buildNonzeroList(const Grid& g, const SymTensorField& tau, const IntList& cell) {
  const SymTensorField t = tau;
  return listCellsWhere("elastic_nonzero_list", g, cellRange(g), cell, KOKKOS_LAMBDA(int i, int j, int k) {
    bool nz = false;
    VOIGT_UNROLL
    for (int c = 0; c < 6; ++c) nz = nz || t.c[c](i, j, k) != 0;
    return nz;
  });
}

using voigt::listBox; // kernels/reductions.hpp

constexpr double kAll = -1e300; // jaumannUpdate's `above`: every listed cell, psi not read

// Benson update, Eq. (16), on the listed cells (those with psi > above, when given), in
// the runs of consecutive cells `runs` (listRuns): flat addressing (cellVelocityGradient's
// corners as fixed offsets, the same sums in the same order) and a masked store instead of
// an early return, so that a run vectorises. u needs the nodes of those cells. The
// rotation and the psi mask are template arguments: a runtime choice left Q undefined on
// one path, and a short-circuit read of psi was a masked load; GCC kept the loop scalar.
template <Rotation R, bool Masked>
void jaumannRuns(const Grid& g, const VecField& u, const SymTensorField& tau, double mu, double dt, const IntList& cell,
                 int n, const IntList& runs, int nRuns, double spinScale, const Field& psi, double above,
                 bool neoHookean) {
  const int sj = g.ext[0], sk = g.ext[0] * g.ext[1];
  const double q0 = 4 * g.h[0], q1 = 4 * g.h[1], q2 = 4 * g.h[2];
  const FlatField fp = Masked ? flat(psi) : FlatField();
  const FlatField ux = flat(u.c[0]), uy = flat(u.c[1]), uz = flat(u.c[2]);
  const FlatSym t = flatSym(tau);
  const FlatField t0 = t.c[0], t1 = t.c[1], t2 = t.c[2], t3 = t.c[3], t4 = t.c[4], t5 = t.c[5];
  for_runs("elastic_jaumann", cell, runs, nRuns, n, KOKKOS_LAMBDA(int, int p) {
        bool on = true;
        if (Masked) on = fp(p) > above;
        double L[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}; // as cellVelocityGradient (stress.hpp)
        VOIGT_UNROLL
        for (int c = 0; c < 8; ++c) {
          const int a = c & 1, b = (c >> 1) & 1, e = (c >> 2) & 1, o = p + a + b * sj + e * sk;
          const double sg[3] = {a ? 1.0 : -1.0, b ? 1.0 : -1.0, e ? 1.0 : -1.0};
          const double v[3] = {ux(o), uy(o), uz(o)};
          VOIGT_UNROLL
          for (int comp = 0; comp < 3; ++comp)
            VOIGT_UNROLL
            for (int dir = 0; dir < 3; ++dir) L[comp][dir] += sg[dir] * v[comp];
        }
        VOIGT_UNROLL
        for (int comp = 0; comp < 3; ++comp) L[comp][0] /= q0, L[comp][1] /= q1, L[comp][2] /= q2;
        double s[6] = {t0(p), t1(p), t2(p), t3(p), t4(p), t5(p)};
        const double s0[6] = {s[0], s[1], s[2], s[3], s[4], s[5]};
        bensonUpdate(s, L, mu, dt, spinScale, R, neoHookean);
        t0(p) = on ? s[0] : s0[0], t1(p) = on ? s[1] : s0[1], t2(p) = on ? s[2] : s0[2];
        t3(p) = on ? s[3] : s0[3], t4(p) = on ? s[4] : s0[4], t5(p) = on ? s[5] : s0[5];
      });
}

inline void jaumannUpdate(const Grid& g, const VecField& u, const SymTensorField& tau, double mu, double dt,
                          const IntList& cell, int n, const IntList& runs, int nRuns, double spinScale = 0.5,
                          Rotation rot = Rotation::Cayley, const Field& psi = Field(),
                          double above = kAll, bool neoHookean = false) {
  if (n == 0) return;
  const bool masked = above > kAll;
  const bool nh = neoHookean;
  if (rot == Rotation::Cayley && masked)
    jaumannRuns<Rotation::Cayley, true>(g, u, tau, mu, dt, cell, n, runs, nRuns, spinScale, psi, above, nh);
  else if (rot == Rotation::Cayley)
    jaumannRuns<Rotation::Cayley, false>(g, u, tau, mu, dt, cell, n, runs, nRuns, spinScale, psi, above, nh);
  else if (masked)
    jaumannRuns<Rotation::Explicit, true>(g, u, tau, mu, dt, cell, n, runs, nRuns, spinScale, psi, above, nh);
  else
    jaumannRuns<Rotation::Explicit, false>(g, u, tau, mu, dt, cell, n, runs, nRuns, spinScale, psi, above, nh);
}

// tau += H(psi) tau_S on the listed cells: Eq. (9)/(14). tau already holds the
// viscous part mu D with the blended mu = H mu_solid + (1 - H) mu_L, so the sum
// is Eq. (14) plus the optional Kelvin-Voigt solid viscosity.
inline void addSolidStress(const Grid& g, const Field& psi, double kappa, const SymTensorField& solid,
                           const SymTensorField& tau, const IntList& cell, int n) {
  if (n == 0) return;
  const FlatField fpsi = flat(psi);
  const FlatSym s = flatSym(solid), t = flatSym(tau);
  for_listed("elastic_add_stress", cell, n, KOKKOS_LAMBDA(int, int p) {
        const double H = smoothedHeaviside(fpsi(p), kappa);
        VOIGT_UNROLL
        for (int c = 0; c < 6; ++c) t.c[c](p) += H * s.c[c](p);
      });
}

// The paper's second invariant S2 = t00 t11 + t11 t22 + t22 t00 + t01^2 + t12^2 + t20^2
// (as printed in the falling-block section).
KOKKOS_INLINE_FUNCTION double secondInvariant(double xx, double yy, double zz, double xy, double yz, double zx) {
  return xx * yy + yy * zz + zz * xx + xy * xy + yz * yz + zx * zx;
}


// Initial solid stress: tau_S = a (6 components) where psi > 0, else 0, on the owned cells.
inline void initialStress(const Grid& g, const Field& psi, const SymTensorField& tau, const double a[6]) {
  const SymTensorField t = tau;
  const double a0 = a[0], a1 = a[1], a2 = a[2], a3 = a[3], a4 = a[4], a5 = a[5];
  for_each3("elastic_initial_stress", cellRange(g), KOKKOS_LAMBDA(int i, int j, int k) {
        const bool in = psi(i, j, k) > 0;
        t.c[0](i, j, k) = in ? a0 : 0.0;
        t.c[1](i, j, k) = in ? a1 : 0.0;
        t.c[2](i, j, k) = in ? a2 : 0.0;
        t.c[3](i, j, k) = in ? a3 : 0.0;
        t.c[4](i, j, k) = in ? a4 : 0.0;
        t.c[5](i, j, k) = in ? a5 : 0.0;
      });
}

// tau_S = 0 outside the band (psi <= thr): over the band's box, and on the cells of
// last step's list (prev), whose S2 and log10 S2 also return to their reset values.
inline void zeroOutsideBand(const Grid& g, const Field& psi, double thr, const SymTensorField& tau, Range3 box,
                            bool anyBox, const IntList& prev, int nPrev, const Field& S2, const Field& lg,
                            double floorLog) {
  const SymTensorField t = tau;
  if (anyBox)
    for_each3("elastic_zero_box", box, KOKKOS_LAMBDA(int i, int j, int k) {
          if (psi(i, j, k) <= thr)
            for (int c = 0; c < 6; ++c) t.c[c](i, j, k) = 0;
        });
  if (nPrev <= 0) return;
  const Unpack up{g.ext[0], g.ext[1]};
  Kokkos::parallel_for(
      "elastic_zero_left", Kokkos::RangePolicy<ExecSpace>(0, nPrev), KOKKOS_LAMBDA(int p) {
        int i, j, k;
        up(prev(p), i, j, k);
        if (psi(i, j, k) <= thr) {
          VOIGT_UNROLL
          for (int c = 0; c < 6; ++c) t.c[c](i, j, k) = 0;
          S2(i, j, k) = 0;
          lg(i, j, k) = floorLog;
        }
      });
}


} // namespace elastic
} // namespace voigt
