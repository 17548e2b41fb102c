// Output safety: an existing output directory is never overwritten without
// --overwrite (and --overwrite only replaces Voigt output); an unwritable
// directory or a full disk gives a clear error, and a checkpoint that cannot
// be written leaves the previous one intact.
#include <sys/mount.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "io/checkpoint.hpp"
#include "stability/support.hpp"

using namespace voigt;
using namespace voigt::test;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kSmall = {"domain.cells=[16,16,4]", "output.interval=0.25", "time.end=10"};

// Expects run() to throw a runtime_error whose text contains every `parts` entry.
void expectRunError(Simulation& sim, const std::vector<std::string>& parts) {
  try {
    sim.run();
    ADD_FAILURE() << "run succeeded";
  } catch (const std::runtime_error& e) {
    for (auto& p : parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
  }
}

// A tmpfs mounted by rank 0 (needs root); unmounted by the destructor.
struct TmpfsMount {
  std::string path;
  bool ok = false;
  TmpfsMount(const std::string& p, const char* opts, unsigned long flags) : path(p) {
    int good = 0;
    if (worldRank() == 0) {
      fs::create_directories(p);
      good = geteuid() == 0 && ::mount("tmpfs", p.c_str(), "tmpfs", flags, opts) == 0;
    }
    MPI_Bcast(&good, 1, MPI_INT, 0, MPI_COMM_WORLD);
    ok = good;
  }
  ~TmpfsMount() {
    MPI_Barrier(MPI_COMM_WORLD);
    if (ok && worldRank() == 0) ::umount2(path.c_str(), MNT_DETACH);
  }
};

} // namespace

TEST(OutputSafety, ExistingDirectoryNeedsOverwrite) {
  TempDir tmp;
  const Scene s = caseScene("taylor_green/taylor_green.yaml", kSmall);
  if (worldRank() == 0) {
    fs::create_directories(tmp.sub("out"));
    std::ofstream(tmp.sub("out/summary.json")) << "{\"keep\": true}\n";
  }
  MPI_Barrier(MPI_COMM_WORLD);
  {
    Simulation sim(s, MPI_COMM_WORLD, runOpts(tmp.sub("out"), 2));
    expectRunError(sim, {"output directory '" + tmp.sub("out") + "' exists and is not empty (use --overwrite)"});
  }
  if (worldRank() == 0) {
    std::ifstream in(tmp.sub("out/summary.json"));
    std::string text((std::istreambuf_iterator<char>(in)), {});
    EXPECT_EQ(text, "{\"keep\": true}\n"); // untouched
  }
  // With --overwrite a directory of Voigt output is replaced.
  RunOptions o = runOpts(tmp.sub("out"), 2);
  o.overwrite = true;
  Simulation sim(s, MPI_COMM_WORLD, o);
  sim.run();
  if (worldRank() == 0) EXPECT_TRUE(fs::exists(tmp.sub("out/fields_000000.h5")));
}

TEST(OutputSafety, OverwriteNeverDeletesForeignFiles) {
  TempDir tmp;
  const Scene s = caseScene("taylor_green/taylor_green.yaml", kSmall);
  if (worldRank() == 0) {
    fs::create_directories(tmp.sub("home"));
    std::ofstream(tmp.sub("home/thesis.tex")) << "precious\n";
    std::ofstream(tmp.sub("home/summary.json")) << "{}\n";
  }
  MPI_Barrier(MPI_COMM_WORLD);
  RunOptions o = runOpts(tmp.sub("home"), 2);
  o.overwrite = true;
  Simulation sim(s, MPI_COMM_WORLD, o);
  expectRunError(sim, {"holds files Voigt did not write"});
  if (worldRank() == 0) EXPECT_TRUE(fs::exists(tmp.sub("home/thesis.tex")));
}

TEST(OutputSafety, UnwritableDirectory) {
  TempDir tmp;
  const Scene s = caseScene("taylor_green/taylor_green.yaml", kSmall);
  // Root ignores permission bits: a read-only tmpfs is the honest test then.
  std::string expect;
  std::unique_ptr<TmpfsMount> ro;
  if (geteuid() == 0) {
    ro = std::make_unique<TmpfsMount>(tmp.sub("ro"), "size=64k", MS_RDONLY);
    if (!ro->ok) GTEST_SKIP() << "root but cannot mount a read-only tmpfs";
    expect = "Read-only file system";
  } else {
    if (worldRank() == 0) {
      fs::create_directories(tmp.sub("ro"));
      ::chmod(tmp.sub("ro").c_str(), 0555);
    }
    MPI_Barrier(MPI_COMM_WORLD);
    expect = "Permission denied";
  }
  {
    Simulation sim(s, MPI_COMM_WORLD, runOpts(tmp.sub("ro"), 2));
    expectRunError(sim, {"output directory '" + tmp.sub("ro") + "' is not writable: " + expect});
  }
  {
    Simulation sim(s, MPI_COMM_WORLD, runOpts(tmp.sub("ro/sub"), 2));
    expectRunError(sim, {"cannot create output directory '" + tmp.sub("ro/sub") + "'", expect});
  }
  if (worldRank() == 0 && geteuid() != 0) ::chmod(tmp.sub("ro").c_str(), 0755);
}

TEST(OutputSafety, FullDiskKeepsPreviousCheckpoint) {
  TempDir tmp;
  // 16 x 16 x 4 cells: a checkpoint is ~230 kB, 1 MiB holds four, and keep = 4 needs a fifth
  // for the temporary file.
  TmpfsMount disk(tmp.sub("disk"), "size=1m", 0);
  if (!disk.ok) GTEST_SKIP() << "needs root to mount a 1 MiB tmpfs";
  const Scene s = caseScene("taylor_green/taylor_green.yaml",
                            {"domain.cells=[16,16,4]", "output.enabled=false", "time.end=10",
                             "checkpoint.interval=1", "checkpoint.keep=4"});
  Simulation sim(s, MPI_COMM_WORLD, runOpts(tmp.sub("disk/out"), 40));
  std::string msg;
  try {
    sim.run();
  } catch (const std::runtime_error& e) {
    msg = e.what();
  }
  ASSERT_FALSE(msg.empty()) << "a full disk went unnoticed";
  EXPECT_NE(msg.find("No space left on device"), std::string::npos) << msg;
  EXPECT_NE(msg.find("earlier checkpoints in " + tmp.sub("disk/out") + " are untouched"), std::string::npos) << msg;
  // The newest complete checkpoint restarts.
  const std::string file = findCheckpoint(MPI_COMM_WORLD, tmp.sub("disk/out"));
  Simulation fresh(s, MPI_COMM_WORLD, RunOptions{});
  fresh.restore(file);
  EXPECT_GT(fresh.state().step, 0);
  EXPECT_LT(fresh.state().step, sim.state().step + 1);
  if (worldRank() == 0) EXPECT_FALSE(fs::exists(tmp.sub("disk/out/checkpoint.h5.tmp")));
  if (worldRank() == 0)
    std::printf("[ measured ] full disk after step %ld, newest good checkpoint %s\n", sim.state().step, file.c_str());
}
