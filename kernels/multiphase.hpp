#pragma once
// Several level sets (level_sets:): a fluid's level set under a solid's. Where a solid body
// lies, the fluid's psi is not seen (the solid is blended over it, kernels/levelset.hpp
// blendOver), so it is extended there from the fluid around the body: a body under water
// then holds water beneath its smoothing zone, not the air it carried in, and no film of
// the background is left between the body and the liquid (cases/ball_pool/README.md).
// The fluid's volume is what the later level sets leave uncovered, INT H_i PROD_{j>i} (1 - H_j).
#include "core/field.hpp"
#include "core/index_space.hpp"
#include "kernels/heaviside.hpp"
#include "kernels/levelset.hpp"
#include "kernels/lists.hpp"

namespace voigt::multiphase {

// cover = (first ? 1 : cover) x (1 - H(psi)) over r.
inline void cover(const Field& psi, double kappa, const Field& c, bool first, Range3 r) {
  for_each3("multiphase_cover", r, KOKKOS_LAMBDA(int i, int j, int k) {
        const double keep = 1 - smoothedHeaviside(psi(i, j, k), kappa);
        c(i, j, k) = first ? keep : c(i, j, k) * keep;
      });
}

// Owned cells: INT H(psi) cover dv and INT H'(psi) cover dv (the covered volume and its
// derivative under a uniform shift of psi: the volume correction's Newton step).
inline void localCoveredVolume(const Grid& g, const Field& psi, double kappa, const Field& c, double& vol,
                               double& dvol, const Range3* box = nullptr) {
  const double dv = g.cellVolume();
  double v = 0, d = 0;
  Kokkos::parallel_reduce(
      "multiphase_covered_volume", within(box, 0, cellRange(g)).policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& va, double& da) {
        const double p = psi(i, j, k), w = c(i, j, k);
        va += smoothedHeaviside(p, kappa) * w;
        da += smoothedDelta(p, kappa) * w;
      },
      v, d);
  vol = v * dv;
  dvol = d * dv;
}

// The box of the cells of r with psi > threshold (empty, b >= e, if none): the extension's
// sweeps run on it, so a body costs its own neighbourhood, not the grid.
inline Range3 boxWhere(const Field& psi, double threshold, Range3 r) {
  ListBoxAcc acc; // kernels/lists.hpp
  reduce_rows(
      "multiphase_box", r,
      KOKKOS_LAMBDA(int i, int j, int k, ListBoxAcc& a) {
        if (!(psi(i, j, k) > threshold)) return;
        const int x[3] = {i, j, k};
        for (int d = 0; d < 3; ++d) {
          if (x[d] < a.lo[d]) a.lo[d] = x[d];
          if (x[d] > a.hi[d]) a.hi[d] = x[d];
        }
      },
      AccReducer<ListBoxAcc>(acc));
  Range3 b{{0, 0, 0}, {0, 0, 0}};
  if (acc.lo[0] > acc.hi[0]) return b;
  for (int d = 0; d < 3; ++d) b.b[d] = acc.lo[d], b.e[d] = acc.hi[d] + 1;
  return b;
}

// The cells to fill under a body: -outside < psiBody <= inside. known = 1 where the
// fluid's value is a source (psiBody <= -outside), 0 elsewhere.
inline void markSources(const Field& body, double outside, const Field& known, Range3 r) {
  for_each3("multiphase_mark", r, KOKKOS_LAMBDA(int i, int j, int k) {
        known(i, j, k) = body(i, j, k) <= -outside ? 1.0 : 0.0;
      });
}

// One Jacobi sweep of the extension along the body's normals: a cell to fill that is not yet
// known takes the mean of its known face neighbours farther out (smaller psiBody), each
// weighted by how much farther (so the neighbour along the normal counts most). Reads
// (fluid, known), writes (outF, outK) on r.
inline void extendSweep(const Field& body, double outside, double inside, const Field& fluid, const Field& known,
                        const Field& outF, const Field& outK, Range3 r) {
  for_each3("multiphase_extend", r, KOKKOS_LAMBDA(int i, int j, int k) {
        const double pb = body(i, j, k);
        outF(i, j, k) = fluid(i, j, k);
        outK(i, j, k) = known(i, j, k);
        if (known(i, j, k) > 0 || !(pb > -outside && pb <= inside)) return;
        double sw = 0, sv = 0;
        const int off[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
        for (int q = 0; q < 6; ++q) {
          const int a = i + off[q][0], b = j + off[q][1], c = k + off[q][2];
          const double w = pb - body(a, b, c);
          if (known(a, b, c) > 0 && w > 0) sw += w, sv += w * fluid(a, b, c);
        }
        if (sw > 0) {
          outF(i, j, k) = sv / sw;
          outK(i, j, k) = 1;
        }
      });
}

// A body's initial velocity (level_sets[i].velocity): u <- u + H (v - u) at the nodes, H of the
// mean of the 8 cells around each node (the blend's weight there); the first projection
// makes the whole field divergence-free.
inline void setBodyVelocity(const Field& psi, double kappa, double vx, double vy, double vz, const VecField& u,
                            Range3 nodes) {
  for_each3("multiphase_body_velocity", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
        double p = 0;
        for (int c = 0; c < 8; ++c) p += psi(i - 1 + (c & 1), j - 1 + ((c >> 1) & 1), k - 1 + (c >> 2));
        const double H = smoothedHeaviside(0.125 * p, kappa);
        u.c[0](i, j, k) += H * (vx - u.c[0](i, j, k));
        u.c[1](i, j, k) += H * (vy - u.c[1](i, j, k));
        u.c[2](i, j, k) += H * (vz - u.c[2](i, j, k));
      });
}

} // namespace voigt::multiphase
