#pragma once
// Discrete divergence D (nodes -> cells) and gradient G (cells -> nodes) of the
// semi-staggered grid (shared/paper/NUMERICS.md, "Projection").
//   (D u)_c   = sum_d 1/(4 h_d) sum_{corners n of c} s_d(c,n) u_d(n)
//   (G p)_n,d = -1/(w_n 4 h_d) sum_{existing cells c around n} s_d(c,n) p_c
// s_d = +1 when n is the high corner of c along d, -1 when the low one.
// w_n is the node's share of a dual cell (1/2 per non-periodic boundary face it
// sits on), so G = -W^{-1} D^T and D B G is symmetric; a missing outside cell
// stands for p = 0, i.e. the outflow pressure (p is stored relative to it).
#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/index_space.hpp"

namespace voigt {

// Everything a projection kernel needs, by value (no `this` in device lambdas).
struct GridGeom {
  int n[3], c0[3], ng;
  bool per[3];
  double h[3];
  explicit GridGeom(const Grid& g) : ng(g.ng) {
    VOIGT_UNROLL
    for (int d = 0; d < 3; ++d) {
      n[d] = g.n[d];
      c0[d] = g.c0[d];
      per[d] = g.periodic[d];
      h[d] = g.h[d];
    }
  }
  KOKKOS_INLINE_FUNCTION int glob(int d, int l) const { return l - ng + c0[d]; }
  // Node weight w_n from local node indices: a factor 1/2 per axis on which the node lies on a wall.
  KOKKOS_INLINE_FUNCTION double nodeWeight(int i, int j, int k) const { return wallFactor(i, j, k, 0.5); }
  // 1 / nodeWeight, exactly (a power of two): x * nodeWeightInv == x / nodeWeight bit for
  // bit, without a division.
  KOKKOS_INLINE_FUNCTION double nodeWeightInv(int i, int j, int k) const { return wallFactor(i, j, k, 2.0); }
  // f^(the number of axes on which the node lies on a non-periodic wall).
  KOKKOS_INLINE_FUNCTION double wallFactor(int i, int j, int k, double f) const {
    const int l[3] = {i, j, k};
    double w = 1;
    VOIGT_UNROLL
    for (int d = 0; d < 3; ++d) {
      const int gi = glob(d, l[d]);
      w *= ((!per[d]) & ((gi == 0) | (gi == n[d]))) ? f : 1.0; // bitwise ops and a select: no branch
    }
    return w;
  }
  // Does the cell with local index l along axis d exist (not beyond a wall)?
  KOKKOS_INLINE_FUNCTION bool cellExists(int d, int l) const {
    const int gi = glob(d, l);
    return per[d] | ((gi >= 0) & (gi < n[d])); // bitwise, not short-circuit: no branch
  }
  KOKKOS_INLINE_FUNCTION bool cellExists3(int ci, int cj, int ck) const {
    return cellExists(0, ci) & cellExists(1, cj) & cellExists(2, ck);
  }
  // The node stencils below read all 8 cells around a node (ghost cells exist
  // in memory) and select, rather than skip, the missing ones: no branch, so
  // the loops vectorise. Adding +0.0 leaves a sum that started at +0 unchanged,
  // so the results are bit-identical to skipping.
  // Mean of a cell field over the existing cells around node (i,j,k).
  KOKKOS_INLINE_FUNCTION double nodeMean(const Field& f, int i, int j, int k) const {
    double s = 0;
    int m = 0;
    VOIGT_UNROLL
    for (int c = 0; c < 8; ++c) {
      const int ci = i - 1 + (c & 1), cj = j - 1 + ((c >> 1) & 1), ck = k - 1 + ((c >> 2) & 1);
      const bool ok = cellExists3(ci, cj, ck);
      const double v = f(ci, cj, ck);
      s += ok ? v : 0.0;
      m += ok;
    }
    return s / m;
  }
};

// div = D u over the given cells.
inline void divergence(const Grid& g, const VecField& u, const Field& div, Range3 cells) {
  GridGeom G(g);
  auto ux = u.c[0], uy = u.c[1], uz = u.c[2];
  for_each3("divergence", cells, KOKKOS_LAMBDA(int i, int j, int k) {
        double s[3] = {0, 0, 0};
        VOIGT_UNROLL
        for (int c = 0; c < 8; ++c) {
          const int a = c & 1, b = (c >> 1) & 1, e = (c >> 2) & 1;
          s[0] += (a ? 1 : -1) * ux(i + a, j + b, k + e);
          s[1] += (b ? 1 : -1) * uy(i + a, j + b, k + e);
          s[2] += (e ? 1 : -1) * uz(i + a, j + b, k + e);
        }
        div(i, j, k) = s[0] / (4 * G.h[0]) + s[1] / (4 * G.h[1]) + s[2] / (4 * G.h[2]);
      });
}

// (G p)_n,d at one node.
KOKKOS_INLINE_FUNCTION void nodeGradient(const GridGeom& G, const Field& p, int i, int j, int k,
                                         double grad[3]) {
  grad[0] = grad[1] = grad[2] = 0;
  VOIGT_UNROLL
  for (int c = 0; c < 8; ++c) {
    const int a = c & 1, b = (c >> 1) & 1, e = (c >> 2) & 1; // 1: cell on the high side of the node
    const int ci = i - 1 + a, cj = j - 1 + b, ck = k - 1 + e;
    const bool ok = G.cellExists3(ci, cj, ck);
    const double v = p(ci, cj, ck);
    grad[0] += ok ? (a ? v : -v) : 0.0;
    grad[1] += ok ? (b ? v : -v) : 0.0;
    grad[2] += ok ? (e ? v : -v) : 0.0;
  }
  const double w = G.nodeWeight(i, j, k);
  VOIGT_UNROLL
  for (int d = 0; d < 3; ++d) grad[d] /= (4 * G.h[d] * w);
}

// u_d -= scale * coef_d * (G p)_d at the given nodes. coef_d = 0 at prescribed
// components (no correction there), 1/rho elsewhere.
inline void subtractGradient(const Grid& g, const Field& p, const VecField& coef, double scale,
                             const VecField& u, Range3 nodes) {
  GridGeom G(g);
  for_each3("subtract_gradient", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
        double gr[3];
        nodeGradient(G, p, i, j, k, gr);
        VOIGT_UNROLL
        for (int d = 0; d < 3; ++d) u.c[d](i, j, k) -= scale * coef.c[d](i, j, k) * gr[d];
      });
}

// projection.variable_density: split (Dodd & Ferrante 2014). coef0 = b0 where the component
// is free (coef != 0), else 0: B0, the one-density operator's coefficients.
inline void splitCoefficients(const VecField& coef, double b0, const VecField& coef0, Range3 nodes) {
  for_each3("projection_coef_split", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
        VOIGT_UNROLL
        for (int d = 0; d < 3; ++d) coef0.c[d](i, j, k) = coef.c[d](i, j, k) != 0 ? b0 : 0.0;
      });
}

// u -= scale (B - B0) G p: the part of the pressure gradient the split takes from the
// extrapolated increment.
inline void subtractSplitGradient(const Grid& g, const Field& p, const VecField& coef, double b0, double scale,
                                  const VecField& u, Range3 nodes) {
  GridGeom G(g);
  for_each3("subtract_split_gradient", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
        double gr[3];
        nodeGradient(G, p, i, j, k, gr);
        VOIGT_UNROLL
        for (int d = 0; d < 3; ++d) {
          const double c = coef.c[d](i, j, k);
          u.c[d](i, j, k) -= scale * (c != 0 ? c - b0 : 0.0) * gr[d];
        }
      });
}

// coef_d(n) = 0 where component d is prescribed (mask bit d), else 1/rho_n (the mean
// of the existing cells around the node): B of the projection, 1/rho of Eq. (7).
inline void projectionCoefficients(const Grid& g, const Field& rho, const IntField& mask, const VecField& coef,
                                   Range3 nodes) {
  GridGeom G(g);
  for_each3("projection_coef", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
        const double inv = 1 / G.nodeMean(rho, i, j, k);
        const int m = mask(i, j, k);
        VOIGT_UNROLL
        for (int d = 0; d < 3; ++d) coef.c[d](i, j, k) = (m >> d) & 1 ? 0.0 : inv;
      });
}

// The Poisson right-hand side rhs = -div / dt (dt = 1: the initial pressure's -div, exactly).
inline void poissonRhs(const Field& div, const Field& rhs, double dt, Range3 cells) {
  for_each3("poisson_rhs", cells, KOKKOS_LAMBDA(int i, int j, int k) { rhs(i, j, k) = -div(i, j, k) / dt; });
}

// dst = src + c over the whole array, ghosts included (output: the pressure with its reference).
inline void shiftedCopy(const Field& src, const Field& dst, double c) {
  for_each3("shifted_copy", Range3{{0, 0, 0}, {int(src.extent(0)), int(src.extent(1)), int(src.extent(2))}},
            KOKKOS_LAMBDA(int i, int j, int k) { dst(i, j, k) = src(i, j, k) + c; });
}

// The CG initial guess from the pressure rate of the last steps (f1 = dp/dt of the last,
// f2 of the one before): dp = dt (2 f1 - f2), linear in time, or dt f1 (only one rate yet).
inline void extrapolateIncrement(const Field& f1, const Field& f2, const Field& dp, double dt, bool linear,
                                 Range3 cells) {
  const double a = linear ? 2 * dt : dt, b = linear ? dt : 0;
  for_each3("extrapolate_increment", cells,
            KOKKOS_LAMBDA(int i, int j, int k) { dp(i, j, k) = a * f1(i, j, k) - b * f2(i, j, k); });
}

// After a solve: f2 = f1, f1 = dp / dt.
inline void shiftPressureRates(const Field& f1, const Field& f2, const Field& dp, double dt, Range3 cells) {
  for_each3("shift_pressure_rates", cells, KOKKOS_LAMBDA(int i, int j, int k) {
    f2(i, j, k) = f1(i, j, k);
    f1(i, j, k) = dp(i, j, k) / dt;
  });
}

// dst += src (the pressure update p += dp).
inline void addTo(const Field& src, const Field& dst, Range3 cells) {
  for_each3("add_to", cells, KOKKOS_LAMBDA(int i, int j, int k) { dst(i, j, k) += src(i, j, k); });
}

} // namespace voigt
