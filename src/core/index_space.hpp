#pragma once
// Local index ranges (owned cells, owned nodes, with extra ghost layers) as
// Kokkos MDRange policies. Every kernel loops over one of these.
#include "core/field.hpp"
#include "core/grid.hpp"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace voigt {

// Do kernels run on a device (CUDA, HIP, SYCL) rather than on the host? Chooses launch
// shapes and loop forms; one definition for every kernel family.
constexpr bool kOnDevice = !std::is_same<ExecSpace, Kokkos::DefaultHostExecutionSpace>::value;

struct Range3 {
  std::array<int, 3> b, e; // local [b, e)
  long long size() const { return 1LL * (e[0] - b[0]) * (e[1] - b[1]) * (e[2] - b[2]); }
  Policy3 policy() const { return Policy3({b[0], b[1], b[2]}, {e[0], e[1], e[2]}); }
  // for_each3's device policy. Tile (threads per block in x, y, z) 32x2x2: on an H200 the
  // stencil kernels ran 3-9 % faster than with Kokkos 3.4's 16x2x2, and fastest (or within
  // 0.5 %) of 8 shapes in every family (perf/portability/README.md, "Launch shapes").
  // VOIGT_DEVICE_TILE="x,y,z" overrides it, to tune another GPU (perf/portability/device-tune).
  Policy3 devicePolicy() const {
    static const std::array<int, 3> t = [] {
      std::array<int, 3> v{32, 2, 2};
      if (const char* s = std::getenv("VOIGT_DEVICE_TILE")) {
        std::array<int, 3> w{0, 0, 0};
        if (std::sscanf(s, "%d,%d,%d", &w[0], &w[1], &w[2]) == 3 && w[0] > 0 && w[1] > 0 && w[2] > 0 &&
            w[0] * w[1] * w[2] <= 1024)
          v = w;
      }
      return v;
    }();
    return Policy3({b[0], b[1], b[2]}, {e[0], e[1], e[2]}, {t[0], t[1], t[2]});
  }
};

// for_each3(name, r, f): f(i, j, k) over r. On host backends each (j, k) runs
// a plain loop over i (x fastest, LayoutLeft) that the compiler vectorises:
// 1.5-3x faster than the MDRange tiles on the stencil kernels (perf/README.md).
// Device backends keep the 3-D MDRange. Contract: f(i, j, k) writes only what
// no other point reads or writes (a pure stencil); scatter-adds and atomics
// stay in Kokkos::parallel_for.
// The i-loop must see the whole body to vectorise it: flatten inlines f (large
// stencil bodies are otherwise left as calls, which "clobber memory").
#if defined(__GNUC__) && !defined(__CUDACC__) && !defined(__HIPCC__)
#define VOIGT_FLATTEN __attribute__((flatten))
#else
#define VOIGT_FLATTEN
#endif
// Before a stencil's short inner loops (8 corners, 3 axes): unrolled, they
// leave the i-loop a straight line the vectoriser accepts.
#if defined(__GNUC__) && !defined(__clang__) && !defined(__CUDACC__) && !defined(__HIPCC__)
#define VOIGT_UNROLL _Pragma("GCC unroll 8")
#else
#define VOIGT_UNROLL
#endif

// How many pieces a host loop over n items is cut into (a few per thread, for balance).
inline long long hostChunks(long long n) {
  const long long most = 8LL * ExecSpace().concurrency();
  return n < 0 ? 0 : n < most ? n : most;
}

template <class F>
inline void for_each3(const char* name, const Range3& r, const F& f) {
#if defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL)
  if constexpr (kOnDevice) {
    Kokkos::parallel_for(name, r.devicePolicy(), f);
    return;
  }
#endif
  // The (j, k) rows as one flat range (j fastest): a 2-D MDRange with 1x1 tiles paid
  // ~20 ns per row, most of the work on faces two cells thick (ghost fills).
  // Chunks of rows, each with its own copy of f, for the reason given at for_runs below.
  const int b0 = r.b[0], e0 = r.e[0], b1 = r.b[1], b2 = r.b[2], nj = r.e[1] - r.b[1];
  const long long rows = 1LL * nj * (r.e[2] - r.b[2]);
  if (rows <= 0 || e0 <= b0) return;
  const long long chunks = hostChunks(rows);
  Kokkos::parallel_for(
      name, Kokkos::RangePolicy<ExecSpace, Kokkos::IndexType<long long>>(0, chunks), KOKKOS_LAMBDA(long long c) VOIGT_FLATTEN {
        const F fl = f;
        const long long q1 = rows * (c + 1) / chunks;
        for (long long q = rows * c / chunks; q < q1; ++q) {
          const int j = b1 + int(q % nj), k = b2 + int(q / nj);
          // No loop-carried dependence (the contract above): ivdep lets the
          // compiler vectorise without run-time alias checks between views.
#pragma GCC ivdep
          for (int i = b0; i < e0; ++i) fl(i, j, k);
        }
      });
}

// for_listed(name, list, n, f): f(q, p) for q < n, p = list(q), over a packed cell list
// (IntList below), whose entries are memory offsets (flat()). Same contract as for_each3.
template <class L, class F>
inline void for_listed(const char* name, const L& list, int n, const F& f) {
  Kokkos::parallel_for(
      name, Kokkos::RangePolicy<ExecSpace>(0, n), KOKKOS_LAMBDA(int q) VOIGT_FLATTEN { f(q, list(q)); });
}

// r grown by n layers on every side.
inline Range3 grown(Range3 r, int n) {
  for (int d = 0; d < 3; ++d) {
    r.b[d] -= n;
    r.e[d] += n;
  }
  return r;
}

// The cells in both a and b; empty (e = b) if they do not meet.
inline Range3 intersect(Range3 a, const Range3& b) {
  bool empty = false;
  for (int d = 0; d < 3; ++d) {
    a.b[d] = a.b[d] > b.b[d] ? a.b[d] : b.b[d];
    a.e[d] = a.e[d] < b.e[d] ? a.e[d] : b.e[d];
    empty = empty || a.e[d] <= a.b[d];
  }
  if (empty)
    for (int d = 0; d < 3; ++d) a.e[d] = a.b[d];
  return a;
}

// A kernel's range: `full`, or with a box given (several level sets: where a level set can be
// active, effects/level_set/level_set.hpp) the box grown by `grow` layers and clipped to full.
inline Range3 within(const Range3* box, int grow, const Range3& full) {
  if (!box) return full;
  for (int d = 0; d < 3; ++d)
    if (box->e[d] <= box->b[d]) return intersect(*box, *box); // empty stays empty
  return intersect(grown(*box, grow), full);
}

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

// for_runs(name, list, start, nRuns, n, f): f(q, p) for q < n, p = list(q), as
// for_listed, but on host backends each run of consecutive cells (listRuns, kernels/reductions.hpp) is a plain
// loop over p = list(q0) + m that the compiler vectorises (contiguous loads instead of a
// gather per access). Same contract as for_each3. Device backends ignore the runs.
template <class F>
inline void for_runs(const char* name, const IntList& list, const IntList& start, int nRuns, int n, const F& f) {
#if defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL)
  if constexpr (kOnDevice) {
    Kokkos::parallel_for(
        name, Kokkos::RangePolicy<ExecSpace>(0, n), KOKKOS_LAMBDA(int q) { f(q, list(q)); });
    return;
  }
#endif
  // Chunks of runs, each with its own copy of f: in an OpenMP region the closure is shared
  // memory reached through a pointer, and GCC would not vectorise the run loop over it (the
  // extension sweep ran scalar, 2.2x slower at one OpenMP thread than on Serial). Copies made
  // inside a parallel region do not touch the views' reference counts.
  const int chunks = int(hostChunks(nRuns));
  Kokkos::parallel_for(
      name, Kokkos::RangePolicy<ExecSpace>(0, chunks), KOKKOS_LAMBDA(int c) VOIGT_FLATTEN {
        const F fl = f;
        const int r1 = int((long long)nRuns * (c + 1) / chunks);
        for (int r = int((long long)nRuns * c / chunks); r < r1; ++r) {
          const int q0 = start(r), len = (r + 1 < nRuns ? start(r + 1) : n) - q0, p0 = list(q0);
#pragma GCC ivdep
          for (int m = 0; m < len; ++m) fl(q0 + m, p0 + m);
        }
      });
}

struct Unpack {
  int e0, e1;
  KOKKOS_INLINE_FUNCTION void operator()(int p, int& i, int& j, int& k) const {
    i = p % e0;
    const int t = p / e0;
    j = t % e1;
    k = t / e1;
  }
};

// The same memory as a 1-D view: f(i, j, k) = flat(f)(i + e0 (j + e1 k)), the packed
// index itself. Band kernels over packed lists address a cell and its neighbours by
// fixed offsets (+-1, +-e0, +-e0 e1) instead of unpacking i, j, k (two integer
// divisions) and rebuilding each neighbour's index. Fields are unpadded LayoutLeft
// views over Grid::ext (FieldStore::allocate); flat() checks it.
using FlatField = Kokkos::View<double*, MemSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>;
inline FlatField flat(const Field& f) {
  if (f.stride(0) != 1 || f.stride(1) != f.extent(0) || f.stride(2) != f.extent(0) * f.extent(1))
    throw std::logic_error("flat(): field '" + f.label() + "' is padded");
  return FlatField(f.data(), f.size());
}

} // namespace voigt
