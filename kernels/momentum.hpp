#pragma once
// Momentum predictor kernel family, Eq. (7) with SSP-RK2 (Heun), as
// effects/navier_stokes/momentum.cpp drives it:
//   u1 = u^n + dt R(u^n);   u* = (u^n + u1 + dt R(u1)) / 2
// and, where the density varies, the conservative form (node density r, r0 = rho^n):
//   r1 = r0 + dt Rr(r0, u^n),          u1 = r0 (u^n + dt R(u^n)) / r1
//   r* = (r0 + r1 + dt Rr(r1, u1))/2,  u* = (r0 u^n + r1 u1 + dt r0 R(u1)) / (2 r*)
// Each stage update re-imposes the prescribed components (mask bit d: u_d = val_d)
// in the same pass, and stage 1 stores u^n for stage 2: one sweep over the nodes
// where there were three (copy, update, applyFixed), with the same operations in the
// same order (bit-identical to the separate passes).
#include "core/field.hpp"
#include "core/index_space.hpp"
#include "kernels/projection_ops.hpp"
#include "kernels/stress.hpp"

namespace voigt {

// r0 = rho^n at the nodes: the mean of the cells around each node, as the projection's 1/rho.
inline void nodeDensity(const Grid& g, const Field& rho, const Field& r0, Range3 nodes) {
  GridGeom G(g);
  for_each3("node_density", nodes, KOKKOS_LAMBDA(int i, int j, int k) { r0(i, j, k) = G.nodeMean(rho, i, j, k); });
}

// Non-conservative SSP-RK2 stage, prescribed components re-imposed:
//   stage 1: u0 = u; u += dt rhs;   stage 2: u = (u0 + u + dt rhs) / 2.
template <int Stage>
inline void momentumStage(const VecField& u, const VecField& u0, const VecField& rhs, double dt, const IntField& mask,
                          const VecField& val, Range3 nodes) {
  for_each3(Stage == 1 ? "rk2_stage1" : "rk2_stage2", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
    const int m = mask(i, j, k);
    VOIGT_UNROLL
    for (int c = 0; c < 3; ++c) {
      const double un = u.c[c](i, j, k);
      double s;
      if (Stage == 1) { // not constexpr: nvcc refuses a first capture inside one
        u0.c[c](i, j, k) = un;
        s = un + dt * rhs.c[c](i, j, k);
      } else {
        s = 0.5 * (u0.c[c](i, j, k) + un + dt * rhs.c[c](i, j, k));
      }
      u.c[c](i, j, k) = (m >> c) & 1 ? val.c[c](i, j, k) : s;
    }
  });
}
inline void momentumStage1(const VecField& u, const VecField& u0, const VecField& rhs, double dt,
                           const IntField& mask, const VecField& val, Range3 nodes) {
  momentumStage<1>(u, u0, rhs, dt, mask, val, nodes);
}
inline void momentumStage2(const VecField& u, const VecField& u0, const VecField& rhs, double dt,
                           const IntField& mask, const VecField& val, Range3 nodes) {
  momentumStage<2>(u, u0, rhs, dt, mask, val, nodes);
}

// Conservative stage 1: r1 = r0 + dt rr; u0 = u; u = r0 (u + dt rhs) / r1. A prescribed
// node keeps its value, so its momentum is r u with the prescribed u: no special case.
inline void momentumStage1Conservative(const Field& r0, const Field& rr, const Field& r1, const VecField& u,
                                       const VecField& u0, const VecField& rhs, double dt, const IntField& mask,
                                       const VecField& val, Range3 nodes) {
  for_each3("rk2_stage1_conservative", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
    const double a = r0(i, j, k), b = a + dt * rr(i, j, k);
    r1(i, j, k) = b;
    const int m = mask(i, j, k);
    VOIGT_UNROLL
    for (int c = 0; c < 3; ++c) {
      const double un = u.c[c](i, j, k);
      u0.c[c](i, j, k) = un;
      u.c[c](i, j, k) = (m >> c) & 1 ? val.c[c](i, j, k) : a * (un + dt * rhs.c[c](i, j, k)) / b;
    }
  });
}

// Conservative stage 2: u = (r0 u0 + r1 u + dt r0 rhs) / (2 r*), r* = (r0 + r1 + dt rr) / 2.
inline void momentumStage2Conservative(const Field& r0, const Field& r1, const Field& rr, const VecField& u,
                                       const VecField& u0, const VecField& rhs, double dt, const IntField& mask,
                                       const VecField& val, Range3 nodes) {
  for_each3("rk2_stage2_conservative", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
    const double a = r0(i, j, k), b = r1(i, j, k), r = 0.5 * (a + b + dt * rr(i, j, k));
    const int m = mask(i, j, k);
    VOIGT_UNROLL
    for (int c = 0; c < 3; ++c) {
      const double s = (a * u0.c[c](i, j, k) + b * u.c[c](i, j, k) + dt * a * rhs.c[c](i, j, k)) / (2 * r);
      u.c[c](i, j, k) = (m >> c) & 1 ? val.c[c](i, j, k) : s;
    }
  });
}

// The predictor's stress and pressure terms in one pass, as addStressDivergence then
// subtractGradient (same operations in the same order, one read and write of rhs):
//   rhs_d += coef_d (div tau)_d,   rhs_d -= pscale coef_d (G p)_d.
inline void addStressMinusGradient(const Grid& g, const SymTensorField& tau, const Field& p, const VecField& coef,
                                   double pscale, const VecField& rhs, Range3 nodes) {
  GridGeom G(g);
  const SymTensorField t = tau;
  for_each3("stress_divergence_gradient", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
        double f[3], gr[3];
        nodeStressDivergence(G, t, i, j, k, f);
        const double iw = G.nodeWeightInv(i, j, k); // "/ w" exactly, w a power of two
        nodeGradient(G, p, i, j, k, gr);
        VOIGT_UNROLL
        for (int d = 0; d < 3; ++d) {
          const double c = coef.c[d](i, j, k);
          double r = rhs.c[d](i, j, k);
          r += c * f[d] * iw;
          r -= pscale * c * gr[d];
          rhs.c[d](i, j, k) = r;
        }
      });
}

// rhs += g, a uniform body force per unit mass (the gravity effect's Forces task).
inline void addBodyForce(const VecField& rhs, double g0, double g1, double g2, Range3 nodes) {
  for_each3("gravity", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
    rhs.c[0](i, j, k) += g0;
    rhs.c[1](i, j, k) += g1;
    rhs.c[2](i, j, k) += g2;
  });
}

// One value per column of cells along an axis (the owned cells of the other two axes).
using Plane = Kokkos::View<double**, Kokkos::LayoutLeft, MemSpace>;

// Balanced gravity (effects/gravity.cpp): the hydrostatic pressure of the cell density
// along axis a, integrated from the top (the end that g_a points away from) down, one
// sequential loop per column, s = |g_a| h_a:
//   p_h(top) = s rho(top) / 2                          at the domain's top (p = 0 on that face)
//   p_h(top) = top + s (rho(top) + rho(above)) / 2     below another rank (top: its last p_h)
//   p_h(c)   = p_h(above) + s (rho(c) + rho(above)) / 2
// so that nodeGradient's G p_h equals nodeMean's rho_n times g_a (to round-off) wherever rho
// varies only along a, at walls and outflow faces too (projection_ops.hpp). Then
// p += p_h - ph and ph = p_h: the stored pressure keeps its hydrostatic part current and
// the solve finds only the departure from it. last receives the bottom layer's p_h.
inline void hydrostaticShift(const Grid& g, int a, double ga, const Field& rho, const Field& ph, const Field& p,
                             const Plane& top, bool atTop, const Plane& last) {
  const int b = a == 0 ? 1 : 0, c = a == 2 ? 1 : 2, ng = g.ng, n = g.ln[a];
  const bool down = ga < 0; // the top is the high end
  const double s = (ga < 0 ? -ga : ga) * g.h[a];
  using P2 = Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2, Kokkos::Iterate::Left, Kokkos::Iterate::Left>>;
  Kokkos::parallel_for(
      "hydrostatic_shift", P2({0, 0}, {g.ln[b], g.ln[c]}), KOKKOS_LAMBDA(int qb, int qc) {
        int ix[3];
        ix[b] = qb + ng;
        ix[c] = qc + ng;
        const int step = down ? -1 : 1;
        int j = down ? ng + n - 1 : ng;
        ix[a] = j - step;
        double rAbove = rho(ix[0], ix[1], ix[2]);
        ix[a] = j;
        double r = rho(ix[0], ix[1], ix[2]);
        double v = atTop ? 0.5 * s * r : top(qb, qc) + 0.5 * s * (r + rAbove);
        for (int m = 0; m < n; ++m) {
          if (m > 0) {
            rAbove = r;
            ix[a] = j;
            r = rho(ix[0], ix[1], ix[2]);
            v = v + 0.5 * s * (r + rAbove);
          }
          p(ix[0], ix[1], ix[2]) += v - ph(ix[0], ix[1], ix[2]);
          ph(ix[0], ix[1], ix[2]) = v;
          j += step;
        }
        last(qb, qc) = v;
      });
}

// Initial pressure (momentum.cpp): the velocity rate of the conservative form,
// acc -= u rr / r0, and zero acceleration at prescribed components.
inline void initialVelocityRate(const VecField& acc, const VecField& u, const Field& rr, const Field& r0,
                                bool conservative, const IntField& mask, Range3 nodes) {
  for_each3("initial_velocity_rate", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
    const int m = mask(i, j, k);
    VOIGT_UNROLL
    for (int d = 0; d < 3; ++d) {
      double a = acc.c[d](i, j, k);
      if (conservative) a -= u.c[d](i, j, k) * rr(i, j, k) / r0(i, j, k);
      acc.c[d](i, j, k) = (m >> d) & 1 ? 0.0 : a;
    }
  });
}

} // namespace voigt
