#pragma once
// Constant extension of a cell field across a level of psi, from psi > below
// into psi <= below (below = 0: across the interface): the discrete form of n . grad q = 0 on the fluid side, as used for
// ghost-fluid extrapolation (Aslam 2004, J. Comput. Phys. 193, 349; Peng et al.
// 1999). One Jacobi sweep sets each listed fluid-side cell to the weighted mean
// of its 26 neighbours lying further into the solid (psi_nb > psi):
//   q(c) = sum_nb w q(nb) / sum_nb w,   w = ((psi_nb - psi_c) / |x_nb - x_c|)^2
// For a signed distance psi, (psi_nb - psi_c)/|d| is the cosine between the
// neighbour's direction and the normal: neighbours along the normal dominate,
// tangential ones (cosine ~ 0) drop out. Sweep s reaches the cells s layers
// out; the values persist between steps, so the iteration continues in time.
// Cells with psi > below keep their value: the sweeps run over the fluid-side
// cells only (fluidSide), after copySolidSide has made both buffers agree on the
// others. Source and destination are distinct fields (Jacobi), so the result is
// independent of the order and of the rank decomposition; the source needs
// fresh ghosts.
#include <Kokkos_Core.hpp>

#include <cmath>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/index_space.hpp"
#include "kernels/lists.hpp"
#include "kernels/stress.hpp"

namespace voigt {
namespace extension {

// The listed cells with psi <= below (or, solid: psi > below), packed into `side`; returns
// their count.
inline int fluidSide(const Field& psi, const Grid& g, const IntList& cell, int n, double below, const IntList& side,
                     bool solid = false) {
  const FlatField fpsi = flat(psi); // the packed index is the offset: no (i, j, k) decoding
  int count = 0;
  Kokkos::parallel_scan(
      "extension_fluid_side", Kokkos::RangePolicy<ExecSpace>(0, n), KOKKOS_LAMBDA(int p, int& upd, bool final) {
        if ((fpsi(cell(p)) <= below) != solid) {
          if (final) side(upd) = cell(p);
          ++upd;
        }
      },
      count);
  return count;
}

// dst = src on the listed cells with psi > below (the cells the sweeps leave alone).
inline void copySolidSide(const Grid& g, const Field& psi, const SymTensorField& src, const SymTensorField& dst,
                          const IntList& cell, int n, double below) {
  if (n == 0) return;
  const FlatField fpsi = flat(psi);
  const FlatSym s = flatSym(src), d = flatSym(dst);
  for_listed("extension_copy_solid", cell, n, KOKKOS_LAMBDA(int, int p) {
        if (fpsi(p) > below) {
          VOIGT_UNROLL
          for (int c = 0; c < 6; ++c) d.c[c](p) = s.c[c](p);
        }
      });
}

// One sweep over the fluid-side cells `cell` (fluidSide), in the runs of consecutive
// cells `runs` (listRuns, core/index_space.hpp). Cells and neighbours are addressed in
// flat memory (core/index_space.hpp flat()): the packed index is the offset, a neighbour
// is a fixed offset from it; the weights multiply by a table of 1/|d|^2 instead of
// dividing (the weights change in the last bit, the sweep's result by rounding only: a
// common factor cancels in acc / wsum). Branch-free, so that a run vectorises: a
// neighbour that does not count adds w = 0 (a + 0 * s = a for finite s; no sum starts
// or becomes -0), the same sums in the same order as skipping it.
inline void sweep(const Grid& g, const Field& psi, const SymTensorField& src, const SymTensorField& dst,
                  const IntList& cell, int n, const IntList& runs, int nRuns, double below = 0) {
  if (n == 0) return;
  const int sj = g.ext[0], sk = g.ext[0] * g.ext[1];
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  const FlatField ps = flat(psi);
  // 1 / |x_nb - x_c|^2 for the 27 offsets (0 for the cell itself, which never has dp > 0).
  Kokkos::Array<double, 27> inv; // (a type local to the function cannot be captured by a CUDA lambda)
  for (int dk = -1; dk <= 1; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const double x = di * h0, y = dj * h1, z = dk * h2, r2 = x * x + y * y + z * z;
        inv[(dk + 1) * 9 + (dj + 1) * 3 + di + 1] = r2 > 0 ? 1 / r2 : 0;
      }
  FlatField s[6], d[6];
  for (int c = 0; c < 6; ++c) s[c] = flat(src.c[c]), d[c] = flat(dst.c[c]);
  const FlatField s0 = s[0], s1 = s[1], s2 = s[2], s3 = s[3], s4 = s[4], s5 = s[5];
  const FlatField d0 = d[0], d1 = d[1], d2 = d[2], d3 = d[3], d4 = d[4], d5 = d[5];
  for_runs("extension_sweep", cell, runs, nRuns, n, KOKKOS_LAMBDA(int, int p) {
        const double pc = ps(p);
        double a0 = 0, a1 = 0, a2 = 0, a3 = 0, a4 = 0, a5 = 0, wsum = 0;
        VOIGT_UNROLL
        for (int dk = -1; dk <= 1; ++dk)
          VOIGT_UNROLL
          for (int dj = -1; dj <= 1; ++dj)
            VOIGT_UNROLL
            for (int di = -1; di <= 1; ++di) {
              const int o = p + di + dj * sj + dk * sk;
              const double dp = ps(o) - pc;
              const double w = dp > 0 ? dp * dp * inv[(dk + 1) * 9 + (dj + 1) * 3 + di + 1] : 0.0;
              a0 += w * s0(o), a1 += w * s1(o), a2 += w * s2(o);
              a3 += w * s3(o), a4 += w * s4(o), a5 += w * s5(o);
              wsum += w;
            }
        // A local maximum of psi on the fluid side (no higher neighbour), or a listed
        // cell above `below`, keeps its value.
        const bool keep = !(pc <= below && wsum > 0);
        d0(p) = keep ? s0(p) : a0 / wsum;
        d1(p) = keep ? s1(p) : a1 / wsum;
        d2(p) = keep ? s2(p) : a2 / wsum;
        d3(p) = keep ? s3(p) : a3 / wsum;
        d4(p) = keep ? s4(p) : a4 / wsum;
        d5(p) = keep ? s5(p) : a5 / wsum;
      });
}

} // namespace extension
} // namespace voigt
