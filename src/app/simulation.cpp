#include "app/simulation.hpp"

#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <climits>
#include <csignal>
#include <cmath>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#include "core/build_info.hpp"
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

Simulation::Simulation(const Scene& scene, MPI_Comm comm, RunOptions opt)
    : scene_(scene), sceneYaml_(YAML::Dump(scene_.root)), opt_(opt), engine_(st_, pipeline_, scene_.time) {
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
  for (auto& e : effects_) engine_.addLimit([eff = e.get()](const State& st) { return eff->dtLimit(st); });
  engine_.addAfterStep([](State& st) {
    if (st.fields.allocated(field::density)) // kinematic scenes (prescribed_flow) carry no mass
      st.diag["kinetic_energy"] = kineticEnergy(st.grid, st.fields.vector(field::velocity), st.fields.scalar(field::density));
    const VecField u = st.fields.vector(field::velocity);
    const Range3 nodes = nodeRange(st.grid);
    const double m = std::max({localMaxAbs(u.c[0], nodes), localMaxAbs(u.c[1], nodes), localMaxAbs(u.c[2], nodes)});
    double mg = m;
    MPI_Allreduce(&m, &mg, 1, MPI_DOUBLE, MPI_MAX, st.grid.comm);
    st.diag["max_velocity"] = mg; // largest |u_d|: what rest-at-rest is judged by
  });
  const Section c = topSection(scene_, "checkpoint");
  ck_.interval = c.integer("interval", ck_.interval, 0, 1000000000L);
  ck_.wallInterval = c.number("wall_interval", ck_.wallInterval, Range::nonNegative());
  ck_.keep = int(c.integer("keep", ck_.keep, 1, 1000));
  ck_.lastGood = c.boolean("last_good", ck_.lastGood);
  ck_.lastGoodInterval = c.integer("last_good_interval", ck_.lastGoodInterval, 1, 1000000000L);
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
  nlohmann::json sj; // what the effects report now: the fast diagonalization's rank grid
  for (auto& e : effects_) e->summary(st_, sj);
  if (sj.contains("poisson") && sj["poisson"].contains("fast_diagonalization_ranks")) {
    const auto fr = sj["poisson"]["fast_diagonalization_ranks"];
    const int p1 = fr[0], p2 = fr[1];
    os << "           projection's fast diagonalization: " << p1 << " x " << p2
       << (p1 == 1 ? " (slabs: every rank holds whole planes)" : " pencils (more ranks than planes for slabs)");
    if (p1 * p2 < g.size) os << ", " << g.size - p1 * p2 << " ranks idle in its passes";
    // perf/scaling/README.md, "Traffic": the projection's one-rank cost, fast diagonalization
    // (iterations flat in n, O(n) flops a cell and iteration) against multigrid on the same
    // operator (iterations growing with n): multigrid is the cheaper from n ~ 650 on the dam
    // break (density ratio 1000), never up to 4096 on the falling block (ratio 83).
    double rmin = 1e300, rmax = 0;
    for (const auto& [name, m] : scene_.materials) rmin = std::min(rmin, m.density), rmax = std::max(rmax, m.density);
    const int n = std::max({g.n[0], g.n[1], g.n[2]});
    const double ratio = rmax / rmin;
    os << "\n           scaling model: multigrid is the cheaper projection only from ~650 cells an axis at "
          "density ratio 1000 (here "
       << n << ", ratio " << ratio << ")";
    if (n >= 650 && ratio >= 1000) os << ": consider projection.preconditioner: multigrid";
    os << "\n";
  }
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
  if (ck_.interval > 0 || ck_.wallInterval > 0) {
    os << "checkpoint every ";
    if (ck_.interval > 0) os << ck_.interval << " steps" << (ck_.wallInterval > 0 ? " and every " : "");
    if (ck_.wallInterval > 0) os << ck_.wallInterval << " s of wall time";
    os << ", keep " << ck_.keep << (ck_.lastGood ? ", last good state kept in memory every " + std::to_string(ck_.lastGoodInterval) +
                                            " steps (x2 field memory)"
                                      : std::string()) << "\n";
  }
  for (auto& [n, d] : st_.fields.decls())
    os << "             " << n << " (" << (d.centring == Centring::Cell ? "cell" : "node") << ", "
       << d.components << ", " << d.owner << ")\n";
  return os.str();
}

DtLimit Simulation::stableDt() const {
  if (!initialized_) throw std::logic_error("Simulation::stableDt before initialize()");
  return engine_.stableDt();
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
  engine_.advance(dt);
}

long Simulation::advanceTo(double t, const StepEngine::Each& each, long maxSteps) {
  initialize();
  return engine_.advanceTo(t, each, maxSteps);
}

// Where the flow is fastest (the advective limit's cell), for a dt-collapse message.
std::string Simulation::fastestNode() const {
  if (!st_.fields.allocated(field::velocity)) return "";
  const Grid& g = st_.grid;
  const VecField u = st_.fields.vector(field::velocity);
  const Range3 r = nodeRange(g);
  const double m = maxNodeRate(g, u, r);
  double gm = m;
  MPI_Allreduce(&m, &gm, 1, MPI_DOUBLE, MPI_MAX, g.comm);
  const long long nx = g.n[0] + 1;
  const long long ny = g.n[1] + 1;
  const long long first = firstNodeWithRate(g, u, r, gm);
  long long gfirst = first;
  MPI_Allreduce(&first, &gfirst, 1, MPI_LONG_LONG, MPI_MIN, g.comm);
  if (gfirst == LLONG_MAX) return "";
  std::ostringstream os;
  os << "; fastest flow: field 'velocity' at node (" << gfirst % nx << ", " << (gfirst / nx) % ny << ", "
     << gfirst / (nx * ny) << "), sum |u_d|/h_d = " << gm;
  return os.str();
}


nlohmann::json Simulation::summary(const RunResult& r) const {
  const Grid& g = st_.grid;
  nlohmann::json j;
  j["scene"] = scene_.path;
  j["scene_overrides"] = nlohmann::json::array();  // scene.yaml beside this file: the whole scene
  if (scene_.source)
    for (const auto& o : scene_.source->overrides) j["scene_overrides"].push_back(o.text);
  j["grid"] = {{"cells", g.n}, {"ranks", g.size}, {"decomposition", g.dims}};
  j["effects"] = scene_.effects;
  j["steps"] = r.steps;
  j["simulated_time"] = r.simTime;
  j["wall_seconds"] = r.wallSeconds;
  j["steps_this_run"] = r.stepsThisRun;
  j["wall_seconds_total"] = r.wallSecondsTotal;  // NaN (null): restarted from an older checkpoint
  j["run_segments"] = r.segments;
  j["revision"] = buildRevision();
  j["segment_history"] = segmentRecord();
  // null: a fresh run, or a checkpoint that carries no scene to compare with
  j["restart_scene_changes"] = restartSceneCompared_ ? nlohmann::json(restartSceneChanges_) : nlohmann::json();
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
  if (!opt_.estimate.is_null()) j["estimate"] = opt_.estimate;
  j["fields_allocated"] = st_.fields.allocatedNames();
  // Single phase: the fluid fills the domain (obstacle nodes are velocity constraints).
  double vol = 1;
  for (int d = 0; d < 3; ++d) vol *= g.hi[d] - g.lo[d];
  j["volume_per_phase"] = {{scene_.fluid, vol}};
  for (auto& e : effects_) e->summary(st_, j);
  // Wall seconds inside the Poisson solves (CG + preconditioner apply), for perf/scaling/.
  if (j.contains("poisson") && st_.counters.count("poisson_seconds"))
    j["poisson"]["solve_seconds"] = st_.counters.at("poisson_seconds");
  if (j.contains("poisson") && st_.counters.count("poisson_setup_seconds"))
    j["poisson"]["setup_seconds"] = st_.counters.at("poisson_setup_seconds");
  return j;
}

} // namespace voigt
