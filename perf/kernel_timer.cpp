// A Kokkos Tools library that times every parallel_for/reduce/scan by label:
// where a whole run's time goes, kernel by kernel, Tpetra's and MueLu's included
// (Ifpack2's Gauss-Seidel sweeps on host are plain loops, not kernels: they show
// as a gap). Load it into any Kokkos program through the environment:
//   KOKKOS_PROFILE_LIBRARY=build/perf/libvoigt_kernel_timer.so \
//   VOIGT_KERNEL_TIMES=times.txt build/voigt run SCENE ...
// At Kokkos::finalize each rank writes "seconds calls label" lines, longest first,
// to VOIGT_KERNEL_TIMES (".rankN" appended beyond rank 0 under MPI), or stderr.
// Kernels on host backends finish before their end hook; on a GPU the times are
// launch times unless the program fences (set CUDA_LAUNCH_BLOCKING=1).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unordered_map>
#include <vector>

namespace {
using Clock = std::chrono::steady_clock;
struct Total {
  double seconds = 0;
  long calls = 0;
};
std::unordered_map<std::string, Total> totals;
struct Open {
  std::string label;
  Clock::time_point start;
};
std::vector<Open> open; // kernels may nest (a reduce launched inside a host loop): a stack

void begin(const char* label, uint64_t* id) {
  open.push_back({label, Clock::now()});
  *id = open.size() - 1;
}

void end(uint64_t id) {
  if (id >= open.size()) return;
  Total& t = totals[open[id].label];
  t.seconds += std::chrono::duration<double>(Clock::now() - open[id].start).count();
  t.calls += 1;
  open.resize(id);
}

std::string outputPath() {
  const char* p = std::getenv("VOIGT_KERNEL_TIMES");
  if (!p || !*p) return "";
  std::string path = p;
  for (const char* v : {"OMPI_COMM_WORLD_RANK", "PMI_RANK"}) {
    const char* r = std::getenv(v);
    if (r && std::string(r) != "0") return path + ".rank" + r;
  }
  return path;
}
} // namespace

extern "C" {
void kokkosp_init_library(int, uint64_t, uint32_t, void*) {}

void kokkosp_finalize_library() {
  std::vector<std::pair<std::string, Total>> rows(totals.begin(), totals.end());
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.second.seconds > b.second.seconds; });
  const std::string path = outputPath();
  FILE* f = path.empty() ? stderr : std::fopen(path.c_str(), "w");
  if (!f) {
    std::fprintf(stderr, "voigt_kernel_timer: cannot write %s\n", path.c_str());
    return;
  }
  std::fprintf(f, "# seconds calls label\n");
  for (const auto& [label, t] : rows) std::fprintf(f, "%12.6f %9ld %s\n", t.seconds, t.calls, label.c_str());
  if (f != stderr) std::fclose(f);
}

void kokkosp_begin_parallel_for(const char* n, uint32_t, uint64_t* id) { begin(n, id); }
void kokkosp_end_parallel_for(uint64_t id) { end(id); }
void kokkosp_begin_parallel_reduce(const char* n, uint32_t, uint64_t* id) { begin(n, id); }
void kokkosp_end_parallel_reduce(uint64_t id) { end(id); }
void kokkosp_begin_parallel_scan(const char* n, uint32_t, uint64_t* id) { begin(n, id); }
void kokkosp_end_parallel_scan(uint64_t id) { end(id); }
}
