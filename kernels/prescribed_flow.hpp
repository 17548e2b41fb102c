#pragma once
// Kinematic velocity fields in closed form (the prescribed_flow effect,
// effects/prescribed_flow.cpp, which documents the flows): evaluation at a point, the
// field at the nodes, and the largest advective rate sum_d |v_d| / h_d over the nodes.
#include <cmath>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/index_space.hpp"

namespace voigt {

struct FlowParams {
  int type = 0; // 0 rotation, 1 single_vortex, 2 uniform
  double c[3] = {0, 0, 0}, w[3] = {0, 0, 0}, v[3] = {0, 0, 0};
  double period = 1, lo[2] = {0, 0}, len[2] = {1, 1};
};

KOKKOS_INLINE_FUNCTION void flowAt(const FlowParams& p, const double x[3], double t, double out[3]) {
  if (p.type == 0) {
    const double r[3] = {x[0] - p.c[0], x[1] - p.c[1], x[2] - p.c[2]};
    out[0] = p.w[1] * r[2] - p.w[2] * r[1];
    out[1] = p.w[2] * r[0] - p.w[0] * r[2];
    out[2] = p.w[0] * r[1] - p.w[1] * r[0];
  } else if (p.type == 1) {
    const double xs = (x[0] - p.lo[0]) / p.len[0], ys = (x[1] - p.lo[1]) / p.len[1];
    const double f = km::cos(M_PI * t / p.period);
    const double sx = km::sin(M_PI * xs), sy = km::sin(M_PI * ys);
    out[0] = -2 * sx * sx * sy * km::cos(M_PI * ys) * f * p.len[0];
    out[1] = 2 * sy * sy * sx * km::cos(M_PI * xs) * f * p.len[1];
    out[2] = 0;
  } else {
    out[0] = p.v[0];
    out[1] = p.v[1];
    out[2] = p.v[2];
  }
}

// u = v(x, t) at every node of the array, ghosts included.
inline void fillPrescribedFlow(const Grid& g, const FlowParams& p, double t, const VecField& u) {
  const double lo0 = g.lo[0], lo1 = g.lo[1], lo2 = g.lo[2], h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  const int ng = g.ng, c0 = g.c0[0], c1 = g.c0[1], c2 = g.c0[2];
  Kokkos::parallel_for(
      "prescribed_flow", Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}), KOKKOS_LAMBDA(int i, int j, int k) {
        const double x[3] = {lo0 + (i - ng + c0) * h0, lo1 + (j - ng + c1) * h1, lo2 + (k - ng + c2) * h2};
        double v[3];
        flowAt(p, x, t, v);
        for (int d = 0; d < 3; ++d) u.c[d](i, j, k) = v[d];
      });
}

// Local max over the owned nodes of sum_d |v_d(x, 0)| / h_d (|cos| <= 1: the largest over all t).
inline double prescribedFlowRate(const Grid& g, const FlowParams& p) {
  const double lo0 = g.lo[0], lo1 = g.lo[1], lo2 = g.lo[2], h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  const int ng = g.ng, c0 = g.c0[0], c1 = g.c0[1], c2 = g.c0[2];
  double inv = 0;
  Kokkos::parallel_reduce(
      "prescribed_cfl", nodeRange(g).policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& m) {
        const double x[3] = {lo0 + (i - ng + c0) * h0, lo1 + (j - ng + c1) * h1, lo2 + (k - ng + c2) * h2};
        double v[3];
        flowAt(p, x, 0.0, v);
        const double s = km::fabs(v[0]) / h0 + km::fabs(v[1]) / h1 + km::fabs(v[2]) / h2;
        if (s > m) m = s;
      },
      Kokkos::Max<double>(inv));
  return inv;
}

} // namespace voigt
