// The cost of a run before it starts: see estimate.hpp.
#include "app/estimate.hpp"

#include <Kokkos_Core.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "app/simulation.hpp"

namespace voigt {

namespace {
// Assumed disk rate for outputs and checkpoints (not measured: calibration writes nothing).
constexpr double kDiskBytesPerSecond = 2e8, kSecondsPerFile = 0.02;

// Resident memory of this process (Linux /proc), 0 if unknown.
long long residentBytes() {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stoll(line.substr(6)) * 1024;
  return 0;
}

double maxOver(MPI_Comm comm, double v) {
  MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MAX, comm);
  return v;
}

std::string mib(double bytes) {
  std::ostringstream os;
  os.precision(3);
  if (bytes >= 1073741824.0) os << bytes / 1073741824.0 << " GiB";
  else os << bytes / 1048576.0 << " MiB";
  return os.str();
}

std::string dur(double s) {
  std::ostringstream os;
  os.precision(3);
  if (s >= 7200) os << s / 3600 << " h";
  else if (s >= 120) os << s / 60 << " min";
  else os << s << " s";
  return os.str();
}
} // namespace

std::string durationText(double seconds) { return dur(seconds); }

Estimate estimateRun(const Scene& scene, MPI_Comm comm, double tEnd, long maxSteps, bool withOutput,
                     int calibrationSteps) {
  Estimate e;
  if (tEnd <= 0) tEnd = scene.time.endTime;
  if (maxSteps < 0) maxSteps = scene.time.maxSteps;
  const long long rss0 = residentBytes();
  MPI_Barrier(comm);
  double w = MPI_Wtime();
  Simulation sim(scene, comm); // no output directory: nothing is written, no last-good copy
  sim.initialize();
  e.setupSeconds = maxOver(comm, MPI_Wtime() - w);
  const Grid& g = sim.state().grid;
  const TimeCfg& tc = scene.time;
  const DtLimit lim0 = sim.stableDt();
  e.fixedDt = tc.dt > 0;
  e.dtSetup = lim0.dt;
  e.dtReason = lim0.reason;
  // The dt a step takes, by the engine's rule (StepEngine::chooseDt) without the clip to
  // outputs and the end: the calibration runs past neither.
  const StepEngine& engine = sim.engine();
  const double st0 = sim.state().t;
  auto stepDt = [&](const DtLimit& l) { return engine.rule(l, tEnd - st0).dt; };
  // One warm-up step (first solver set-up, first touch of memory), then the timed ones.
  sim.advance(stepDt(lim0));
  Kokkos::fence();
  MPI_Barrier(comm);
  w = MPI_Wtime();
  for (int s = 0; s < calibrationSteps; ++s) sim.advance(stepDt(sim.stableDt()));
  Kokkos::fence();
  e.calibrationSteps = calibrationSteps;
  e.secondsPerStep = maxOver(comm, MPI_Wtime() - w) / std::max(1, calibrationSteps);
  e.cellStepsPerSecond = e.secondsPerStep > 0 ? double(g.cellsGlobal()) / e.secondsPerStep : 0;
  const DtLimit lim1 = sim.stableDt();
  e.dtCalibrated = lim1.dt;
  if (lim1.dt < lim0.dt) e.dtReason = lim1.reason;
  const double dt = e.dt = e.fixedDt ? tc.dt : stepDt(lim1.dt < lim0.dt ? lim1 : lim0);
  e.tEnd = tEnd;
  e.maxSteps = maxSteps;
  e.cells = g.cellsGlobal();
  // Limited by the computed flow's speed: a body that speeds up makes more steps. A
  // prescribed flow is known in advance (and its limit is not counted as a bound).
  const auto has = [&](const char* w) { return e.dtReason.find(w) != std::string::npos; };
  e.stepsLowerBound = !e.fixedDt && dt < tc.maxDt && (has("advect") || has("CFL")) && !has("prescribed");

  // Steps and outputs: the run's loop with this dt, landing on output times and the end.
  const OutputCfg& oc = scene.output;
  const double iv = oc.interval;
  long crossings = 0;
  if (tEnd / dt < 5e7) {
    double t = 0, next = iv > 0 ? iv : tEnd;
    while (t < tEnd * (1 - 1e-12) && (maxSteps < 0 || e.steps < maxSteps)) {
      double d = dt;
      for (double target : {iv > 0 ? next : tEnd, tEnd})
        if (target > t && t + d * (1 + 1e-9) >= target) d = target - t;
      t += d;
      ++e.steps;
      if (iv > 0 && t >= next - 1e-12 * tEnd) {
        ++crossings;
        while (next <= t + 1e-12 * tEnd) next += iv;
      }
    }
    if (iv == 0 || next - iv < t - 1e-12) ++crossings; // the final output, as Simulation::run decides it
  } else { // too many to walk: the plain quotient
    e.steps = long(std::ceil(tEnd / dt));
    if (maxSteps >= 0) e.steps = std::min(e.steps, maxSteps);
    crossings = iv > 0 ? long(std::ceil(tEnd / iv - 1e-9)) : 1;
  }

  // Memory: the fields every rank allocates (the largest rank), and what calibration grew by.
  const auto& decls = sim.state().fields.decls();
  e.memoryDoubled = withOutput && sim.checkpointConfig().lastGood;
  e.memoryBytesPerRank = (long long)maxOver(comm, double(sim.bytesPerRank())) * (e.memoryDoubled ? 2 : 1);
  e.rssGrowthBytesPerRank = (long long)maxOver(comm, double(std::max(0LL, residentBytes() - rss0)));

  // Disk: outputs (first, every interval, last) x fields written; checkpoints hold every field.
  auto points = [&](Centring c) {
    return c == Centring::Cell ? double(g.cellsGlobal()) : double(g.n[0] + 1) * (g.n[1] + 1) * (g.n[2] + 1);
  };
  if (withOutput && oc.enabled) {
    e.outputs = 1 + crossings;
    for (auto& f : oc.fields)
      if (decls.count(f)) e.bytesPerOutput += (long long)(points(decls.at(f).centring) * decls.at(f).components * 8);
  }
  const CheckpointCfg& ck = sim.checkpointConfig();
  if (withOutput && ck.interval > 0) {
    for (auto& [n, d] : decls) e.bytesPerCheckpoint += (long long)(points(d.centring) * d.components * (d.isInt ? 4 : 8));
    e.checkpoints = e.steps / ck.interval + (e.steps % ck.interval ? 1 : 0); // a run with checkpoints ends with one
    e.checkpointsKept = int(std::min<long>(ck.keep, e.checkpoints));
  }
  e.diskBytes = e.outputs * e.bytesPerOutput + e.checkpointsKept * e.bytesPerCheckpoint;
  e.writeSeconds = (e.outputs + e.checkpoints) * kSecondsPerFile +
                   double(e.outputs * e.bytesPerOutput + e.checkpoints * e.bytesPerCheckpoint) / kDiskBytesPerSecond;
  e.wallSeconds = e.steps * e.secondsPerStep + e.writeSeconds;
  return e;
}

nlohmann::json Estimate::json() const {
  return {{"steps", steps},
          {"steps_lower_bound", stepsLowerBound},
          {"dt_setup", dtSetup},
          {"dt_calibrated", dtCalibrated},
          {"dt_reason", fixedDt ? std::string("fixed") : dtReason},
          {"setup_seconds", setupSeconds},
          {"calibration_steps", calibrationSteps},
          {"seconds_per_step", secondsPerStep},
          {"rate_cell_steps_per_second", cellStepsPerSecond},
          {"write_seconds", writeSeconds},
          {"wall_seconds", wallSeconds},
          {"memory_bytes_per_rank", memoryBytesPerRank},
          {"rss_growth_bytes_per_rank", rssGrowthBytesPerRank},
          {"outputs", outputs},
          {"checkpoints", checkpoints},
          {"disk_bytes", diskBytes}};
}

std::string Estimate::text() const {
  std::ostringstream os;
  os.precision(3);
  os << "estimate   (measured on this machine at these ranks; assumptions in 'assumes')\n";
  os << "  steps      " << steps << (stepsLowerBound ? " or more" : "") << " to t = " << tEnd;
  if (maxSteps >= 0 && steps == maxSteps) os << " (time.max_steps)";
  if (fixedDt) os << " with the fixed dt " << dt << " (stable limit at set-up " << dtSetup << ", " << dtReason << ")\n";
  else
    os << " with dt = " << dt << " (" << dtReason << "; " << dtSetup << " at set-up, " << dtCalibrated << " after "
       << calibrationSteps + 1 << " calibration steps)\n"
       << (stepsLowerBound ? "             or more: dt is limited by the flow's speed, so it shrinks as a falling body "
                             "speeds up\n             (a start-up transient, as past a cylinder, can go the other way)\n"
                           : "             dt may still shrink if the flow speeds up until it limits dt\n");
  os << "  memory     " << mib(memoryBytesPerRank) << " per rank in fields"
     << (memoryDoubled ? " (x2: checkpoint.last_good keeps a copy)" : "") << "\n             the calibration run grew by "
     << mib(rssGrowthBytesPerRank) << " resident (fields, Poisson matrix and solver, buffers)\n";
  os << "  disk       " << mib(diskBytes) << ": " << outputs << " outputs x " << mib(bytesPerOutput)
     << " (output.fields, 8 bytes per value)";
  if (checkpoints > 0)
    os << " + " << checkpointsKept << " kept of " << checkpoints << " checkpoints x " << mib(bytesPerCheckpoint);
  os << "; timeseries.csv and probes not counted\n";
  os << "  set-up     " << dur(setupSeconds) << " once (grid, fields, effect set-up)\n";
  os << "  rate       " << cellStepsPerSecond << " cell-steps/s: " << secondsPerStep << " s per step over "
     << calibrationSteps << " steps after 1 warm-up step, " << cells << " cells\n";
  os << "  wall time  " << dur(wallSeconds) << (stepsLowerBound ? " or more" : "") << " = " << steps << " steps x "
     << secondsPerStep << " s + " << dur(writeSeconds) << " writing (assumed " << kDiskBytesPerSecond / 1e6
     << " MB/s + " << kSecondsPerFile << " s per file); set-up not included\n";
  os << "  assumes    the calibration rate holds for the whole run (the first steps of a falling body are cheaper\n"
     << "             than an impact; Poisson iterations may grow), the machine's load stays as now, and\n"
     << "             checkpoint.wall_interval adds no checkpoints\n";
  return os.str();
}

} // namespace voigt
