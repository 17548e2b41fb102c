#pragma once
// Copies between a box of a 3-D grid array (local indices [b, e)) and a packed buffer:
// the halo's messages (a flat buffer, x fastest, from an offset) and the HDF5 blocks
// (a (z, y, x, component) LayoutRight buffer, one component at a time). ToBuffer picks
// the direction (a plain if: nvcc refuses a lambda's first capture inside an if constexpr);
// the index arithmetic is shared by both directions.
#include "core/field.hpp"
#include "core/index_space.hpp"

namespace voigt {

// buf(off + (i - b0) + n0 ((j - b1) + n1 (k - b2))) <-> f(i, j, k).
template <bool ToBuffer, class Array, class Flat>
void copyBoxFlat(const Array& f, const int b[3], const int e[3], const Flat& buf, long long off) {
  const int n0 = e[0] - b[0], n1 = e[1] - b[1];
  const int b0 = b[0], b1 = b[1], b2 = b[2];
  // for_each3: on host each x row is one vectorised copy (the 3-D MDRange it replaces
  // ran the halo's slabs, two cells thick, at about a third of the copy bandwidth).
  for_each3(
      ToBuffer ? "box::pack_flat" : "box::unpack_flat", Range3{{b[0], b[1], b[2]}, {e[0], e[1], e[2]}},
      KOKKOS_LAMBDA(int i, int j, int k) {
        const long long p = off + (i - b0) + n0 * ((j - b1) + 1LL * n1 * (k - b2));
        if (ToBuffer) buf(p) = f(i, j, k);
        else f(i, j, k) = buf(p);
      });
}

// buf(k - b2, j - b1, i - b0, c) <-> f(i, j, k).
template <bool ToBuffer, class Array, class Packed>
void copyBoxPacked(const Array& f, const int b[3], const int e[3], const Packed& buf, int c) {
  const int b0 = b[0], b1 = b[1], b2 = b[2];
  Kokkos::parallel_for(
      ToBuffer ? "box::pack" : "box::unpack", Policy3({b[0], b[1], b[2]}, {e[0], e[1], e[2]}),
      KOKKOS_LAMBDA(int i, int j, int k) {
        if (ToBuffer) buf(k - b2, j - b1, i - b0, c) = f(i, j, k);
        else f(i, j, k) = buf(k - b2, j - b1, i - b0, c);
      });
}

} // namespace voigt
