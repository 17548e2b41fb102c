#pragma once
// The step engine: one time step through the pipeline's stages, and the dt it takes.
// `voigt run`, the tests and perf all step through it; none writes its own time loop.
//
//   dt = time.dt                          (fixed step), else
//   dt = min(stable limit, time.max_dt)   (adaptive: the smallest of the effects' limits)
//   infinite (nothing moves): time.max_dt if set, else the time left to the end;
//   then clipped to land exactly on the next target (an output time, the end),
//   with 1e-9 relative slack so that no sliver step is left.
//
// A step runs the stages of kStepStages in order, advances t and the step count,
// checks the state fields for non-finite values (one fused count and one Allreduce; BlowUp
// names the first bad point of each field), honours State::stopRequest, then the after-step
// hooks run (diagnostics of the finished step, e.g. the kinetic energy).
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/pipeline.hpp"
#include "core/state.hpp"

namespace voigt {

struct ArrayBoxes;

// A run stopped because a field went non-finite or dt collapsed; what() names
// the field, the cell (global i, j, k), the time, and where the last good
// state was written. `voigt run` exits with kExitBlowUp.
struct BlowUp : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class StepEngine {
 public:
  using Limit = std::function<DtLimit(const State&)>;
  using Hook = std::function<void(State&)>;
  using Each = std::function<void(const State&)>;

  StepEngine(State& st, Pipeline& p, const TimeCfg& time) : st_(st), p_(p), time_(time) {}
  void addLimit(Limit l) { limits_.push_back(std::move(l)); }   // an effect's stable-dt limit
  void addAfterStep(Hook h) { after_.push_back(std::move(h)); } // runs after each good step

  // The smallest of the limits (infinite, reason "none", when nothing limits).
  DtLimit stableDt() const;
  // The rule above without the landing: the step `stable` allows, with tLeft the time
  // left (the step when nothing moves and time.max_dt is not set).
  DtLimit rule(const DtLimit& stable, double tLeft) const;
  // The dt of the next step by the rule above, landing on the targets that lie
  // ahead; sets State::dtReason ("... (clipped to output/end)" when it landed).
  double chooseDt(double tEnd, double tNext = std::numeric_limits<double>::infinity());
  // A reason without chooseDt's landing note (a limit's own text may hold " (...)").
  static std::string unclipped(const std::string& reason);
  // One step of size dt. Throws BlowUp on a non-finite value or a stop request.
  void advance(double dt);
  // Steps with chooseDt until t is reached exactly (the loop `voigt run` makes,
  // without output), or maxSteps steps (< 0: no cap); `each` sees the state after
  // every step. Returns the steps taken.
  long advanceTo(double t, const Each& each = {}, long maxSteps = -1);
  // n steps of one size dt (a uniformly sampled record, e.g. for a Prony fit).
  void advanceSteps(long n, double dt, const Each& each = {});
  // Throws BlowUp naming every non-finite field component and its first point
  // in global (k, j, i) order (the same point whatever the decomposition). Each
  // step checks the state fields only: a derived field is recomputed from them
  // within a step, so a non-finite value there reaches the state by the next step
  // (FieldStore::Decl::derived). Whoever writes or copies fields (output, probes,
  // checkpoints, the last good state) first checks the derived ones it takes.
  void checkFinite() const;
  // What checkFinite would throw for these fields (integer ones skipped); "" when
  // every value is finite. Collective.
  std::string nonFinite(const std::vector<std::string>& names) const;
  // The allocated real fields that are derived (true) or state (false).
  std::vector<std::string> fieldsWhere(bool derived) const;

 private:
  State& st_;
  Pipeline& p_;
  TimeCfg time_;
  std::vector<Limit> limits_;
  std::vector<Hook> after_;
  mutable std::vector<std::string> stateNames_;
  // Device tables of each scanned field set (kernels/reductions.hpp), by the names.
  mutable std::map<std::string, std::shared_ptr<ArrayBoxes>> scans_;
};

} // namespace voigt
