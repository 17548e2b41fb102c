#include "app/simulation.hpp"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/index_space.hpp"
#include "io/fields_out.hpp"
#include "io/probes.hpp"
#include "kernels/reductions.hpp"
#include "scene/reader.hpp"

namespace voigt {

namespace fs = std::filesystem;

Simulation::Simulation(const Scene& scene, MPI_Comm comm, RunOptions opt) : scene_(scene), opt_(opt) {
  st_.scene = &scene_;
  std::array<bool, 3> per{scene_.periodic(0), scene_.periodic(1), scene_.periodic(2)};
  st_.grid = makeGrid(comm, scene_.cells, scene_.lo, scene_.hi, per, scene_.ranks);
  st_.halo = std::make_unique<Halo>(st_.grid);
  effects_ = makeEffects(scene_);
  for (auto& e : effects_) e->declareFields(st_.fields);
  for (auto& e : effects_) e->registerTasks(pipeline_);
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
  os << "\neffects    ";
  for (auto& e : scene_.effects) os << e << " ";
  os << "\npipeline (one time step, in order):\n" << pipeline_.describe();
  const double mb = st_.fields.bytes(g) / 1048576.0;
  os << "fields     " << st_.fields.decls().size() << " declared, " << mb << " MiB per rank, "
     << double(st_.fields.bytes(g)) / g.cellsOwned() << " bytes per cell (incl. ghosts)\n";
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

namespace {
// Physical memory available to this process group, from sysconf.
double availableBytes() {
  return double(sysconf(_SC_AVPHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
}
} // namespace

void Simulation::initialize() {
  if (initialized_) return;
  // Refuse a grid that cannot fit before touching memory: sum over the ranks
  // sharing this node's memory, compare with what the node has free.
  double need = double(st_.fields.bytes(st_.grid)), total = need;
  MPI_Comm node;
  MPI_Comm_split_type(st_.grid.comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  MPI_Allreduce(&need, &total, 1, MPI_DOUBLE, MPI_SUM, node);
  MPI_Comm_free(&node);
  int tooBig = total > 0.9 * availableBytes(), any = 0;
  MPI_Allreduce(&tooBig, &any, 1, MPI_INT, MPI_MAX, st_.grid.comm);
  if (any)
    throw SceneError((scene_.path.empty() ? scene_.name : scene_.path) + ": key 'domain.cells': the fields need " +
                     std::to_string(total / 1073741824.0) + " GiB but only " +
                     std::to_string(availableBytes() / 1073741824.0) + " GiB of memory is available");
  st_.fields.allocate(st_.grid);
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
  for (auto& name : st_.fields.allocatedNames()) {
    auto d = st_.fields.decls().at(name);
    if (d.isInt) continue;
    std::vector<Field> comps;
    if (d.components == 1) comps.push_back(st_.fields.scalar(name));
    else for (int c = 0; c < 3; ++c) comps.push_back(st_.fields.vector(name).c[c]);
    const Range3 r = d.centring == Centring::Cell ? cellRange(g) : nodeRange(g);
    for (auto& f : comps) {
      const double m = globalMaxAbs(g, f, r);
      if (!std::isfinite(m)) {
        std::ostringstream os;
        os << "blow-up: field '" << name << "' is not finite at step " << st_.step << ", t = " << st_.t
           << " (dt = " << st_.dt << ", limited by " << st_.dtReason << ")";
        throw std::runtime_error(os.str());
      }
    }
  }
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
  if (opt_.outDir.empty() || st_.grid.rank != 0) return;
  const std::string path = opt_.outDir + "/timeseries.csv";
  std::ofstream os(path, std::ios::app);
  // Columns are fixed by the first row; a diagnostic that appears later (an
  // effect running every N steps) is left empty until it exists, and one
  // that was not there at the first row is not written, so rows stay aligned.
  if (tsColumns_.empty()) {
    for (auto& [k, v] : st_.diag) tsColumns_.push_back(k);
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

RunResult Simulation::run() {
  const Grid& g = st_.grid;
  if (!opt_.outDir.empty()) {
    int bad = 0;
    std::string msg;
    if (g.rank == 0) {
      std::error_code ec;
      if (fs::exists(opt_.outDir) && !fs::is_empty(opt_.outDir) && !opt_.overwrite) {
        bad = 1;
        msg = "output directory '" + opt_.outDir + "' exists and is not empty (use --overwrite)";
      } else {
        if (opt_.overwrite) fs::remove_all(opt_.outDir, ec);
        fs::create_directories(opt_.outDir, ec);
        if (ec) bad = 1, msg = "cannot create output directory '" + opt_.outDir + "': " + ec.message();
      }
    }
    MPI_Bcast(&bad, 1, MPI_INT, 0, g.comm);
    if (bad) throw std::runtime_error(g.rank == 0 ? msg : "output directory error (see rank 0)");
    writer_ = std::make_unique<FieldWriter>(g, opt_.outDir);
    probes_ = std::make_unique<ProbeSet>(g, scene_.probes, opt_.outDir);
  }
  initialize();
  const double tEnd = opt_.endTime > 0 ? opt_.endTime : scene_.time.endTime;
  const long maxSteps = opt_.maxSteps >= 0 ? opt_.maxSteps : scene_.time.maxSteps;
  nextOutput_ = scene_.output.interval > 0 ? scene_.output.interval : tEnd;
  output(true);
  const bool tty = opt_.progress && isatty(2) && g.rank == 0;
  const double w0 = MPI_Wtime();
  while (st_.t < tEnd * (1 - 1e-12) && (maxSteps < 0 || st_.step < maxSteps)) {
    const double dt = chooseDt(tEnd, scene_.output.interval > 0 ? nextOutput_ : tEnd);
    if (dt < scene_.time.minDt && dt < tEnd - st_.t)
      throw std::runtime_error("time step collapsed to " + std::to_string(dt) + " at t = " +
                               std::to_string(st_.t) + " (limited by " + st_.dtReason + ")");
    dtReasons_[st_.dtReason.substr(0, st_.dtReason.find(" ("))] += 1;
    advance(dt);
    writeTimeSeries();
    output(false);
    if (tty) {
      const double el = MPI_Wtime() - w0, eta = el / st_.t * (tEnd - st_.t);
      fprintf(stderr, "\rstep %ld  t = %.5g  dt = %.3g (%s)  ETA %.0f s   ", st_.step, st_.t, st_.dt,
              st_.dtReason.c_str(), eta);
    }
  }
  if (tty) fprintf(stderr, "\n");
  RunResult r;
  r.steps = st_.step;
  r.simTime = st_.t;
  r.wallSeconds = MPI_Wtime() - w0;
  r.cellStepsPerSecond = r.wallSeconds > 0 ? double(g.cellsGlobal()) * r.steps / r.wallSeconds : 0;
  if (scene_.output.interval == 0 || outputIndex_ == 0 || nextOutput_ - scene_.output.interval < st_.t - 1e-12)
    output(true);
  if (!opt_.outDir.empty() && g.rank == 0) {
    std::ofstream os(opt_.outDir + "/summary.json");
    os << summary(r).dump(2) << "\n";
  }
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
