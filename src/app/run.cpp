// Simulation::run: the time loop with output, checkpoints (by steps and by wall time),
// signals, the wall-clock limit and the blow-up stop (last good state, non-zero exit).
#include "app/simulation.hpp"

#include <unistd.h>

#include <algorithm>
#include <climits>
#include <csignal>
#include <cmath>
#include <filesystem>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iostream>
#include <sstream>

#include "core/index_space.hpp"
#include "io/checkpoint.hpp"
#include "io/fields_out.hpp"
#include "io/probes.hpp"
#include "kernels/reductions.hpp"
#include "scene/reader.hpp"

namespace voigt {

namespace fs = std::filesystem;

namespace {
std::string utcNow() { // ISO 8601, as the case ledgers write it
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// SIGINT/SIGTERM/SIGUSR1: the handler only records the signal; the time loop acts
// on it between steps, collectively (an MPI_MAX over ranks), so a signal that
// reaches one rank stops them all at the same step. SIGUSR1 is a batch system's
// warning before its time limit (SLURM --signal=USR1@T; Open MPI's mpirun forwards
// it to every rank, where SIGTERM to mpirun kills the ranks 1 s later): it stops
// the run as --wall-limit does (checkpoint, exit 75, resumable).
volatile std::sig_atomic_t gSignal = 0;
extern "C" void onSignal(int s) { gSignal = s; }

struct SignalGuard {
  struct sigaction oldInt{}, oldTerm{}, oldUsr1{};
  bool on = false;
  explicit SignalGuard(bool enable) : on(enable) {
    if (!on) return;
    gSignal = 0;
    struct sigaction sa{};
    sa.sa_handler = onSignal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART | SA_RESETHAND; // a second Ctrl-C kills at once
    sigaction(SIGINT, &sa, &oldInt);
    sigaction(SIGTERM, &sa, &oldTerm);
    // A warning may come twice (to the script and to the run): a second one must not kill.
    sa.sa_flags = SA_RESTART;
    sigaction(SIGUSR1, &sa, &oldUsr1);
  }
  ~SignalGuard() {
    if (!on) return;
    sigaction(SIGINT, &oldInt, nullptr);
    sigaction(SIGTERM, &oldTerm, nullptr);
    sigaction(SIGUSR1, &oldUsr1, nullptr);
  }
};
// --wall-limit: stop before the next step when it, a checkpoint and a margin might
// not fit in what is left. Estimates from the slowest recent step (outputs and
// solver set-ups make some slower) and the last checkpoint write.
struct WallLimit {
  double deadline = 0;  // MPI_Wtime; 0 = no limit
  double margin = 0;
  double steps[8] = {};
  int n = 0;
  void stepTook(double s) { steps[n++ % 8] = s; }
  bool reached(double now, double checkpointSeconds) const {
    double step = 0;
    for (double s : steps) step = std::max(step, s);
    return deadline > 0 && now + 1.25 * step + 1.5 * checkpointSeconds + margin > deadline;
  }
};
} // namespace

RunResult Simulation::run() {
  const Grid& g = st_.grid;
  SignalGuard signals(opt_.handleSignals);
  std::string ckFile;
  if (!opt_.restart.empty()) ckFile = findCheckpoint(g.comm, opt_.restart);
  if (!opt_.outDir.empty()) {
    prepareOutputDir();
    writer_ = std::make_unique<FieldWriter>(g, opt_.outDir);
    checkpointer_ = std::make_unique<Checkpointer>(g, opt_.outDir, ck_.keep);
  }
  initialize();
  const double tEnd = endTime();
  const long maxSteps = opt_.maxSteps >= 0 ? opt_.maxSteps : scene_.time.maxSteps;
  nextOutput_ = scene_.output.interval > 0 ? scene_.output.interval : tEnd;
  if (!ckFile.empty()) {
    const nlohmann::json ckMeta = restore(ckFile);
    if (g.rank == 0) {
      std::cout << "restart: " << ckFile << " (step " << st_.step << ", t = " << st_.t << ")" << std::endl;
      if (!restartSceneCompared_) {
        std::cout << "restart: the checkpoint carries no scene; this one is not compared with it" << std::endl;
      } else if (!restartSceneChanges_.empty()) {
        std::cout << "restart: the scene differs from the checkpoint's in:";
        for (const auto& k : restartSceneChanges_) std::cout << " " << k;
        std::cout << " (the new values apply from here; recorded in scene_segment" << segments_ << ".yaml)" << std::endl;
      }
      if (!opt_.outDir.empty()) recordRestartScene();
      // Rows a crashed run wrote after its checkpoint are written again.
      if (!opt_.outDir.empty()) truncateOutputs(opt_.outDir, ckMeta.value("output_file_sizes", nlohmann::json::object()));
    }
  }
  if (!opt_.outDir.empty()) probes_ = std::make_unique<ProbeSet>(g, scene_.probes, opt_.outDir, ckFile.empty() ? -1 : st_.t);
  if (ckFile.empty()) output(true);
  const bool tty = opt_.progress && isatty(2) && g.rank == 0;
  // Batch logs (stderr not a terminal): a full progress line every kBatchProgressSeconds.
  constexpr double kBatchProgressSeconds = 10;
  const bool batch = opt_.progress && !isatty(2) && g.rank == 0;
  const double w0 = MPI_Wtime();
  double lastProgress = w0;
  runStart_ = w0;
  segmentFirstStep_ = st_.step;
  segmentStartUtc_ = utcNow();
  lastCheckpointWall_ = w0;
  WallLimit wall;
  if (opt_.wallLimit > 0) {
    wall.deadline = (opt_.wallStart >= 0 ? opt_.wallStart : w0) + opt_.wallLimit;
    wall.margin = std::min(60.0, 0.05 * opt_.wallLimit); // summary, MPI_Finalize, clock skew
  }
  // Before the first checkpoint its cost is a guess: 100 MB/s for every field.
  const double ckGuess = 0.5 + double(st_.fields.bytes(g)) * g.size / 1e8;
  const bool wallChecks = opt_.wallLimit > 0 || (ck_.wallInterval > 0 && checkpointer_);
  const long step0 = st_.step;
  const double t0 = st_.t; // the ETA counts from this segment's start
  RunResult r;
  auto finish = [&]() {
    r.steps = st_.step;
    r.simTime = st_.t;
    r.wallSeconds = MPI_Wtime() - w0;
    r.stepsThisRun = st_.step - step0;
    r.wallSecondsTotal = wallBefore_ + r.wallSeconds;
    r.segments = segments_;
    r.cellStepsPerSecond = r.wallSeconds > 0 ? double(g.cellsGlobal()) * r.stepsThisRun / r.wallSeconds : 0;
    const auto capped = st_.counters.find("poisson_unconverged");
    r.poissonCapped = capped == st_.counters.end() ? 0 : long(capped->second);
  };
  // Each step checks the state fields (StepEngine::checkFinite); the derived ones that
  // are about to be written or copied are checked first, once a step.
  const std::vector<std::string> derived = engine_.fieldsWhere(true);
  std::vector<std::string> probeDerived; // the derived fields that probes sample
  for (auto& p : scene_.probes)
    for (auto& f : p.fields)
      if (std::count(derived.begin(), derived.end(), f) && !std::count(probeDerived.begin(), probeDerived.end(), f))
        probeDerived.push_back(f);
  // A blow-up: write the last good state, the summary, and stop (collective).
  auto blowUp = [&](std::string msg, bool currentIsGood) {
    if (currentIsGood && checkpointer_ && !engine_.nonFinite(derived).empty()) currentIsGood = false;
    if (checkpointer_) {
      std::string path;
      if (currentIsGood) path = writeCheckpoint(st_.fields, checkpointMeta());
      else if (haveBackup_) path = writeCheckpoint(backup_, backupMeta_);
      if (!path.empty())
        msg += "; last good state (step " +
               std::to_string(currentIsGood ? st_.step : backupMeta_.at("step").get<long>()) + ") written to " + path;
      else
        msg += "; no last good state kept (checkpoint.last_good is false)";
    }
    finish();
    writeSummary(r, msg);
    throw BlowUp(msg);
  };
  long verified = -1;
  auto verify = [&](const std::vector<std::string>& names) {
    if (names.empty()) return;
    const std::string m = engine_.nonFinite(names);
    if (!m.empty()) blowUp(m, false);
  };
  auto verifyAll = [&] {
    if (verified == st_.step) return;
    verify(derived);
    verified = st_.step;
  };
  while (st_.t < tEnd * (1 - 1e-12) && (maxSteps < 0 || st_.step < maxSteps)) {
    // One collective per step: a signal on any rank, and rank 0's clock decides the
    // wall limit and wall-interval checkpoints, so all ranks act at the same step.
    int flags[3] = {opt_.handleSignals ? int(gSignal) : 0, 0, 0};
    if (g.rank == 0 && wallChecks) {
      const double now = MPI_Wtime(), ck = checkpointsWritten_ > 0 ? checkpointer_->lastSeconds() : ckGuess;
      flags[2] = ck_.wallInterval > 0 && checkpointer_ && now - lastCheckpointWall_ >= ck_.wallInterval;
      flags[1] = wall.reached(now, flags[2] ? 2 * ck : ck); // a wall-interval checkpoint first
    }
    if (opt_.handleSignals || wallChecks) MPI_Allreduce(MPI_IN_PLACE, flags, 3, MPI_INT, MPI_MAX, g.comm);
    if (flags[0] == SIGUSR1) { // the batch system's warning: as the wall limit
      r.wallLimit = true;
      r.wallWarning = true;
      break;
    }
    if (flags[0]) {
      r.signal = flags[0];
      break;
    }
    if (flags[1]) {
      r.wallLimit = true;
      break;
    }
    if (flags[2] && lastCheckpointStep_ != st_.step) {
      verifyAll();
      r.checkpoint = writeCheckpoint(st_.fields, checkpointMeta());
    }
    else if (flags[2]) lastCheckpointWall_ = MPI_Wtime(); // restarted from this very step
    const double stepStart = MPI_Wtime();
    const double dt = engine_.chooseDt(tEnd, scene_.output.interval > 0 ? nextOutput_ : tEnd);
    if (!std::isfinite(dt) || dt <= 0 || (dt < scene_.time.minDt && dt < tEnd - st_.t)) {
      std::ostringstream os;
      os << "blow-up: time step collapsed to " << dt << " (time.min_dt = " << scene_.time.minDt << ") at step "
         << st_.step << ", t = " << st_.t << ", limited by " << st_.dtReason << fastestNode();
      blowUp(os.str(), true);
    }
    dtReasons_[StepEngine::unclipped(st_.dtReason)] += 1;
    if (snapshotDue()) verifyAll();
    snapshot();
    try {
      advance(dt);
    } catch (const BlowUp& e) {
      blowUp(e.what(), false);
    }
    writeTimeSeries();
    if (fieldOutputDue()) verifyAll();
    else if (probesDue()) verify(probeDerived);
    output(false);
    wall.stepTook(MPI_Wtime() - stepStart);
    if (ck_.interval > 0 && st_.step % ck_.interval == 0 && checkpointer_) {
      verifyAll();
      r.checkpoint = writeCheckpoint(st_.fields, checkpointMeta());
    }
    if (tty || (batch && MPI_Wtime() - lastProgress >= kBatchProgressSeconds)) {
      const double now = MPI_Wtime(), el = now - w0, eta = el / (st_.t - t0) * (tEnd - st_.t);
      fprintf(stderr, "%sstep %ld  t = %.5g  dt = %.3g (%s)  %.0f s  ETA %.0f s%s", tty ? "\r" : "", st_.step, st_.t,
              st_.dt, st_.dtReason.c_str(), el, eta, tty ? "   " : "\n");
      lastProgress = now;
    }
  }
  if (tty) fprintf(stderr, "\n");
  finish();
  if (r.signal || r.wallLimit) {
    if (checkpointer_ && lastCheckpointStep_ != st_.step) {
      verifyAll();
      r.checkpoint = writeCheckpoint(st_.fields, checkpointMeta());
    }
    else if (checkpointer_ && r.checkpoint.empty()) r.checkpoint = findCheckpoint(g.comm, opt_.outDir);
    finish(); // the wall time with the checkpoint
    writeSummary(r, r.wallWarning ? std::string("signal SIGUSR1")
                    : r.wallLimit ? std::string("wall_limit")
                                  : std::string("signal ") +
                                        (r.signal == SIGINT ? "SIGINT" : r.signal == SIGTERM ? "SIGTERM" : "?"));
    return r;
  }
  // A run with checkpoints ends with one, so it can be extended (--restart --end-time ...);
  // before the final forced output, which a longer run would not have made.
  if (checkpointer_) verifyAll(); // the final checkpoint and output
  if ((ck_.interval > 0 || ck_.wallInterval > 0) && checkpointer_ && lastCheckpointStep_ != st_.step)
    r.checkpoint = writeCheckpoint(st_.fields, checkpointMeta());
  if (scene_.output.interval == 0 || outputIndex_ == 0 || nextOutput_ - scene_.output.interval < st_.t - 1e-12)
    output(true);
  writeSummary(r, "");
  return r;
}

} // namespace voigt
