// Simulation: the output directory, checkpoints (write, restore, last good
// state) and summary.json, all written atomically (temporary file, rename).
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

#include "core/build_info.hpp"
#include "core/host_access.hpp"
#include "core/index_space.hpp"
#include "io/checkpoint.hpp"
#include "io/fields_out.hpp"
#include "io/probes.hpp"
#include "kernels/reductions.hpp"
#include "scene/reader.hpp"

#include <yaml-cpp/yaml.h>

namespace voigt {

namespace fs = std::filesystem;

namespace {
// Files a Voigt run writes: --overwrite removes a directory only if it holds
// nothing else (it never deletes a directory it did not make).
bool isVoigtOutput(const fs::path& dir) {
  std::error_code ec;
  for (auto& e : fs::directory_iterator(dir, ec)) {
    const std::string n = e.path().filename().string();
    auto starts = [&](const char* p) { return n.rfind(p, 0) == 0; };
    if (!(starts("fields") || starts("probe_") || starts("checkpoint") || n == "summary.json" ||
          n == "timeseries.csv" || n == "latest" || n == "latest.tmp" || starts("timeseries.csv") ||
          starts("scene.yaml") || starts("scene_segment")))
      return false;
  }
  return !ec;
}
} // namespace


void Simulation::prepareOutputDir() {
  const Grid& g = st_.grid;
  int bad = 0;
  std::string msg;
  if (g.rank == 0) {
    std::error_code ec;
    const bool exists = fs::exists(opt_.outDir, ec);
    if (exists && !fs::is_directory(opt_.outDir, ec)) {
      bad = 1, msg = "output path '" + opt_.outDir + "' exists and is not a directory";
    } else if (!opt_.restart.empty()) {
      // Restarting continues in place: keep everything.
    } else if (exists && !fs::is_empty(opt_.outDir, ec)) {
      if (!opt_.overwrite)
        bad = 1, msg = "output directory '" + opt_.outDir + "' exists and is not empty (use --overwrite)";
      else if (!isVoigtOutput(opt_.outDir))
        bad = 1, msg = "output directory '" + opt_.outDir +
                       "' holds files Voigt did not write; --overwrite only replaces Voigt output (remove it yourself)";
      else {
        fs::remove_all(opt_.outDir, ec);
        if (ec) bad = 1, msg = "cannot remove output directory '" + opt_.outDir + "': " + ec.message();
      }
    }
    if (!bad) {
      fs::create_directories(opt_.outDir, ec);
      if (ec) bad = 1, msg = "cannot create output directory '" + opt_.outDir + "': " + ec.message();
    }
    if (!bad) { // writable? (a read-only or full file system says so here, before any work)
      const std::string probe = opt_.outDir + "/.voigt_write_test";
      errno = 0;
      FILE* f = std::fopen(probe.c_str(), "w");
      const bool ok = f && std::fputs("ok\n", f) >= 0 && std::fflush(f) == 0;
      const int e = errno;
      if (f) std::fclose(f);
      std::remove(probe.c_str());
      if (!ok)
        bad = 1, msg = "output directory '" + opt_.outDir + "' is not writable: " + std::strerror(e ? e : EIO);
    }
    if (!bad && opt_.restart.empty()) { // a restart records its scene once it has restored (run.cpp)
      try {
        writeSceneRecord("scene.yaml", "segment 1");
      } catch (const std::exception& e) {
        bad = 1, msg = e.what();
      }
    }
  }
  MPI_Bcast(&bad, 1, MPI_INT, 0, g.comm);
  if (bad) {
    unsigned long long n = msg.size();
    MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, g.comm);
    msg.resize(n);
    MPI_Bcast(msg.data(), int(n), MPI_CHAR, 0, g.comm);
    throw std::runtime_error(msg);
  }
}

nlohmann::json Simulation::checkpointMeta() const {
  nlohmann::json j;
  j["scene"] = scene_.name;
  j["scene_yaml"] = sceneYaml_; // a restart names the sections it changes
  j["t"] = st_.t;
  j["dt"] = st_.dt;
  j["step"] = st_.step;
  j["dt_reason"] = st_.dtReason;
  j["diag"] = st_.diag;
  j["counters"] = st_.counters;
  j["wall_seconds_total"] = wallBefore_ + (runStart_ < 0 ? 0.0 : MPI_Wtime() - runStart_); // NaN -> null
  j["run_segments"] = segments_;
  j["segment_history"] = segmentRecord();
  j["next_output"] = nextOutput_;
  j["output_index"] = outputIndex_;
  j["dt_reasons"] = dtReasons_;
  j["timeseries_columns"] = tsColumns_;
  j["output_entries"] = writer_ ? writer_->entries() : nlohmann::json::array();
  // Sizes of the append-only text outputs: a restart cuts them back to these,
  // dropping what a crashed run wrote after the checkpoint (rank 0's view).
  nlohmann::json sizes = nlohmann::json::object();
  if (!opt_.outDir.empty() && st_.grid.rank == 0) {
    std::vector<std::string> names{"timeseries.csv"};
    for (auto& p : scene_.probes) names.push_back("probe_" + p.name + ".csv");
    for (auto& n : names) {
      std::error_code ec;
      const auto sz = fs::file_size(opt_.outDir + "/" + n, ec);
      sizes[n] = ec ? 0 : (long long)sz;
    }
  }
  j["output_file_sizes"] = sizes;
  nlohmann::json eff = nlohmann::json::object();
  for (auto& e : effects_) {
    nlohmann::json s = nlohmann::json::object();
    e->saveState(s);
    eff[e->name()] = s;
  }
  j["effects"] = eff;
  return j;
}

// The segments so far, this one last: which binary ran which steps (a long run may
// continue on a newer build; its results differ from one binary's by round-off at most
// when the revisions only sped it up, and the record says where to look if not).
nlohmann::json Simulation::segmentRecord() const {
  nlohmann::json h = segmentHistory_;
  h.push_back({{"segment", segments_},
               {"revision", buildRevision()},
               {"ranks", st_.grid.size},
               {"first_step", segmentFirstStep_},
               {"last_step", st_.step},
               {"wall_seconds", runStart_ < 0 ? 0.0 : MPI_Wtime() - runStart_},
               {"started_utc", segmentStartUtc_}});
  return h;
}

nlohmann::json Simulation::restore(const std::string& file) {
  initialize();
  const nlohmann::json m = readCheckpoint(st_.grid, st_.fields, file);
  auto num = [](const nlohmann::json& v) { return v.is_number() ? v.get<double>() : std::nan(""); };
  st_.t = m.at("t").get<double>();
  st_.dt = m.at("dt").get<double>();
  st_.step = m.at("step").get<long>();
  st_.dtReason = m.value("dt_reason", "");
  st_.diag.clear();
  for (auto& [k, v] : m.at("diag").items()) st_.diag[k] = num(v);
  st_.counters.clear();
  for (auto& [k, v] : m.at("counters").items()) st_.counters[k] = num(v);
  wallBefore_ = num(m.value("wall_seconds_total", nlohmann::json()));
  segments_ = m.value("run_segments", 1L) + 1;
  segmentHistory_ = m.value("segment_history", nlohmann::json::array());
  if (segmentHistory_.empty()) // a checkpoint from before the record: its segments, binaries unknown
    segmentHistory_.push_back({{"segment", 1}, {"segments", segments_ - 1}, {"revision", nullptr},
                               {"first_step", 0}, {"last_step", st_.step}});
  compareScene(m);
  nextOutput_ = m.at("next_output").get<double>();
  outputIndex_ = m.at("output_index").get<int>();
  dtReasons_ = m.at("dt_reasons").get<std::map<std::string, long>>();
  tsColumns_ = m.at("timeseries_columns").get<std::vector<std::string>>();
  if (writer_) writer_->restoreEntries(m.at("output_entries"));
  const auto& eff = m.at("effects");
  for (auto& e : effects_) {
    if (!eff.contains(e->name()))
      throw std::runtime_error(file + ": the checkpoint has no state for effect '" + e->name() + "'");
    e->loadState(eff.at(e->name()));
  }
  // Ghost layers: neighbours' owned values, then each effect's boundary fills.
  for (auto& n : st_.fields.allocatedNames()) {
    const auto& d = st_.fields.decls().at(n);
    if (d.isInt) continue; // masks: set up identically by the effects, not exchanged
    if (d.components == 1) st_.halo->exchange(st_.fields.scalar(n));
    else st_.halo->exchange(st_.fields.vector(n));
  }
  for (auto& e : effects_) e->restored(st_);
  st_.propertiesChanged = true;
  st_.velocityHalosCurrent = false;
  lastCheckpointStep_ = st_.step;
  return m;
}

std::string Simulation::writeCheckpoint(const FieldStore& fields, const nlohmann::json& meta) {
  if (!checkpointer_) return "";
  const std::string path = checkpointer_->write(meta.at("step").get<long>(), fields, meta);
  lastCheckpointStep_ = meta.at("step").get<long>();
  lastCheckpointWall_ = MPI_Wtime();
  checkpointsWritten_ += 1;
  checkpointSeconds_ += checkpointer_->lastSeconds();
  checkpointBytes_ = checkpointer_->lastBytes();
  return path;
}

// The state before a step, for a blow-up's "last good state": refreshed every
// last_good_interval steps (and at the first step of a run).
bool Simulation::snapshotDue() const {
  return ck_.lastGood && checkpointer_ && (!haveBackup_ || st_.step % ck_.lastGoodInterval == 0);
}

void Simulation::snapshot() {
  if (!snapshotDue()) return;
  for (auto& n : st_.fields.allocatedNames()) {
    const auto& d = st_.fields.decls().at(n);
    if (d.isInt) Kokkos::deep_copy(backup_.integer(n), st_.fields.integer(n));
    else if (d.components == 1) Kokkos::deep_copy(backup_.scalar(n), st_.fields.scalar(n));
    else
      for (int c = 0; c < 3; ++c) Kokkos::deep_copy(backup_.vector(n).c[c], st_.fields.vector(n).c[c]);
  }
  backupMeta_ = checkpointMeta();
  haveBackup_ = true;
}

namespace {
// What the ranks sent through MPI (core/mpi_traffic.hpp): per stage and since start-up, for
// rank 0 and the most over the ranks (element-wise; an interior rank has the most
// neighbours). Collective.
nlohmann::json mpiTraffic(const std::map<std::string, mpi_traffic::Counts>& stages, MPI_Comm comm, int rank) {
  std::vector<std::pair<std::string, mpi_traffic::Counts>> all(stages.begin(), stages.end());
  all.emplace_back("", mpi_traffic::now()); // the total
  std::vector<long long> mine, most(2 * mpi_traffic::kKinds * all.size());
  for (const auto& [name, c] : all)
    for (int k = 0; k < mpi_traffic::kKinds; ++k) mine.push_back(c.messages[k]), mine.push_back(c.bytes[k]);
  MPI_Reduce(mine.data(), most.data(), (int)mine.size(), MPI_LONG_LONG, MPI_MAX, 0, comm);
  nlohmann::json j;
  if (rank != 0) return j;
  size_t q = 0;
  for (const auto& [name, c] : all) {
    nlohmann::json& o = name.empty() ? j["total"] : j["per_stage"][name];
    for (int k = 0; k < mpi_traffic::kKinds; ++k, q += 2)
      o[mpi_traffic::name(mpi_traffic::Kind(k))] = {{"messages", mine[q]},     {"bytes", mine[q + 1]},
                                                    {"messages_max", most[q]}, {"bytes_max", most[q + 1]}};
  }
  return j;
}
} // namespace

void Simulation::writeSummary(const RunResult& r, const std::string& stop) {
  if (opt_.outDir.empty()) return;
  const nlohmann::json traffic = mpiTraffic(pipeline_.stageTraffic, st_.grid.comm, st_.grid.rank); // collective
  if (st_.grid.rank != 0) return;
  nlohmann::json j = summary(r);
  // Rank 0's and the most over the ranks: messages (point to point: sends; all to all:
  // destinations with data; collective: calls) and bytes sent. Stress and forces run inside
  // momentum and are counted there too, as their wall seconds are.
  j["mpi"] = traffic;
  // Rank 0's copies between device and host memory by reason (core/host_access.hpp): what a
  // device build moves across the bus; on the host they alias and cost nothing.
  nlohmann::json hc = nlohmann::json::object();
  for (const auto& [why, c] : host_access::copies()) hc[why] = {{"count", c.count}, {"bytes", c.bytes}};
  j["host_copies"] = hc;
  if (host_access::armed()) { // VOIGT_HOST_TOUCH_CHECK: it ran and nothing touched a field
    nlohmann::json& h = j["host_touch_check"];
    h = {{"kernels", host_access::kernels()}, {"deep_copies", host_access::deepCopies()}};
    for (const auto& [stage, w] : host_access::stageWork()) {
      nlohmann::json& o = h["per_stage"][stage.empty() ? "between_stages" : stage];
      o["kernels"] = w.kernels;
      if (host_access::countsPages()) o["bytes_touched"] = w.bytes;
    }
  }
  if (!stop.empty()) j["stopped"] = stop;
  // finished, or why not; stopped by a signal or the wall limit, it continues with --restart.
  const bool blowUp = !stop.empty() && !r.signal && !r.wallLimit;
  j["state"] = stop.empty() ? "finished" : r.wallLimit ? "wall_limit" : r.signal ? "stopped" : "blow_up";
  j["resumable"] = !stop.empty() && !blowUp && !r.checkpoint.empty();
  if (opt_.wallLimit > 0) j["wall_limit_seconds"] = opt_.wallLimit;
  j["end_time"] = endTime(); // what a resume runs to
  const std::string path = opt_.outDir + "/summary.json", tmp = path + ".tmp";
  std::ofstream os(tmp, std::ios::trunc);
  os << j.dump(2) << "\n";
  os.close();
  if (!os || std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
}

} // namespace voigt
