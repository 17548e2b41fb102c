#pragma once
// A simulation: a scene, its grid and effects, the pipeline they fill, and the
// time loop with output. `voigt run` and `voigt check` are thin shells over it,
// and so are the verification tests.
#include <iosfwd>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/pipeline.hpp"
#include "core/state.hpp"
#include "core/step_engine.hpp"
#include "effects/effect.hpp"

namespace voigt {

class FieldWriter;
class ProbeSet;
class Checkpointer;

// BlowUp (core/step_engine.hpp): a field went non-finite or dt collapsed.
constexpr int kExitBlowUp = 3;
// --wall-limit reached: a checkpoint was written, the run is unfinished and resumable
// (--restart). 75 is sysexits' EX_TEMPFAIL: "try again later".
constexpr int kExitWallLimit = 75;

struct RunOptions {
  std::string outDir;      // "" = no output at all (tests)
  bool overwrite = false;
  long maxSteps = -1;      // overrides scene time.max_steps when >= 0
  double endTime = -1;     // overrides scene time.end when > 0
  bool progress = true;    // progress on stderr: a live line on a terminal, else a line every 10 s
  // Restart from a checkpoint: a checkpoint file, or a directory whose newest
  // readable checkpoint is used (`voigt run --restart`: the output directory).
  std::string restart;
  // SIGINT/SIGTERM: finish the current step, write a checkpoint, stop (voigt run);
  // SIGUSR1 the same, reported as the wall limit (exit 75, resumable).
  bool handleSignals = false;
  // Wall-clock limit in seconds (0: none), counted from MPI_Wtime() == wallStart (voigt's
  // start; -1: run()'s start). Before it would be passed, the run checkpoints and stops.
  double wallLimit = 0;
  double wallStart = -1;
  nlohmann::json estimate;  // `voigt run --estimate`: recorded in summary.json beside the measurement
};

// Scene section `checkpoint` (all optional):
//   interval: N     write a checkpoint every N steps (0 = never; default 0)
//   keep: K         keep the newest K checkpoints (default 2)
//   last_good: b    keep a copy of an earlier step's fields in memory so a
//                   blow-up can write the last good state (default true; it
//                   doubles the field memory)
//   wall_interval: S  also write one when S seconds of wall time have passed since
//                   the last (0 = never; default 0)
//   last_good_interval: N  refresh that copy every N steps (default 10): the
//                   state a blow-up leaves is at most N steps old. The copy is
//                   all fields, 4 % of a falling-block step when made every step.
struct CheckpointCfg {
  long interval = 0;
  double wallInterval = 0;
  int keep = 2;
  bool lastGood = true;
  long lastGoodInterval = 10;
};

struct RunResult {
  long steps = 0;             // the step reached (a restarted run counts from step 0)
  long stepsThisRun = 0;      // steps taken by this process
  double simTime = 0, wallSeconds = 0;  // wallSeconds: this process
  double wallSecondsTotal = 0;  // with the earlier segments' checkpointed steps (NaN: unknown)
  long segments = 1;          // this run and the restarts before it
  double cellStepsPerSecond = 0;
  long poissonCapped = 0;     // Poisson solves that stopped at their iteration cap (whole run)
  int signal = 0;            // SIGINT/SIGTERM that stopped the run (0: it ran to the end)
  bool wallLimit = false;    // stopped before RunOptions::wallLimit or by SIGUSR1 (resumable)
  bool wallWarning = false;  // ... because of SIGUSR1, the batch system's warning
  std::string checkpoint;    // the last checkpoint written ("" if none)
};

class Simulation {
 public:
  Simulation(const Scene& scene, MPI_Comm comm, RunOptions opt = {});
  ~Simulation();

  std::string describe() const; // grid, pipeline, memory, stable dt (voigt check)
  long long bytesPerRank() const { return st_.fields.bytes(st_.grid); }
  DtLimit stableDt() const;
  void initialize();            // allocate fields, set up effects (idempotent)
  void advance(double dt);      // one time step of size dt (StepEngine::advance)
  // Steps with the scene's dt rule until t, landing on it (StepEngine::advanceTo).
  long advanceTo(double t, const StepEngine::Each& each = {}, long maxSteps = -1);
  StepEngine& engine() { return engine_; }
  RunResult run();              // until end time or max steps, with output
  double endTime() const { return opt_.endTime > 0 ? opt_.endTime : scene_.time.endTime; } // --end-time wins
  State& state() { return st_; }
  const State& state() const { return st_; }
  // The scene's effect of that name, or nullptr (tests and diagnostics).
  Effect* effect(const std::string& name) const {
    for (auto& e : effects_)
      if (e->name() == name) return e.get();
    return nullptr;
  }
  const Pipeline& pipeline() const { return pipeline_; }
  Pipeline& pipeline() { return pipeline_; } // tests add tasks (e.g. a fault to inject)
  nlohmann::json summary(const RunResult& r) const;
  const CheckpointCfg& checkpointConfig() const { return ck_; }
  // Everything but the fields that a checkpoint holds (io/checkpoint.hpp).
  nlohmann::json checkpointMeta() const;
  // Collective: loads a checkpoint file (fields and meta) into an initialized
  // simulation and rebuilds the ghost layers as a normal step leaves them.
  nlohmann::json restore(const std::string& checkpointFile);

 private:
  void output(bool force);
  bool fieldOutputDue() const; // output(false) would write fields now
  bool probesDue() const;      // ... or sample probes
  bool snapshotDue() const; // snapshot() would copy the fields now
  std::string fastestNode() const;
  void writeTimeSeries();
  void writeTimeSeriesRow(std::ostream& os, bool header);
  void prepareOutputDir();
  void writeSceneRecord(const std::string& file, const std::string& note) const; // scene_record.cpp
  void compareScene(const nlohmann::json& checkpointMeta);
  void recordRestartScene() const;
  std::string writeCheckpoint(const FieldStore& fields, const nlohmann::json& meta);
  void snapshot();
  void writeSummary(const RunResult& r, const std::string& stop);

  Scene scene_;
  std::string sceneYaml_;  // scene_.root dumped once: every checkpoint (and last-good snapshot) carries it
  RunOptions opt_;
  State st_;
  Pipeline pipeline_;
  StepEngine engine_;  // the time step and its dt (core/step_engine.hpp)
  std::vector<std::unique_ptr<Effect>> effects_;
  std::unique_ptr<FieldWriter> writer_;
  std::unique_ptr<ProbeSet> probes_;
  bool initialized_ = false;
  int outputIndex_ = 0;
  double nextOutput_ = 0;
  std::map<std::string, long> dtReasons_;
  std::vector<std::string> tsColumns_; // timeseries.csv columns, fixed by the first row
  CheckpointCfg ck_;
  std::unique_ptr<Checkpointer> checkpointer_;
  FieldStore backup_;          // fields before the current step (ck_.lastGood)
  nlohmann::json backupMeta_;  // and the rest of that state
  bool haveBackup_ = false;
  long lastCheckpointStep_ = -1;
  double lastCheckpointWall_ = 0;  // MPI_Wtime after the last checkpoint (checkpoint.wall_interval)
  long checkpointsWritten_ = 0;
  double checkpointSeconds_ = 0;
  long long checkpointBytes_ = 0;
  // A run continued over restarts: the wall time up to the checkpoint it started from (NaN if
  // that checkpoint predates the record) and the number of segments; checkpoints carry both.
  double wallBefore_ = 0;
  double runStart_ = -1;  // MPI_Wtime when run() started its loop
  long segments_ = 1;
  // Provenance per segment: the earlier ones (from the checkpoint) and this one's start;
  // segmentRecord() adds this one (binary revision, ranks, steps, wall time).
  nlohmann::json segmentHistory_ = nlohmann::json::array();
  long segmentFirstStep_ = 0;
  std::string segmentStartUtc_;
  nlohmann::json segmentRecord() const;
  std::vector<std::string> restartSceneChanges_; // top-level scene keys unlike the checkpoint's
  bool restartSceneCompared_ = false;            // false: fresh run, or checkpoint without a scene
};

} // namespace voigt
