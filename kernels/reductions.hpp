#pragma once
// Global reductions over owned index ranges (Kokkos reduce + MPI_Allreduce).
#include <mpi.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "core/field.hpp"
#include "core/host_access.hpp"
#include "core/index_space.hpp"
#include "kernels/projection_ops.hpp"

namespace voigt {

// A Kokkos reducer for a plain struct Acc of running values: Acc::init(v) sets the
// identity, Acc::join(d, s) merges s into d (a template, for Kokkos's volatile overloads).
template <class Acc>
struct AccReducer {
  using reducer = AccReducer;
  using value_type = Acc;
  using result_view_type = Kokkos::View<value_type, Kokkos::HostSpace, Kokkos::MemoryUnmanaged>;
  result_view_type value;
  AccReducer(value_type& v) : value(&v) {}
  KOKKOS_INLINE_FUNCTION void join(value_type& d, const value_type& s) const { Acc::join(d, s); }
  KOKKOS_INLINE_FUNCTION void join(volatile value_type& d, const volatile value_type& s) const { Acc::join(d, s); }
  KOKKOS_INLINE_FUNCTION void init(value_type& v) const { Acc::init(v); }
  KOKKOS_INLINE_FUNCTION value_type& reference() const { return *value.data(); }
  result_view_type view() const { return value; }
  KOKKOS_INLINE_FUNCTION bool references_scalar() const { return true; }
};

// reduce_rows(name, r, f, result): Kokkos::parallel_reduce of f(i, j, k, acc) over r, as
// with a 3-D MDRange, but on a host backend the (j, k) rows as one flat range with a
// plain i loop inside (for_each3's layout): the MDRange's tiles cost more than the work of
// the light diagnostics (kinetic energy, phase measures, solid moments). The sum order is
// then x fastest, y, z. result: a double& or a reducer (AccReducer).
template <class Value, class F, class Result>
inline void reduceRowsImpl(const char* name, const Range3& r, const F& f, const Result& result) {
#if defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL)
  if constexpr (kOnDevice) {
    Kokkos::parallel_reduce(name, r.devicePolicy(), f, result);
    return;
  }
#endif
  const int b0 = r.b[0], e0 = r.e[0], b1 = r.b[1], b2 = r.b[2], nj = r.e[1] - r.b[1];
  const long long rows = e0 > b0 ? 1LL * nj * (r.e[2] - r.b[2]) : 0;
  Kokkos::parallel_reduce(
      name, Kokkos::RangePolicy<ExecSpace, Kokkos::IndexType<long long>>(0, rows > 0 ? rows : 0),
      KOKKOS_LAMBDA(long long q, Value& a) {
        const int j = b1 + int(q % nj), k = b2 + int(q / nj);
        for (int i = b0; i < e0; ++i) f(i, j, k, a);
      },
      result);
}
template <class F>
inline void reduce_rows(const char* name, const Range3& r, const F& f, double& result) {
  reduceRowsImpl<double>(name, r, f, Kokkos::Sum<double>(result));
}
template <class F, class Acc>
inline void reduce_rows(const char* name, const Range3& r, const F& f, const AccReducer<Acc>& result) {
  reduceRowsImpl<Acc>(name, r, f, result);
}

// |v| as its IEEE bits (sign cleared): for non-negative doubles the bit patterns order
// as the values do, and every NaN lies above +inf. So an integer max gives max |v|
// exactly and lets a NaN win, and it vectorises (a floating max reduction does not
// without -ffinite-math-only).
KOKKOS_INLINE_FUNCTION long long absBits(double v) {
  long long b;
  __builtin_memcpy(&b, &v, sizeof b);
  return b & 0x7fffffffffffffffLL;
}
constexpr long long kInfBits = 0x7ff0000000000000LL;

KOKKOS_INLINE_FUNCTION long long maxAbsBitsInRow(const double* row, int b0, int e0, long long m) {
#pragma GCC ivdep
  for (int i = b0; i < e0; ++i) {
    const long long a = absBits(row[i]);
    m = a > m ? a : m;
  }
  return m;
}

// max |f| over r on this rank; NaN if any value is NaN (a blow-up must show).
inline double localMaxAbs(const Field& f, Range3 r) {
  long long m = 0;
#if defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL)
  if constexpr (kOnDevice) {
    Kokkos::parallel_reduce(
        "max_abs", r.policy(),
        KOKKOS_LAMBDA(int i, int j, int k, long long& acc) {
          const long long a = absBits(f(i, j, k));
          acc = a > acc ? a : acc;
        },
        Kokkos::Max<long long>(m));
  } else
#endif
  {
    // Host: the (j, k) rows as one flat range, as for_each3 (index_space.hpp).
    const int b0 = r.b[0], e0 = r.e[0], b1 = r.b[1], b2 = r.b[2], nj = r.e[1] - r.b[1];
    const long long rows = 1LL * nj * (r.e[2] - r.b[2]);
    if (rows <= 0 || e0 <= b0) return 0;
    Kokkos::parallel_reduce(
        "max_abs", Kokkos::RangePolicy<ExecSpace, Kokkos::IndexType<long long>>(0, rows),
        KOKKOS_LAMBDA(long long q, long long& acc) {
          acc = maxAbsBitsInRow(&f(0, b1 + int(q % nj), b2 + int(q / nj)), b0, e0, acc);
        },
        Kokkos::Max<long long>(m));
  }
  if (m > kInfBits) return NAN;
  if (m < 0) return 0; // an empty range: the reducer's identity
  double v;
  __builtin_memcpy(&v, &m, sizeof v);
  return v;
}

inline double globalMaxAbs(const Grid& g, const Field& f, Range3 r) {
  const double m = localMaxAbs(f, r);
  double out = m;
  MPI_Allreduce(&m, &out, 1, MPI_DOUBLE, MPI_MAX, g.comm);
  return out;
}

// Non-finite values in row[b0, e0), host form. Integer, which vectorises (SSE2 has
// 64-bit add, and, shift but no 64-bit compare): adding 1 to the exponent field carries
// into the sign bit exactly when the exponent is all ones (inf or NaN).
KOKKOS_INLINE_FUNCTION long long nonFiniteInRow(const double* row, int b0, int e0) {
  unsigned long long c = 0;
#pragma GCC ivdep
  for (int i = b0; i < e0; ++i) {
    unsigned long long bits;
    __builtin_memcpy(&bits, row + i, sizeof bits);
    c += ((bits & 0x7ff0000000000000ULL) + 0x0010000000000000ULL) >> 63;
  }
  return static_cast<long long>(c);
}

// Arrays of one grid's extents, each with its own range (owned cells or nodes): the
// fields the blow-up check scans every step, as device tables, so that one reduction
// counts them all (one launch and one fence a step, not one per component).
struct ArrayBoxes {
  Kokkos::View<std::uintptr_t*, MemSpace> ptr; // data pointers
  Kokkos::View<int* [6], MemSpace> box;        // b0, e0, b1, e1, b2, e2
  std::vector<const double*> host;             // the pointers, to see when an array changes
  int n = 0;
  long long sj = 0, sk = 0;                    // the strides of j and k (LayoutLeft, shared)
  int lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};    // the union of the boxes
};

inline ArrayBoxes arrayBoxes(const std::vector<Field>& fs, const std::vector<Range3>& rs) {
  ArrayBoxes a;
  a.n = int(fs.size());
  a.ptr = Kokkos::View<std::uintptr_t*, MemSpace>("nonfinite::ptr", a.n);
  a.box = Kokkos::View<int* [6], MemSpace>("nonfinite::box", a.n);
  auto hp = hostMirror(a.ptr);
  auto hb = hostMirror(a.box);
  for (int q = 0; q < a.n; ++q) {
    if (q == 0) a.sj = fs[0].stride(1), a.sk = fs[0].stride(2);
    if (fs[q].stride(0) != 1 || (long long)fs[q].stride(1) != a.sj || (long long)fs[q].stride(2) != a.sk)
      throw std::logic_error("arrayBoxes: arrays of different extents");
    a.host.push_back(fs[q].data());
    hp(q) = reinterpret_cast<std::uintptr_t>(fs[q].data());
    for (int d = 0; d < 3; ++d) {
      hb(q, 2 * d) = rs[q].b[d], hb(q, 2 * d + 1) = rs[q].e[d];
      a.lo[d] = q ? std::min(a.lo[d], rs[q].b[d]) : rs[q].b[d];
      a.hi[d] = q ? std::max(a.hi[d], rs[q].e[d]) : rs[q].e[d];
    }
  }
  toDevice(a.ptr, hp, "setup");
  toDevice(a.box, hb, "setup");
  return a;
}

// Non-finite values (NaN, +-Inf) in all of a's arrays over their boxes, on this rank:
// countNonFinite's test (integer, vectorised i-loop on host) in one reduction.
inline long long countNonFinite(const ArrayBoxes& a) {
  long long n = 0;
  if (a.n == 0) return 0;
  const auto ptr = a.ptr;
  const auto box = a.box;
  const long long sj = a.sj, sk = a.sk;
#if defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL)
  if constexpr (kOnDevice) {
    using Policy4 = Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<4, Kokkos::Iterate::Left, Kokkos::Iterate::Left>>;
    Kokkos::parallel_reduce(
        "count_non_finite_all", Policy4({a.lo[0], a.lo[1], a.lo[2], 0}, {a.hi[0], a.hi[1], a.hi[2], a.n}),
        KOKKOS_LAMBDA(int i, int j, int k, int q, long long& acc) {
          if (i < box(q, 0) || i >= box(q, 1) || j < box(q, 2) || j >= box(q, 3) || k < box(q, 4) || k >= box(q, 5))
            return;
          const double v = reinterpret_cast<const double*>(ptr(q))[i + sj * j + sk * k];
          acc += !(v - v == 0);
        },
        n);
    return n;
  }
#endif
  // Host: every array's (j, k) rows as one flat range (j fastest, array slowest), as
  // for_each3 (index_space.hpp): a 3-D MDRange of 1x1x1 tiles paid ~20 ns a row.
  const int j0 = a.lo[1], nj = a.hi[1] - a.lo[1], k0 = a.lo[2], nk = a.hi[2] - a.lo[2];
  const long long rows = 1LL * nj * nk * a.n;
  if (nj <= 0 || nk <= 0) return 0;
  Kokkos::parallel_reduce(
      "count_non_finite_all", Kokkos::RangePolicy<ExecSpace, Kokkos::IndexType<long long>>(0, rows),
      KOKKOS_LAMBDA(long long r, long long& acc) {
        const int j = j0 + int(r % nj), k = k0 + int((r / nj) % nk), q = int(r / (1LL * nj * nk));
        if (j < box(q, 2) || j >= box(q, 3) || k < box(q, 4) || k >= box(q, 5)) return;
        acc += nonFiniteInRow(reinterpret_cast<const double*>(ptr(q)) + sj * j + sk * k, box(q, 0), box(q, 1));
      },
      n);
  return n;
}

// Non-finite values (NaN, +-Inf) of one field over r on this rank (the tables of a
// one-array ArrayBoxes: for occasional use, not every step).
inline long long countNonFinite(const Field& f, Range3 r) { return countNonFinite(arrayBoxes({f}, {r})); }

// Owned nodes whose three components are all prescribed (mask == 7), on this rank.
inline long long countFullyFixed(const IntField& mask, Range3 nodes) {
  long long n = 0;
  Kokkos::parallel_reduce(
      "count_fixed", nodes.policy(),
      KOKKOS_LAMBDA(int i, int j, int k, long long& acc) { acc += mask(i, j, k) == 7 ? 1 : 0; }, n);
  return n;
}

// Local max of the kinematic viscosity mu / rho over the range (the viscous dt limit).
inline double maxKinematicViscosity(const Field& mu, const Field& rho, Range3 cells) {
  double m = 0;
  Kokkos::parallel_reduce(
      "max_nu", cells.policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
        const double nu = mu(i, j, k) / rho(i, j, k);
        if (nu > acc) acc = nu;
      },
      Kokkos::Max<double>(m));
  return m;
}

// Global linear index of local (i, j, k): i + nx (j + ny k) in global indices, nx = n0 + 1,
// ny = n1 + 1 (the node numbering, which also orders cells): the same point, and the same
// (k, j, i) order, whatever the decomposition.
struct GlobalLinear {
  long long nx, ny;
  int ng, c0, c1, c2;
  explicit GlobalLinear(const Grid& g)
      : nx(g.n[0] + 1), ny(g.n[1] + 1), ng(g.ng), c0(g.c0[0]), c1(g.c0[1]), c2(g.c0[2]) {}
  KOKKOS_INLINE_FUNCTION long long operator()(int i, int j, int k) const {
    return (i - ng + c0) + nx * ((j - ng + c1) + ny * (long long)(k - ng + c2));
  }
};

// GlobalLinear index of the first non-finite value of f in r on this rank, or LLONG_MAX.
inline long long firstNonFinite(const Grid& g, const Field& f, Range3 r) {
  const GlobalLinear lin(g);
  long long first = LLONG_MAX;
  Kokkos::parallel_reduce(
      "find_non_finite", r.policy(),
      KOKKOS_LAMBDA(int i, int j, int k, long long& m) {
        const double v = f(i, j, k);
        if (!(v - v == 0) && lin(i, j, k) < m) m = lin(i, j, k); // NaN or +-Inf
      },
      Kokkos::Min<long long>(first));
  return first;
}

// The advective rate sum_d |u_d| / h_d at a node.
KOKKOS_INLINE_FUNCTION double nodeRate(const VecField& u, double ih0, double ih1, double ih2, int i, int j, int k) {
  return km::fabs(u.c[0](i, j, k)) * ih0 + km::fabs(u.c[1](i, j, k)) * ih1 + km::fabs(u.c[2](i, j, k)) * ih2;
}

// Local max of nodeRate over r (the fastest node, for a dt-collapse message).
inline double maxNodeRate(const Grid& g, const VecField& u, Range3 r) {
  const double ih0 = 1 / g.h[0], ih1 = 1 / g.h[1], ih2 = 1 / g.h[2];
  double m = 0;
  Kokkos::parallel_reduce(
      "fastest_node_max", r.policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
        const double s = nodeRate(u, ih0, ih1, ih2, i, j, k);
        if (s > acc) acc = s;
      },
      Kokkos::Max<double>(m));
  return m;
}

// GlobalLinear index of the first node of r where nodeRate equals rate, or LLONG_MAX.
inline long long firstNodeWithRate(const Grid& g, const VecField& u, Range3 r, double rate) {
  const double ih0 = 1 / g.h[0], ih1 = 1 / g.h[1], ih2 = 1 / g.h[2];
  const GlobalLinear lin(g);
  long long first = LLONG_MAX;
  Kokkos::parallel_reduce(
      "fastest_node_where", r.policy(),
      KOKKOS_LAMBDA(int i, int j, int k, long long& acc) {
        if (nodeRate(u, ih0, ih1, ih2, i, j, k) == rate && lin(i, j, k) < acc) acc = lin(i, j, k);
      },
      Kokkos::Min<long long>(first));
  return first;
}

inline double globalSum(const Grid& g, double local) {
  double out = 0;
  MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_SUM, g.comm);
  return out;
}

// Mean |f| over r on all ranks (cells of equal volume): the divergence's L1 norm, the
// measure OpenFOAM's "sum local" continuity error takes times dt (perf/peers).
inline double globalMeanAbs(const Grid& g, const Field& f, Range3 r) {
  double local[2] = {0, double(r.e[0] - r.b[0]) * (r.e[1] - r.b[1]) * (r.e[2] - r.b[2])};
  reduce_rows(
      "sum_abs", r, KOKKOS_LAMBDA(int i, int j, int k, double& acc) { acc += km::fabs(f(i, j, k)); },
      local[0]);
  double out[2] = {0, 0};
  MPI_Allreduce(local, out, 2, MPI_DOUBLE, MPI_SUM, g.comm);
  return out[1] > 0 ? out[0] / out[1] : 0;
}

// Kinetic energy 0.5 sum rho_n |u_n|^2 w_n dV over owned nodes (dual-cell volumes).
inline double kineticEnergy(const Grid& g, const VecField& u, const Field& rhoCell) {
  GridGeom G(g);
  const double vol = g.cellVolume();
  double e = 0;
  reduce_rows(
      "kinetic_energy", nodeRange(g),
      KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
        const double rho = G.nodeMean(rhoCell, i, j, k);
        const double u2 = u.c[0](i, j, k) * u.c[0](i, j, k) + u.c[1](i, j, k) * u.c[1](i, j, k) +
                          u.c[2](i, j, k) * u.c[2](i, j, k);
        acc += 0.5 * rho * u2 * G.nodeWeight(i, j, k) * vol;
      },
      e);
  return globalSum(g, e);
}

} // namespace voigt
