// voigt: run | check | info. Runs unchanged under mpirun.
#include <CLI/CLI.hpp>
#include <Kokkos_Core.hpp>
#include <mpi.h>

#include <climits>
#include <cmath>
#include <iostream>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <sstream>

#include "app/estimate.hpp"
#include "app/presets_estimate.hpp"
#include "app/simulation.hpp"
#include "core/build_info.hpp"
#include "core/host_access.hpp"
#include "scene/load.hpp"
#include "scene/reader.hpp"

using namespace voigt;

namespace {
int rankOf() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

// --wall-limit: 3h, 170m, 3600s, 3600 (seconds), 2h30m, or SLURM's HH:MM:SS / MM:SS.
// Seconds, or -1 if the text is not such a duration.
double parseDuration(const std::string& text) {
  double total = 0;
  if (text.find(':') != std::string::npos) {
    std::istringstream in(text);
    int parts = 0;
    for (std::string f; std::getline(in, f, ':'); ++parts) {
      if (f.empty() || f.find_first_not_of("0123456789") != std::string::npos || parts == 3) return -1;
      total = total * 60 + std::stod(f);
    }
    if (parts < 2 || text.back() == ':') return -1;
  } else {
    for (size_t i = 0; i < text.size();) {
      if (!std::isdigit(static_cast<unsigned char>(text[i])) && text[i] != '.') return -1;
      size_t used = 0;
      double v = 0;
      try {
        v = std::stod(text.substr(i), &used);
      } catch (const std::exception&) {
        return -1;
      }
      i += used;
      const char u = i < text.size() ? text[i++] : 's';
      const double scale = u == 'd' ? 86400 : u == 'h' ? 3600 : u == 'm' ? 60 : u == 's' ? 1 : -1;
      if (scale < 0) return -1;
      total += v * scale;
    }
  }
  return total > 0 && std::isfinite(total) ? total : -1;
}

int info() {
  if (rankOf() == 0) {
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    std::cout << "voigt " << VOIGT_VERSION << " (" << buildRevision() << ")\n";
    std::cout << "kokkos execution space: " << Kokkos::DefaultExecutionSpace::name()
              << " (concurrency " << Kokkos::DefaultExecutionSpace().concurrency() << ")\n";
    std::cout << "mpi ranks: " << size << "\n";
    std::cout << "instruction set: " << buildIsa() << " (CMake VOIGT_ARCH)\n";
    std::cout << "effects:";
    for (auto& e : effectRegistry()) std::cout << " " << e.name;
    std::cout << "\n";
  }
  return 0;
}

// --presets: the scene under each preset, loaded again from `path` with `sets` (presets_estimate.hpp).
int check(const Scene& scene, bool estimate, bool presets, const std::string& path, const std::vector<std::string>& sets) {
  DtLimit dt;
  {
    Simulation sim(scene, MPI_COMM_WORLD);
    sim.initialize();
    dt = sim.stableDt();
    if (rankOf() == 0) std::cout << sim.describe();
  } // freed before the estimate's calibration run
  if (rankOf() == 0) {
    if (scene.time.dt > 0)
      std::cout << "time step  fixed " << scene.time.dt << " (stable limit " << dt.dt << ", " << dt.reason << ")\n";
    else
      std::cout << "time step  adaptive, first dt = " << dt.dt << " (" << dt.reason << ")\n";
    if (scene.time.dt > dt.dt)
      std::cout << "warning    fixed dt exceeds the stable limit\n";
    std::cout << std::flush;
  }
  if (dt.reason == "viscous") { // what the semi-implicit viscous step would give (collective)
    LoadOptions o = effectLoadOptions(sets);
    o.overrides.push_back("navier_stokes.viscous=semi_implicit");
    Simulation alt(loadScene(path, o), MPI_COMM_WORLD);
    alt.initialize();
    const DtLimit a = alt.stableDt();
    if (rankOf() == 0)
      std::cout << "           navier_stokes.viscous: semi_implicit lifts the viscous limit: first dt = " << a.dt << " ("
                << a.reason << "), " << a.dt / dt.dt << "x; first order in time where dt nu k^2 is not small "
                << "(README, \"Semi-implicit viscosity\")\n"
                << std::flush;
  }
  Estimate e;
  if (estimate) {
    e = estimateRun(scene, MPI_COMM_WORLD);
    if (rankOf() == 0) std::cout << e.text() << std::flush;
  }
  if (presets) { // reuses the scene's calibration when --estimate made one
    const std::string text = presetsReport(scene, path, effectLoadOptions(sets), MPI_COMM_WORLD, estimate ? &e : nullptr);
    if (rankOf() == 0) std::cout << text;
  }
  return 0;
}

int run(const Scene& scene, RunOptions opt, bool estimate) {
  if (estimate) { // before the run's own Simulation, so the two never hold memory at once
    const Estimate e = estimateRun(scene, MPI_COMM_WORLD, opt.endTime, opt.maxSteps);
    if (rankOf() == 0) std::cout << e.text() << std::flush;
    opt.estimate = e.json();
  }
  Simulation sim(scene, MPI_COMM_WORLD, opt);
  const RunResult r = sim.run();
  if (r.signal) {
    if (rankOf() == 0)
      std::cerr << "stopped by signal " << r.signal << " at step " << r.steps << ", t = " << r.simTime
                << (r.checkpoint.empty() ? std::string(" (no checkpoint: no output directory)")
                                         : "; checkpoint " + r.checkpoint + " (continue with --restart)")
                << "\n";
    return 128 + r.signal;
  }
  if (r.wallLimit) {
    std::ostringstream why;
    if (r.wallWarning) why << "stopped by SIGUSR1 (the batch system's time-limit warning)";
    else why << "stopped at the wall limit (" << opt.wallLimit << " s)";
    if (rankOf() == 0)
      std::cerr << why.str() << " at step " << r.steps << ", t = " << r.simTime
                << (r.checkpoint.empty() ? std::string(" (no checkpoint: no output directory)")
                                         : "; checkpoint " + r.checkpoint + "; unfinished, resumable: continue with --restart")
                << " (exit code " << kExitWallLimit << ")\n";
    return kExitWallLimit;
  }
  if (rankOf() == 0) {
    if (r.segments > 1)  // a restarted run: this segment, and the whole run's cost
      std::cout << "done: step " << r.steps << ", t = " << r.simTime << "; this segment " << r.stepsThisRun
                << " steps in " << r.wallSeconds << " s (" << r.cellStepsPerSecond << " cell-steps/s); all "
                << r.segments << " segments " << r.wallSecondsTotal << " s\n";
    else
      std::cout << "done: " << r.steps << " steps to t = " << r.simTime << " in " << r.wallSeconds << " s ("
                << r.cellStepsPerSecond << " cell-steps/s)\n";
    if (r.poissonCapped > 0)
      std::cout << "warning: " << r.poissonCapped << " Poisson solve" << (r.poissonCapped > 1 ? "s" : "")
                << " stopped at the iteration cap (projection.max_iterations; summary.json poisson.unconverged)\n";
    if (!opt.outDir.empty())
      std::cout << "output: " << opt.outDir << "/fields.xdmf (open in ParaView: File > Open, choose the "
                << "Xdmf3 reader), summary.json, timeseries.csv\n";
  }
  return 0;
}
} // namespace

int main(int argc, char** argv) {
#if defined(__GLIBC__)
  // Keep freed memory in the process: MueLu's set-up allocates and frees the same large
  // arrays (the R A P products) at every step; glibc served each from mmap and gave it
  // back at free, so every step page-faulted and zeroed them again (perf/README.md,
  // "Allocator": falling block 75^3 2-3 % a step). Peak RSS grows ~3 % (fragmentation).
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
#endif
  MPI_Init(&argc, &argv);
  const double start = MPI_Wtime(); // --wall-limit counts from here
  int code = 0;
  {
    // Kokkos sees only its own --kokkos-* options: a plain --help is ours.
    std::vector<char*> kargv{argv[0]}, appArgv{argv[0]};
    for (int i = 1; i < argc; ++i)
      (std::string(argv[i]).rfind("--kokkos-", 0) == 0 ? kargv : appArgv).push_back(argv[i]);
    int kargc = int(kargv.size());
    kargv.push_back(nullptr);
    Kokkos::ScopeGuard kokkos(kargc, kargv.data());
    host_access::armFromEnvironment(); // VOIGT_HOST_TOUCH_CHECK=1: core/host_access.hpp
    CLI::App app{"Voigt: fluids and elastic solids on one Eulerian grid"};
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("voigt ") + VOIGT_VERSION + " (" + buildRevision() + ")");
    std::string scenePath, outDir;
    std::vector<std::string> sets;
    long steps = -1;
    double endTime = -1;
    bool overwrite = false, restart = false, estimate = false, presets = false;
    std::string restartFrom, wallLimit;
    auto* runCmd = app.add_subcommand("run", "run a scene");
    runCmd->add_option("scene", scenePath, "scene YAML file")->required();
    runCmd->add_option("-o,--output", outDir, "output directory (default output/<scene name>)");
    runCmd->add_option("--set", sets, "override a scene value: a.b.c=value");
    runCmd->add_option("--steps", steps, "stop after N steps");
    runCmd->add_option("--end-time", endTime, "stop at this simulated time");
    runCmd->add_flag("--overwrite", overwrite, "replace an existing output directory (of Voigt output only)");
    runCmd->add_flag("--restart", restart,
                     "continue from the newest readable checkpoint in the output directory (scene key "
                     "checkpoint.interval); output is appended there");
    runCmd->add_option("--restart-from", restartFrom, "continue from this checkpoint file or directory");
    runCmd->add_flag("--estimate", estimate,
                     "first print the cost estimate (as voigt check --estimate) and record it in summary.json");
    runCmd->add_option("--wall-limit", wallLimit,
                       "wall-clock limit from voigt's start (3h, 170m, 3600s, 3600, 02:50:00): before it, write a "
                       "checkpoint and exit with code 75 (unfinished, resumable with --restart)")
        ->check([](const std::string& v) {
          return parseDuration(v) > 0 ? std::string() : "'" + v + "' is not a duration (3h, 170m, 3600s, 02:50:00)";
        });
    runCmd->footer("Exit codes: 0 done, 2 bad scene, 3 blow-up (last good state written), 75 stopped "
                   "at --wall-limit (checkpoint written; continue with --restart), 128 + N stopped by signal N "
                   "(SIGINT, SIGTERM: checkpoint written; SIGUSR1, a batch system's warning, stops as the wall limit: 75), 1 other errors; bad arguments: CLI11's codes (>= 100).");
    auto* checkCmd = app.add_subcommand("check", "validate a scene and print what a run would do");
    checkCmd->add_option("scene", scenePath, "scene YAML file")->required();
    checkCmd->add_option("--set", sets, "override a scene value: a.b.c=value");
    checkCmd->add_flag("--estimate", estimate,
                       "also estimate the run's steps, memory, disk and wall time from a few calibration steps "
                       "(in memory, nothing written)");
    checkCmd->add_flag("--presets", presets,
                       "what accuracy costs here: the value of each preset knob and the estimated steps and wall "
                       "time of the scene as written and under the presets fast, balanced and accurate (one "
                       "calibration each); measured errors: perf/accuracy/README.md");
    app.add_subcommand("info", "version, Kokkos backend, MPI ranks");
    try {
      app.parse(int(appArgv.size()), appArgv.data());
      if (app.got_subcommand("info")) {
        code = info();
      } else {
        Scene scene = loadScene(scenePath, effectLoadOptions(sets));
        if (app.got_subcommand("check")) {
          code = check(scene, estimate, presets, scenePath, sets);
        } else {
          RunOptions opt;
          opt.outDir = outDir.empty() ? "output/" + scene.name : outDir;
          opt.overwrite = overwrite;
          opt.maxSteps = steps;
          opt.endTime = endTime;
          opt.restart = !restartFrom.empty() ? restartFrom : restart ? opt.outDir : "";
          opt.handleSignals = true;
          if (!wallLimit.empty()) opt.wallLimit = parseDuration(wallLimit), opt.wallStart = start;
          code = run(scene, opt, estimate);
        }
      }
    } catch (const CLI::ParseError& e) {
      code = rankOf() == 0 ? app.exit(e) : 2;
      if (code == 0 && !e.get_exit_code()) code = 0;
    } catch (const BlowUp& e) {
      if (rankOf() == 0) std::cerr << "error: " << e.what() << "\n";
      code = kExitBlowUp;
    } catch (const SceneError& e) {
      if (rankOf() == 0) std::cerr << "error: " << e.what() << "\n";
      code = 2;
    } catch (const std::exception& e) {
      std::cerr << "error (rank " << rankOf() << "): " << e.what() << "\n";
      code = 1;
    }
  }
  MPI_Finalize();
  return code;
}
