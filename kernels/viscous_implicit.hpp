#pragma once
// Semi-implicit viscosity (navier_stokes.viscous: semi_implicit, issue 54), as
// effects/navier_stokes/viscous_implicit.cpp drives it. Each explicit Euler stage of the
// predictor (Eq. 7), u_e = u_o + dt R(u_o), becomes an implicit-explicit one:
//   (M - dt K) u = M u_e - dt K u_o,   i.e.   u = u_e + d,   (M - dt K) d = dt K (u_e - u_o),
// per component, with K the scalar variable-coefficient Laplacian on the 7-point node stencil
//   (K v)_n = sum over the node's edges e = (n, m) of c_e (v_m - v_n),
//   c_e = mu_e / h_e^2,   mu_e = (1/4) sum of mu over the existing cells around e,
// and M = diag(w_n rho_n) (node weight, node density): M - dt K is symmetric positive definite.
// Why any dt is stable: the explicit stress term's energy sum_cells mu/2 |L + L^T|^2 is at
// most 2 sum_cells mu |L|^2 <= 2 (-v.K v) (each cell-centre derivative of kernels/stress.hpp is
// the mean of 4 edge differences: Jensen), so dt A_V <= 2 (M + dt A_K) and each stage's
// amplification is at most 1 in the (M - dt K) norm. What it costs: dt K (u - u_e), an
// O(dt^2 nu k^2) error a step. A mode with K = V is advanced by backward Euler in each stage:
// Heun then multiplies it by (1 + 1/(1 - z)^2) / 2 a step, z = dt lambda.
#include "core/field.hpp"
#include "core/index_space.hpp"
#include "kernels/projection_ops.hpp"
#include "kernels/reductions.hpp"

namespace voigt {
namespace viscous {

// c_d(n) = mu_e / h_d^2 for the edge from node n to n + e_d, at the nodes of r (0 where no
// cell touches the edge). mu fresh one cell layer beyond the nodes' cells.
inline void edgeCoefficients(const Grid& g, const Field& mu, const VecField& c, Range3 nodes) {
  GridGeom G(g);
  const double i0 = 0.25 / (g.h[0] * g.h[0]), i1 = 0.25 / (g.h[1] * g.h[1]), i2 = 0.25 / (g.h[2] * g.h[2]);
  const Field c0 = c.c[0], c1 = c.c[1], c2 = c.c[2];
  for_each3("viscous_edge_coefficients", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
    // The edge along d from node n spans cell index n along d and n-1, n on the other axes.
    double sx = 0, sy = 0, sz = 0;
    VOIGT_UNROLL
    for (int q = 0; q < 4; ++q) {
      const int a = q & 1, b = (q >> 1) & 1;
      const bool ox = G.cellExists3(i, j - 1 + a, k - 1 + b);
      const bool oy = G.cellExists3(i - 1 + a, j, k - 1 + b);
      const bool oz = G.cellExists3(i - 1 + a, j - 1 + b, k);
      const double vx = mu(i, j - 1 + a, k - 1 + b), vy = mu(i - 1 + a, j, k - 1 + b), vz = mu(i - 1 + a, j - 1 + b, k);
      sx += ox ? vx : 0.0;
      sy += oy ? vy : 0.0;
      sz += oz ? vz : 0.0;
    }
    c0(i, j, k) = sx * i0;
    c1(i, j, k) = sy * i1;
    c2(i, j, k) = sz * i2;
  });
}

// (K v)_n: c fresh at the node and one node below it on each axis, v one node around it.
KOKKOS_FORCEINLINE_FUNCTION double edgeLaplacian(const VecField& c, const Field& v, int i, int j, int k) {
  const double vc = v(i, j, k);
  return c.c[0](i, j, k) * (v(i + 1, j, k) - vc) + c.c[0](i - 1, j, k) * (v(i - 1, j, k) - vc) +
         c.c[1](i, j, k) * (v(i, j + 1, k) - vc) + c.c[1](i, j - 1, k) * (v(i, j - 1, k) - vc) +
         c.c[2](i, j, k) * (v(i, j, k + 1) - vc) + c.c[2](i, j, k - 1) * (v(i, j, k - 1) - vc);
}

// m = w rho_n (the node's mass per cell volume) and invDiag = 1 / (m + dt sum c) on the nodes
// of r (Jacobi). rho fresh around the nodes, c as edgeLaplacian reads it.
inline void massAndDiagonal(const Grid& g, const Field& rho, const VecField& c, double dt, const Field& m,
                            const Field& invDiag, Range3 nodes) {
  GridGeom G(g);
  for_each3("viscous_mass_diagonal", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
    const double mass = G.nodeWeight(i, j, k) * G.nodeMean(rho, i, j, k);
    const double s = c.c[0](i, j, k) + c.c[0](i - 1, j, k) + c.c[1](i, j, k) + c.c[1](i, j - 1, k) +
                     c.c[2](i, j, k) + c.c[2](i, j, k - 1);
    m(i, j, k) = mass;
    invDiag(i, j, k) = 1 / (mass + dt * s);
  });
}

// q = v - v0 on the nodes of r (one stage's increment u_e - u_o).
inline void stageIncrement(const VecField& v, const VecField& v0, const VecField& q, Range3 nodes) {
  for_each3("viscous_stage_increment", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
    VOIGT_UNROLL
    for (int d = 0; d < 3; ++d) q.c[d](i, j, k) = v.c[d](i, j, k) - v0.c[d](i, j, k);
  });
}

// Heun's second stage: q = u* - (u0 + q) / 2 in place (q holds u1): half the increment of
// the Euler step u1 -> 2 u* - u0.
inline void secondStageIncrement(const VecField& u, const VecField& u0, const VecField& q, Range3 nodes) {
  for_each3("viscous_stage2_increment", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
    VOIGT_UNROLL
    for (int d = 0; d < 3; ++d) q.c[d](i, j, k) = u.c[d](i, j, k) - 0.5 * (u0.c[d](i, j, k) + q.c[d](i, j, k));
  });
}

// r = dt K q on the free components (0 where prescribed: d is 0 there), x = 0, p = r / diag;
// returns the local (r.r, r.p). q fresh one node around, c as edgeLaplacian reads it.
struct TwoSums {
  double a, b;
  template <class D, class S>
  KOKKOS_INLINE_FUNCTION static void join(D& d, const S& s) {
    d.a += s.a;
    d.b += s.b;
  }
  KOKKOS_INLINE_FUNCTION static void init(TwoSums& v) { v.a = 0, v.b = 0; }
};

inline TwoSums startResidual(const IntField& mask, const VecField& c, const Field& invDiag, double dt,
                             const VecField& q, const VecField& r, const VecField& x, const VecField& p, Range3 nodes) {
  TwoSums acc;
  reduce_rows(
      "viscous_start", nodes,
      KOKKOS_LAMBDA(int i, int j, int k, TwoSums& s) {
        const int msk = mask(i, j, k);
        const double id = invDiag(i, j, k);
        VOIGT_UNROLL
        for (int d = 0; d < 3; ++d) {
          const double v = (msk >> d) & 1 ? 0.0 : dt * edgeLaplacian(c, q.c[d], i, j, k);
          r.c[d](i, j, k) = v;
          x.c[d](i, j, k) = 0;
          p.c[d](i, j, k) = v * id;
          s.a += v * v;
          s.b += v * v * id;
        }
      },
      AccReducer<TwoSums>(acc));
  return acc;
}

// q = (M - dt K) p on the free components (0 where prescribed); returns the local p.q.
inline double applyOperator(const IntField& mask, const VecField& c, const Field& m, double dt, const VecField& p,
                            const VecField& q, Range3 nodes) {
  double pq = 0;
  reduce_rows(
      "viscous_apply", nodes,
      KOKKOS_LAMBDA(int i, int j, int k, double& s) {
        const int msk = mask(i, j, k);
        const double mass = m(i, j, k);
        VOIGT_UNROLL
        for (int d = 0; d < 3; ++d) {
          const double pv = p.c[d](i, j, k);
          const double v = (msk >> d) & 1 ? 0.0 : mass * pv - dt * edgeLaplacian(c, p.c[d], i, j, k);
          q.c[d](i, j, k) = v;
          s += pv * v;
        }
      },
      pq);
  return pq;
}

// x += alpha p, r -= alpha q; returns the local (r.r, r.z), z = r / diag.
inline TwoSums updateIterate(const Field& invDiag, double alpha, const VecField& p, const VecField& q,
                             const VecField& x, const VecField& r, Range3 nodes) {
  TwoSums acc;
  reduce_rows(
      "viscous_update", nodes,
      KOKKOS_LAMBDA(int i, int j, int k, TwoSums& s) {
        const double id = invDiag(i, j, k);
        VOIGT_UNROLL
        for (int d = 0; d < 3; ++d) {
          x.c[d](i, j, k) += alpha * p.c[d](i, j, k);
          const double rv = r.c[d](i, j, k) - alpha * q.c[d](i, j, k);
          r.c[d](i, j, k) = rv;
          s.a += rv * rv;
          s.b += rv * rv * id;
        }
      },
      AccReducer<TwoSums>(acc));
  return acc;
}

// p = r / diag + beta p.
inline void newDirection(const Field& invDiag, double beta, const VecField& r, const VecField& p, Range3 nodes) {
  for_each3("viscous_direction", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
    const double id = invDiag(i, j, k);
    VOIGT_UNROLL
    for (int d = 0; d < 3; ++d) p.c[d](i, j, k) = r.c[d](i, j, k) * id + beta * p.c[d](i, j, k);
  });
}

// u += scale x on the nodes of r (x is 0 at prescribed components).
inline void addCorrection(const VecField& x, double scale, const VecField& u, Range3 nodes) {
  for_each3("viscous_correct", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
    VOIGT_UNROLL
    for (int d = 0; d < 3; ++d) u.c[d](i, j, k) += scale * x.c[d](i, j, k);
  });
}

} // namespace viscous
} // namespace voigt
