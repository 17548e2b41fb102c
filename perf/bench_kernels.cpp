// Per-kernel throughput (Google Benchmark): cell updates per second and the
// effective bandwidth from a minimal-traffic byte count per cell (each array
// read or written once per cell; stencil reuse assumed from cache).
// Usage: perf_kernels [--benchmark_filter=...] ; grid size from VOIGT_BENCH_N (default 64).
#include <benchmark/benchmark.h>

#include <cstdlib>

#include "common.hpp"
#include "core/halo.hpp"
#include "kernels/advection.hpp"
#include "kernels/projection_ops.hpp"
#include "kernels/stress.hpp"

using namespace voigt;

namespace {
struct Fixture {
  Grid g;
  VecField u, rhs, coef;
  Field p, div, mu;
  SymTensorField tau;
  Fixture() {
    const int n = getenv("VOIGT_BENCH_N") ? atoi(getenv("VOIGT_BENCH_N")) : 64;
    g = makeGrid(MPI_COMM_SELF, {n, n, n}, {0, 0, 0}, {1, 1, 1}, {true, true, true});
    auto mk = [&](const char* name) { return Field(std::string(name), g.ext[0], g.ext[1], g.ext[2]); };
    for (int c = 0; c < 3; ++c) {
      u.c[c] = mk("u");
      rhs.c[c] = mk("rhs");
      coef.c[c] = mk("coef");
      Kokkos::deep_copy(coef.c[c], 1.0);
    }
    for (int c = 0; c < 6; ++c) tau.c[c] = mk("tau");
    p = mk("p");
    div = mk("div");
    mu = mk("mu");
    Kokkos::deep_copy(mu, 1e-3);
    auto uu = u;
    Kokkos::parallel_for(
        Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}), KOKKOS_LAMBDA(int i, int j, int k) {
          uu.c[0](i, j, k) = std::sin(0.1 * i) * std::cos(0.2 * j);
          uu.c[1](i, j, k) = std::cos(0.1 * i) * std::sin(0.3 * k);
          uu.c[2](i, j, k) = std::sin(0.2 * j + 0.1 * k);
        });
  }
};
Fixture* gFixture = nullptr; // freed before Kokkos::finalize
Fixture& fx() {
  if (!gFixture) gFixture = new Fixture;
  return *gFixture;
}

void report(benchmark::State& s, double doublesPerCell) {
  const double cells = double(fx().g.cellsOwned());
  s.SetItemsProcessed(int64_t(s.iterations() * cells));
  s.SetBytesProcessed(int64_t(s.iterations() * cells * doublesPerCell * 8));
}

// 3 components, reads u (3) and writes rhs (1) per component: 3*(3+2) doubles.
void BM_NodeAdvection(benchmark::State& s) {
  auto& f = fx();
  for (auto _ : s) {
    for (int c = 0; c < 3; ++c) addNodeAdvection(f.g, f.u.c[c], f.u, f.rhs.c[c], nodeRange(f.g), Limiter::MinMod);
    Kokkos::fence();
  }
  report(s, 15);
}
// Reads u (3) and mu, writes 6 stress components.
void BM_ViscousStress(benchmark::State& s) {
  auto& f = fx();
  for (auto _ : s) {
    viscousStress(f.g, f.u, f.mu, f.tau, cellRange(f.g));
    Kokkos::fence();
  }
  report(s, 10);
}
// Reads 6 stress components and coef (3), read-modify-writes rhs (3).
void BM_StressDivergence(benchmark::State& s) {
  auto& f = fx();
  for (auto _ : s) {
    addStressDivergence(f.g, f.tau, f.coef, f.rhs, nodeRange(f.g));
    Kokkos::fence();
  }
  report(s, 15);
}
// Reads u (3), writes div (1).
void BM_Divergence(benchmark::State& s) {
  auto& f = fx();
  for (auto _ : s) {
    divergence(f.g, f.u, f.div, cellRange(f.g));
    Kokkos::fence();
  }
  report(s, 4);
}
// Reads p and coef (3), read-modify-writes u (3).
void BM_SubtractGradient(benchmark::State& s) {
  auto& f = fx();
  for (auto _ : s) {
    subtractGradient(f.g, f.p, f.coef, 1e-3, f.u, nodeRange(f.g));
    Kokkos::fence();
  }
  report(s, 10);
}
// Halo exchange of a vector field (periodic self-exchange on one rank).
void BM_HaloVector(benchmark::State& s) {
  auto& f = fx();
  Halo h(f.g);
  for (auto _ : s) h.exchange(f.u);
  report(s, 0);
  s.counters["halo_MB_per_exchange"] = double(h.bytes) / s.iterations() / 1e6;
}
} // namespace

BENCHMARK(BM_NodeAdvection)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ViscousStress)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StressDivergence)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Divergence)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SubtractGradient)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HaloVector)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  perf::Env env(argc, argv);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  if (gFixture) freeGrid(gFixture->g);
  delete gFixture;
  return 0;
}
