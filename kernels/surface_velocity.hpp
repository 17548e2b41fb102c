#pragma once
// The velocity a solid body's surface moves with (level_set.surface_velocity: solid).
// Eq. (1) advects psi with the grid's velocity, which across the smoothing zone blends the
// solid's and the surrounding fluid's. In the zone's fluid half (-kappa < psi < 0) the nodes
// carry the fluid's slip past the body, and with elasticity.fluid_side: extend that layer has
// no stiffness of its own to hold it: a gas jet along the surface then drags psi = 0 with it,
// and the surface wrinkles at 5-15 cells with an amplitude of ~0.3 h at every grid
// (cases/falling_block/NOTEBOOK.md, "A smooth surface"). In the continuum the fluid has no
// slip on the surface, so the surface moves with the solid: here the solid's velocity,
// extended along the normal from psi > 0 into the fluid half, as the stress is
// (kernels/extension.hpp, the same weights), moves its level set.
//   psi_n(node) = mean of psi over the node's 8 cells
//   v(n) = sum_nb w v(nb) / sum_nb w over the 26 neighbours with psi_n(nb) > psi_n(n),
//          w = ((psi_n(nb) - psi_n(n)) / |x_nb - x_n|)^2,   for lo < psi_n(n) <= 0
// Jacobi sweeps from v = u; sweep s fixes the nodes s layers out. Prescribed components
// (walls, obstacles: fix_mask) keep the grid's value, so a surface never moves into them.
#include <Kokkos_Core.hpp>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/index_space.hpp"
#include "kernels/lists.hpp"

namespace voigt {
namespace surface_velocity {

// psi at the nodes of `nodes`: the mean of the 8 cells around each (cells i-1..i per axis).
inline void nodeLevels(const Field& psi, const Field& pn, Range3 nodes) {
  for_each3("surface_velocity_node_levels", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
    pn(i, j, k) = 0.125 * (psi(i - 1, j - 1, k - 1) + psi(i, j - 1, k - 1) + psi(i - 1, j, k - 1) + psi(i, j, k - 1) +
                           psi(i - 1, j - 1, k) + psi(i, j - 1, k) + psi(i - 1, j, k) + psi(i, j, k));
  });
}

// The nodes of `nodes` with lo < psi_n <= 0, packed into `list`; returns their count.
inline int listLayer(const Grid& g, const Field& pn, double lo, Range3 nodes, const IntList& list) {
  return listCellsWhere("surface_velocity_layer", g, nodes, list, KOKKOS_LAMBDA(int i, int j, int k) {
    const double p = pn(i, j, k);
    return p <= 0 && p > lo;
  });
}

// One Jacobi sweep over the listed nodes: to = the weighted mean of from over the higher
// neighbours (header). from and to agree on every node not listed; pn needs one ghost layer.
inline void sweep(const Grid& g, const Field& pn, const IntField& mask, const VecField& from, const VecField& to,
                  const IntList& list, int n) {
  if (n == 0) return;
  const Unpack up{g.ext[0], g.ext[1]};
  Kokkos::Array<double, 27> inv; // 1 / |x_nb - x_n|^2, 0 for the node itself
  for (int dk = -1; dk <= 1; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const double x = di * g.h[0], y = dj * g.h[1], z = dk * g.h[2], r2 = x * x + y * y + z * z;
        inv[(dk + 1) * 9 + (dj + 1) * 3 + di + 1] = r2 > 0 ? 1 / r2 : 0;
      }
  const VecField f = from, t = to;
  Kokkos::parallel_for(
      "surface_velocity_sweep", Kokkos::RangePolicy<ExecSpace>(0, n), KOKKOS_LAMBDA(int q) {
        int i, j, k;
        up(list(q), i, j, k);
        const double pc = pn(i, j, k);
        double a0 = 0, a1 = 0, a2 = 0, wsum = 0;
        for (int dk = -1; dk <= 1; ++dk)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
              const double dp = pn(i + di, j + dj, k + dk) - pc;
              const double w = dp > 0 ? dp * dp * inv[(dk + 1) * 9 + (dj + 1) * 3 + di + 1] : 0.0;
              a0 += w * f.c[0](i + di, j + dj, k + dk);
              a1 += w * f.c[1](i + di, j + dj, k + dk);
              a2 += w * f.c[2](i + di, j + dj, k + dk);
              wsum += w;
            }
        const int m = mask(i, j, k);
        const bool ext = wsum > 0;
        t.c[0](i, j, k) = ext && !(m & 1) ? a0 / wsum : f.c[0](i, j, k);
        t.c[1](i, j, k) = ext && !(m & 2) ? a1 / wsum : f.c[1](i, j, k);
        t.c[2](i, j, k) = ext && !(m & 4) ? a2 / wsum : f.c[2](i, j, k);
      });
}

} // namespace surface_velocity
} // namespace voigt
