#include "core/pipeline.hpp"

#include <mpi.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "core/field.hpp"
#include "core/host_access.hpp"

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
  ts.push_back(Task{effect, name, std::move(fn), std::move(after)});
  // Registration order, except that a task moves to just behind the last task of
  // an effect it declared `after` (the others keep their relative order).
  auto follows = [](const Task& t, const std::string& e) {
    return std::find(t.after.begin(), t.after.end(), e) != t.after.end();
  };
  for (size_t pass = 0, moved = 1; moved; ++pass) {
    if (pass > ts.size()) throw std::logic_error("pipeline: the tasks of a stage declare a cycle with `after`");
    moved = 0;
    for (size_t i = 0; i < ts.size() && !moved; ++i) {
      size_t last = i;
      for (size_t j = i + 1; j < ts.size(); ++j)
        if (follows(ts[i], ts[j].effect)) last = j;
      if (last != i) {
        Task t = std::move(ts[i]);
        ts.erase(ts.begin() + long(i));
        ts.insert(ts.begin() + long(last), std::move(t)); // lands behind the old ts[last]
        moved = 1;
      }
    }
  }
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
    const mpi_traffic::Counts c0 = mpi_traffic::now();
    const std::string outer = host_access::setStage(toString(s)); // the check's counts by stage
    t.fn(st);
    Kokkos::fence(); // honest timings on asynchronous backends
    host_access::setStage(outer);
    const double dt = MPI_Wtime() - t0;
    stageTraffic[toString(s)] += mpi_traffic::now() - c0;
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
