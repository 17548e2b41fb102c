// Poisson iterations and time against grid size, both operators, for the
// projection of the first step of a lid-driven cavity (cold start, x0 = 0) and
// the second step (warm start from the previous increment).
// Usage: perf_poisson_scaling [tol] [preconditioner] [sizes...]
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "common.hpp"

using namespace voigt;

int main(int argc, char** argv) {
  perf::Env env(argc, argv);
  const std::string tol = argc > 1 ? argv[1] : "1e-8";
  const std::string pc = argc > 2 ? argv[2] : "sgs";
  std::vector<int> sizes;
  for (int i = 3; i < argc; ++i) sizes.push_back(atoi(argv[i]));
  if (sizes.empty()) sizes = {32, 64, 96};
  if (perf::rank() == 0)
    printf("| n | operator | preconditioner | tol | cold its | cold s | warm its | warm s | null modes |\n"
           "|---|---|---|---|---|---|---|---|---|\n");
  for (int n : sizes) {
    for (std::string op : {"approximate", "exact"}) {
      Scene s = perf::scene(perf::cavity(n, op, pc, tol));
      RunOptions opt;
      opt.progress = false;
      Simulation sim(s, MPI_COMM_WORLD, opt);
      sim.initialize();
      const double dt = sim.stableDt().dt;
      auto& c = sim.state().counters;
      sim.advance(std::isfinite(dt) ? dt : 1e-3);
      const double its1 = c["poisson_iterations"], s1 = c["poisson_seconds"];
      sim.advance(sim.stableDt().dt);
      const double its2 = c["poisson_iterations"] - its1, s2 = c["poisson_seconds"] - s1;
      const auto j = sim.summary(RunResult{});
      if (perf::rank() == 0)
        printf("| %d | %s | %s | %s | %.0f | %.2f | %.0f | %.2f | %d |\n", n, op.c_str(), pc.c_str(), tol.c_str(), its1,
               s1, its2, s2, j["poisson"]["null_modes"].get<int>());
      fflush(stdout);
    }
  }
  return 0;
}
