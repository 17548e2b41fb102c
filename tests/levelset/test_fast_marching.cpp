// Fast Marching signed distance (levelset/fast_marching.hpp, Sethian 1996/1999):
// sphere and box from implicit functions that are not distances, sign and
// interface cells, the cap, a periodic wrap, anisotropic cells, 1 vs 2 ranks.
// Errors are in units of h (max over axes) and printed on rank 0; each bound
// says what it was measured against. Every run is repeated on MPI_COMM_SELF
// (the whole grid on each rank) and must agree bit for bit with the
// decomposed run: the result does not depend on the rank count.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "core/index_space.hpp"
#include "levelset/fast_marching.hpp"

using namespace voigt;

namespace {
using Fn = std::function<double(double, double, double)>;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kGhostMark = 12345.0;

bool rank0() {
  int r;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r == 0;
}

struct Geo {
  std::array<int, 3> n;
  std::array<double, 3> lo{0, 0, 0}, hi{1, 1, 1};
  std::array<bool, 3> per{false, false, false};
};

// Global result (every rank holds all cells, x fastest) and the geometry.
struct Result {
  Geo s;
  std::array<double, 3> h;
  std::vector<double> v, v0; // after and before
  FastMarchingStats st;
  bool ghostsKept = true;
  double hmax() const { return std::max({h[0], h[1], h[2]}); }
  double x(int d, int i) const { return s.lo[d] + (i + 0.5) * h[d]; }
  size_t at(int i, int j, int k) const { return i + size_t(s.n[0]) * (j + size_t(s.n[1]) * k); }
  template <class F>
  void cells(F f) const {
    for (int k = 0; k < s.n[2]; ++k)
      for (int j = 0; j < s.n[1]; ++j)
        for (int i = 0; i < s.n[0]; ++i) f(i, j, k, at(i, j, k));
  }
};

// psi = fn at owned cell centres (ghosts marked), fastMarching, gather.
Result march(MPI_Comm comm, const Geo& s, const Fn& fn, double cap = kInf) {
  Grid g = makeGrid(comm, s.n, s.lo, s.hi, s.per);
  Field psi("psi", g.ext[0], g.ext[1], g.ext[2]);
  auto hp = Kokkos::create_mirror_view(psi);
  Kokkos::deep_copy(hp, kGhostMark);
  const Range3 own = cellRange(g);
  auto c = [&](int d, int l) { return g.lo[d] + (g.global(d, l) + 0.5) * g.h[d]; };
  for (int k = own.b[2]; k < own.e[2]; ++k)
    for (int j = own.b[1]; j < own.e[1]; ++j)
      for (int i = own.b[0]; i < own.e[0]; ++i) hp(i, j, k) = fn(c(0, i), c(1, j), c(2, k));
  Kokkos::deep_copy(psi, hp);

  Result r{s, g.h, std::vector<double>(size_t(g.cellsGlobal()), 0.0), {}, {}, true};
  r.v0 = r.v;
  for (int k = own.b[2]; k < own.e[2]; ++k)
    for (int j = own.b[1]; j < own.e[1]; ++j)
      for (int i = own.b[0]; i < own.e[0]; ++i) r.v0[r.at(g.global(0, i), g.global(1, j), g.global(2, k))] = hp(i, j, k);
  r.st = fastMarching(g, psi, cap);
  Kokkos::deep_copy(hp, psi);
  for (int k = 0; k < g.ext[2]; ++k)
    for (int j = 0; j < g.ext[1]; ++j)
      for (int i = 0; i < g.ext[0]; ++i) {
        const bool isOwn = i >= own.b[0] && i < own.e[0] && j >= own.b[1] && j < own.e[1] && k >= own.b[2] && k < own.e[2];
        if (isOwn) r.v[r.at(g.global(0, i), g.global(1, j), g.global(2, k))] = hp(i, j, k);
        else if (hp(i, j, k) != kGhostMark) r.ghostsKept = false;
      }
  int kept = r.ghostsKept;
  MPI_Allreduce(MPI_IN_PLACE, &kept, 1, MPI_INT, MPI_LAND, comm);
  r.ghostsKept = kept;
  MPI_Allreduce(MPI_IN_PLACE, r.v.data(), int(r.v.size()), MPI_DOUBLE, MPI_SUM, comm);
  MPI_Allreduce(MPI_IN_PLACE, r.v0.data(), int(r.v0.size()), MPI_DOUBLE, MPI_SUM, comm);
  freeGrid(g);
  return r;
}

// Decomposed run, checked against the same grid marched whole on each rank.
Result marchChecked(const Geo& s, const Fn& fn, double cap = kInf) {
  Result r = march(MPI_COMM_WORLD, s, fn, cap);
  const Result serial = march(MPI_COMM_SELF, s, fn, cap);
  EXPECT_TRUE(r.v == serial.v) << "result depends on the decomposition";
  EXPECT_EQ(r.st.initialCells, serial.st.initialCells);
  EXPECT_EQ(r.st.acceptedCells, serial.st.acceptedCells);
  EXPECT_TRUE(r.ghostsKept) << "ghost cells were written";
  return r;
}

// Max |psi - exact| / hmax over the cells where keep(x, exact) holds.
using Keep = std::function<bool(const double*, double)>;
double maxError(const Result& r, const Fn& exact, const Keep& keep = nullptr) {
  double m = 0;
  r.cells([&](int i, int j, int k, size_t c) {
    const double x[3] = {r.x(0, i), r.x(1, j), r.x(2, k)}, ex = exact(x[0], x[1], x[2]);
    if (!keep || keep(x, ex)) m = std::max(m, std::fabs(r.v[c] - ex) / r.hmax());
  });
  return m;
}
// {within 3 cells (hmax) of the interface, everywhere}.
std::array<double, 2> errors(const Result& r, const Fn& exact) {
  const double band = 3 * r.hmax();
  return {maxError(r, exact, [&](const double*, double ex) { return std::fabs(ex) < band; }), maxError(r, exact)};
}

constexpr double kR = 0.3, kC[3] = {0.53, 0.46, 0.51};
double r2(double x, double y, double z) {
  return (x - kC[0]) * (x - kC[0]) + (y - kC[1]) * (y - kC[1]) + (z - kC[2]) * (z - kC[2]);
}
double sphere0(double x, double y, double z) { return kR * kR - r2(x, y, z); } // |grad| = 2r, not a distance
double sphereExact(double x, double y, double z) { return kR - std::sqrt(r2(x, y, z)); }

// Box [c - half, c + half]; f = max_a(|x_a - c_a| - half_a) is > 0 outside.
constexpr double kBc[3] = {0.5, 0.48, 0.51}, kHalf[3] = {0.22, 0.15, 0.28};
double boxF(double x, double y, double z) {
  const double p[3] = {x, y, z};
  double f = -kInf;
  for (int a = 0; a < 3; ++a) f = std::max(f, std::fabs(p[a] - kBc[a]) - kHalf[a]);
  return f;
}
// Input scaled by 3 inside, 0.2 outside: a kinked, non-distance implicit function.
double box0(double x, double y, double z) {
  const double f = boxF(x, y, z);
  return f < 0 ? -3 * f : -0.2 * f;
}
double boxExact(double x, double y, double z) {
  const double p[3] = {x, y, z};
  double out = 0;
  for (int a = 0; a < 3; ++a) out += std::pow(std::max(std::fabs(p[a] - kBc[a]) - kHalf[a], 0.0), 2);
  const double f = boxF(x, y, z);
  return f < 0 ? -f : -std::sqrt(out); // positive inside
}

// Smooth positive factor (0.55 .. 1.8): the input keeps the kinks of f but
// has no slope jump across the interface.
double distortion(double x, double y, double z) {
  return std::exp(0.35 * std::sin(3 * x + 0.3) * std::cos(2 * y - 0.2) + 0.25 * std::sin(2.5 * z + 0.7));
}
double boxSmooth0(double x, double y, double z) { return -boxF(x, y, z) * distortion(x, y, z); }

void report(const char* what, const std::array<double, 2>& e, const Result& r) {
  if (rank0())
    printf("fast marching %-18s n=%dx%dx%d: max error near %.4f h, everywhere %.4f h (init %lld, marched %lld, %.3f s)\n",
           what, r.s.n[0], r.s.n[1], r.s.n[2], e[0], e[1], r.st.initialCells, r.st.acceptedCells, r.st.seconds);
}
double order(double eCoarse, double eFine) { return std::log2(eCoarse / eFine); } // errors in length units
} // namespace

// Sphere R = 0.3 from R^2 - |x-c|^2 (|grad| = 2r, not a distance). Measured
// max error / h, second-order march (the default) | first-order march:
//   32^3: near 0.021 | 0.164, everywhere 0.275 | 0.841, r > 0.1: 0.091 | 0.601
//   64^3: near 0.005 | 0.081, everywhere 0.285 | 1.075, r > 0.1: 0.057 | 0.623
// (secant-only initial estimate, second-order march: near 0.042, 0.024.)
// Near the interface the error converges at order 3.2 (curvature-aware initial
// estimate, second-order stencils over a few cells). "Everywhere" is set by the
// centre, the apex of R - r, where the inward front's curvature ~ 1/(cells from
// the centre) keeps the error O(h) at any resolution; with r > 0.1 the order is
// 1.67 (Sethian's scheme is usually ~1.5 in the max norm). Bounds: 1.5x measured;
// orders asserted > 2.2 and > 1.3.
TEST(FastMarching, SphereAndConvergence) {
  const Result r32 = marchChecked({{32, 32, 32}}, sphere0);
  const Result r64 = march(MPI_COMM_WORLD, {{64, 64, 64}}, sphere0);
  const auto e32 = errors(r32, sphereExact), e64 = errors(r64, sphereExact);
  const Keep away = [](const double* x, double) { return std::sqrt(r2(x[0], x[1], x[2])) > 0.1; };
  const double a32 = maxError(r32, sphereExact, away), a64 = maxError(r64, sphereExact, away);
  report("sphere", e32, r32);
  report("sphere", e64, r64);
  const double pNear = order(e32[0] / 32, e64[0] / 64), pAway = order(a32 / 32, a64 / 64);
  if (rank0()) printf("  r > 0.1: %.4f h, %.4f h; orders: near %.2f, r > 0.1 %.2f\n", a32, a64, pNear, pAway);
  EXPECT_EQ(r32.st.initialCells + r32.st.acceptedCells, 32 * 32 * 32); // every cell reached
  EXPECT_LT(e32[0], 0.032);
  EXPECT_LT(e64[0], 0.007);
  EXPECT_LT(e32[1], 0.42);
  EXPECT_LT(e64[1], 0.42);
  EXPECT_LT(a64, 0.086);
  EXPECT_GT(pNear, 2.2);
  EXPECT_GT(pAway, 1.3);
}

// No bias near the interface, which integral measures (the phase volume of
// H(psi), Eq. 4) would see: mean signed error over cells within 2h, for the
// implicit input and for the exact distance as input. Measured at 32^3:
// -0.0002 h and +0.0001 h (secant-only initial estimate: -0.011 h, -0.015 h,
// i.e. a 0.3 % volume error at R = 9.6 cells). Bound 0.003 h.
TEST(FastMarching, SphereNoBias) {
  for (const Fn& fn : {Fn(sphereExact), Fn(sphere0)}) {
    const Result r = march(MPI_COMM_WORLD, {{32, 32, 32}}, fn);
    double sum = 0, cnt = 0;
    r.cells([&](int i, int j, int k, size_t c) {
      const double ex = sphereExact(r.x(0, i), r.x(1, j), r.x(2, k));
      if (std::fabs(ex) < 2 * r.hmax()) sum += (r.v[c] - ex) / r.hmax(), cnt += 1;
    });
    if (rank0()) printf("  sphere mean signed error within 2h: %.5f h over %.0f cells\n", sum / cnt, cnt);
    EXPECT_LT(std::fabs(sum / cnt), 0.003);
  }
}

// Box: the exact distance is non-smooth at edges and corners, so the error is
// O(h) there whatever the input. Measured max error / h at 32^3 and 64^3
// (second-order march | first-order march):
//  * input 3f inside, 0.2f outside: 0.625, 0.716 | 1.70, 2.00. The input's
//    slope jumps 15x across the interface, so no estimate from cell values can
//    place the crossing well: linear interpolation puts it 0.44h off for a cell
//    half a cell from a face. Bound 1.05h.
//  * input f times a smooth factor 0.55..1.8 (no slope jump): 0.908, 0.762 |
//    1.88, 2.23, at outer corners: a cell diagonal to an edge is updated as if
//    the front were planar (0.5h too far in 2D, more at a corner). Bound 1.4h.
//    Outside, facing a face and >= 1.5/32 from its edges: 0.041 (1.5 cells),
//    0.0002 (3 cells): inner-edge cells (whose estimate assumes one smooth
//    surface) leak through the second-order stencil across the interface; bound 0.062h.
//  * the exact signed distance as input: the march makes it worse at the edges
//    (the same outer-corner error): 0.918h at 32^3 (bound 1.4h); its mean signed error
//    within 2h is -0.048h, a -1 % change of the smoothed volume at kappa = 2h.
// All first order in length units (error / h about constant): ratio > 1.5 asserted.
TEST(FastMarching, Box) {
  const Keep facing = [](const double* x, double ex) {
    int out = 0;
    for (int a = 0; a < 3; ++a) out += std::fabs(x[a] - kBc[a]) > kHalf[a] - 1.5 / 32;
    return ex < 0 && out == 1;
  };
  std::array<double, 2> jump[2], smooth[2];
  for (int l = 0; l < 2; ++l) {
    const int n = 32 << l;
    const Result r = l == 0 ? marchChecked({{n, n, n}}, box0) : march(MPI_COMM_WORLD, {{n, n, n}}, box0);
    const Result q = l == 0 ? marchChecked({{n, n, n}}, boxSmooth0) : march(MPI_COMM_WORLD, {{n, n, n}}, boxSmooth0);
    jump[l] = errors(r, boxExact);
    smooth[l] = errors(q, boxExact);
    const double face = maxError(q, boxExact, facing);
    report("box 3/0.2 jump", jump[l], r);
    report("box smooth factor", smooth[l], q);
    if (rank0()) printf("  smooth factor, outside facing a face: %.4f h\n", face);
    EXPECT_LT(jump[l][1], 1.05) << n;
    EXPECT_LT(smooth[l][1], 1.4) << n;
    EXPECT_LT(face, 0.062) << n;
  }
  EXPECT_GT(jump[0][1] / 32 / (jump[1][1] / 64), 1.5);
  EXPECT_GT(smooth[0][1] / 32 / (smooth[1][1] / 64), 1.5);
  const Result e = marchChecked({{32, 32, 32}}, boxExact);
  report("box exact input", errors(e, boxExact), e);
  EXPECT_LT(errors(e, boxExact)[1], 1.4);
}

// Sign kept everywhere. Interface cells (psi0 changes sign to a face
// neighbour) are initialised and frozen: 0 < |psi| <= 2 x their nearest axis
// crossing min_a h_a psi0 / (psi0 - psi0_nb), the range in which the
// curvature-aware estimate is accepted. Measured max |psi| / crossing: 1.05
// (sphere: the secant crossing of R^2 - r^2 is slightly short) and 1.86 (box
// with the 15x slope jump, where no estimate is good).
TEST(FastMarching, SignAndInterfaceCells) {
  for (const Fn& fn : {Fn(sphere0), Fn(box0)}) {
    const Result r = marchChecked({{32, 32, 32}}, fn);
    long long flipped = 0, iface = 0, outside = 0;
    double ratio = 0;
    r.cells([&](int i, int j, int k, size_t c) {
      const double p = r.v0[c], q = r.v[c];
      if ((p > 0) != (q > 0) || (p < 0) != (q < 0)) ++flipped;
      double dmin = kInf;
      for (int a = 0; a < 3; ++a)
        for (int s = -1; s <= 1; s += 2) {
          int m[3] = {i, j, k};
          m[a] += s;
          if (m[a] < 0 || m[a] >= r.s.n[a]) continue;
          const double pn = r.v0[r.at(m[0], m[1], m[2])];
          if ((pn > 0) != (p > 0)) dmin = std::min(dmin, r.h[a] * p / (p - pn));
        }
      if (dmin == kInf) return;
      ++iface;
      ratio = std::max(ratio, std::fabs(q) / dmin);
      if (!(std::fabs(q) > 0 && std::fabs(q) <= 2 * dmin * (1 + 1e-12))) ++outside;
    });
    if (rank0()) printf("  max |psi| / nearest axis crossing over %lld interface cells: %.4f\n", iface, ratio);
    EXPECT_EQ(flipped, 0);
    EXPECT_EQ(iface, r.st.initialCells);
    EXPECT_EQ(outside, 0);
  }
}

// Cap: the capped result is the uncapped one clipped at +-cap, bit for bit
// (the march accepts cells in increasing order, so stopping early changes no
// accepted value); everything farther gets exactly +-cap.
TEST(FastMarching, Cap) {
  const Geo s{{32, 32, 32}};
  const double cap = 3.5 / 32;
  const Result full = march(MPI_COMM_WORLD, s, sphere0), r = marchChecked(s, sphere0, cap);
  long long wrong = 0, atCap = 0, over = 0;
  r.cells([&](int, int, int, size_t c) {
    const double want = std::copysign(std::min(std::fabs(full.v[c]), cap), full.v[c]);
    wrong += r.v[c] != want;
    atCap += std::fabs(r.v[c]) == cap;
    over += std::fabs(r.v[c]) > cap;
  });
  if (rank0()) printf("  cap %.4f: %lld cells at the cap, %lld marched\n", cap, atCap, r.st.acceptedCells);
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(over, 0);
  EXPECT_GT(atCap, 20000); // most of the box is farther than 3.5 cells
  EXPECT_LT(r.st.acceptedCells, full.st.acceptedCells / 4);
}

// Periodic x: psi0 = -cos(2 pi (x - 0.33)) < 0 in the slab (0.08, 0.58). A cell
// at x = 0.95 is 0.13 from the plane x = 0.08 across the wrap (0.37 from
// x = 0.58 without it). Measured 5e-4 h (the estimated crossing of a cosine);
// bound 0.01 h (ignoring the wrap would be off by up to 9.6 h here). On 2 ranks
// the wrap also crosses ranks.
double pdist(double x, double a) {
  const double d = std::fabs(x - a) - std::floor(std::fabs(x - a));
  return std::min(d, 1 - d);
}
TEST(FastMarching, PeriodicWrap) {
  Geo s{{40, 8, 8}};
  s.per = {true, false, false};
  const Result r = marchChecked(s, [](double x, double, double) { return -std::cos(2 * M_PI * (x - 0.33)); });
  const auto e = errors(r, [](double x, double, double) { return pdist(x, 0.33) - 0.25; });
  report("periodic slab", e, r);
  EXPECT_LT(e[1], 0.01);
}

// Anisotropic cells hx = 2 hy = 2 hz (24 x 48 x 48) on the sphere. Measured
// (error / hx): near 0.022, everywhere 0.192 (first-order march: 0.156, 0.579).
// Bound 1.5x measured.
TEST(FastMarching, AnisotropicSphere) {
  const Result r = marchChecked({{24, 48, 48}}, sphere0);
  const auto e = errors(r, sphereExact);
  report("sphere hx=2hy=2hz", e, r);
  EXPECT_LT(e[0], 0.033);
  EXPECT_LT(e[1], 0.29);
}

// No interface: nothing to measure from. Infinite cap leaves psi as it was;
// a finite cap sets every cell to sign * cap.
TEST(FastMarching, NoInterface) {
  const Geo s{{8, 8, 8}};
  const Fn pos = [](double x, double y, double z) { return 1 + x + y * z; };
  const Result r = marchChecked(s, pos), c = marchChecked(s, pos, 0.25);
  EXPECT_TRUE(r.v == r.v0);
  EXPECT_EQ(r.st.initialCells + r.st.acceptedCells, 0);
  EXPECT_TRUE(std::all_of(c.v.begin(), c.v.end(), [](double v) { return v == 0.25; }));
}
