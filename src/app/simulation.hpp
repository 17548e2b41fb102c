#pragma once
// A simulation: a scene, its grid and effects, the pipeline they fill, and the
// time loop with output. `voigt run` and `voigt check` are thin shells over it,
// and so are the verification tests.
#include <memory>
#include <string>
#include <vector>

#include "core/pipeline.hpp"
#include "core/state.hpp"
#include "effects/effect.hpp"

namespace voigt {

class FieldWriter;
class ProbeSet;

struct RunOptions {
  std::string outDir;      // "" = no output at all (tests)
  bool overwrite = false;
  long maxSteps = -1;      // overrides scene time.max_steps when >= 0
  double endTime = -1;     // overrides scene time.end when > 0
  bool progress = true;    // progress line on stderr (only if it is a terminal)
};

struct RunResult {
  long steps = 0;
  double simTime = 0, wallSeconds = 0;
  double cellStepsPerSecond = 0;
};

class Simulation {
 public:
  Simulation(const Scene& scene, MPI_Comm comm, RunOptions opt = {});
  ~Simulation();

  std::string describe() const; // grid, pipeline, memory, stable dt (voigt check)
  long long bytesPerRank() const { return st_.fields.bytes(st_.grid); }
  DtLimit stableDt() const;
  void initialize();            // allocate fields, set up effects (idempotent)
  void advance(double dt);      // one time step of size dt
  RunResult run();              // until end time or max steps, with output
  State& state() { return st_; }
  const State& state() const { return st_; }
  // The scene's effect of that name, or nullptr (tests and diagnostics).
  Effect* effect(const std::string& name) const {
    for (auto& e : effects_)
      if (e->name() == name) return e.get();
    return nullptr;
  }
  const Pipeline& pipeline() const { return pipeline_; }
  nlohmann::json summary(const RunResult& r) const;

 private:
  double chooseDt(double tEnd, double tNextOut);
  void output(bool force);
  void checkFinite();
  void writeTimeSeries();

  Scene scene_;
  RunOptions opt_;
  State st_;
  Pipeline pipeline_;
  std::vector<std::unique_ptr<Effect>> effects_;
  std::unique_ptr<FieldWriter> writer_;
  std::unique_ptr<ProbeSet> probes_;
  bool initialized_ = false;
  int outputIndex_ = 0;
  double nextOutput_ = 0;
  std::map<std::string, long> dtReasons_;
  std::vector<std::string> tsColumns_; // timeseries.csv columns, fixed by the first row
};

} // namespace voigt
