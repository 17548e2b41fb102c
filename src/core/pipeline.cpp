#include "core/pipeline.hpp"

#include <mpi.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "core/field.hpp"

namespace voigt {

const char* toString(Stage s) {
  switch (s) {
    case Stage::Properties: return "properties";
    case Stage::Advection: return "advection";
    case Stage::Momentum: return "momentum";
    case Stage::Stress: return "stress";
    case Stage::Forces: return "forces";
    case Stage::Projection: return "projection";
    case Stage::Corrections: return "corrections";
    case Stage::Diagnostics: return "diagnostics";
  }
  return "?";
}

void Pipeline::add(Stage s, const std::string& effect, const std::string& name, Fn fn,
                   std::vector<std::string> after) {
  auto& ts = tasks_[s];
  auto pos = ts.end();
  for (auto it = ts.begin(); it != ts.end(); ++it)
    if (std::find(it->after.begin(), it->after.end(), effect) != it->after.end()) {
      pos = it;
      break;
    }
  // A task placed early must not land before an effect it follows itself.
  for (auto it = pos; it != ts.end(); ++it)
    if (std::find(after.begin(), after.end(), it->effect) != after.end())
      throw std::logic_error("pipeline: " + effect + " and " + it->effect + " each declare the other first");
  ts.insert(pos, Task{effect, name, std::move(fn), std::move(after)});
}

const std::vector<Pipeline::Task>& Pipeline::tasks(Stage s) const {
  static const std::vector<Task> none;
  auto it = tasks_.find(s);
  return it == tasks_.end() ? none : it->second;
}

void Pipeline::run(Stage s, State& st) {
  auto it = tasks_.find(s);
  if (it == tasks_.end()) return;
  for (auto& t : it->second) {
    const double t0 = MPI_Wtime();
    t.fn(st);
    Kokkos::fence(); // honest timings on asynchronous backends
    const double dt = MPI_Wtime() - t0;
    stageSeconds[toString(s)] += dt;
    effectSeconds[t.effect] += dt;
  }
}

std::string Pipeline::describe() const {
  std::ostringstream os;
  const Stage all[] = {Stage::Properties, Stage::Advection, Stage::Momentum, Stage::Stress,
                       Stage::Forces,     Stage::Projection, Stage::Corrections, Stage::Diagnostics};
  int n = 1;
  for (Stage s : all) {
    const auto& ts = tasks(s);
    if (ts.empty()) continue;
    const bool sub = (s == Stage::Stress || s == Stage::Forces);
    os << "  " << n++ << ". " << toString(s) << (sub ? "  (per Runge-Kutta substage)" : "") << "\n";
    for (auto& t : ts) os << "       - " << t.effect << ": " << t.name << "\n";
  }
  return os.str();
}

} // namespace voigt
