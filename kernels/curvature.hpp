#pragma once
// Curvature and the capillary force (surface_tension, issue 51).
//
// Curvature of the level sets at cell centres: kernels/curvature_point.hpp (central differences).
// At the interface, not across a smeared band: in a cell next to the zero level (psi changes
// sign across a face) kappa is interpolated linearly to the crossing on each such face and
// averaged; the other zone cells take it constant along the normal (Jacobi sweeps, the
// weights of kernels/extension.hpp with |psi| for psi). A distance's cell curvature varies
// as 2 / (R - psi) across the band; the interface value does not.
// Capillary force in balanced form (Francois et al. 2006): on the pressure's own node
// gradient G and coefficient (1/rho_n), rhs += coef sigma kappa_n G H(psi), kappa_n the mean
// of the extended kappa over the node's zone cells. Where kappa_n is one constant the force
// is coef G(sigma kappa H) exactly, so a pressure p = sigma kappa H balances it to round-off.
#include <Kokkos_Core.hpp>

#include <cmath>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/index_space.hpp"
#include "kernels/curvature_point.hpp"
#include "kernels/heaviside.hpp"
#include "kernels/projection_ops.hpp"

namespace voigt {
namespace curvature {

// kappa at the cells of r (psi fresh one layer beyond r); 0 where |grad psi| < 0.5 (no
// interface shape to speak of), limited to |kappa| <= 1 / hmin (a radius below one cell).
inline void cellCurvature(const Grid& g, const Field& psi, const Field& kap, Range3 r) {
  const double i0 = 1 / g.h[0], i1 = 1 / g.h[1], i2 = 1 / g.h[2];
  const double kmax = 1 / minOf(g.h[0], minOf(g.h[1], g.h[2]));
  for_each3("cell_curvature", r, KOKKOS_LAMBDA(int i, int j, int k) {
    kap(i, j, k) = curvatureAt(psi, i, j, k, i0, i1, i2, kmax); // kernels/curvature_point.hpp
  });
}

// ext = kappa interpolated to the zero level on the cells of r next to it (a face
// neighbour of the other sign), else 0; known = 1 there, else 0. kap fresh one layer beyond r.
inline void interfaceCurvature(const Field& psi, const Field& kap, const Field& ext, const Field& known, Range3 r) {
  for_each3("interface_curvature", r, KOKKOS_LAMBDA(int i, int j, int k) {
    const double pc = psi(i, j, k), kc = kap(i, j, k);
    double s = 0, n = 0;
    VOIGT_UNROLL
    for (int f = 0; f < 6; ++f) {
      const int a = f >> 1, sg = (f & 1) ? 1 : -1;
      const int ii = i + (a == 0 ? sg : 0), jj = j + (a == 1 ? sg : 0), kk = k + (a == 2 ? sg : 0);
      const double pn = psi(ii, jj, kk);
      const bool cross = (pc > 0) != (pn > 0);
      const double den = km::fabs(pc) + km::fabs(pn);
      const double v = den > 0 ? (km::fabs(pn) * kc + km::fabs(pc) * kap(ii, jj, kk)) / den : kc;
      s += cross ? v : 0.0;
      n += cross ? 1.0 : 0.0;
    }
    ext(i, j, k) = n > 0 ? s / n : 0.0;
    known(i, j, k) = n > 0 ? 1.0 : 0.0;
  });
}

// One Jacobi sweep on the cells of r with |psi| < reach that are not known: the weighted
// mean of the known neighbours closer to the zero level, w = ((|psi_c| - |psi_nb|) / |d|)^2;
// a cell that gets a value becomes known. src/dst (ext, known) pairs, sources fresh one layer beyond r.
inline void extendSweep(const Grid& g, const Field& psi, const Field& src, const Field& srcKnown, const Field& dst,
                        const Field& dstKnown, double reach, Range3 r) {
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  for_each3("curvature_extend", r, KOKKOS_LAMBDA(int i, int j, int k) {
    const double ac = km::fabs(psi(i, j, k));
    double acc = 0, wsum = 0;
    VOIGT_UNROLL
    for (int dk = -1; dk <= 1; ++dk)
      VOIGT_UNROLL
      for (int dj = -1; dj <= 1; ++dj)
        VOIGT_UNROLL
        for (int di = -1; di <= 1; ++di) {
          const double x = di * h0, y = dj * h1, z = dk * h2, r2 = x * x + y * y + z * z;
          const double dp = ac - km::fabs(psi(i + di, j + dj, k + dk));
          const double w = (dp > 0 && r2 > 0) ? dp * dp / r2 * srcKnown(i + di, j + dj, k + dk) : 0.0;
          acc += w * src(i + di, j + dj, k + dk);
          wsum += w;
        }
    const bool was = srcKnown(i, j, k) > 0, fill = !was && ac < reach && wsum > 0;
    dst(i, j, k) = fill ? acc / wsum : src(i, j, k);
    dstKnown(i, j, k) = (was || fill) ? 1.0 : 0.0;
  });
}

// H(psi) of Eq. (4) on the cells of r (the balanced force's potential).
inline void heavisideField(const Field& psi, const Field& H, double kappa, Range3 r) {
  for_each3("heaviside_field", r,
            KOKKOS_LAMBDA(int i, int j, int k) { H(i, j, k) = smoothedHeaviside(psi(i, j, k), kappa); });
}

// rhs += coef sigma kappa_n G H (balanced) at the nodes of r; kappa_n the mean of ext over the
// node's cells with |psi| < reach (0 if none: then G H is 0 there too). H, ext, psi fresh one layer.
inline void addCapillaryForce(const Grid& g, const Field& psi, const Field& H, const Field& ext, const VecField& coef,
                              double sigma, double reach, const VecField& rhs, Range3 r) {
  GridGeom G(g);
  for_each3("capillary_force", r, KOKKOS_LAMBDA(int i, int j, int k) {
    double s = 0, n = 0;
    VOIGT_UNROLL
    for (int c = 0; c < 8; ++c) {
      const int ci = i - 1 + (c & 1), cj = j - 1 + ((c >> 1) & 1), ck = k - 1 + ((c >> 2) & 1);
      const bool in = G.cellExists3(ci, cj, ck) && km::fabs(psi(ci, cj, ck)) < reach;
      s += in ? ext(ci, cj, ck) : 0.0;
      n += in ? 1.0 : 0.0;
    }
    const double kn = n > 0 ? s / n : 0.0;
    double gr[3];
    nodeGradient(G, H, i, j, k, gr);
    VOIGT_UNROLL
    for (int d = 0; d < 3; ++d) rhs.c[d](i, j, k) += coef.c[d](i, j, k) * sigma * kn * gr[d];
  });
}

// The plain CSF for comparison (`form: csf`): rhs += coef sigma kappa_n H'(psi_n) grad psi_n at
// the nodes of r, psi_n and kappa_n the means of the node's cells, grad psi_n the node gradient.
inline void addPlainCsf(const Grid& g, const Field& psi, const Field& kap, const VecField& coef, double sigma,
                        double kappa, const VecField& rhs, Range3 r) {
  GridGeom G(g);
  for_each3("capillary_force_csf", r, KOKKOS_LAMBDA(int i, int j, int k) {
    const double pn = G.nodeMean(psi, i, j, k), kn = G.nodeMean(kap, i, j, k);
    double gr[3];
    nodeGradient(G, psi, i, j, k, gr);
    const double a = sigma * kn * smoothedDelta(pn, kappa);
    VOIGT_UNROLL
    for (int d = 0; d < 3; ++d) rhs.c[d](i, j, k) += coef.c[d](i, j, k) * a * gr[d];
  });
}

} // namespace curvature
} // namespace voigt
