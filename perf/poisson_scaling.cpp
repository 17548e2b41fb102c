// Poisson iterations and time against grid size, both operators, for the
// projections of a lid-driven cavity (Re 100):
//   cold1: step 1 (x0 = 0: there is no previous increment);
//   warm:  step M (x0 = the previous step's increment, what `voigt run` does);
//   cold:  the same step M, same right-hand side, from x0 = 0 (a second simulation
//          replays steps 1..M-1 with the same dt, zeroes the increment, then step M).
// Also the preconditioner set-up (matrix refill + Ifpack2/MueLu compute), which a run
// repeats every step in which the density changed (two-phase scenes): timed on a
// separate solver with this scene's coefficients, first call and a repeat.
// Usage: perf_poisson_scaling [tol] [preconditioner] [sizes...]
//          [--operators=approximate,exact] [--step=M] [--csv]
// Defaults: 1e-8 sgs 32 64 96, both operators, M = 2, a markdown table on stdout.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <vector>

#include "common.hpp"
#include "effects/navier_stokes/navier_stokes.hpp" // poissonSettings()
#include "solvers/poisson.hpp"

using namespace voigt;

namespace {
struct Solve {
  double its = 0, s = 0;
};

// Steps 1..M of the cavity; zeroCold: zero the increment before step M.
// dts: replayed when given (same steps as the first simulation), else filled.
std::vector<Solve> runSteps(const Scene& s, int M, bool zeroCold, std::vector<double>& dts, double& setupFirst,
                            double& setupRepeat, int& nullModes, long long& nnz) {
  RunOptions opt;
  opt.progress = false;
  Simulation sim(s, MPI_COMM_WORLD, opt);
  sim.initialize();
  auto& c = sim.state().counters;
  std::vector<Solve> out;
  const bool replay = !dts.empty();
  for (int m = 1; m <= M; ++m) {
    double dt = replay ? dts[m - 1] : sim.engine().chooseDt(s.time.endTime); // the run's dt rule
    if (!std::isfinite(dt)) dt = 1e-3;
    if (!replay) dts.push_back(dt);
    if (zeroCold && m == M) Kokkos::deep_copy(sim.state().fields.scalar("pressure_increment"), 0.0);
    const double i0 = c["poisson_iterations"], s0 = c["poisson_seconds"];
    sim.advance(dt);
    out.push_back({c["poisson_iterations"] - i0, c["poisson_seconds"] - s0});
  }
  const auto j = sim.summary(RunResult{});
  nullModes = j["poisson"]["null_modes"].get<int>();
  nnz = j["poisson"]["matrix_nonzeros"].get<long long>();
  if (zeroCold) { // set-up cost on a separate solver with this state's coefficients
    auto ps = makePoissonSolver(sim.state().grid, poissonSettings(s.projection));
    const VecField coef = sim.state().fields.vector("proj_coef");
    MPI_Barrier(MPI_COMM_WORLD);
    double t0 = MPI_Wtime();
    ps->setCoefficients(coef);
    Kokkos::fence();
    setupFirst = MPI_Wtime() - t0;
    MPI_Barrier(MPI_COMM_WORLD);
    t0 = MPI_Wtime();
    ps->setCoefficients(coef);
    Kokkos::fence();
    setupRepeat = MPI_Wtime() - t0;
  }
  return out;
}
} // namespace

int main(int argc, char** argv) {
  perf::Env env(argc, argv);
  std::vector<std::string> pos, ops = {"approximate", "exact"};
  int M = 2;
  bool csv = false;
  for (int i = 1; i < argc; ++i) {
    if (!strncmp(argv[i], "--operators=", 12)) {
      ops.clear();
      std::stringstream ss(argv[i] + 12);
      for (std::string o; std::getline(ss, o, ',');) ops.push_back(o);
    } else if (!strncmp(argv[i], "--step=", 7)) {
      M = std::max(2, atoi(argv[i] + 7));
    } else if (!strcmp(argv[i], "--csv")) {
      csv = true;
    } else {
      pos.push_back(argv[i]);
    }
  }
  const std::string tol = pos.size() > 0 ? pos[0] : "1e-8";
  const std::string pc = pos.size() > 1 ? pos[1] : "sgs";
  std::vector<int> sizes;
  for (size_t i = 2; i < pos.size(); ++i) sizes.push_back(atoi(pos[i].c_str()));
  if (sizes.empty()) sizes = {32, 64, 96};
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (perf::rank() == 0) {
    if (csv)
      printf("n,cells,operator,preconditioner,tol,ranks,step,cold1_its,cold1_s,warm_its,warm_s,cold_its,cold_s,"
             "setup_first_s,setup_s,null_modes,nnz\n");
    else
      printf("| n | operator | preconditioner | tol | step 1 its | step 1 s | step %d warm its | warm s | step %d "
             "cold its | cold s | set-up s | null modes |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
             M, M);
  }
  for (int n : sizes) {
    for (const std::string& op : ops) {
      const Scene s = perf::scene(perf::cavity(n, op, pc, tol));
      std::vector<double> dts;
      double f0 = 0, r0 = 0, setupFirst = 0, setupRepeat = 0;
      int nm = 0;
      long long nnz = 0;
      const auto warm = runSteps(s, M, false, dts, f0, r0, nm, nnz);
      const auto cold = runSteps(s, M, true, dts, setupFirst, setupRepeat, nm, nnz);
      if (perf::rank() == 0) {
        if (csv)
          printf("%d,%lld,%s,%s,%s,%d,%d,%.0f,%.4f,%.0f,%.4f,%.0f,%.4f,%.4f,%.4f,%d,%lld\n", n, 1LL * n * n * n,
                 op.c_str(), pc.c_str(), tol.c_str(), size, M, warm[0].its, warm[0].s, warm[M - 1].its,
                 warm[M - 1].s, cold[M - 1].its, cold[M - 1].s, setupFirst, setupRepeat, nm, nnz);
        else
          printf("| %d | %s | %s | %s | %.0f | %.2f | %.0f | %.2f | %.0f | %.2f | %.2f | %d |\n", n, op.c_str(),
                 pc.c_str(), tol.c_str(), warm[0].its, warm[0].s, warm[M - 1].its, warm[M - 1].s, cold[M - 1].its,
                 cold[M - 1].s, setupRepeat, nm);
      }
      fflush(stdout);
    }
  }
  return 0;
}
