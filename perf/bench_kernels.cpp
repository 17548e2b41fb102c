// Per-kernel throughput (Google Benchmark), every kernel family: advection,
// stress, elastic stress, reinit, projection pieces, Poisson (Tpetra).
// Columns: cell updates per second (items_per_second), effective bandwidth
// GBps from a minimal byte count per cell (each array a kernel call touches
// read or written once per cell, stencil reuse assumed from cache; stated
// beside each benchmark), and frac_triad = GBps / the STREAM triad bandwidth
// measured at start in this process (3 x 80 MB, best of 5; or VOIGT_TRIAD_GBS
// from a perf_stream run), both timed by CPU time on a single-threaded backend
// (perf/common_kokkos.hpp seconds()). Band kernels count band cells only.
// Usage: perf_kernels [--benchmark_filter=...] ; grid n^3 from VOIGT_BENCH_N (64).
// VOIGT_NO_TPETRA (tests/device, a Kokkos-only build, e.g. for CUDA): without the Poisson benchmarks.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define VOIGT_CALLGRIND(x) x
#else
#define VOIGT_CALLGRIND(x)
#endif

#include "bench_fixture.hpp"
#include "common_kokkos.hpp"
#include "core/halo.hpp"
#include "kernels/advection.hpp"
#include "kernels/advection_faces.hpp"
#include "kernels/elastic.hpp"
#include "kernels/levelset.hpp"
#include "kernels/projection_ops.hpp"
#include "kernels/extension.hpp"
#include "kernels/fast_diag.hpp"
#include "kernels/reinit.hpp"
#include "kernels/stress.hpp"
#ifndef VOIGT_NO_TPETRA
#include "solvers/poisson.hpp"
#endif

using namespace voigt;
using namespace voigt::bench;

namespace {
double gTriad = 0; // STREAM triad, bytes per second

// Rates per benchmark iteration: `cells` updates of `bytesPerCell` bytes each.
void report(benchmark::State& s, double bytesPerCell, double cells = -1) {
  if (cells < 0) cells = double(fx().g.cellsOwned());
  using C = benchmark::Counter;
  s.SetItemsProcessed(int64_t(s.iterations() * cells));
  s.counters["GBps"] = C(cells * bytesPerCell / 1e9, C::kIsIterationInvariantRate);
  s.counters["frac_triad"] = C(cells * bytesPerCell / gTriad, C::kIsIterationInvariantRate);
  s.counters["cells"] = cells;
}
std::string gName; // the benchmark running (registerAll)
// Under callgrind (perf/flops/run) only the timed loop is counted, one dump per
// benchmark run named "<benchmark> iterations=<n>"; natively these are a few no-op
// instructions outside the loop.
template <class F>
void loop(benchmark::State& s, F&& f) {
  VOIGT_CALLGRIND(CALLGRIND_TOGGLE_COLLECT);
  for (auto _ : s) {
    f();
    Kokkos::fence();
  }
  VOIGT_CALLGRIND(CALLGRIND_TOGGLE_COLLECT);
  const std::string dump = gName + " iterations=" + std::to_string(s.iterations());
  VOIGT_CALLGRIND(CALLGRIND_DUMP_STATS_AT(dump.c_str()));
  (void)dump;
}

// --- advection ---
// Node advection of u by u, 3 components, as the step runs it (addVelocityAdvectionFaces,
// kernels/advection_faces.hpp: the face-flux form on host backends, the point-wise form on
// a GPU since 2026-12-04): reads u (3), RMW rhs (3 * 2): 9 doubles. The point-wise form
// (3 addNodeAdvection calls, each face flux twice) beside it for the ratio; same byte count.
FluxScratch* gScratch = nullptr; // freed before Kokkos::finalize
FluxScratch& scratch() {
  if (!gScratch) gScratch = new FluxScratch;
  return *gScratch;
}
void BM_NodeAdvection(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] { addVelocityAdvectionFaces(f.g, f.u, f.rhs, nodeRange(f.g), Limiter::MinMod, scratch()); });
  report(s, 9 * 8);
}
void BM_NodeAdvectionPointwise(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] { for (int c = 0; c < 3; ++c) addNodeAdvection(f.g, f.u.c[c], f.u, f.rhs.c[c], nodeRange(f.g), Limiter::MinMod); });
  report(s, 9 * 8);
}
// Conservative momentum advection (two phases): reads rho, u (3), rhoRef,
// writes rhsRho, RMW rhs (3 * 2): 12 doubles. Face-flux form, then point-wise.
void BM_MomentumAdvection(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] {
    addMomentumAdvectionFaces(f.g, f.mu, f.u, f.mu, f.div, f.rhs, nodeRange(f.g), Limiter::MinMod, scratch());
  });
  report(s, 12 * 8);
}
void BM_MomentumAdvectionPointwise(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] { addMomentumAdvection(f.g, f.mu, f.u, f.mu, f.div, f.rhs, nodeRange(f.g), Limiter::MinMod); });
  report(s, 12 * 8);
}
// Level-set advection, one RK2 stage as the step runs it (advanceCellAdvection,
// face-flux form, update fused): reads psi, old, u (3), writes psi: 6 doubles.
// Point-wise beside it: zero rhs, addCellAdvection, update (same byte count).
void BM_LevelSetAdvection(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] { advanceCellAdvection(f.g, f.psi1, f.old, f.u, cellRange(f.g), Limiter::MinMod, 1e-6, 0.5, false, scratch()); });
  report(s, 6 * 8);
}
void BM_LevelSetAdvectionPointwise(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] {
    Field q = f.psi1, o = f.old, r = f.rhsCell;
    const Range3 cells = cellRange(f.g);
    Kokkos::deep_copy(r, 0.0);
    addCellAdvection(f.g, q, f.u, r, cells, Limiter::MinMod);
    Kokkos::parallel_for(
        "bench_ls_rk2", cells.policy(), KOKKOS_LAMBDA(int i, int j, int k) {
          q(i, j, k) = 0.5 * o(i, j, k) + 0.5 * (q(i, j, k) + 1e-6 * r(i, j, k));
        });
  });
  report(s, 6 * 8);
}
// --- stress ---
// Reads u (3) and mu, writes 6 stress components.
void BM_ViscousStress(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] { viscousStress(f.g, f.u, f.mu, f.tau, cellRange(f.g)); });
  report(s, 10 * 8);
}
// Reads 6 stress components and coef (3), RMW rhs (3).
void BM_StressDivergence(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] { addStressDivergence(f.g, f.tau, f.coef, f.rhs, nodeRange(f.g)); });
  report(s, 15 * 8);
}
// --- elastic stress (band of a sphere of radius 0.3, ~17 % of the cells) ---
// Jaumann/Cayley update (Eq. 16): list index (4 B), u (3), RMW tau_S (12).
void BM_ElasticJaumann(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] { elastic::jaumannUpdate(f.g, f.u, f.tauS, 1.0, 1e-4, f.owned, f.nOwned, f.ownedRuns, f.nOwnedRuns); });
  report(s, 15 * 8 + 4, f.nOwned);
}
// tau += H(psi) tau_S: list (4 B), psi, tau_S (6), RMW tau (12).
void BM_ElasticAddStress(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] { elastic::addSolidStress(f.g, f.psi, 2 * f.h, f.tauS, f.tau, f.grown, f.nGrown); });
  report(s, 19 * 8 + 4, f.nGrown);
}
// Stress advection, one SSP-RK2 stage of 6 components over the band's box, as
// effects/elasticity/advect.cpp runs it (advanceCellAdvection per component, face fluxes,
// update fused): reads q (6), o (6), u (3), writes q (6): 21 doubles per box cell.
void BM_ElasticStressAdvection(benchmark::State& s) {
  auto& f = fx();
  const Range3 box = elastic::listBox(f.g, f.owned, f.nOwned);
  loop(s, [&] {
    for (int c = 0; c < 6; ++c) {
      advanceCellAdvection(f.g, f.tauS.c[c], f.tau.c[c], f.u, box, Limiter::MinMod, 1e-6, 0.5, false, scratch());
    }
  });
  report(s, 21 * 8, double(box.size()));
}
// The point-wise form it replaced: per component zero r, addCellAdvection,
// update (same 21-double count, for the ratio).
void BM_ElasticStressAdvectionPointwise(benchmark::State& s) {
  auto& f = fx();
  const Range3 box = elastic::listBox(f.g, f.owned, f.nOwned);
  loop(s, [&] {
    for (int c = 0; c < 6; ++c) {
      Field q = f.tauS.c[c], o = f.old, r = f.rhsCell;
      Kokkos::parallel_for("bench_rk2_zero", box.policy(), KOKKOS_LAMBDA(int i, int j, int k) { r(i, j, k) = 0; });
      addCellAdvection(f.g, q, f.u, r, box, Limiter::MinMod);
      Kokkos::parallel_for(
          "bench_rk2", box.policy(), KOKKOS_LAMBDA(int i, int j, int k) {
            q(i, j, k) = 0.5 * o(i, j, k) + 0.5 * (q(i, j, k) + 1e-6 * r(i, j, k));
          });
    }
  });
  report(s, 21 * 8, double(box.size()));
}
// One Jacobi sweep of the stress extension (kernels/extension.hpp) over the band's
// fluid side: list (4 B), psi, tau_S (6) read, tau (6) written; neighbours from cache.
void BM_ExtensionSweep(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] { extension::sweep(f.g, f.psi, f.tauS, f.tau, f.side, f.nSide, f.sideRuns, f.nSideRuns, 0.0); });
  report(s, 13 * 8 + 4, f.nSide);
}
// --- reinit (band |psi| < 6 h around the sphere) ---
// One Eikonal RK stage: list, flags (4 B each), sgn, in, base, out (8 B each).
void BM_ReinitStage(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] { reinit::eikonalStage(f.g, f.band, f.nBand, f.psi, f.psi, f.psi1, 0.0, 0.25 * f.h, false); });
  report(s, 40, f.nBand);
}
// One pseudo-time iteration as levelset/reinit.cpp (volume constraint on, halo
// refreshes left out): 2 stages (80 B), constraint (list, coef, dH, psiT, psiM,
// out: 44 B), copy (list, src, dst: 20 B) = 144 B per band cell.
void BM_ReinitIteration(benchmark::State& s) {
  auto& f = fx();
  const double dtau = 0.5 * f.h;
  loop(s, [&] {
    reinit::eikonalStage(f.g, f.band, f.nBand, f.psi, f.psi, f.psi1, 0.0, dtau, false);
    reinit::eikonalStage(f.g, f.band, f.nBand, f.psi1, f.psi, f.psiT, 0.5, dtau, false);
    reinit::applyConstraint(f.g, f.band, f.nBand, f.psiT, f.psi, f.dH, f.psi1);
    reinit::copyBand(f.g, f.band, f.nBand, f.psi1, f.psi);
  });
  report(s, 144, f.nBand);
}
// The volume constraint alone (Eq. 19-21): a copy over the band, then the constrained
// cells (list, coef, out: 20 B; dH, psiT, psiM: 24 B), counted per band cell.
void BM_ReinitConstraint(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] { reinit::applyConstraint(f.g, f.band, f.nBand, f.psiT, f.psi, f.dH, f.psi1); });
  report(s, 44, f.nBand);
}
// The per-call band set-up with the constraint (gradMagField over the owned cells and one
// layer, then flags, S, D and coef per band cell: list, flags, sgn, dist, coef 32 B; psi0, dH,
// gm 24 B).
void BM_ReinitPrepare(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] { reinit::prepareBand(f.g, f.band, f.nBand, f.psi, f.dH, f.gm, 6 * f.h, true); });
  report(s, 56, f.nBand);
}
// --- projection pieces ---
// Reads u (3), writes div (1).
void BM_Divergence(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] { divergence(f.g, f.u, f.div, cellRange(f.g)); });
  report(s, 4 * 8);
}
// Reads p and coef (3), RMW u (3).
void BM_SubtractGradient(benchmark::State& s) {
  auto& f = fx();
  loop(s, [&] { subtractGradient(f.g, f.p, f.coef, 1e-3, f.u, nodeRange(f.g)); });
  report(s, 10 * 8);
}
// Halo exchange of a vector field (periodic self-exchange on one rank).
void BM_HaloVector(benchmark::State& s) {
  auto& f = fx();
  Halo h(f.g);
  for (auto _ : s) h.exchange(f.u);
  s.counters["halo_MB_per_exchange"] = double(h.bytes) / s.iterations() / 1e6;
}
// --- fast diagonalization (kernels/fast_diag.hpp) ---
// A 1-D transform of the grid along an axis (Arg 0-2 forward, 3-5 back; 2nd Arg 1: folded, half; 3rd Arg 1:
// float, the mixed-precision preconditioner's passes): 2 n flops a cell, in and out once (16 B, float 8 B;
// lines reused from cache): GFLOPs against the core's peak is the measure.
template <class T>
void fastDiagTransform(benchmark::State& s) {
  auto& f = fx();
  const int axis = s.range(0) % 3, m = f.g.ln[axis];
  Grid3Of<T> a("a", f.g.ln[0], f.g.ln[1], f.g.ln[2]), b("b", f.g.ln[0], f.g.ln[1], f.g.ln[2]);
  DenseOf<T> V("V", m, m);
  Kokkos::deep_copy(a, T(1)), Kokkos::deep_copy(V, T(1) / m);
  void (*t[6])(const CGrid3Of<T>&, const Grid3Of<T>&, const DenseOf<T>&, int) = {fdTransform<0, false, T>, fdTransform<1, false, T>, fdTransform<2, false, T>, fdTransform<0, true, T>, fdTransform<1, true, T>, fdTransform<2, true, T>};
  loop(s, [&] { t[s.range(0)](a, b, V, s.range(1) ? (m + 1) / 2 : m); });
  report(s, 2 * sizeof(T)), s.counters["GFLOPs"] = benchmark::Counter(2.0 * m * f.g.cellsOwned() / 1e9, benchmark::Counter::kIsIterationInvariantRate);
}
void BM_FastDiagTransform(benchmark::State& s) { s.range(2) ? fastDiagTransform<float>(s) : fastDiagTransform<double>(s); }
#ifndef VOIGT_NO_TPETRA
// --- Poisson (Tpetra through PoissonSolver) ---
std::unique_ptr<PoissonSolver> solver(bool exact, const char* pc, int maxIt) {
  PoissonSettings cfg;
  cfg.op = exact ? PoissonSettings::Op::Exact : PoissonSettings::Op::Approximate;
  cfg.preconditioner = pc;
  cfg.tolerance = 1e-30; // never converges: always maxIt iterations
  cfg.maxIterations = maxIt;
  auto s = makePoissonSolver(fx().g, cfg);
  s->setCoefficients(fx().coef);
  return s;
}
// y = A x through apply(): CRS matvec (nnz x (8 B value + 4 B column) + 8 B row
// pointer + x + y) plus the field <-> vector copies (32 B). Arg 0: 7-point, 1: 27-point.
void BM_PoissonMatvec(benchmark::State& s) {
  auto& f = fx();
  const bool exact = s.range(0) == 1;
  auto A = solver(exact, "none", 1);
  loop(s, [&] { A->apply(f.p, f.div); });
  report(s, (exact ? 27 : 7) * 12 + 8 + 16 + 32);
}
// One CG iteration (7-point): time (perf::seconds) of a 25-iteration solve minus
// a 5-iteration one, over 20 (so set-up, null-mode removal and residual checks cancel). Bytes:
// matvec 108 + CG vector updates ~104 (3 axpy, 2 dots); SGS adds a forward and a
// backward sweep, 2 x (matrix 92 + x RMW 16 + b 8) = 232. Arg 0: none, 1: jacobi, 2: sgs.
void BM_CGIteration(benchmark::State& s) {
  auto& f = fx();
  const char* pcs[3] = {"none", "jacobi", "sgs"};
  auto s5 = solver(false, pcs[s.range(0)], 5), s25 = solver(false, pcs[s.range(0)], 25);
  for (auto _ : s) {
    Kokkos::deep_copy(f.div, 0.0);
    const double t0 = perf::seconds();
    s5->solve(f.p, f.div);
    const double t1 = perf::seconds();
    Kokkos::deep_copy(f.div, 0.0);
    const double t2 = perf::seconds();
    const PoissonStats st = s25->solve(f.p, f.div);
    const double t3 = perf::seconds();
    if (st.iterations != 25) s.SkipWithError("CG did not run 25 iterations");
    s.SetIterationTime(((t3 - t2) - (t1 - t0)) / 20);
  }
  const double b[3] = {212, 212 + 40, 212 + 232}; // Jacobi: z = D^-1 r (24) + null-mode removal (~16)
  report(s, b[s.range(0)]);
}
#endif
} // namespace

// Registered at run time: threaded backends time by wall clock (the default,
// CPU time, would sum the threads); the triad yardstick uses the same clock.
void registerAll(bool wall) {
  auto add = [&](const char* name, void (*f)(benchmark::State&)) {
    auto run = [name, f](benchmark::State& s) {
      gName = name;
      f(s);
    };
    auto* b = benchmark::RegisterBenchmark(name, run)->Unit(benchmark::kMillisecond);
    if (wall) b->UseRealTime();
    return b;
  };
  add("NodeAdvection", BM_NodeAdvection);
  add("NodeAdvectionPointwise", BM_NodeAdvectionPointwise);
  add("MomentumAdvection", BM_MomentumAdvection);
  add("MomentumAdvectionPointwise", BM_MomentumAdvectionPointwise);
  add("LevelSetAdvection", BM_LevelSetAdvection);
  add("LevelSetAdvectionPointwise", BM_LevelSetAdvectionPointwise);
  add("ViscousStress", BM_ViscousStress);
  add("StressDivergence", BM_StressDivergence);
  add("ElasticJaumann", BM_ElasticJaumann);
  add("ElasticAddStress", BM_ElasticAddStress);
  add("ElasticStressAdvection", BM_ElasticStressAdvection);
  add("ElasticStressAdvectionPointwise", BM_ElasticStressAdvectionPointwise);
  add("ExtensionSweep", BM_ExtensionSweep);
  add("ReinitStage", BM_ReinitStage);
  add("ReinitIteration", BM_ReinitIteration);
  add("ReinitConstraint", BM_ReinitConstraint);
  add("ReinitPrepare", BM_ReinitPrepare);
  add("Divergence", BM_Divergence);
  add("SubtractGradient", BM_SubtractGradient);
  add("HaloVector", BM_HaloVector);
  add("FastDiagTransform", BM_FastDiagTransform)->ArgsProduct({{0, 1, 2, 3, 4, 5}, {0, 1}, {0, 1}});
#ifndef VOIGT_NO_TPETRA
  add("PoissonMatvec", BM_PoissonMatvec)->Arg(0)->Arg(1);
  add("CGIteration", BM_CGIteration)->Arg(0)->Arg(1)->Arg(2)->UseManualTime();
#endif
}

int main(int argc, char** argv) {
  perf::Env env(argc, argv);
  benchmark::Initialize(&argc, argv);
  // The yardstick, measured in this process unless a perf_stream run gave it.
  const char* t = getenv("VOIGT_TRIAD_GBS");
  const bool given = t && atof(t) > 0;
  gTriad = given ? atof(t) * 1e9 : perf::stream(10000000, 5).gbs[3] * 1e9;
  registerAll(!perf::singleThreaded());
  benchmark::AddCustomContext("stream_triad_GBs", std::to_string(gTriad / 1e9) + (given ? " (VOIGT_TRIAD_GBS)" : " (measured)"));
  std::fprintf(stderr, "STREAM triad: %.2f GB/s (%s, %s time)\n", gTriad / 1e9,
               given ? "VOIGT_TRIAD_GBS" : "measured, 3 x 80 MB", perf::singleThreaded() ? "CPU" : "wall");
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  if (gFixture) freeGrid(gFixture->g);
  delete gFixture;
  delete gScratch;
  return 0;
}
