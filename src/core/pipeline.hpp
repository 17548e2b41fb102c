#pragma once
// The time step as an ordered list of stages; effects register named tasks
// into stages (Basilisk-style: a scene runs only the physics it lists).
// Stress and Forces are evaluated by the momentum integrator once per
// Runge-Kutta substage; the others run once per step, in this order.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/mpi_traffic.hpp"

namespace voigt {

struct State;

enum class Stage { Properties, Advection, Momentum, Stress, Forces, Projection, Corrections, Diagnostics };
constexpr Stage kStepStages[] = {Stage::Properties, Stage::Advection,   Stage::Momentum,
                                 Stage::Projection, Stage::Corrections, Stage::Diagnostics};
const char* toString(Stage s);

class Pipeline {
 public:
  using Fn = std::function<void(State&)>;
  struct Task {
    std::string effect, name;
    Fn fn;
    std::vector<std::string> after; // effects whose tasks in this stage must run first
  };
  // Appends the task to its stage; `after` names effects (absent ones are
  // ignored) whose tasks in this stage must run before this one, whichever
  // registers first: such a task moves behind them, the others keep their order.
  void add(Stage s, const std::string& effect, const std::string& name, Fn fn, std::vector<std::string> after = {});
  // Runs the tasks of one stage in order, timing each.
  void run(Stage s, State& st);
  const std::vector<Task>& tasks(Stage s) const;
  bool empty(Stage s) const { return tasks(s).empty(); }
  std::string describe() const; // for `voigt check`

  // Wall seconds per stage and per effect (accumulated over the run), and what this rank
  // sent through MPI in each stage (core/mpi_traffic.hpp).
  std::map<std::string, double> stageSeconds, effectSeconds;
  std::map<std::string, mpi_traffic::Counts> stageTraffic;

 private:
  std::map<Stage, std::vector<Task>> tasks_;
};

} // namespace voigt
