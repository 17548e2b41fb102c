#pragma once
// The stability matrix's runner (test_matrix.cpp): energy and amplitude
// measures, the step loop with its per-step records, the table row and the
// common assertions. Included by test_matrix.cpp and test_matrix_rest.cpp.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "effects/elasticity/elasticity.hpp"
#include "kernels/reductions.hpp"
#include "stability/support.hpp"
#include "support/flow.hpp"

using namespace voigt;

namespace {

bool full() {
  const char* e = std::getenv("VOIGT_STABILITY_FULL");
  return e && std::string(e) == "1";
}

// VOIGT_STABILITY_SET="level_set.smoothing=1 ..." runs the matrix with these --set
// overrides (to measure a default before changing it); each applies only to the
// cases whose scene has its top-level section, e.g. no level_set in single-phase cases.
std::vector<std::string> envOverrides(const std::string& yaml) {
  std::vector<std::string> out;
  const char* e = std::getenv("VOIGT_STABILITY_SET");
  std::istringstream in(e ? e : "");
  for (std::string a; in >> a;) {
    const std::string section = a.substr(0, a.find_first_of(".="));
    if (yaml.rfind(section + ":", 0) == 0 || yaml.find("\n" + section + ":") != std::string::npos) out.push_back(a);
  }
  return out;
}

// Amplitude: for a rigidly rotated stressed solid (prescribed flow, no mass), the
// elastic energy per unit of the transported indicator s(x): every cell holds
// s(x) M tau0 (see test_objectivity.cpp), so (amp / amp0)^2 - 1 is the growth of
// the elastic energy the rotation map alone makes, free of the MUSCL smearing.
enum class Energy { Unforced, Gravity, Forced, Amplitude };

struct Series {
  std::vector<double> t, dt, E, Emech, drift, div, divPred, elastic, speed; // speed: max_d |u_d| over nodes
  std::vector<double> amp; // sqrt(sum |tau_S|_F^2 / sum tau_zz^2) over cells (rotation cases)
  std::vector<std::string> reason;
};

struct Result {
  long steps = 0;
  double wall = 0;
  double E0 = 0, Emech0 = 0, Escale = 0, amp0 = 0;
  double growth = 0;       // the case's energy measure (see the header)
  double maxDrift = 0;     // max |volume_drift|
  double corrected = 0;    // volume the global correction moved (level_set diag volume_corrected)
  double maxStrain = 0;    // max over steps and solid cells of |tau_S| / (2 mu_S) = sqrt(2 |S2|) / (2 mu_S)
  double maxElastic = 0;   // max elastic energy
  double maxSpeed = 0;     // max over steps and nodes of max_d |u_d|
  std::string name, gridText, expectedGrowth;
  bool completed = false;
  double allowed = 0;      // the energy tolerance (relative, same measure as growth), see energyTolerance
  double maxDiv = 0;       // max over steps of max|div| after projection
  double worstDivRatio = 0; // max over steps of max|div after| / (tol sqrt(N) max|div before|)
  std::map<std::string, long> reasons;
  Series s;
};

// Potential energy -sum rho g.x dV over owned cells (cell centres).
double potentialEnergy(const State& st, const Vec3& grav) {
  const Grid& g = st.grid;
  if (!st.fields.allocated("density")) return 0;
  const Field rho = st.fields.scalar("density");
  const double lo0 = g.lo[0], lo1 = g.lo[1], lo2 = g.lo[2], h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  const int ng = g.ng, c0 = g.c0[0], c1 = g.c0[1], c2 = g.c0[2];
  const double g0 = grav[0], g1 = grav[1], g2 = grav[2], dv = g.cellVolume();
  double e = 0;
  Kokkos::parallel_reduce(
      "stability_pe", cellRange(g).policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
        const double x = lo0 + (i - ng + c0 + 0.5) * h0, y = lo1 + (j - ng + c1 + 0.5) * h1,
                     z = lo2 + (k - ng + c2 + 0.5) * h2;
        acc -= rho(i, j, k) * (g0 * x + g1 * y + g2 * z) * dv;
      },
      e);
  return globalSum(g, e);
}

// sqrt(sum |tau_S|_F^2 / sum tau_zz^2) over owned cells (0 without elasticity or zz).
double stressAmplitude(const State& st) {
  if (!st.fields.allocated("solid_stress")) return 0;
  const Grid& g = st.grid;
  const SymTensorField t = solidStressField(st.fields);
  double a = 0, z = 0;
  Kokkos::parallel_reduce(
      "stability_amp", cellRange(g).policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
        const double xx = t.c[0](i, j, k), yy = t.c[1](i, j, k), zz = t.c[2](i, j, k);
        const double xy = t.c[3](i, j, k), yz = t.c[4](i, j, k), zx = t.c[5](i, j, k);
        acc += xx * xx + yy * yy + zz * zz + 2 * (xy * xy + yz * yz + zx * zx);
      },
      a);
  Kokkos::parallel_reduce(
      "stability_zz", cellRange(g).policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& acc) { acc += t.c[2](i, j, k) * t.c[2](i, j, k); }, z);
  a = globalSum(g, a);
  z = globalSum(g, z);
  return z > 0 ? std::sqrt(a / z) : 0;
}

double diagOr(const State& st, const char* k, double d = 0) {
  auto it = st.diag.find(k);
  return it == st.diag.end() ? d : it->second;
}

// Runs `steps` steps (or to tEnd) with the simulation's own dt rule (StepEngine),
// recording the diagnostics after every step. `phaseRelease` = |rho_1 - rho_2| V_phase
// (kg) for the gravity energy scale.
Result runCase(const std::string& name, const std::string& gridText, const std::string& yaml, long steps,
               Energy mode, double phaseRelease = 0, double tEnd = 1e300, const char* expectedGrowth = nullptr) {
  Scene sc = loadSceneWithEffectsFromString(yaml, name, envOverrides(yaml));
  RunOptions o;
  o.progress = false;
  Simulation sim(sc, MPI_COMM_WORLD, o);
  sim.initialize();
  State& st = sim.state();
  const Grid& g = st.grid;
  Result r;
  auto kinetic = [&]() {
    return st.fields.allocated("density") && st.fields.allocated("velocity")
               ? kineticEnergy(g, st.fields.vector("velocity"), st.fields.scalar("density"))
               : 0.0;
  };
  const Vec3 grav = sc.gravity;
  const bool hasGravity = std::find(sc.effects.begin(), sc.effects.end(), "gravity") != sc.effects.end();
  const Vec3 g0 = hasGravity ? grav : Vec3{0, 0, 0};
  r.E0 = kinetic() + diagOr(st, "elastic_energy");
  r.Emech0 = r.E0 + potentialEnergy(st, g0);
  r.amp0 = stressAmplitude(st);
  double H = 0, gmag = std::sqrt(g0[0] * g0[0] + g0[1] * g0[1] + g0[2] * g0[2]);
  for (int d = 0; d < 3; ++d)
    if (g0[d] != 0) H = std::max(H, g.hi[d] - g.lo[d]);
  r.Escale = r.E0 + phaseRelease * gmag * H;
  const double tolCG = sc.projection.tolerance;
  double muS = 0;
  if (sc.root["level_set"] && sc.root["level_set"]["phase"] &&
      sc.materials.count(sc.root["level_set"]["phase"].as<std::string>()))
    muS = sc.materials.at(sc.root["level_set"]["phase"].as<std::string>()).shearModulus;
  const double sqrtN = std::sqrt(double(g.cellsGlobal()));
  const double w0 = MPI_Wtime();
  // The engine's dt rule (time.dt, time.max_dt, the stable limit; landing on tEnd);
  // a step throws BlowUp on a non-finite value anywhere.
  long n = 0;
  auto each = [&](const State&) {
    const double dt = st.dt;
    const std::string reason = StepEngine::unclipped(st.dtReason);
    const double E = diagOr(st, "kinetic_energy") + diagOr(st, "elastic_energy");
    const double Em = E + potentialEnergy(st, g0);
    r.s.t.push_back(st.t);
    r.s.dt.push_back(dt);
    r.s.reason.push_back(reason);
    r.s.E.push_back(E);
    r.s.Emech.push_back(Em);
    r.s.elastic.push_back(diagOr(st, "elastic_energy"));
    r.s.amp.push_back(stressAmplitude(st));
    r.s.drift.push_back(diagOr(st, "volume_drift"));
    r.reasons[reason] += 1;
    if (st.fields.allocated("velocity")) {
      const VecField u = st.fields.vector("velocity");
      double sp = 0;
      for (int d = 0; d < 3; ++d) sp = std::max(sp, globalMaxAbs(g, u.c[d], nodeRange(g)));
      r.s.speed.push_back(sp);
      r.maxSpeed = std::max(r.maxSpeed, sp);
    }
    r.maxDrift = std::max(r.maxDrift, std::abs(diagOr(st, "volume_drift")));
    r.corrected = diagOr(st, "volume_corrected"); // cumulative: the last value is the largest
    r.maxElastic = std::max(r.maxElastic, diagOr(st, "elastic_energy"));
    if (muS > 0) r.maxStrain = std::max(r.maxStrain, std::sqrt(2 * std::abs(diagOr(st, "max_S2"))) / (2 * muS));
    if (st.diag.count("max_divergence")) {
      const double d = st.diag.at("max_divergence"), dp = st.diag.at("max_divergence_predicted");
      r.maxDiv = std::max(r.maxDiv, d);
      if (dp > 0) r.worstDivRatio = std::max(r.worstDivRatio, d / (tolCG * sqrtN * dp));
    }
    r.steps = st.step;
    if (std::getenv("VOIGT_STABILITY_SPLIT") && st.fields.allocated("density") && test::worldRank() == 0 &&
        (n % 10 == 0)) {
      // Kinetic energy and max speed split by node density (heavy / interface / light), and
      // where the fastest node is: diagnosis of energy growth.
      GridGeom G(g);
      auto hu = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.fields.vector("velocity").c[0]);
      auto hv = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.fields.vector("velocity").c[1]);
      auto hw = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.fields.vector("velocity").c[2]);
      auto hr = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.fields.scalar("density"));
      double ke[3] = {0, 0, 0}, um[3] = {0, 0, 0};
      int where[3] = {0, 0, 0};
      double rmax = 0, rmin = 1e300;
      auto rr = cellRange(g);
      for (int k = rr.b[2]; k < rr.e[2]; ++k)
        for (int j = rr.b[1]; j < rr.e[1]; ++j)
          for (int i = rr.b[0]; i < rr.e[0]; ++i) rmax = std::max(rmax, hr(i, j, k)), rmin = std::min(rmin, hr(i, j, k));
      auto nr = nodeRange(g);
      for (int k = nr.b[2]; k < nr.e[2]; ++k)
        for (int j = nr.b[1]; j < nr.e[1]; ++j)
          for (int i = nr.b[0]; i < nr.e[0]; ++i) {
            double rho = 0;
            int m = 0;
            for (int c = 0; c < 8; ++c) {
              const int ci = i - 1 + (c & 1), cj = j - 1 + ((c >> 1) & 1), ck = k - 1 + ((c >> 2) & 1);
              if (ci < rr.b[0] || ci >= rr.e[0] || cj < rr.b[1] || cj >= rr.e[1] || ck < rr.b[2] || ck >= rr.e[2]) continue;
              rho += hr(ci, cj, ck), ++m;
            }
            rho /= std::max(m, 1);
            const double u2 = hu(i, j, k) * hu(i, j, k) + hv(i, j, k) * hv(i, j, k) + hw(i, j, k) * hw(i, j, k);
            const double f = (rho - rmin) / (rmax - rmin);
            const int b = f > 0.95 ? 0 : f < 0.05 ? 2 : 1;
            ke[b] += 0.5 * rho * u2 * G.nodeWeight(i, j, k) * g.cellVolume();
            if (std::sqrt(u2) > um[b]) um[b] = std::sqrt(u2), where[b] = i + 1000 * j + 1000000 * k;
          }
      std::printf("  split step %ld KE heavy %.4g iface %.4g light %.4g | max|u| heavy %.3g iface %.3g (node %d) light %.3g (node %d)\n",
                  st.step, ke[0], ke[1], ke[2], um[0], um[1], where[1], um[2], where[2]);
    }
    ++n;
  };
  sim.advanceTo(tEnd, each, steps);
  r.wall = MPI_Wtime() - w0;
  if (std::getenv("VOIGT_STABILITY_TRACE") && test::worldRank() == 0)
    for (size_t n = 0; n < r.s.E.size(); n += std::max<size_t>(1, r.s.E.size() / 25))
      std::printf("  trace %s step %zu t %.4g dt %.3g (%s) E %.5g Emech-Emech0 %.5g Eel %.5g drift %.4g\n",
                  name.c_str(), n + 1, r.s.t[n], r.s.dt[n], r.s.reason[n].c_str(), r.s.E[n],
                  r.s.Emech[n] - r.Emech0, r.s.elastic[n], r.s.drift[n]);
  for (size_t n = 0; n < r.s.E.size(); ++n) {
    double gr = 0;
    if (mode == Energy::Unforced) gr = r.E0 > 0 ? r.s.E[n] / r.E0 - 1 : r.s.E[n];
    else if (mode == Energy::Gravity) gr = (r.s.Emech[n] - r.Emech0) / r.Escale;
    else if (mode == Energy::Amplitude) gr = r.amp0 > 0 ? std::pow(r.s.amp[n] / r.amp0, 2) - 1 : 0;
    else gr = r.E0 > 0 ? r.s.E[n] / r.E0 - 1 : r.s.E[n];
    r.growth = n ? std::max(r.growth, gr) : gr;
  }
  if (mode == Energy::Forced && r.s.E.size() >= 2) { // max over the second half / max over the first - 1
    const size_t half = r.s.E.size() / 2;
    r.growth = *std::max_element(r.s.E.begin() + half, r.s.E.end()) /
                   *std::max_element(r.s.E.begin(), r.s.E.begin() + half) - 1;
  }
  // Energy tolerance (same units as growth). Physically E (unforced) and E_mech
  // (gravity) cannot grow. The discrete budget has three known, measurable
  // error sources, each bounded from the run itself, none tuned:
  //  - volume drift: the level set creates or destroys up to max|drift| of the
  //    phase, i.e. potential energy up to max|drift| |rho_1 - rho_2| V g H
  //    (gravity cases: max|drift| (E_scale - E(0)) / E_scale); with the global
  //    volume correction the drift stays ~0 and the volume the correction moved
  //    (put back at the interface what the numerics destroyed) counts instead;
  //  - the elastic energy measure tau:tau / (4 mu_S) is the linear-elastic
  //    energy: for the hypoelastic (Jaumann) solid, the stress power and its
  //    rate agree only to first order in strain, so the measure may be off by
  //    max strain x max elastic energy;
  //  - CG tolerance 1e-8 and SSP-RK2 truncation: 1e-3 of the scale (three
  //    orders below the instabilities this is meant to catch).
  if (mode == Energy::Gravity)
    r.allowed = (r.Escale > r.E0 ? (r.maxDrift + r.corrected) * (r.Escale - r.E0) / r.Escale : 0) +
                r.maxStrain * r.maxElastic / r.Escale + 1e-3;
  else if (mode == Energy::Unforced)
    r.allowed = r.maxStrain * r.maxElastic / std::max(r.E0, 1e-300) + 1e-3;
  else if (mode == Energy::Forced)
    r.allowed = 1.0; // no runaway: the late energy below twice the early maximum (see the case)
  else if (mode == Energy::Amplitude)
    r.allowed = 1e-9; // Cayley keeps |tau| to round-off (test_objectivity.cpp: 9e-14 .. 7e-13 per turn)
  r.name = name;
  r.gridText = gridText;
  r.completed = r.steps == steps || st.t >= tEnd * (1 - 1e-12);
  r.expectedGrowth = expectedGrowth ? expectedGrowth : "";
  test::report(name + "_energy_growth", r.growth);
  test::report(name + "_volume_drift", r.maxDrift);
  test::report(name + "_volume_corrected", r.corrected);
  test::report(name + "_max_divergence", r.maxDiv);
  test::report(name + "_max_speed", r.maxSpeed);
  test::report(name + "_div_over_cg_bound", r.worstDivRatio);
  return r;
}


// The table row (rank 0): status names every bound the case misses.
void printRow(const Result& r, double driftBound, bool energyAsserted = true) {
  if (test::worldRank() != 0) return;
  std::string rs, st;
  for (auto& [k, v] : r.reasons) rs += (rs.empty() ? "" : ", ") + k + " " + std::to_string(v);
  if (!r.completed) st += "steps ";
  if (r.growth > r.allowed && r.expectedGrowth.empty()) st += energyAsserted ? "energy " : "energy (known) ";
  if (r.maxDrift > driftBound) st += "drift ";
  if (r.worstDivRatio > 1) st += "divergence ";
  std::string status = st.empty() ? "pass" : "FAIL: " + st.substr(0, st.size() - 1);
  if (r.growth > r.allowed && !r.expectedGrowth.empty()) status = r.expectedGrowth;
  std::printf("[ matrix ] | %s | %s | %ld | %.3e | %.2e | %.2e | %.2e | %.2e | %.2e | %s | %.1f | %d | %s |\n",
              r.name.c_str(), r.gridText.c_str(), r.steps, r.growth, r.allowed, r.maxDrift, r.corrected, driftBound,
              r.maxDiv, status.c_str(),
              r.wall, test::worldSize(), rs.c_str());
  std::fflush(stdout);
}

// The common assertions. driftBound: the case's volume-drift bound, the drift
// measured on the fast grid + 25 % (a measured discretisation error: the
// objects are 2.4-4 cells in radius against a smoothing half-width of 2 cells,
// and the level set's volume error is first order in h); the full matrix, at
// twice the resolution, must stay under the same bound.
void expectStable(const Result& r, long steps, double driftBound, bool checkEnergy = true) {
  printRow(r, driftBound, checkEnergy);
  EXPECT_EQ(r.steps, steps) << "the run stopped early";
  if (checkEnergy) EXPECT_LE(r.growth, r.allowed) << "energy grows";
  EXPECT_LE(r.maxDrift, driftBound);
  // CG bound (header): max|div after| <= tol sqrt(N) max|div before|, every step.
  EXPECT_LE(r.worstDivRatio, 1.0);
}

std::string fmt(const char* f, ...) __attribute__((format(printf, 1, 2)));
std::string fmt(const char* f, ...) {
  char buf[4096];
  va_list a;
  va_start(a, f);
  std::vsnprintf(buf, sizeof buf, f, a);
  va_end(a);
  return buf;
}

std::string cellsText(int nx, int ny, int nz) { return fmt("%dx%dx%d", nx, ny, nz); }

} // namespace
