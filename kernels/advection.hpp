#pragma once
// Advection kernel family: MUSCL reconstruction with a slope limiter and the
// semi-discrete central (Kurganov-Tadmor 2000) flux, the non-staggered
// descendant of Nessyahu-Tadmor (NUMERICS.md). Second order in space away from
// extrema; paired with SSP-RK2 in time by the caller.
//   dq/dt = -[div(v q) - q div_h(v)]
// The q div_h(v) term removes the compression of the dual-cell divergence,
// which the projection does not zero (it zeroes D, a different stencil), so a
// uniform q stays uniform.
#include "core/field.hpp"
#include "core/index_space.hpp"

namespace voigt {

enum class Limiter { MinMod = 0, VanLeer = 1, MC = 2, None = 3 };

KOKKOS_INLINE_FUNCTION double limitedSlope(int lim, double a, double b) {
  if (lim == 3) return 0.5 * (a + b); // unlimited central slope (Fromm)
  if (a * b <= 0) return 0;
  const double sgn = a > 0 ? 1 : -1;
  const double aa = a * sgn, bb = b * sgn;
  if (lim == 0) return sgn * (aa < bb ? aa : bb);
  if (lim == 1) return 2 * a * b / (a + b);
  const double m = 2 * (aa < bb ? aa : bb), c = 0.5 * (aa + bb);
  return sgn * (m < c ? m : c);
}

// Flux through the face between q(-1..2) positions 0|1, advecting speed a.
KOKKOS_INLINE_FUNCTION double centralFlux(int lim, double qm1, double q0, double q1, double q2, double a) {
  const double qL = q0 + 0.5 * limitedSlope(lim, q0 - qm1, q1 - q0);
  const double qR = q1 - 0.5 * limitedSlope(lim, q1 - q0, q2 - q1);
  const double aa = a < 0 ? -a : a;
  return 0.5 * a * (qL + qR) - 0.5 * aa * (qR - qL);
}

// rhs += -(advection of node field q by node velocity v) over the given nodes.
// Dual-cell face speed: mean of the two nodes' normal velocities.
inline void addNodeAdvection(const Grid& g, const Field& q, const VecField& v, const Field& rhs,
                             Range3 nodes, Limiter limiter) {
  const int lim = static_cast<int>(limiter);
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  auto vx = v.c[0], vy = v.c[1], vz = v.c[2];
  Kokkos::parallel_for(
      "node_advection", nodes.policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        double tend = 0;
        const double q0 = q(i, j, k);
        {
          const double ap = 0.5 * (vx(i, j, k) + vx(i + 1, j, k)), am = 0.5 * (vx(i - 1, j, k) + vx(i, j, k));
          const double fp = centralFlux(lim, q(i - 1, j, k), q0, q(i + 1, j, k), q(i + 2, j, k), ap);
          const double fm = centralFlux(lim, q(i - 2, j, k), q(i - 1, j, k), q0, q(i + 1, j, k), am);
          tend -= (fp - fm - q0 * (ap - am)) / h0;
        }
        {
          const double ap = 0.5 * (vy(i, j, k) + vy(i, j + 1, k)), am = 0.5 * (vy(i, j - 1, k) + vy(i, j, k));
          const double fp = centralFlux(lim, q(i, j - 1, k), q0, q(i, j + 1, k), q(i, j + 2, k), ap);
          const double fm = centralFlux(lim, q(i, j - 2, k), q(i, j - 1, k), q0, q(i, j + 1, k), am);
          tend -= (fp - fm - q0 * (ap - am)) / h1;
        }
        {
          const double ap = 0.5 * (vz(i, j, k) + vz(i, j, k + 1)), am = 0.5 * (vz(i, j, k - 1) + vz(i, j, k));
          const double fp = centralFlux(lim, q(i, j, k - 1), q0, q(i, j, k + 1), q(i, j, k + 2), ap);
          const double fm = centralFlux(lim, q(i, j, k - 2), q(i, j, k - 1), q0, q(i, j, k + 1), am);
          tend -= (fp - fm - q0 * (ap - am)) / h2;
        }
        rhs(i, j, k) += tend;
      });
}

} // namespace voigt
