// Whole-step throughput: cell-steps per second of an n^3 single-phase
// lid-driven cavity, split by stage. Usage: perf_step_throughput [n] [steps] [operator]
#include <cstdio>
#include <cstdlib>

#include "common.hpp"

using namespace voigt;

int main(int argc, char** argv) {
  perf::Env env(argc, argv);
  const int n = argc > 1 ? atoi(argv[1]) : 64;
  const long steps = argc > 2 ? atol(argv[2]) : 20;
  const std::string op = argc > 3 ? argv[3] : "approximate";
  {
    Scene s = perf::scene(perf::cavity(n, op, "sgs", "1e-6"));
    RunOptions opt;
    opt.maxSteps = steps;
    opt.progress = false;
    Simulation sim(s, MPI_COMM_WORLD, opt);
    const RunResult r = sim.run();
    const auto j = sim.summary(r);
    if (perf::rank() == 0) {
      int size = 1;
      MPI_Comm_size(MPI_COMM_WORLD, &size);
      printf("cavity %d^3, %s projection, %d rank(s), %ld steps: %.3g cell-steps/s, %.3f s/step\n", n, op.c_str(),
             size, r.steps, r.cellStepsPerSecond, r.wallSeconds / r.steps);
      for (auto& [stage, sec] : j["wall_seconds_per_stage"].items())
        printf("  %-12s %6.1f %%\n", stage.c_str(), 100 * sec.get<double>() / r.wallSeconds);
      printf("  poisson iterations mean %.1f max %.0f; halo %.3f s\n", j["poisson"]["iterations_mean"].get<double>(),
             j["poisson"]["iterations_max"].get<double>(), j["halo"]["seconds"].get<double>());
      printf("  field memory %.1f bytes per cell\n", double(sim.bytesPerRank()) * size / (double(n) * n * n));
    }
  }
  return 0;
}
