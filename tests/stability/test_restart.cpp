// Checkpoint and restart: N steps uninterrupted vs N/2 + restart + N/2 must
// agree bit for bit on the same rank count and to solver tolerance on another;
// checkpoint files are complete, pruned and pointed at atomically. Blow-ups:
// test_blow_up.cpp.
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/build_info.hpp"
#include "io/checkpoint.hpp"
#include "stability/support.hpp"
#include "support/flow.hpp"

using namespace voigt;
using namespace voigt::test;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kTaylorGreen = {"domain.cells=[16,16,4]", "output.interval=0.25", "time.end=10"};
const std::vector<std::string> kRayleighTaylor = {"domain.cells=[16,64,2]", "output.interval=0.05",
                                                  "projection.tolerance=1e-10"};

std::vector<std::string> with(std::vector<std::string> s, const std::vector<std::string>& more) {
  s.insert(s.end(), more.begin(), more.end());
  return s;
}

// Runs `n` steps in one go and as n/2 + restart + n/2; expects identical fields.
void expectBitIdenticalRestart(const std::string& scenePath, const std::vector<std::string>& sets, long n) {
  TempDir tmp;
  const long half = n / 2;
  const Scene s = caseScene(scenePath, with(sets, {"checkpoint.interval=" + std::to_string(half)}));
  Simulation full(s, MPI_COMM_WORLD, runOpts(tmp.sub("full"), n));
  full.run();
  {
    Simulation first(s, MPI_COMM_WORLD, runOpts(tmp.sub("split"), half));
    first.run();
  }
  Simulation second(s, MPI_COMM_WORLD, runOpts(tmp.sub("split"), n, tmp.sub("split")));
  second.run();
  EXPECT_EQ(second.state().step, n);
  EXPECT_EQ(std::memcmp(&second.state().t, &full.state().t, sizeof(double)), 0)
      << second.state().t << " vs " << full.state().t;
  std::string which;
  EXPECT_EQ(compareFields(full, second, 0, nullptr, &which), 0) << "first differing field: " << which;
  EXPECT_EQ(full.state().diag, second.state().diag);
  auto counters = full.state().counters, counters2 = second.state().counters;
  for (const char* k : {"poisson_seconds", "poisson_setup_seconds"}) { // wall times
    counters.erase(k);
    counters2.erase(k);
  }
  EXPECT_EQ(counters, counters2);
  // The CSV a restarted run continues equals the uninterrupted one.
  if (worldRank() == 0) {
    auto read = [](const std::string& p) {
      std::ifstream in(p);
      return std::string(std::istreambuf_iterator<char>(in), {});
    };
    EXPECT_EQ(read(tmp.sub("full/timeseries.csv")), read(tmp.sub("split/timeseries.csv")));
    EXPECT_EQ(read(tmp.sub("full/fields.xdmf")), read(tmp.sub("split/fields.xdmf")));
    // The cost of a run continued over a restart: both segments, the steps of each.
    auto summary = [&](const std::string& d) { return nlohmann::json::parse(read(tmp.sub(d + "/summary.json"))); };
    const auto a = summary("full"), b = summary("split");
    EXPECT_EQ(a.at("run_segments"), 1);
    EXPECT_EQ(a.at("steps_this_run"), n);
    EXPECT_EQ(a.at("wall_seconds_total").get<double>(), a.at("wall_seconds").get<double>());
    EXPECT_EQ(b.at("run_segments"), 2);
    EXPECT_EQ(b.at("steps_this_run"), n - half);
    EXPECT_EQ(b.at("steps"), n);
    EXPECT_GT(b.at("wall_seconds_total").get<double>(), b.at("wall_seconds").get<double>());
    // Which binary ran which steps: one record per segment, contiguous, this build's revision.
    const auto& h = b.at("segment_history");
    ASSERT_EQ(h.size(), 2u) << h;
    EXPECT_EQ(h[0].at("first_step"), 0);
    EXPECT_EQ(h[0].at("last_step"), half);
    EXPECT_EQ(h[1].at("first_step"), half);
    EXPECT_EQ(h[1].at("last_step"), n);
    for (const auto& seg : h) {
      EXPECT_EQ(seg.at("revision"), std::string(buildRevision()));
      EXPECT_EQ(seg.at("ranks"), worldSize());
    }
    EXPECT_EQ(b.at("revision"), std::string(buildRevision()));
    EXPECT_EQ(a.at("segment_history").size(), 1u);
    // scene.yaml records the scene as run (file plus --set): it loads back to the same tree,
    // and summary.json lists the --set overrides in order.
    const Scene rec = loadSceneWithEffects(tmp.sub("split/scene.yaml"));
    EXPECT_EQ(YAML::Dump(rec.root), YAML::Dump(s.root));
    EXPECT_TRUE(a.at("restart_scene_changes").is_null());  // a fresh run compares nothing
    EXPECT_EQ(b.at("restart_scene_changes"), nlohmann::json::array()) << b.at("restart_scene_changes");
    EXPECT_FALSE(fs::exists(tmp.sub("split/scene_segment2.yaml")));  // same scene: one record
    ASSERT_EQ(b.at("scene_overrides").size(), s.source->overrides.size());
    for (size_t i = 0; i < s.source->overrides.size(); ++i)
      EXPECT_EQ(b.at("scene_overrides")[i], s.source->overrides[i].text);
    for (auto& p : s.probes) {
      const std::string f = "/probe_" + p.name + ".csv";
      EXPECT_FALSE(read(tmp.sub("full") + f).empty()) << f;
      EXPECT_EQ(read(tmp.sub("full") + f), read(tmp.sub("split") + f)) << f;
    }
  }
}

} // namespace

TEST(Restart, TaylorGreenBitIdentical) { expectBitIdenticalRestart("taylor_green/taylor_green.yaml", kTaylorGreen, 12); }

TEST(Restart, LevelSetBitIdentical) {
  // navier_stokes + gravity + level_set + reinit: density ratio 3, psi re-initialised every step.
  expectBitIdenticalRestart("rayleigh_taylor/rayleigh_taylor.yaml", kRayleighTaylor, 8);
}

TEST(Restart, CylinderBitIdentical) {
  // Inflow/outflow faces (pressure reference), an obstacle mask, the multigrid-free default solver.
  expectBitIdenticalRestart("cylinder/cylinder.yaml", {"domain.cells=[64,16,4]", "output.interval=0.5"}, 8);
}

TEST(Restart, FromFinalCheckpointBitIdentical) {
  // The first run stops at step 7, between checkpoints (every 5): its final
  // checkpoint, written before its final forced output, is the restart point.
  TempDir tmp;
  const Scene s = caseScene("taylor_green/taylor_green.yaml", with(kTaylorGreen, {"checkpoint.interval=5"}));
  Simulation full(s, MPI_COMM_WORLD, runOpts(tmp.sub("full"), 12));
  full.run();
  {
    Simulation first(s, MPI_COMM_WORLD, runOpts(tmp.sub("split"), 7));
    EXPECT_EQ(first.run().checkpoint, tmp.sub("split/checkpoint_000000007.h5"));
  }
  Simulation second(s, MPI_COMM_WORLD, runOpts(tmp.sub("split"), 12, tmp.sub("split")));
  second.run();
  EXPECT_EQ(compareFields(full, second, 0), 0);
  if (worldRank() == 0) {
    auto read = [](const std::string& p) {
      std::ifstream in(p);
      return std::string(std::istreambuf_iterator<char>(in), {});
    };
    for (const char* f : {"/timeseries.csv", "/fields.xdmf", "/probe_quarter.csv"})
      EXPECT_EQ(read(tmp.sub("full") + f), read(tmp.sub("split") + f)) << f;
  }
}

TEST(Restart, NamesTheSceneSectionsItChanges) {
  // A restart may change the scene (here the output interval):
  // it goes on, and summary.json names the top-level sections that differ from the checkpoint's.
  TempDir tmp;
  const auto sets = with(kTaylorGreen, {"checkpoint.interval=3"});
  {
    Simulation first(caseScene("taylor_green/taylor_green.yaml", sets), MPI_COMM_WORLD, runOpts(tmp.sub("r"), 3));
    first.run();
  }
  Simulation second(caseScene("taylor_green/taylor_green.yaml", with(sets, {"output.interval=0.5"})), MPI_COMM_WORLD,
                    runOpts(tmp.sub("r"), 6, tmp.sub("r")));
  second.run();
  EXPECT_EQ(second.state().step, 6);
  if (worldRank() == 0) {
    std::ifstream in(tmp.sub("r/summary.json"));
    const auto j = nlohmann::json::parse(in);
    EXPECT_EQ(j.at("restart_scene_changes"), nlohmann::json::array({"output"}));
    // The first segment's record stays; the second's is beside it, with its own interval.
    EXPECT_NE(loadSceneWithEffects(tmp.sub("r/scene.yaml")).output.interval, 0.5);
    EXPECT_EQ(loadSceneWithEffects(tmp.sub("r/scene_segment2.yaml")).output.interval, 0.5);
  }
}

TEST(Restart, FromCheckpointWithoutPressureRates) {
  // initial_guess: extrapolate keeps two pressure-rate fields in the checkpoint (Taylor-Green's
  // default: exact operator, fast diagonalization; the bit-identical restarts above cover them).
  // A checkpoint written without them (here: initial_guess previous; or by an older Voigt)
  // restarts with them zero and rebuilds them in two steps instead of failing.
  TempDir tmp;
  const auto sets = with(kTaylorGreen, {"checkpoint.interval=3"});
  {
    Simulation first(caseScene("taylor_green/taylor_green.yaml", with(sets, {"projection.initial_guess=previous"})),
                     MPI_COMM_WORLD, runOpts(tmp.sub("r"), 3));
    first.run();
  }
  Simulation second(caseScene("taylor_green/taylor_green.yaml", sets), MPI_COMM_WORLD,
                    runOpts(tmp.sub("r"), 6, tmp.sub("r")));
  second.run();
  EXPECT_EQ(second.state().step, 6);
  const auto& c = second.state().counters;
  EXPECT_TRUE(!c.count("poisson_unconverged") || c.at("poisson_unconverged") == 0);
  // Tolerance 1e-10: the divergence left is the residual, at most 1e-10 of |D u*|_2 (O(1) here),
  // so 1e-6 is a loose bound that only a failed solve or a garbage initial guess would cross.
  EXPECT_LT(second.state().diag.at("max_divergence"), 1e-6);
}

TEST(Restart, SceneStyleIsNoChange) {
  // cases/cylinder's obstacle again, as a flow list, keys in another order, the radius 0.05
  // written 5.0e-2: the same scene, so the restart reports no change.
  TempDir tmp;
  const std::vector<std::string> sets = {"domain.cells=[32,8,4]", "checkpoint.interval=2"};
  {
    Simulation first(caseScene("cylinder/cylinder.yaml", sets), MPI_COMM_WORLD, runOpts(tmp.sub("r"), 2));
    first.run();
  }
  const Scene again = caseScene(
      "cylinder/cylinder.yaml",
      with(sets, {"obstacles=[{axis: z, radius: 5.0e-2, type: cylinder, center: [0.3, 0.195, 0.025]}]"}));
  Simulation second(again, MPI_COMM_WORLD, runOpts(tmp.sub("r"), 4, tmp.sub("r")));
  second.run();
  if (worldRank() == 0) {
    std::ifstream in(tmp.sub("r/summary.json"));
    EXPECT_EQ(nlohmann::json::parse(in).at("restart_scene_changes"), nlohmann::json::array());
  }
}

TEST(Restart, PrescribedFlowBitIdentical) {
  expectBitIdenticalRestart("zalesak/zalesak.yaml", {"domain.cells=[48,48,2]", "reinit.interval=3"}, 12);
}

TEST(Restart, CheckpointFilesAtomicAndPruned) {
  TempDir tmp;
  const Scene s = caseScene("taylor_green/taylor_green.yaml",
                            with(kTaylorGreen, {"checkpoint.interval=3", "checkpoint.keep=2"}));
  Simulation sim(s, MPI_COMM_WORLD, runOpts(tmp.sub("out"), 10));
  const RunResult r = sim.run();
  // Every 3 steps (3, 6, 9) and at the end (10); the newest two are kept.
  if (worldRank() == 0) {
    std::vector<std::string> names;
    for (auto& e : fs::directory_iterator(tmp.sub("out")))
      if (e.path().filename().string().rfind("checkpoint", 0) == 0) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"checkpoint_000000009.h5", "checkpoint_000000010.h5"}));
    std::ifstream l(tmp.sub("out/latest"));
    std::string latest;
    l >> latest;
    EXPECT_EQ(latest, "checkpoint_000000010.h5");
  }
  EXPECT_EQ(r.checkpoint, tmp.sub("out/checkpoint_000000010.h5"));
  // Every allocated field is in it (generically: the file lists them), and it loads.
  const std::string file = findCheckpoint(MPI_COMM_WORLD, tmp.sub("out"));
  EXPECT_EQ(file, r.checkpoint);
  Simulation fresh(s, MPI_COMM_WORLD, RunOptions{});
  const nlohmann::json meta = fresh.restore(file);
  std::vector<std::string> inFile;
  for (auto& [k, v] : meta.at("fields").items()) inFile.push_back(k);
  auto names = fresh.state().fields.allocatedNames();
  std::sort(names.begin(), names.end());
  EXPECT_EQ(inFile, names);
  EXPECT_EQ(fresh.state().step, 10);
  EXPECT_EQ(compareFields(sim, fresh, 0), 0);
  EXPECT_TRUE(meta.at("effects").contains("navier_stokes"));
  EXPECT_EQ(meta.at("effects").at("navier_stokes").at("initial_pressure_done"), true);
}

// Rank 0 alone writes a checkpoint at step `half`; both ranks continue it to n and must match
// a 2-rank run from the start to 1e-8 relative (the rank count changes only the order of the
// solver's sums; the scenes solve to 1e-10 or tighter). `diag`: a state diagnostic, to 1e-12.
static void expectOneRankContinuedOnTwo(const Scene& s, long n, long half, TempDir& tmp,
                                        const std::string& metric, const std::string& diag = "") {
  if (worldRank() == 0) {
    Simulation one(s, MPI_COMM_SELF, runOpts(tmp.sub("one"), half));
    one.run();
  }
  MPI_Barrier(MPI_COMM_WORLD);
  Simulation two(s, MPI_COMM_WORLD, runOpts(tmp.sub("one"), n, tmp.sub("one")));
  two.run();
  Simulation ref(s, MPI_COMM_WORLD, runOpts(tmp.sub("ref2"), n));
  ref.run();
  double worst = 0;
  std::string bad;
  EXPECT_EQ(compareFields(ref, two, 1e-8, &worst, &bad), 0) << "worst relative difference " << worst << " in " << bad;
  report(metric, worst);
  EXPECT_EQ(two.state().step, n);
  EXPECT_NEAR(two.state().t, ref.state().t, 1e-12);
  if (!diag.empty()) EXPECT_NEAR(two.state().diag.at(diag), ref.state().diag.at(diag), 1e-12);
}

TEST(Restart, OtherRankCount) {
  if (worldSize() != 2) GTEST_SKIP() << "needs 2 ranks (runs as stability.restart.mpi2)";
  const long n = 12, half = 6;
  const Scene s = caseScene("taylor_green/taylor_green.yaml",
                            with(kTaylorGreen, {"checkpoint.interval=" + std::to_string(half)}));
  TempDir tmp;
  expectOneRankContinuedOnTwo(s, n, half, tmp, "restart_1_to_2_ranks_max_rel_diff");

  // 2 ranks write, 1 rank continues.
  Simulation w2(s, MPI_COMM_WORLD, runOpts(tmp.sub("two"), half));
  w2.run();
  if (worldRank() == 0) {
    Simulation c1(s, MPI_COMM_SELF, runOpts(tmp.sub("two"), n, tmp.sub("two")));
    c1.run();
    Simulation r1(s, MPI_COMM_SELF, runOpts(tmp.sub("ref1"), n));
    r1.run();
    double w = 0;
    std::string bad1;
    EXPECT_EQ(compareFields(r1, c1, 1e-8, &w, &bad1), 0) << "worst relative difference " << w << " in " << bad1;
    report("restart_2_to_1_ranks_max_rel_diff", w);
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

TEST(Restart, LevelSetOtherRankCount) {
  if (worldSize() != 2) GTEST_SKIP() << "needs 2 ranks (runs as stability.restart.mpi2)";
  const long n = 8, half = 4;
  const Scene s = caseScene("rayleigh_taylor/rayleigh_taylor.yaml",
                            with(kRayleighTaylor, {"checkpoint.interval=" + std::to_string(half)}));
  TempDir tmp;
  expectOneRankContinuedOnTwo(s, n, half, tmp, "level_set_restart_1_to_2_ranks_max_rel_diff", "volume_drift");
}

TEST(Restart, RefusesAnotherGrid) {
  TempDir tmp;
  const Scene s = caseScene("taylor_green/taylor_green.yaml", with(kTaylorGreen, {"checkpoint.interval=2"}));
  Simulation a(s, MPI_COMM_WORLD, runOpts(tmp.sub("a"), 2));
  a.run();
  const Scene other = caseScene("taylor_green/taylor_green.yaml", {"domain.cells=[8,16,4]"});
  Simulation b(other, MPI_COMM_WORLD, runOpts(tmp.sub("b"), 4, tmp.sub("a")));
  try {
    b.run();
    ADD_FAILURE() << "restart on another grid was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("checkpoint grid is 16 x 16 x 4 cells, the scene's is 8 x 16 x 4"),
              std::string::npos)
        << e.what();
  }
  // No checkpoint at all: a clear error, not a crash.
  Simulation c(s, MPI_COMM_WORLD, runOpts(tmp.sub("c"), 4, tmp.sub("nothing_here")));
  try {
    c.run();
    ADD_FAILURE() << "restart without a checkpoint was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("restart: no checkpoint at"), std::string::npos) << e.what();
  }
}

TEST(Restart, CheckpointSectionValidated) {
  try {
    const Scene s = caseScene("taylor_green/taylor_green.yaml", {"checkpoint.intervall=3"});
    Simulation sim(s, MPI_COMM_WORLD);
    ADD_FAILURE() << "unknown key accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("checkpoint.intervall"), std::string::npos) << e.what();
  }
  try {
    const Scene s = caseScene("taylor_green/taylor_green.yaml", {"checkpoint.keep=0"});
    Simulation sim(s, MPI_COMM_WORLD);
    ADD_FAILURE() << "keep = 0 accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("checkpoint.keep"), std::string::npos) << e.what();
  }
}
