#pragma once
// Zalesak and single-vortex set-ups, the exact shapes and the area and shape
// error measures of the transport tests (test_transport.cpp only).
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "core/index_space.hpp"
#include "kernels/heaviside.hpp"
#include "support/flow.hpp"

using namespace voigt;

namespace {

bool longRuns() {
  const char* v = std::getenv("VOIGT_LONG");
  return v && std::string(v) == "1";
}

bool rank0() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r == 0;
}

// The first three are the level set without the global volume correction
// (level_set.volume_correction: none); the Global modes add it (the default).
enum class Mode { NoReinit, Constrained, Unconstrained, GlobalConstrained, GlobalUnconstrained, GlobalNoReinit };
const char* modeName(Mode m) {
  switch (m) {
    case Mode::NoReinit: return "no_reinit";
    case Mode::Constrained: return "constrained";
    case Mode::Unconstrained: return "unconstrained";
    case Mode::GlobalConstrained: return "global+constrained";
    case Mode::GlobalUnconstrained: return "global+unconstrained";
    case Mode::GlobalNoReinit: return "global+no_reinit";
  }
  return "?";
}
bool globalCorrection(Mode m) {
  return m == Mode::GlobalConstrained || m == Mode::GlobalUnconstrained || m == Mode::GlobalNoReinit;
}
const char* correctionFor(Mode m) { return globalCorrection(m) ? "global" : "none"; }
std::string effectsFor(Mode m) {
  if (m == Mode::NoReinit || m == Mode::GlobalNoReinit) return "effects: [prescribed_flow, level_set]\n";
  const bool con = m == Mode::Constrained || m == Mode::GlobalConstrained;
  return std::string("effects: [prescribed_flow, level_set, reinit]\n") +
         (con ? "reinit: {volume_constraint: true}\n" : "reinit: {volume_constraint: false}\n");
}

// A square [0, side]^2 of n^2 cells, 2 cubic cells along periodic z.
std::string domain(double side, int n) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "domain: {lo: [0, 0, 0], hi: [%.17g, %.17g, %.17g], cells: [%d, %d, 2], ranks: [0, 0, 1]}\n"
                "boundaries: {default: {type: slip}, z-: {type: periodic}, z+: {type: periodic}}\n",
                side, side, 2 * side / n, n, n);
  return buf;
}

// ---- Zalesak's slotted disk ----------------------------------------------------
// Zalesak (1979), in the units of Enright et al., J. Comput. Phys. 183 (2002):
// [0,100]^2, disk centre (50, 75), radius 15, slot 5 wide reaching from the
// bottom of the disk up to y = 85 (25 long), rigid rotation about (50, 50) with
// omega = pi/314: one revolution at T = 628. Same scene as cases/zalesak.
constexpr double kZR = 15, kZcx = 50, kZcy = 75, kZw = 5, kZtop = 85, kZT = 628;

std::string zalesakScene(int n, Mode m) {
  // psi = min(cylinder, -box) has the exact zero set and |grad psi| = 1 almost
  // everywhere, so Fast Marching is off (and not under test here).
  return "name: zalesak\n" + domain(100, n) +
         "time: {end: 628, cfl: 0.5}\n"
         "materials: {disk: {density: 1, viscosity: 0}, air: {density: 1, viscosity: 0}}\n"
         "fluid: air\n" + effectsFor(m) +
         "prescribed_flow: {type: rotation, center: [50, 50, 0], omega: [0, 0, 0.010005072145190]}\n"
         "level_set:\n"
         "  phase: disk\n"
         "  volume_correction: " + correctionFor(m) + "\n"
         "  fast_marching: false\n"
         "  shape:\n"
         "    type: intersection\n"
         "    of:\n"
         "      - {type: cylinder, center: [50, 75, 0], radius: 15, axis: z}\n"
         "      - {type: complement, of: {type: box, lo: [47.5, 50, -100], hi: [52.5, 85, 100]}}\n"
         "output: {enabled: false}\n";
}

bool insideZalesak(double x, double y) {
  const bool inSlot = std::abs(x - kZcx) < 0.5 * kZw && y < kZtop;
  return !inSlot && std::hypot(x - kZcx, y - kZcy) < kZR;
}

// Exact perimeter and area: the circle less the arc under the slot's mouth, two
// walls from the circle up to y = 85, and the slot's top.
double zalesakPerimeter() {
  const double a = std::asin(0.5 * kZw / kZR), yb = kZcy - kZR * std::cos(a);
  return kZR * (2 * M_PI - 2 * a) + 2 * (kZtop - yb) + kZw;
}
double zalesakArea() {
  const double a = std::asin(0.5 * kZw / kZR), yb = kZcy - kZR * std::cos(a);
  return M_PI * kZR * kZR - kZw * (kZtop - yb) - kZR * kZR * (a - std::sin(a) * std::cos(a));
}

// ---- Single vortex ---------------------------------------------------------------
// LeVeque (1996), Rider & Kothe (1998), Enright et al. (2002): a circle of radius
// 0.15 at (0.5, 0.75) in the unit square, stream function
// sin^2(pi x) sin^2(pi y) cos(pi t / T) / pi; reversed at T/2, exact again at T.
constexpr double kVR = 0.15, kVcx = 0.5, kVcy = 0.75;

std::string vortexScene(int n, double T, Mode m) {
  char tp[160];
  std::snprintf(tp, sizeof tp, "time: {end: %.17g, cfl: 0.5}\nprescribed_flow: {type: single_vortex, period: %.17g}\n",
                T, T);
  return "name: single_vortex\n" + domain(1, n) + tp +
         "materials: {blob: {density: 1, viscosity: 0}, air: {density: 1, viscosity: 0}}\n"
         "fluid: air\n" + effectsFor(m) +
         "level_set: {phase: blob, fast_marching: false, volume_correction: " + correctionFor(m) + ",\n"
         "            shape: {type: cylinder, center: [0.5, 0.75, 0], radius: 0.15, axis: z}}\n"
         "output: {enabled: false}\n";
}

// prescribed_flow's single_vortex on the unit square.
void vortexVelocity(double x, double y, double t, double T, double& u, double& v) {
  const double f = std::cos(M_PI * t / T), sx = std::sin(M_PI * x), sy = std::sin(M_PI * y);
  u = -2 * sx * sx * sy * std::cos(M_PI * y) * f;
  v = 2 * sy * sy * sx * std::cos(M_PI * x) * f;
}

// A closed polygon (the exact interface as traced markers).
struct Poly {
  std::vector<double> x, y;
  double length() const {
    double L = 0;
    for (size_t i = 0; i < x.size(); ++i) {
      const size_t j = (i + 1) % x.size();
      L += std::hypot(x[j] - x[i], y[j] - y[i]);
    }
    return L;
  }
  // Even-odd rule.
  bool inside(double px, double py) const {
    bool in = false;
    for (size_t i = 0, j = x.size() - 1; i < x.size(); j = i++)
      if ((y[i] > py) != (y[j] > py) && px < x[j] + (py - y[j]) * (x[i] - x[j]) / (y[i] - y[j])) in = !in;
    return in;
  }
};

// The initial circle as m markers moved by RK4 to time tEnd (steps steps).
Poly traceCircle(double tEnd, double T, int m, int steps) {
  Poly p;
  const double dt = tEnd / steps;
  for (int q = 0; q < m; ++q) {
    const double a = 2 * M_PI * q / m;
    double x = kVcx + kVR * std::cos(a), y = kVcy + kVR * std::sin(a), t = 0;
    for (int s = 0; s < steps; ++s, t += dt) {
      double u1, v1, u2, v2, u3, v3, u4, v4;
      vortexVelocity(x, y, t, T, u1, v1);
      vortexVelocity(x + 0.5 * dt * u1, y + 0.5 * dt * v1, t + 0.5 * dt, T, u2, v2);
      vortexVelocity(x + 0.5 * dt * u2, y + 0.5 * dt * v2, t + 0.5 * dt, T, u3, v3);
      vortexVelocity(x + dt * u3, y + dt * v3, t + dt, T, u4, v4);
      x += dt / 6 * (u1 + 2 * u2 + 2 * u3 + u4);
      y += dt / 6 * (v1 + 2 * v2 + 2 * v3 + v4);
    }
    p.x.push_back(x);
    p.y.push_back(y);
  }
  return p;
}

// ---- Running and measuring ---------------------------------------------------------

struct Snapshot {
  double sharpChange = 0; // sharp area / initial - 1
  double hChange = 0;     // smoothed H area / initial - 1
  double sharpArea = 0;   // 2-D area (volume / Lz)
  double length = 0;      // interface length: diag interface_area / Lz
  double maxPsi = 0;
  double shapeError = 0;  // sum |H(exact) - H(psi)| dA / L (a length)
  double width() const { return length > 0 ? 2 * sharpArea / length : 0; }
};

Snapshot measure(const Simulation& sim, const std::function<bool(double, double)>& insideExact, double perimeter) {
  const State& st = sim.state();
  const Grid& g = st.grid;
  const double Lz = g.hi[2] - g.lo[2];
  nlohmann::json j;
  sim.effect("level_set")->summary(st, j);
  const auto& ls = j["level_set"];
  Snapshot s;
  s.sharpChange = ls["sharp_volume"].get<double>() / ls["sharp_volume_initial"].get<double>() - 1;
  s.hChange = ls["volume"].get<double>() / ls["volume_initial"].get<double>() - 1;
  s.sharpArea = ls["sharp_volume"].get<double>() / Lz;
  s.length = ls["interface_area"].get<double>() / Lz;
  auto psi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.fields.scalar("psi"));
  const Range3 r = cellRange(g);
  double err = 0, mx = -1e300;
  for (int jj = r.b[1]; jj < r.e[1]; ++jj)
    for (int i = r.b[0]; i < r.e[0]; ++i) {
      const double x = g.lo[0] + (g.global(0, i) + 0.5) * g.h[0];
      const double y = g.lo[1] + (g.global(1, jj) + 0.5) * g.h[1];
      const double He = insideExact(x, y) ? 1.0 : 0.0;
      for (int k = r.b[2]; k < r.e[2]; ++k) {
        err += std::abs(He - sharpHeaviside(psi(i, jj, k)));
        mx = std::max(mx, psi(i, jj, k));
      }
    }
  MPI_Allreduce(MPI_IN_PLACE, &err, 1, MPI_DOUBLE, MPI_SUM, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, &mx, 1, MPI_DOUBLE, MPI_MAX, g.comm);
  s.shapeError = err * g.cellVolume() / (perimeter * Lz);
  s.maxPsi = mx;
  return s;
}

void record(const std::string& key, const Snapshot& s, double h, double seconds) {
  if (rank0()) {
    std::printf("%-36s area %+.3e  H-area %+.3e  E %.3e (%.3f h)  length %.4g  width %.3g h  max psi %.3g h",
                key.c_str(), s.sharpChange, s.hChange, s.shapeError, s.shapeError / h, s.length, s.width() / h,
                s.maxPsi / h);
    if (seconds > 0) std::printf("  %.1f s", seconds);
    std::printf("\n");
    std::fflush(stdout);
  }
  char buf[32];
  auto prop = [&](const std::string& name, double v) {
    std::snprintf(buf, sizeof buf, "%.6e", v);
    ::testing::Test::RecordProperty(key + "." + name, buf);
  };
  prop("area_change", s.sharpChange);
  prop("H_area_change", s.hChange);
  prop("shape_error_cells", s.shapeError / h);
  prop("width_cells", s.width() / h);
  prop("max_psi_cells", s.maxPsi / h);
}

struct ZalesakResult {
  Snapshot end;
  double h = 0;
};

ZalesakResult runZalesak(int n, Mode m) {
  const double w0 = MPI_Wtime();
  Simulation sim(test::scene(zalesakScene(n, m)), MPI_COMM_WORLD, RunOptions{});
  sim.initialize();
  sim.advanceTo(kZT);
  ZalesakResult r;
  r.h = 100.0 / n;
  r.end = measure(sim, insideZalesak, zalesakPerimeter());
  record("zalesak." + std::to_string(n) + "." + modeName(m), r.end, r.h, MPI_Wtime() - w0);
  return r;
}

struct VortexResult {
  Snapshot half, end;
  double h = 0;
};

// Runs to T/2 (measured against the traced filament) and, unless halfOnly, on to
// T (measured against the initial circle).
VortexResult runVortex(int n, double T, Mode m, const Poly& exactHalf, bool halfOnly = false,
                       MPI_Comm comm = MPI_COMM_WORLD, bool quiet = false) {
  const double w0 = MPI_Wtime();
  Simulation sim(test::scene(vortexScene(n, T, m)), comm, RunOptions{});
  sim.initialize();
  VortexResult r;
  r.h = 1.0 / n;
  sim.advanceTo(0.5 * T);
  r.half = measure(sim, [&](double x, double y) { return exactHalf.inside(x, y); }, exactHalf.length());
  if (!halfOnly) {
    sim.advanceTo(T);
    r.end = measure(sim, [](double x, double y) { return std::hypot(x - kVcx, y - kVcy) < kVR; }, 2 * M_PI * kVR);
  }
  if (!quiet) {
    char key[64];
    std::snprintf(key, sizeof key, "vortex.T%g.%d.%s", T, n, modeName(m));
    record(std::string(key) + ".half", r.half, r.h, halfOnly ? MPI_Wtime() - w0 : 0);
    if (!halfOnly) record(std::string(key) + ".end", r.end, r.h, MPI_Wtime() - w0);
  }
  return r;
}

} // namespace
