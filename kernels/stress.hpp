#pragma once
// Stress kernel family: velocity gradient at cell centres from the 8 corner
// nodes, tau = mu D at cells, and div(tau) back to the nodes (paper,
// "Numerical methodology": grad v at the centre of each cell from its edges).
// Elastic stress (Eq. 9/14) reuses this exact path.
#include "core/field.hpp"
#include "core/index_space.hpp"
#include "kernels/projection_ops.hpp"

namespace voigt {

// Symmetric tensor at cells: xx, yy, zz, xy, yz, zx.
struct SymTensorField {
  Field c[6];
};

// The six components as flat views (core/index_space.hpp): kernels over packed cell
// lists address a cell by its packed index, which is its memory offset.
struct FlatSym {
  FlatField c[6];
};
inline FlatSym flatSym(const SymTensorField& t) {
  FlatSym f;
  for (int c = 0; c < 6; ++c) f.c[c] = flat(t.c[c]);
  return f;
}

// L_ij = du_i/dx_j at the centre of local cell (i,j,k).
KOKKOS_INLINE_FUNCTION void cellVelocityGradient(const GridGeom& G, const VecField& u, int i, int j,
                                                 int k, double L[3][3]) {
  VOIGT_UNROLL
  for (int a = 0; a < 3; ++a)
    VOIGT_UNROLL
    for (int b = 0; b < 3; ++b) L[a][b] = 0;
  VOIGT_UNROLL
  for (int c = 0; c < 8; ++c) {
    const int a = c & 1, b = (c >> 1) & 1, e = (c >> 2) & 1;
    const int s[3] = {a ? 1 : -1, b ? 1 : -1, e ? 1 : -1};
    VOIGT_UNROLL
    for (int comp = 0; comp < 3; ++comp) {
      const double v = u.c[comp](i + a, j + b, k + e);
      VOIGT_UNROLL
      for (int dir = 0; dir < 3; ++dir) L[comp][dir] += s[dir] * v;
    }
  }
  VOIGT_UNROLL
  for (int comp = 0; comp < 3; ++comp)
    VOIGT_UNROLL
    for (int dir = 0; dir < 3; ++dir) L[comp][dir] /= 4 * G.h[dir];
}

// tau = mu (L + L^T), Eq. (10) with D = grad v + grad v^T (no 1/2).
inline void viscousStress(const Grid& g, const VecField& u, const Field& mu, const SymTensorField& tau,
                          Range3 cells) {
  GridGeom G(g);
  auto t0 = tau.c[0], t1 = tau.c[1], t2 = tau.c[2], t3 = tau.c[3], t4 = tau.c[4], t5 = tau.c[5];
  for_each3("viscous_stress", cells, KOKKOS_LAMBDA(int i, int j, int k) {
        double L[3][3];
        cellVelocityGradient(G, u, i, j, k, L);
        const double m = mu(i, j, k);
        t0(i, j, k) = 2 * m * L[0][0];
        t1(i, j, k) = 2 * m * L[1][1];
        t2(i, j, k) = 2 * m * L[2][2];
        t3(i, j, k) = m * (L[0][1] + L[1][0]);
        t4(i, j, k) = m * (L[1][2] + L[2][1]);
        t5(i, j, k) = m * (L[2][0] + L[0][2]);
      });
}

// (div tau)_i * w at node (i, j, k) (w: the node's weight, not divided out), with the same
// one-sided weighting at boundary nodes as G (projection_ops.hpp), so sum u.div(tau) =
// -sum tau:D.
KOKKOS_FORCEINLINE_FUNCTION void nodeStressDivergence(const GridGeom& G, const SymTensorField& t, int i, int j, int k,
                                                      double f[3]) {
  f[0] = f[1] = f[2] = 0;
  VOIGT_UNROLL
  for (int c = 0; c < 8; ++c) {
    const int a = c & 1, b = (c >> 1) & 1, e = (c >> 2) & 1;
    const int ci = i - 1 + a, cj = j - 1 + b, ck = k - 1 + e;
    const bool ok = G.cellExists3(ci, cj, ck); // selected, not skipped (projection_ops.hpp)
    const double sx = (a ? 1 : -1) / (4 * G.h[0]), sy = (b ? 1 : -1) / (4 * G.h[1]), sz = (e ? 1 : -1) / (4 * G.h[2]);
    const double xx = t.c[0](ci, cj, ck), yy = t.c[1](ci, cj, ck), zz = t.c[2](ci, cj, ck);
    const double xy = t.c[3](ci, cj, ck), yz = t.c[4](ci, cj, ck), zx = t.c[5](ci, cj, ck);
    f[0] += ok ? sx * xx + sy * xy + sz * zx : 0.0;
    f[1] += ok ? sx * xy + sy * yy + sz * yz : 0.0;
    f[2] += ok ? sx * zx + sy * yz + sz * zz : 0.0;
  }
}

// rhs_i += scale_i(n) * (div tau)_i at nodes.
inline void addStressDivergence(const Grid& g, const SymTensorField& tau, const VecField& scale,
                                const VecField& rhs, Range3 nodes) {
  GridGeom G(g);
  const SymTensorField t = tau;
  for_each3("stress_divergence", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
        double f[3];
        nodeStressDivergence(G, t, i, j, k, f);
        const double iw = G.nodeWeightInv(i, j, k); // "/ w" exactly, w a power of two
        VOIGT_UNROLL
        for (int d = 0; d < 3; ++d) rhs.c[d](i, j, k) += scale.c[d](i, j, k) * f[d] * iw;
      });
}

} // namespace voigt
