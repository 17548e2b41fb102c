// Simulation: field output, probes and the time-series CSV.
#include "app/simulation.hpp"

#include <unistd.h>

#include <climits>
#include <csignal>
#include <cmath>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#include "core/field_names.hpp"
#include "core/index_space.hpp"
#include "io/checkpoint.hpp"
#include "io/fields_out.hpp"
#include "io/probes.hpp"
#include "kernels/reductions.hpp"
#include "scene/reader.hpp"

namespace voigt {

namespace fs = std::filesystem;

namespace {
// Output fields by name; the pressure is shifted by the outflow reference. Their halos
// are exchanged together (one message per neighbour), the velocity's only when stale.
std::vector<OutField> gatherFields(State& st, const std::vector<std::string>& names) {
  std::vector<OutField> out;
  std::vector<Field> halos; // exchanged in one call
  bool velocity = false;
  for (auto& n : names) {
    if (!st.fields.allocated(n))
      throw SceneError(st.scene->path + ": key 'output.fields': field '" + n +
                       "' is not produced by this scene's effects");
    const auto& d = st.fields.decls().at(n);
    OutField f{n, d.centring, {}};
    if (d.components == 3) {
      VecField v = st.fields.vector(n);
      f.comps = {v.c[0], v.c[1], v.c[2]};
      if (n == field::velocity) velocity = true;
      else halos.insert(halos.end(), v.c, v.c + 3);
    } else {
      Field s = st.fields.scalar(n);
      if (n == field::pressure) {
        const double ref = st.diag.count("pressure_reference") ? st.diag.at("pressure_reference") : 0.0;
        Field c("pressure_out", s.extent(0), s.extent(1), s.extent(2));
        shiftedCopy(s, c, ref);
        s = c;
      }
      f.comps = {s};
      halos.push_back(s);
    }
    out.push_back(f);
  }
  if (velocity && !st.velocityHalosCurrent) {
    const VecField v = st.fields.vector(field::velocity);
    halos.insert(halos.end(), v.c, v.c + 3);
    st.velocityHalosCurrent = true;
  }
  if (!halos.empty()) st.halo->exchange(halos);
  return out;
}
} // namespace

bool Simulation::probesDue() const {
  return !opt_.outDir.empty() && probes_ && !scene_.probes.empty() && probes_->due(st_.t);
}

bool Simulation::fieldOutputDue() const {
  return !opt_.outDir.empty() && scene_.output.enabled && scene_.output.interval > 0 &&
         st_.t >= nextOutput_ - 1e-12 * scene_.time.endTime;
}

void Simulation::output(bool force) {
  if (opt_.outDir.empty()) return;
  if (probes_ && !scene_.probes.empty() && (force || probes_->due(st_.t))) {
    std::vector<std::string> names;
    for (auto& p : scene_.probes)
      for (auto& f : p.fields)
        if (std::find(names.begin(), names.end(), f) == names.end()) names.push_back(f);
    probes_->sample(st_.t, gatherFields(st_, names), force);
  }
  const bool due = force || (scene_.output.interval > 0 && st_.t >= nextOutput_ - 1e-12 * scene_.time.endTime);
  if (!due || !scene_.output.enabled) return;
  writer_->write(outputIndex_++, st_.t, gatherFields(st_, scene_.output.fields));
  if (scene_.output.interval > 0)
    while (nextOutput_ <= st_.t + 1e-12 * scene_.time.endTime) nextOutput_ += scene_.output.interval;
}

void Simulation::writeTimeSeries() {
  if (opt_.outDir.empty()) return;
  // Rank 0 writes; every rank learns whether that worked (a full disk stops all).
  int ok = 1;
  std::string err;
  if (st_.grid.rank == 0) {
    const std::string path = opt_.outDir + "/timeseries.csv";
    errno = 0;
    std::error_code ec;
    const bool fresh = !fs::exists(path, ec) || fs::file_size(path, ec) == 0; // new, or a restart elsewhere
    std::ofstream os(path, std::ios::app);
    writeTimeSeriesRow(os, fresh);
    os.flush();
    if (!os) ok = 0, err = path + ": write failed: " + std::strerror(errno ? errno : EIO);
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, st_.grid.comm);
  if (!ok) throw std::runtime_error(st_.grid.rank == 0 ? err : "timeseries.csv write failed (see rank 0)");
}

void Simulation::writeTimeSeriesRow(std::ostream& os, bool header) {
  // Columns are fixed by the first row; a diagnostic that appears later (an
  // effect running every N steps) is left empty until it exists, and one
  // that was not there at the first row is not written, so rows stay aligned.
  if (tsColumns_.empty())
    for (auto& [k, v] : st_.diag) tsColumns_.push_back(k);
  if (header) {
    os << "step,t,dt,dt_reason";
    for (auto& k : tsColumns_) os << "," << k;
    os << "\n";
  }
  os << st_.step << "," << st_.t << "," << st_.dt << "," << st_.dtReason;
  for (auto& k : tsColumns_) {
    os << ",";
    auto it = st_.diag.find(k);
    if (it != st_.diag.end()) os << it->second;
  }
  os << "\n";
}

} // namespace voigt
