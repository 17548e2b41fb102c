#pragma once
// Local index ranges (owned cells, owned nodes, with extra ghost layers) as
// Kokkos MDRange policies. Every kernel loops over one of these.
#include "core/field.hpp"
#include "core/grid.hpp"

namespace voigt {

struct Range3 {
  std::array<int, 3> b, e; // local [b, e)
  long long size() const { return 1LL * (e[0] - b[0]) * (e[1] - b[1]) * (e[2] - b[2]); }
  Policy3 policy() const { return Policy3({b[0], b[1], b[2]}, {e[0], e[1], e[2]}); }
};

// Owned cells grown by `grow` layers into the ghosts.
inline Range3 cellRange(const Grid& g, int grow = 0) {
  Range3 r;
  for (int d = 0; d < 3; ++d) {
    r.b[d] = g.ng - grow;
    r.e[d] = g.ng + g.ln[d] + grow;
  }
  return r;
}

// Owned nodes grown by `grow` layers.
inline Range3 nodeRange(const Grid& g, int grow = 0) {
  Range3 r;
  for (int d = 0; d < 3; ++d) {
    r.b[d] = g.ng - grow;
    r.e[d] = g.local(d, g.nodeHi(d)) + grow;
  }
  return r;
}

// Packed lists of cells (narrow bands: reinit, elastic stress): local index
// p = i + e0 (j + e1 k) with e = Grid::ext, looped over by a 1-D RangePolicy.
using IntList = Kokkos::View<int*, MemSpace>;
struct Unpack {
  int e0, e1;
  KOKKOS_INLINE_FUNCTION void operator()(int p, int& i, int& j, int& k) const {
    i = p % e0;
    const int t = p / e0;
    j = t % e1;
    k = t / e1;
  }
};

} // namespace voigt
