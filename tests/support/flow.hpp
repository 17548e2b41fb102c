#pragma once
// Helpers for flow tests: scenes from strings, errors against exact fields.
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "app/simulation.hpp"
#include "core/index_space.hpp"
#include "scene/load.hpp"

namespace voigt::test {

inline Scene scene(const std::string& yaml) {
  return loadSceneWithEffectsFromString(yaml, "test");
}

// A scene file of the repository (path relative to its root) with --set style overrides,
// loaded as `voigt run` loads it.
inline Scene repoScene(const std::string& rel, std::vector<std::string> sets = {}) {
  return loadSceneWithEffects(std::string(VOIGT_SOURCE_DIR) + "/" + rel, std::move(sets));
}

// The SceneError a scene raises when loaded and set up ("" if none).
inline std::string sceneErrorOf(const std::string& yaml) {
  try {
    Simulation sim(scene(yaml), MPI_COMM_WORLD, RunOptions{});
    sim.initialize();
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

// Position of local node (i,j,k).
inline Vec3 nodePos(const Grid& g, int i, int j, int k) {
  return {g.lo[0] + g.global(0, i) * g.h[0], g.lo[1] + g.global(1, j) * g.h[1],
          g.lo[2] + g.global(2, k) * g.h[2]};
}

// Global RMS and max of (u - exact) over owned nodes; exact(x, c) gives component c.
struct ErrorNorms {
  double l2 = 0, linf = 0;
};
inline ErrorNorms nodeError(const Grid& g, const VecField& u,
                            const std::function<double(const Vec3&, int)>& exact) {
  auto r = nodeRange(g);
  double s = 0, m = 0;
  long long n = 0;
  std::array<decltype(Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), u.c[0])), 3> h;
  for (int c = 0; c < 3; ++c) h[c] = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), u.c[c]);
  for (int k = r.b[2]; k < r.e[2]; ++k)
    for (int j = r.b[1]; j < r.e[1]; ++j)
      for (int i = r.b[0]; i < r.e[0]; ++i) {
        const Vec3 x = nodePos(g, i, j, k);
        for (int c = 0; c < 3; ++c) {
          const double e = h[c](i, j, k) - exact(x, c);
          s += e * e;
          m = std::max(m, std::abs(e));
        }
        ++n;
      }
  ErrorNorms out;
  MPI_Allreduce(MPI_IN_PLACE, &s, 1, MPI_DOUBLE, MPI_SUM, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPI_LONG_LONG, MPI_SUM, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, &m, 1, MPI_DOUBLE, MPI_MAX, g.comm);
  out.l2 = std::sqrt(s / n);
  out.linf = m;
  return out;
}

// Runs a simulation to its end time (no output) and returns it for inspection.
inline std::unique_ptr<Simulation> runScene(const Scene& s, MPI_Comm comm = MPI_COMM_WORLD) {
  RunOptions opt;
  opt.progress = false;
  auto sim = std::make_unique<Simulation>(s, comm, opt);
  sim->run();
  return sim;
}

// A measured number: printed on rank 0 and recorded in the GoogleTest XML.
inline void report(const std::string& key, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6e", v);
  ::testing::Test::RecordProperty(key, buf);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0) std::printf("[ measured ] %s = %s\n", key.c_str(), buf);
}

} // namespace voigt::test
