#pragma once
// Probe sampling (io/probes.cpp): trilinear interpolation of a field at points, each given
// by its base index and weights per axis, for node fields (offset 0: the next node is +1)
// and cell fields (offset 3: the step to the second cell, idx 6-8, may be 0 at a wall).
#include "core/field.hpp"

namespace voigt {

using ProbeIdx = Kokkos::View<int* [9], MemSpace>;     // node xyz, cell xyz, cell step xyz
using ProbeWeights = Kokkos::View<double* [6], MemSpace>; // node xyz, cell xyz
using ProbeValues = Kokkos::View<double**, Kokkos::LayoutRight, MemSpace>;

// res(q, col) = v interpolated at point q (q < n); o = 0 for node fields, 3 for cell fields.
inline void sampleProbes(const Field& v, const ProbeIdx& idx, const ProbeWeights& w, int o, int n,
                         const ProbeValues& res, int col) {
  const int c = col;
  Kokkos::parallel_for("probe::sample", Kokkos::RangePolicy<ExecSpace>(0, n), KOKKOS_LAMBDA(int q) {
    const int i = idx(q, o), j = idx(q, o + 1), k = idx(q, o + 2);
    const int si = o ? idx(q, 6) : 1, sj = o ? idx(q, 7) : 1, sk = o ? idx(q, 8) : 1;
    const double wx = w(q, o), wy = w(q, o + 1), wz = w(q, o + 2);
    auto lx = [&](int jj, int kk) { return (1 - wx) * v(i, jj, kk) + wx * v(i + si, jj, kk); };
    const double z0 = (1 - wy) * lx(j, k) + wy * lx(j + sj, k);
    const double z1 = (1 - wy) * lx(j, k + sk) + wy * lx(j + sj, k + sk);
    res(q, c) = (1 - wz) * z0 + wz * z1;
  });
}

} // namespace voigt
