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

#include "core/index_space.hpp"
#include "io/checkpoint.hpp"
#include "io/fields_out.hpp"
#include "io/probes.hpp"
#include "kernels/reductions.hpp"
#include "scene/reader.hpp"

namespace voigt {

namespace fs = std::filesystem;

namespace {
// Physical memory available to this process group, from sysconf.
double availableBytes() {
  return double(sysconf(_SC_AVPHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
}

// Scene checks that need the effects' field declarations; run at construction,
// so `voigt check` reports them and `voigt run` refuses before it makes the
// output directory. Collective.
void checkSceneAgainstFields(const Scene& sc, const State& st, bool backup) {
  // Refuse a grid that cannot fit before touching memory: sum over the ranks
  // sharing this node's memory, compare with what the node has free.
  double need = double(st.fields.bytes(st.grid)) * (backup ? 2 : 1), total = need;
  MPI_Comm node;
  MPI_Comm_split_type(st.grid.comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  MPI_Allreduce(&need, &total, 1, MPI_DOUBLE, MPI_SUM, node);
  MPI_Comm_free(&node);
  int tooBig = total > 0.9 * availableBytes(), any = 0;
  MPI_Allreduce(&tooBig, &any, 1, MPI_INT, MPI_MAX, st.grid.comm);
  if (any)
    topSection(sc, "domain").fail("cells", "the fields need " + std::to_string(total / 1073741824.0) +
                                               " GiB but only " + std::to_string(availableBytes() / 1073741824.0) +
                                               " GiB of memory is available" + (backup ? " (x2: checkpoint.last_good)" : ""));
  // Output and probe fields the scene names must be fields its effects make
  // (the defaults, velocity and pressure, are checked when written).
  const Section top(sc.root, "", sc.source);
  auto known = [&](const std::string& f) { return st.fields.decls().count(f) > 0; };
  const std::string why = "' is not produced by this scene's effects";
  const Section out = topSection(sc, "output");
  if (sc.output.enabled && out.has("fields"))
    for (size_t i = 0; i < sc.output.fields.size(); ++i)
      if (!known(sc.output.fields[i])) out.failItem("fields", i, "field '" + sc.output.fields[i] + why);
  const std::vector<Section> probes = sc.source ? top.list("probes") : std::vector<Section>{};
  for (size_t p = 0; p < probes.size() && p < sc.probes.size(); ++p)
    for (size_t i = 0; probes[p].has("fields") && i < sc.probes[p].fields.size(); ++i)
      if (!known(sc.probes[p].fields[i])) probes[p].failItem("fields", i, "field '" + sc.probes[p].fields[i] + why);
}
} // namespace

Simulation::Simulation(const Scene& scene, MPI_Comm comm, RunOptions opt) : scene_(scene), opt_(opt) {
  st_.scene = &scene_;
  std::array<bool, 3> per{scene_.periodic(0), scene_.periodic(1), scene_.periodic(2)};
  try {
    st_.grid = makeGrid(comm, scene_.cells, scene_.lo, scene_.hi, per, scene_.ranks);
  } catch (const std::runtime_error& e) { // the same on every rank: a scene error at domain.ranks or .cells
    const std::string m = e.what();
    topSection(scene_, "domain").fail(m.find("rank grid") != std::string::npos ? "ranks" : "cells",
                                      m.substr(m.find(':') + 2));
  }
  st_.halo = std::make_unique<Halo>(st_.grid);
  effects_ = makeEffects(scene_);
  for (auto& e : effects_) e->declareFields(st_.fields);
  for (auto& e : effects_) e->registerTasks(pipeline_);
  const Section c = topSection(scene_, "checkpoint");
  ck_.interval = c.integer("interval", ck_.interval, 0, 1000000000L);
  ck_.keep = int(c.integer("keep", ck_.keep, 1, 1000));
  ck_.lastGood = c.boolean("last_good", ck_.lastGood);
  c.finish();
  checkSceneAgainstFields(scene_, st_, ck_.lastGood && !opt_.outDir.empty());
}

Simulation::~Simulation() { freeGrid(st_.grid); }

std::string Simulation::describe() const {
  const Grid& g = st_.grid;
  std::ostringstream os;
  os << "scene      " << (scene_.path.empty() ? scene_.name : scene_.path) << "\n";
  os << "grid       " << g.n[0] << " x " << g.n[1] << " x " << g.n[2] << " cells, h = " << g.h[0] << ", "
     << g.h[1] << ", " << g.h[2] << "\n";
  os << "ranks      " << g.size << " (" << g.dims[0] << " x " << g.dims[1] << " x " << g.dims[2] << ")\n";
  os << "boundaries";
  const char* faces[6] = {"x-", "x+", "y-", "y+", "z-", "z+"};
  for (int f = 0; f < 6; ++f) os << " " << faces[f] << ":" << toString(scene_.bc[f].type);
  for (size_t i = 0; i < scene_.presetNotes.size(); ++i) // scene/presets.hpp
    os << (i ? "\n           " : "\npreset     " + scene_.preset + ": ") << scene_.presetNotes[i];
  os << "\neffects    ";
  for (auto& e : scene_.effects) os << e << " ";
  os << "\npipeline (one time step, in order):\n" << pipeline_.describe();
  const double mb = st_.fields.bytes(g) / 1048576.0;
  os << "fields     " << st_.fields.decls().size() << " declared, " << mb << " MiB per rank, "
     << double(st_.fields.bytes(g)) / g.cellsOwned() << " bytes per cell (incl. ghosts)\n";
  if (ck_.interval > 0)
    os << "checkpoint every " << ck_.interval << " steps, keep " << ck_.keep
       << (ck_.lastGood ? ", last good step kept in memory (x2 field memory)" : "") << "\n";
  for (auto& [n, d] : st_.fields.decls())
    os << "             " << n << " (" << (d.centring == Centring::Cell ? "cell" : "node") << ", "
       << d.components << ", " << d.owner << ")\n";
  return os.str();
}

DtLimit Simulation::stableDt() const {
  if (!initialized_) throw std::logic_error("Simulation::stableDt before initialize()");
  DtLimit best;
  for (auto& e : effects_) {
    DtLimit l = e->dtLimit(st_);
    if (l.dt < best.dt) best = l;
  }
  return best;
}

double Simulation::chooseDt(double tEnd, double tNextOut) {
  const TimeCfg& tc = scene_.time;
  DtLimit lim = stableDt();
  double dt;
  if (tc.dt > 0) {
    dt = tc.dt;
    st_.dtReason = "fixed";
  } else {
    dt = lim.dt;
    st_.dtReason = lim.reason;
    if (tc.maxDt < dt) {
      dt = tc.maxDt;
      st_.dtReason = "max_dt";
    }
    if (!std::isfinite(dt)) {
      dt = tc.maxDt < 1e300 ? tc.maxDt : (tEnd - st_.t);
      st_.dtReason = "nothing moves";
    }
  }
  // Land exactly on outputs and the end (1e-9 relative slack avoids a sliver step).
  bool clipped = false;
  for (double target : {tNextOut, tEnd}) {
    if (target > st_.t && st_.t + dt * (1 + 1e-9) >= target) {
      dt = target - st_.t;
      clipped = true;
    }
  }
  if (clipped) st_.dtReason += " (clipped to output/end)";
  return dt;
}

void Simulation::initialize() {
  if (initialized_) return;
  // The memory check ran in the constructor (checkSceneAgainstFields).
  const bool backup = ck_.lastGood && !opt_.outDir.empty();
  st_.fields.allocate(st_.grid);
  if (backup) {
    for (auto& [n, d] : st_.fields.decls()) backup_.declare(n, d.centring, d.components, d.owner, d.isInt);
    backup_.allocate(st_.grid);
  }
  for (auto& e : effects_) e->setup(st_);
  initialized_ = true;
}

void Simulation::advance(double dt) {
  initialize();
  st_.dt = dt;
  for (Stage s : kStepStages) pipeline_.run(s, st_);
  st_.t += st_.dt;
  st_.step += 1;
  checkFinite();
  if (st_.fields.allocated("density")) // kinematic scenes (prescribed_flow) carry no mass
    st_.diag["kinetic_energy"] = kineticEnergy(st_.grid, st_.fields.vector("velocity"), st_.fields.scalar("density"));
}

void Simulation::checkFinite() {
  const Grid& g = st_.grid;
  std::vector<std::string> bad; // every non-finite field component, with its first point
  for (auto& name : st_.fields.allocatedNames()) {
    auto d = st_.fields.decls().at(name);
    if (d.isInt) continue;
    std::vector<Field> comps;
    if (d.components == 1) comps.push_back(st_.fields.scalar(name));
    else for (int c = 0; c < 3; ++c) comps.push_back(st_.fields.vector(name).c[c]);
    const Range3 r = d.centring == Centring::Cell ? cellRange(g) : nodeRange(g);
    // First non-finite point in global (k, j, i) order: the same cell whatever the decomposition.
    const long long nx = g.n[0] + 1, ny = g.n[1] + 1;
    const int ng = g.ng, c0 = g.c0[0], c1 = g.c0[1], c2 = g.c0[2];
    for (int c = 0; c < int(comps.size()); ++c) {
      const Field f = comps[c];
      long long first = LLONG_MAX;
      Kokkos::parallel_reduce(
          "find_non_finite", r.policy(),
          KOKKOS_LAMBDA(int i, int j, int k, long long& m) {
            const double v = f(i, j, k);
            if (!(v - v == 0)) { // NaN or +-Inf
              const long long lin = (i - ng + c0) + nx * ((j - ng + c1) + ny * (long long)(k - ng + c2));
              if (lin < m) m = lin;
            }
          },
          Kokkos::Min<long long>(first));
      long long gfirst = first;
      MPI_Allreduce(&first, &gfirst, 1, MPI_LONG_LONG, MPI_MIN, g.comm);
      if (gfirst == LLONG_MAX) continue;
      const int gi = int(gfirst % nx), gj = int((gfirst / nx) % ny), gk = int(gfirst / (nx * ny));
      double v = 0;
      if (first == gfirst) {
        auto h = Kokkos::create_mirror_view_and_copy(
            Kokkos::HostSpace(), Kokkos::subview(f, g.local(0, gi), g.local(1, gj), g.local(2, gk)));
        v = h();
      }
      int mine = first == gfirst ? g.rank : g.size, owner = 0;
      MPI_Allreduce(&mine, &owner, 1, MPI_INT, MPI_MIN, g.comm);
      MPI_Bcast(&v, 1, MPI_DOUBLE, owner, g.comm);
      std::ostringstream os;
      os << "field '" << name << "'";
      if (comps.size() == 3) os << " component " << "xyz"[c];
      os << " = " << v << " at " << (d.centring == Centring::Cell ? "cell" : "node") << " (" << gi << ", " << gj
         << ", " << gk << ")";
      bad.push_back(os.str());
    }
  }
  if (bad.empty()) return;
  std::ostringstream os;
  os << "blow-up: non-finite values after step " << st_.step << ", t = " << st_.t << " (dt = " << st_.dt
     << ", limited by " << st_.dtReason << "): ";
  for (size_t i = 0; i < bad.size(); ++i) os << (i ? "; " : "") << bad[i];
  throw BlowUp(os.str());
}

// Where the flow is fastest (the advective limit's cell), for a dt-collapse message.
std::string Simulation::fastestNode() const {
  if (!st_.fields.allocated("velocity")) return "";
  const Grid& g = st_.grid;
  const VecField u = st_.fields.vector("velocity");
  const Range3 r = nodeRange(g);
  const double ih0 = 1 / g.h[0], ih1 = 1 / g.h[1], ih2 = 1 / g.h[2];
  auto speed = KOKKOS_LAMBDA(int i, int j, int k) {
    return std::fabs(u.c[0](i, j, k)) * ih0 + std::fabs(u.c[1](i, j, k)) * ih1 + std::fabs(u.c[2](i, j, k)) * ih2;
  };
  double m = 0;
  Kokkos::parallel_reduce(
      "fastest_node_max", r.policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
        const double s = speed(i, j, k);
        if (s > acc) acc = s;
      },
      Kokkos::Max<double>(m));
  double gm = m;
  MPI_Allreduce(&m, &gm, 1, MPI_DOUBLE, MPI_MAX, g.comm);
  const long long nx = g.n[0] + 1, ny = g.n[1] + 1;
  const int ng = g.ng, c0 = g.c0[0], c1 = g.c0[1], c2 = g.c0[2];
  long long first = LLONG_MAX;
  Kokkos::parallel_reduce(
      "fastest_node_where", r.policy(),
      KOKKOS_LAMBDA(int i, int j, int k, long long& acc) {
        if (speed(i, j, k) == gm) {
          const long long lin = (i - ng + c0) + nx * ((j - ng + c1) + ny * (long long)(k - ng + c2));
          if (lin < acc) acc = lin;
        }
      },
      Kokkos::Min<long long>(first));
  long long gfirst = first;
  MPI_Allreduce(&first, &gfirst, 1, MPI_LONG_LONG, MPI_MIN, g.comm);
  if (gfirst == LLONG_MAX) return "";
  std::ostringstream os;
  os << "; fastest flow: field 'velocity' at node (" << gfirst % nx << ", " << (gfirst / nx) % ny << ", "
     << gfirst / (nx * ny) << "), sum |u_d|/h_d = " << gm;
  return os.str();
}

namespace {
// Output fields by name; "pressure" is shifted by the outflow reference.
std::vector<OutField> gatherFields(State& st, const std::vector<std::string>& names) {
  std::vector<OutField> out;
  for (auto& n : names) {
    if (!st.fields.allocated(n))
      throw SceneError(st.scene->path + ": key 'output.fields': field '" + n +
                       "' is not produced by this scene's effects");
    const auto& d = st.fields.decls().at(n);
    OutField f{n, d.centring, {}};
    if (d.components == 3) {
      VecField v = st.fields.vector(n);
      st.halo->exchange(v);
      f.comps = {v.c[0], v.c[1], v.c[2]};
    } else {
      Field s = st.fields.scalar(n);
      if (n == "pressure") {
        const double ref = st.diag.count("pressure_reference") ? st.diag.at("pressure_reference") : 0.0;
        Field c("pressure_out", s.extent(0), s.extent(1), s.extent(2));
        Kokkos::parallel_for(
            "pressure_out", Policy3({0, 0, 0}, {(int)s.extent(0), (int)s.extent(1), (int)s.extent(2)}),
            KOKKOS_LAMBDA(int i, int j, int k) { c(i, j, k) = s(i, j, k) + ref; });
        s = c;
      }
      st.halo->exchange(s);
      f.comps = {s};
    }
    out.push_back(f);
  }
  return out;
}
} // namespace

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

namespace {
// SIGINT/SIGTERM: the handler only records the signal; the time loop acts on
// it between steps, collectively (an MPI_MAX over ranks), so a signal that
// reaches one rank stops them all at the same step.
volatile std::sig_atomic_t gSignal = 0;
extern "C" void onSignal(int s) { gSignal = s; }

struct SignalGuard {
  struct sigaction oldInt{}, oldTerm{};
  bool on = false;
  explicit SignalGuard(bool enable) : on(enable) {
    if (!on) return;
    gSignal = 0;
    struct sigaction sa{};
    sa.sa_handler = onSignal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART | SA_RESETHAND; // a second Ctrl-C kills at once
    sigaction(SIGINT, &sa, &oldInt);
    sigaction(SIGTERM, &sa, &oldTerm);
  }
  ~SignalGuard() {
    if (!on) return;
    sigaction(SIGINT, &oldInt, nullptr);
    sigaction(SIGTERM, &oldTerm, nullptr);
  }
};

// Files a Voigt run writes: --overwrite removes a directory only if it holds
// nothing else (it never deletes a directory it did not make).
bool isVoigtOutput(const fs::path& dir) {
  std::error_code ec;
  for (auto& e : fs::directory_iterator(dir, ec)) {
    const std::string n = e.path().filename().string();
    auto starts = [&](const char* p) { return n.rfind(p, 0) == 0; };
    if (!(starts("fields") || starts("probe_") || starts("checkpoint") || n == "summary.json" ||
          n == "timeseries.csv" || n == "latest" || n == "latest.tmp" || starts("timeseries.csv")))
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
  j["t"] = st_.t;
  j["dt"] = st_.dt;
  j["step"] = st_.step;
  j["dt_reason"] = st_.dtReason;
  j["diag"] = st_.diag;
  j["counters"] = st_.counters;
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
  lastCheckpointStep_ = st_.step;
  return m;
}

std::string Simulation::writeCheckpoint(const FieldStore& fields, const nlohmann::json& meta) {
  if (!checkpointer_) return "";
  const std::string path = checkpointer_->write(meta.at("step").get<long>(), fields, meta);
  lastCheckpointStep_ = meta.at("step").get<long>();
  checkpointsWritten_ += 1;
  checkpointSeconds_ += checkpointer_->lastSeconds();
  checkpointBytes_ = checkpointer_->lastBytes();
  return path;
}

// The state before a step, for a blow-up's "last good state".
void Simulation::snapshot() {
  if (!ck_.lastGood || !checkpointer_) return;
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

void Simulation::writeSummary(const RunResult& r, const std::string& stop) {
  if (opt_.outDir.empty() || st_.grid.rank != 0) return;
  nlohmann::json j = summary(r);
  if (!stop.empty()) j["stopped"] = stop;
  const std::string path = opt_.outDir + "/summary.json", tmp = path + ".tmp";
  std::ofstream os(tmp, std::ios::trunc);
  os << j.dump(2) << "\n";
  os.close();
  if (!os || std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
}

RunResult Simulation::run() {
  const Grid& g = st_.grid;
  SignalGuard signals(opt_.handleSignals);
  std::string ckFile;
  if (!opt_.restart.empty()) ckFile = findCheckpoint(g.comm, opt_.restart);
  if (!opt_.outDir.empty()) {
    prepareOutputDir();
    writer_ = std::make_unique<FieldWriter>(g, opt_.outDir);
    checkpointer_ = std::make_unique<Checkpointer>(g, opt_.outDir, ck_.keep);
  }
  initialize();
  const double tEnd = opt_.endTime > 0 ? opt_.endTime : scene_.time.endTime;
  const long maxSteps = opt_.maxSteps >= 0 ? opt_.maxSteps : scene_.time.maxSteps;
  nextOutput_ = scene_.output.interval > 0 ? scene_.output.interval : tEnd;
  if (!ckFile.empty()) {
    const nlohmann::json ckMeta = restore(ckFile);
    if (g.rank == 0) {
      std::cout << "restart: " << ckFile << " (step " << st_.step << ", t = " << st_.t << ")" << std::endl;
      // Rows a crashed run wrote after its checkpoint are written again.
      if (!opt_.outDir.empty()) truncateOutputs(opt_.outDir, ckMeta.value("output_file_sizes", nlohmann::json::object()));
    }
  }
  if (!opt_.outDir.empty()) probes_ = std::make_unique<ProbeSet>(g, scene_.probes, opt_.outDir, ckFile.empty() ? -1 : st_.t);
  if (ckFile.empty()) output(true);
  const bool tty = opt_.progress && isatty(2) && g.rank == 0;
  const double w0 = MPI_Wtime();
  const long step0 = st_.step;
  RunResult r;
  auto finish = [&]() {
    r.steps = st_.step;
    r.simTime = st_.t;
    r.wallSeconds = MPI_Wtime() - w0;
    r.cellStepsPerSecond = r.wallSeconds > 0 ? double(g.cellsGlobal()) * (st_.step - step0) / r.wallSeconds : 0;
  };
  // A blow-up: write the last good state, the summary, and stop (collective).
  auto blowUp = [&](std::string msg, bool currentIsGood) {
    if (checkpointer_) {
      std::string path;
      if (currentIsGood) path = writeCheckpoint(st_.fields, checkpointMeta());
      else if (haveBackup_) path = writeCheckpoint(backup_, backupMeta_);
      if (!path.empty())
        msg += "; last good state (step " +
               std::to_string(currentIsGood ? st_.step : backupMeta_.at("step").get<long>()) + ") written to " + path;
      else
        msg += "; no last good state kept (checkpoint.last_good is false)";
    }
    finish();
    writeSummary(r, msg);
    throw BlowUp(msg);
  };
  while (st_.t < tEnd * (1 - 1e-12) && (maxSteps < 0 || st_.step < maxSteps)) {
    int sig = gSignal, anySig = 0;
    if (opt_.handleSignals) {
      MPI_Allreduce(&sig, &anySig, 1, MPI_INT, MPI_MAX, g.comm);
      if (anySig) {
        r.signal = anySig;
        break;
      }
    }
    const double dt = chooseDt(tEnd, scene_.output.interval > 0 ? nextOutput_ : tEnd);
    if (!std::isfinite(dt) || dt <= 0 || (dt < scene_.time.minDt && dt < tEnd - st_.t)) {
      std::ostringstream os;
      os << "blow-up: time step collapsed to " << dt << " (time.min_dt = " << scene_.time.minDt << ") at step "
         << st_.step << ", t = " << st_.t << ", limited by " << st_.dtReason << fastestNode();
      blowUp(os.str(), true);
    }
    dtReasons_[st_.dtReason.substr(0, st_.dtReason.find(" ("))] += 1;
    snapshot();
    try {
      advance(dt);
    } catch (const BlowUp& e) {
      blowUp(e.what(), false);
    }
    writeTimeSeries();
    output(false);
    if (ck_.interval > 0 && st_.step % ck_.interval == 0 && checkpointer_)
      r.checkpoint = writeCheckpoint(st_.fields, checkpointMeta());
    if (tty) {
      const double el = MPI_Wtime() - w0, eta = el / st_.t * (tEnd - st_.t);
      fprintf(stderr, "\rstep %ld  t = %.5g  dt = %.3g (%s)  ETA %.0f s   ", st_.step, st_.t, st_.dt,
              st_.dtReason.c_str(), eta);
    }
  }
  if (tty) fprintf(stderr, "\n");
  finish();
  if (r.signal) {
    if (checkpointer_ && lastCheckpointStep_ != st_.step) r.checkpoint = writeCheckpoint(st_.fields, checkpointMeta());
    else if (checkpointer_ && r.checkpoint.empty()) r.checkpoint = findCheckpoint(g.comm, opt_.outDir);
    writeSummary(r, std::string("signal ") + (r.signal == SIGINT ? "SIGINT" : r.signal == SIGTERM ? "SIGTERM" : "?"));
    return r;
  }
  // A run with checkpoints ends with one, so it can be extended (--restart --end-time ...);
  // before the final forced output, which a longer run would not have made.
  if (ck_.interval > 0 && checkpointer_ && lastCheckpointStep_ != st_.step)
    r.checkpoint = writeCheckpoint(st_.fields, checkpointMeta());
  if (scene_.output.interval == 0 || outputIndex_ == 0 || nextOutput_ - scene_.output.interval < st_.t - 1e-12)
    output(true);
  writeSummary(r, "");
  return r;
}

nlohmann::json Simulation::summary(const RunResult& r) const {
  const Grid& g = st_.grid;
  nlohmann::json j;
  j["scene"] = scene_.path;
  j["grid"] = {{"cells", g.n}, {"ranks", g.size}, {"decomposition", g.dims}};
  j["effects"] = scene_.effects;
  j["steps"] = r.steps;
  j["simulated_time"] = r.simTime;
  j["wall_seconds"] = r.wallSeconds;
  j["cell_steps_per_second"] = r.cellStepsPerSecond;
  j["wall_seconds_per_stage"] = pipeline_.stageSeconds;
  j["wall_seconds_per_effect"] = pipeline_.effectSeconds;
  j["halo"] = {{"seconds", st_.halo->seconds}, {"bytes", st_.halo->bytes}, {"messages", st_.halo->messages}};
  j["dt_reasons"] = dtReasons_;
  j["last_step"] = st_.diag;
  if (checkpointsWritten_ > 0)
    j["checkpoints"] = {{"written", checkpointsWritten_},
                        {"seconds", checkpointSeconds_},
                        {"bytes_last", checkpointBytes_},
                        {"bytes_per_cell", double(checkpointBytes_) / double(g.cellsGlobal())}};
  j["memory_bytes_per_rank"] = st_.fields.bytes(g);
  j["fields_allocated"] = st_.fields.allocatedNames();
  // Single phase: the fluid fills the domain (obstacle nodes are velocity constraints).
  double vol = 1;
  for (int d = 0; d < 3; ++d) vol *= g.hi[d] - g.lo[d];
  j["volume_per_phase"] = {{scene_.fluid, vol}};
  for (auto& e : effects_) e->summary(st_, j);
  return j;
}

} // namespace voigt
