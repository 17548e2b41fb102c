#include "core/step_engine.hpp"

#include <mpi.h>

#include <climits>
#include <cmath>
#include <sstream>

#include "core/host_access.hpp"
#include "core/index_space.hpp"
#include "kernels/reductions.hpp"

namespace voigt {

namespace {
constexpr char kClipped[] = " (clipped to output/end)";
}

std::string StepEngine::unclipped(const std::string& reason) {
  const size_t n = sizeof kClipped - 1;
  return reason.size() >= n && reason.compare(reason.size() - n, n, kClipped) == 0 ? reason.substr(0, reason.size() - n)
                                                                                   : reason;
}

DtLimit StepEngine::stableDt() const {
  DtLimit best;
  for (auto& l : limits_) {
    DtLimit d = l(st_);
    if (d.dt < best.dt) best = d;
  }
  return best;
}

DtLimit StepEngine::rule(const DtLimit& stable, double tLeft) const {
  if (time_.dt > 0) return {time_.dt, "fixed"};
  if (time_.maxDt < stable.dt) return {time_.maxDt, "max_dt"};
  if (!std::isfinite(stable.dt)) return {time_.maxDt < 1e300 ? time_.maxDt : tLeft, "nothing moves"};
  return stable;
}

double StepEngine::chooseDt(double tEnd, double tNext) {
  const DtLimit d = rule(time_.dt > 0 ? DtLimit{} : stableDt(), tEnd - st_.t);
  double dt = d.dt;
  st_.dtReason = d.reason;
  // Land exactly on the targets (1e-9 relative slack avoids a sliver step).
  bool clipped = false;
  for (double target : {tNext, tEnd}) {
    if (target > st_.t && st_.t + dt * (1 + 1e-9) >= target) {
      dt = target - st_.t;
      clipped = true;
    }
  }
  if (clipped) st_.dtReason += kClipped;
  return dt;
}

void StepEngine::advance(double dt) {
  st_.dt = dt;
  for (Stage s : kStepStages) p_.run(s, st_);
  st_.t += st_.dt;
  st_.step += 1;
  checkFinite();
  if (!st_.stopRequest.empty()) throw BlowUp("stopped: " + st_.stopRequest);
  for (auto& h : after_) h(st_);
}

long StepEngine::advanceTo(double t, const Each& each, long maxSteps) {
  long n = 0;
  while (st_.t < t * (1 - 1e-12) && (maxSteps < 0 || n < maxSteps)) {
    advance(chooseDt(t));
    ++n;
    if (each) each(st_);
  }
  return n;
}

void StepEngine::advanceSteps(long n, double dt, const Each& each) {
  for (long i = 0; i < n; ++i) {
    advance(dt);
    if (each) each(st_);
  }
}

std::vector<std::string> StepEngine::fieldsWhere(bool derived) const {
  std::vector<std::string> out;
  for (auto& name : st_.fields.allocatedNames()) {
    const auto& d = st_.fields.decls().at(name);
    if (!d.isInt && d.derived == derived) out.push_back(name);
  }
  return out;
}

void StepEngine::checkFinite() const {
  if (stateNames_.empty()) stateNames_ = fieldsWhere(false);
  const std::string m = nonFinite(stateNames_);
  if (!m.empty()) throw BlowUp(m);
}

std::string StepEngine::nonFinite(const std::vector<std::string>& names) const {
  const Grid& g = st_.grid;
  // Every real field component with its owned range, enumerated once for both paths.
  struct Component {
    std::string name;
    int c, components;
    bool cell;
  };
  std::vector<Component> comps;
  std::vector<Field> arrays;
  std::vector<Range3> ranges;
  for (auto& name : names) {
    const auto& d = st_.fields.decls().at(name);
    if (d.isInt) continue;
    const bool cell = d.centring == Centring::Cell;
    for (int c = 0; c < d.components; ++c) {
      comps.push_back({name, c, d.components, cell});
      arrays.push_back(d.components == 1 ? st_.fields.scalar(name) : st_.fields.vector(name).c[c]);
      ranges.push_back(cell ? cellRange(g) : nodeRange(g));
    }
  }
  // Fast path, every step: one fused count (tables rebuilt when an array changes) and one
  // Allreduce. Only a blow-up pays for the search below (a reduction and Allreduces each).
  std::string key;
  for (auto& n : names) key += n + "\n";
  auto& scan = scans_[key];
  bool same = scan && int(arrays.size()) == scan->n;
  for (size_t q = 0; same && q < arrays.size(); ++q) same = arrays[q].data() == scan->host[q];
  if (!same) scan = std::make_shared<ArrayBoxes>(arrayBoxes(arrays, ranges));
  long long local = countNonFinite(*scan), total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_LONG_LONG, MPI_SUM, g.comm);
  if (total == 0) return "";
  std::vector<std::string> bad; // every non-finite field component, with its first point
  const long long nx = g.n[0] + 1, ny = g.n[1] + 1;
  for (size_t q = 0; q < arrays.size(); ++q) {
    const Field f = arrays[q];
    const long long first = firstNonFinite(g, f, ranges[q]);
    long long gfirst = first;
    MPI_Allreduce(&first, &gfirst, 1, MPI_LONG_LONG, MPI_MIN, g.comm);
    if (gfirst == LLONG_MAX) continue;
    const int gi = int(gfirst % nx), gj = int((gfirst / nx) % ny), gk = int(gfirst / (nx * ny));
    double v = 0;
    if (first == gfirst) {
      auto h = toHost(Kokkos::subview(f, g.local(0, gi), g.local(1, gj), g.local(2, gk)), "blow_up_report");
      v = h();
    }
    int mine = first == gfirst ? g.rank : g.size, owner = 0;
    MPI_Allreduce(&mine, &owner, 1, MPI_INT, MPI_MIN, g.comm);
    MPI_Bcast(&v, 1, MPI_DOUBLE, owner, g.comm);
    const Component& k = comps[q];
    std::ostringstream os;
    os << "field '" << k.name << "'";
    if (k.components == 3) os << " component " << "xyz"[k.c];
    os << " = " << v << " at " << (k.cell ? "cell" : "node") << " (" << gi << ", " << gj << ", " << gk << ")";
    bad.push_back(os.str());
  }
  if (bad.empty()) return "";
  std::ostringstream os;
  os << "blow-up: non-finite values after step " << st_.step << ", t = " << st_.t << " (dt = " << st_.dt
     << ", limited by " << st_.dtReason << "): ";
  for (size_t i = 0; i < bad.size(); ++i) os << (i ? "; " : "") << bad[i];
  return os.str();
}

} // namespace voigt
