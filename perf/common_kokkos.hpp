#pragma once
// Shared set-up for the perf programs that need only MPI and Kokkos (perf_stream,
// perf_kernels; also built against a Kokkos-CUDA by tests/device): Env, the clocks,
// STREAM. Scenes (app/, scene/) are in common.hpp.
#include <Kokkos_Core.hpp>
#include <mpi.h>

#include <ctime>

namespace voigt::perf {

struct Env {
  Env(int& argc, char**& argv) {
    MPI_Init(&argc, &argv);
    Kokkos::initialize(argc, argv);
  }
  ~Env() {
    Kokkos::finalize();
    MPI_Finalize();
  }
};

inline int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

// Seconds for rates on a shared machine: process CPU time when the execution
// space runs on one thread (time-slicing by other jobs then does not count;
// Google Benchmark's default rates use it too), wall time when it is threaded.
inline bool singleThreaded() { return Kokkos::DefaultExecutionSpace().concurrency() == 1; }
inline double cpuSeconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}
inline double seconds() { return singleThreaded() ? cpuSeconds() : MPI_Wtime(); }

// STREAM-style bandwidth (McCalpin): copy c = a, scale b = s c, add c = a + b,
// triad a = b + s c on Views of n doubles on the default execution space; best
// time (seconds() above, and wall) of `reps` repeats. Bytes as STREAM counts them (no write-allocate): 2
// arrays touched for copy and scale, 3 for add and triad. perf_stream prints
// all four; perf_kernels calls it for triad to scale its kernels.
struct StreamResult {
  const char* name[4] = {"copy", "scale", "add", "triad"};
  double gbs[4] = {0, 0, 0, 0};  // best (highest) GB/s
  double best[4] = {0, 0, 0, 0}; // best seconds
  double bytes[4] = {0, 0, 0, 0};
  double wallGbs[4] = {0, 0, 0, 0}; // from the best wall time (= gbs when threaded)
};

inline StreamResult stream(long n, int reps) {
  using V = Kokkos::View<double*, Kokkos::DefaultExecutionSpace::memory_space>;
  using P = Kokkos::RangePolicy<Kokkos::DefaultExecutionSpace>;
  V a("stream_a", n), b("stream_b", n), c("stream_c", n); // first touch by the exec space
  const double s = 3.0;
  Kokkos::parallel_for("stream_init", P(0, n), KOKKOS_LAMBDA(long i) {
    a(i) = 1.0;
    b(i) = 2.0;
    c(i) = 0.0;
  });
  Kokkos::fence();
  StreamResult r;
  double wall[4] = {0, 0, 0, 0};
  const double w[4] = {2, 2, 3, 3};
  for (int t = 0; t < 4; ++t) r.bytes[t] = w[t] * 8.0 * double(n);
  for (int rep = 0; rep < reps; ++rep)
    for (int t = 0; t < 4; ++t) {
      const double t0 = seconds(), w0 = MPI_Wtime();
      if (t == 0) Kokkos::parallel_for("stream_copy", P(0, n), KOKKOS_LAMBDA(long i) { c(i) = a(i); });
      if (t == 1) Kokkos::parallel_for("stream_scale", P(0, n), KOKKOS_LAMBDA(long i) { b(i) = s * c(i); });
      if (t == 2) Kokkos::parallel_for("stream_add", P(0, n), KOKKOS_LAMBDA(long i) { c(i) = a(i) + b(i); });
      if (t == 3) Kokkos::parallel_for("stream_triad", P(0, n), KOKKOS_LAMBDA(long i) { a(i) = b(i) + s * c(i); });
      Kokkos::fence();
      const double dt = seconds() - t0, dw = MPI_Wtime() - w0;
      if (rep == 0 || dt < r.best[t]) r.best[t] = dt;
      if (rep == 0 || dw < wall[t]) wall[t] = dw;
    }
  for (int t = 0; t < 4; ++t) r.gbs[t] = r.bytes[t] / r.best[t] / 1e9, r.wallGbs[t] = r.bytes[t] / wall[t] / 1e9;
  return r;
}

} // namespace voigt::perf
