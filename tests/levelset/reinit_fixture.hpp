#pragma once
// Fields, analytic shapes and error measures shared by the re-initialisation
// tests (test_reinit.cpp only).
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "core/halo.hpp"
#include "core/index_space.hpp"
#include "kernels/heaviside.hpp"
#include "levelset/reinit.hpp"
#include "scene/reader.hpp"
#include "support/flow.hpp"

using namespace voigt;

namespace {
using Fn = std::function<double(double, double, double)>;

bool rank0() {
  int r;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r == 0;
}

// Owned cells at their global index, summed over ranks (so every rank has all).
struct Global {
  Grid g; // copy of the geometry (n, lo, h, periodic); comm unused
  std::vector<double> v;
  int wrap(int d, int i) const { return g.periodic[d] ? (i % g.n[d] + g.n[d]) % g.n[d] : i; }
  bool valid(int d, int i) const { return g.periodic[d] || (i >= 0 && i < g.n[d]); }
  double operator()(int i, int j, int k) const {
    return v[wrap(0, i) + size_t(g.n[0]) * (wrap(1, j) + size_t(g.n[1]) * wrap(2, k))];
  }
  double x(int d, int i) const { return g.lo[d] + (i + 0.5) * g.h[d]; }
  double hmin() const { return std::min({g.h[0], g.h[1], g.h[2]}); }
  template <class F>
  void cells(F f) const {
    for (int k = 0; k < g.n[2]; ++k)
      for (int j = 0; j < g.n[1]; ++j)
        for (int i = 0; i < g.n[0]; ++i) f(i, j, k);
  }
  // Zero crossings between face neighbours by linear interpolation: f(point).
  template <class F>
  void crossings(F f) const {
    cells([&](int i, int j, int k) {
      for (int d = 0; d < 3; ++d) {
        const int l[3] = {i, j, k};
        if (!valid(d, l[d] + 1)) continue;
        const double p = (*this)(i, j, k), q = (*this)(i + (d == 0), j + (d == 1), k + (d == 2));
        if (p * q >= 0) continue;
        double pt[3] = {x(0, i), x(1, j), x(2, k)};
        pt[d] += g.h[d] * p / (p - q);
        f(pt);
      }
    });
  }
  // Integral of the smoothed H(psi) of Eq. (4).
  double volumeH(double kappa) const {
    double s = 0;
    for (double p : v) s += smoothedHeaviside(p, kappa);
    return s * g.cellVolume();
  }
  // Lengths of the psi > 0 runs along lines of the non-periodic axis d
  // (crossings by linear interpolation): {sum of lengths * h_a h_b, longest}.
  std::array<double, 2> runs(int d) const {
    const int a = (d + 1) % 3, b = (d + 2) % 3;
    double vol = 0, longest = 0;
    for (int q = 0; q < g.n[b]; ++q)
      for (int p = 0; p < g.n[a]; ++p) {
        auto at = [&](int s) {
          int l[3];
          l[d] = s, l[a] = p, l[b] = q;
          return (*this)(l[0], l[1], l[2]);
        };
        double start = 0;
        for (int s = 0; s + 1 < g.n[d]; ++s) {
          const double u = at(s), w = at(s + 1);
          if (u * w >= 0) continue;
          const double c = (s + u / (u - w)) * g.h[d];
          if (u < 0) start = c; // entering psi > 0
          else {
            vol += (c - start) * g.h[a] * g.h[b];
            longest = std::max(longest, c - start);
          }
        }
      }
    return {vol, longest};
  }
};

struct Box {
  Grid g;
  Field psi;
  Halo halo;
  Box(std::array<int, 3> n, std::array<double, 3> lo, std::array<double, 3> hi, std::array<bool, 3> per,
      MPI_Comm comm = MPI_COMM_WORLD)
      : g(makeGrid(comm, n, lo, hi, per)), psi("psi", g.ext[0], g.ext[1], g.ext[2]), halo(g) {}
  Box(const Box&) = delete;
  ~Box() { freeGrid(g); }
  double hmin() const { return std::min({g.h[0], g.h[1], g.h[2]}); }
  // psi = fn at the owned cell centres; ghosts are the reinitializer's job.
  void fill(const Fn& fn) {
    auto h = Kokkos::create_mirror(psi);
    for (int k = 0; k < g.ext[2]; ++k)
      for (int j = 0; j < g.ext[1]; ++j)
        for (int i = 0; i < g.ext[0]; ++i) {
          const bool own = i >= g.ng && i < g.ng + g.ln[0] && j >= g.ng && j < g.ng + g.ln[1] && k >= g.ng &&
                           k < g.ng + g.ln[2];
          auto c = [&](int d, int l) { return g.lo[d] + (g.global(d, l) + 0.5) * g.h[d]; };
          h(i, j, k) = own ? fn(c(0, i), c(1, j), c(2, k)) : std::nan("");
        }
    Kokkos::deep_copy(psi, h);
  }
  Global gather() const {
    Global out{g, std::vector<double>(size_t(g.cellsGlobal()), 0.0)};
    auto h = Kokkos::create_mirror(psi);
    Kokkos::deep_copy(h, psi);
    const Range3 r = cellRange(g);
    for (int k = r.b[2]; k < r.e[2]; ++k)
      for (int j = r.b[1]; j < r.e[1]; ++j)
        for (int i = r.b[0]; i < r.e[0]; ++i)
          out.v[g.global(0, i) + size_t(g.n[0]) * (g.global(1, j) + size_t(g.n[1]) * g.global(2, k))] = h(i, j, k);
    MPI_Allreduce(MPI_IN_PLACE, out.v.data(), int(out.v.size()), MPI_DOUBLE, MPI_SUM, g.comm);
    return out;
  }
};

// |grad psi0| far from 1 (factor 0.55 .. 1.8), smooth, no symmetry.
double distortion(double x, double y, double z) {
  return std::exp(0.35 * std::sin(3 * x + 0.3) * std::cos(2 * y - 0.2) + 0.25 * std::sin(2.5 * z + 0.7));
}
constexpr double kR = 0.6, kC[3] = {0.03, -0.02, 0.01};
double sphereDist(double x, double y, double z) {
  return kR - std::sqrt((x - kC[0]) * (x - kC[0]) + (y - kC[1]) * (y - kC[1]) + (z - kC[2]) * (z - kC[2]));
}
double distortedSphere(double x, double y, double z) { return sphereDist(x, y, z) * distortion(x, y, z); }

// 48^3 on [-1,1]^3: h = 1/24, R = 14.4 cells; band 6 cells, kappa 2 cells.
struct Sphere : Box {
  explicit Sphere(MPI_Comm comm = MPI_COMM_WORLD) : Box({48, 48, 48}, {-1, -1, -1}, {1, 1, 1}, {false, false, false}, comm) {}
};

// Max and RMS normal distance (cells) of the interpolated zero crossings from the exact surface.
std::array<double, 2> contourError(const Global& G, const Fn& exact) {
  double m = 0, s = 0, n = 0;
  G.crossings([&](const double* p) {
    const double e = std::fabs(exact(p[0], p[1], p[2])) / G.hmin();
    m = std::max(m, e);
    s += e * e;
    n += 1;
  });
  return {m, std::sqrt(s / n)};
}

// Max and RMS ||grad psi| - 1| (central differences) at cells at least one cell
// off the interface whose 5x5x5 neighbourhood lies in the band of psi0 (two
// layers in from its edge, where the ENO stencil reads frozen cells).
std::array<double, 2> gradError(const Global& G, const Global& G0, double band, const Fn& exact) {
  double m = 0, s = 0, n = 0;
  G.cells([&](int i, int j, int k) {
    if (std::fabs(exact(G.x(0, i), G.x(1, j), G.x(2, k))) < G.hmin()) return;
    for (int c = -2; c <= 2; ++c)
      for (int b = -2; b <= 2; ++b)
        for (int a = -2; a <= 2; ++a) {
          if (!G.valid(0, i + a) || !G.valid(1, j + b) || !G.valid(2, k + c)) return;
          if (std::fabs(G0(i + a, j + b, k + c)) >= band) return;
        }
    const double gx = (G(i + 1, j, k) - G(i - 1, j, k)) / (2 * G.g.h[0]);
    const double gy = (G(i, j + 1, k) - G(i, j - 1, k)) / (2 * G.g.h[1]);
    const double gz = (G(i, j, k + 1) - G(i, j, k - 1)) / (2 * G.g.h[2]);
    const double e = std::fabs(std::sqrt(gx * gx + gy * gy + gz * gz) - 1);
    m = std::max(m, e);
    s += e * e;
    n += 1;
  });
  return {m, std::sqrt(s / n)};
}


// The scheme's variants: the default, and the switches to compare against.
struct Variant {
  const char* name;
  bool con = true, subcell = false;
};
const Variant kDefault{"default (constraint)"};
const Variant kPlain{"no constraint", false};
const Variant kSubcell{"constraint + subcell fix", true, true};
const Variant kSubcellOnly{"subcell fix, no constraint", false, true};

ReinitParams paramsFor(const Box& c, int iters, const Variant& v) {
  ReinitParams p;
  p.iterations = iters;
  p.kappa = 2 * c.hmin(); // paper: 2 cells
  p.band = 6 * c.hmin();  // LevelSetGeometry default
  p.volumeConstraint = v.con;
  p.subcellFix = v.subcell;
  return p;
}

struct SphereRun {
  std::array<double, 2> grad0, grad, contour0, contour;
  double vol0, vol; // int H(psi0), int H(psi)
  ReinitStats st;
  double drift() const { return vol / vol0 - 1; }
};

SphereRun runSphere(const Fn& init, const char* what, int iters, const Variant& v) {
  Sphere c;
  c.fill(init);
  const Global G0 = c.gather();
  Reinitializer re(c.g, paramsFor(c, iters, v));
  SphereRun r;
  r.st = re.run(c.halo, c.psi);
  const Global G = c.gather();
  const double band = 6 * c.hmin(), kappa = 2 * c.hmin();
  r.grad0 = gradError(G0, G0, band, sphereDist);
  r.grad = gradError(G, G0, band, sphereDist);
  r.contour0 = contourError(G0, sphereDist);
  r.contour = contourError(G, sphereDist);
  r.vol0 = G0.volumeH(kappa);
  r.vol = G.volumeH(kappa);
  if (rank0())
    printf("%s, %s, %d steps: ||grad psi|-1| max %.3f rms %.4f -> max %.4f rms %.4f (stats %.4f); "
           "contour error [cells] max %.4f rms %.4f -> max %.4f rms %.4f; int H drift %+.2e; "
           "%lld band cells, %.3f s\n",
           what, v.name, iters, r.grad0[0], r.grad0[1], r.grad[0], r.grad[1], r.st.maxGradError, r.contour0[0],
           r.contour0[1], r.contour[0], r.contour[1], r.drift(), r.st.bandCells, r.st.seconds);
  return r;
}

} // namespace
