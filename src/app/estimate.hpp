#pragma once
// What a run will cost, before it starts (`voigt check --estimate`, `voigt run --estimate`):
// steps from the stable dt, memory per rank, disk for outputs and checkpoints, and the
// wall time from a rate measured in a few in-memory calibration steps (no files written).
#include <mpi.h>
#include <nlohmann/json.hpp>

#include <string>

#include "scene/scene.hpp"

namespace voigt {

struct Estimate {
  long steps = 0;               // to the end time (or max_steps)
  bool stepsLowerBound = false; // dt limited by the flow: it may shrink later
  bool fixedDt = false;
  double dt = 0;                // the dt the count uses
  double dtSetup = 0, dtCalibrated = 0; // stable dt at t = 0 and after the calibration steps
  double tEnd = 0;
  long maxSteps = -1;
  long long cells = 0;
  std::string dtReason;
  double setupSeconds = 0;      // allocation and effect set-up (once)
  int calibrationSteps = 0;
  double secondsPerStep = 0;
  double cellStepsPerSecond = 0;
  double wallSeconds = 0;       // steps x seconds per step + output/checkpoint writes
  double writeSeconds = 0;      // the writes' share, at an assumed disk rate
  long long memoryBytesPerRank = 0;
  bool memoryDoubled = false;   // checkpoint.last_good keeps a second copy of the fields
  long long rssGrowthBytesPerRank = 0; // resident memory the calibration run added (all of it)
  long outputs = 0;
  long long bytesPerOutput = 0;
  long checkpoints = 0;
  int checkpointsKept = 0;
  long long bytesPerCheckpoint = 0;
  long long diskBytes = 0;      // on disk at the end: outputs + kept checkpoints

  nlohmann::json json() const;  // summary.json "estimate"
  std::string text() const;     // what `voigt check --estimate` prints, assumptions included
};

// Collective. tEnd / maxSteps: the run's (overrides applied; <= 0 / < 0: the scene's).
// withOutput: the run writes files (memory: last-good copy; disk: outputs, checkpoints).
Estimate estimateRun(const Scene& scene, MPI_Comm comm, double tEnd = -1, long maxSteps = -1,
                     bool withOutput = true, int calibrationSteps = 5);

// A wall time as the estimate prints it: "42 s", "3.5 min", "2.4 h".
std::string durationText(double seconds);

} // namespace voigt
