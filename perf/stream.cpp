// Memory bandwidth of this machine, STREAM-style (McCalpin's copy, scale, add,
// triad) with Kokkos Views on the default execution space (Serial build: one
// core; an OpenMP build uses its threads). Arrays far larger than the caches;
// best of N repeats; bytes counted as STREAM does (perf/common_kokkos.hpp stream()).
// Timed by process CPU time on one thread (robust to other jobs time-slicing
// this core), by wall time when threaded; the best-wall-time column is printed too.
// Usage: perf_stream [MB per array, default 160] [repeats, default 10] [--json FILE]
// The triad number is the yardstick of perf_kernels' "frac_triad" column.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "common_kokkos.hpp"

int main(int argc, char** argv) {
  voigt::perf::Env env(argc, argv);
  double mb = 160;
  int reps = 10;
  std::string json;
  int pos = 0;
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--json") && a + 1 < argc) json = argv[++a];
    else if (pos++ == 0) mb = std::atof(argv[a]);
    else reps = std::atoi(argv[a]);
  }
  if (mb <= 0 || reps < 2) {
    std::fprintf(stderr, "usage: perf_stream [MB per array > 0] [repeats >= 2] [--json FILE]\n");
    return 2;
  }
  const long n = long(mb * 1e6 / 8);
  if (voigt::perf::rank() != 0) return 0; // one process measures; under MPI run with -np 1
  const auto r = voigt::perf::stream(n, reps);
  std::printf("STREAM (Kokkos %s): 3 arrays x %.0f MB (%ld doubles), best of %d\n",
              Kokkos::DefaultExecutionSpace::name(), n * 8 / 1e6, n, reps);
  const char* clk = voigt::perf::singleThreaded() ? "CPU" : "wall";
  std::printf("| kernel | bytes/element | best %s s | GB/s | GB/s (best wall time) |\n|---|---|---|---|---|\n", clk);
  for (int t = 0; t < 4; ++t)
    std::printf("| %s | %.0f | %.4f | %.2f | %.2f |\n", r.name[t], r.bytes[t] / n, r.best[t], r.gbs[t],
                r.wallGbs[t]);
  if (!json.empty()) {
    FILE* f = std::fopen(json.c_str(), "w");
    if (!f) {
      std::fprintf(stderr, "perf_stream: cannot write %s\n", json.c_str());
      return 1;
    }
    std::fprintf(f, "{\"exec_space\": \"%s\", \"mb_per_array\": %.1f, \"repeats\": %d",
                 Kokkos::DefaultExecutionSpace::name(), n * 8 / 1e6, reps);
    for (int t = 0; t < 4; ++t)
      std::fprintf(f, ", \"%s_GBs\": %.3f, \"%s_wall_GBs\": %.3f", r.name[t], r.gbs[t], r.name[t], r.wallGbs[t]);
    std::fprintf(f, "}\n");
    std::fclose(f);
  }
  return 0;
}
