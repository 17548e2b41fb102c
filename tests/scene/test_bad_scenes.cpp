// The bad-scene corpus (tests/scene/bad/*.yaml, expectations in bad/expected.tsv):
// each scene, loaded as `voigt check`/`run` load it and set up (effects configured,
// fields declared, memory checked; nothing allocated), must throw a SceneError whose
// message starts with "FILE:LINE:" and names the key. Anything else (another
// exception type, acceptance, a crash) fails. Every .yaml in bad/ must be in the table.
#include <gtest/gtest.h>
#include <mpi.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "app/simulation.hpp"
#include "effects/effect.hpp"
#include "scene/load.hpp"
#include "scene/reader.hpp"

using namespace voigt;

namespace {

const std::string kDir = VOIGT_SOURCE_DIR "/tests/scene/bad/";

struct BadFile {
  std::string file;
  int line = 0;
  std::string expect; // key path, or a message fragment for invalid YAML
};

std::vector<BadFile> readTable() {
  std::vector<BadFile> out;
  std::ifstream in(kDir + "expected.tsv");
  for (std::string row; std::getline(in, row);) {
    if (row.empty() || row[0] == '#') continue;
    std::istringstream r(row);
    BadFile b;
    std::string line;
    std::getline(r, b.file, '\t');
    std::getline(r, line, '\t');
    std::getline(r, b.expect);
    b.line = std::stoi(line);
    out.push_back(b);
  }
  return out;
}

// As src/cli/main.cpp loads a scene, then what the Simulation constructor checks.
void loadAndSetUp(const std::string& path) {
  const Scene scene = loadSceneWithEffects(path);
  Simulation sim(scene, MPI_COMM_WORLD);
}

class BadFiles : public ::testing::TestWithParam<BadFile> {};

TEST_P(BadFiles, RefusedWithFileLineAndKey) {
  const BadFile& c = GetParam();
  const std::string path = kDir + c.file;
  try {
    loadAndSetUp(path);
    ADD_FAILURE() << c.file << " was accepted";
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path + ":" + std::to_string(c.line) + ":", 0), 0u)
        << "expected " << c.file << ":" << c.line << ":, got: " << msg;
    EXPECT_NE(msg.find(c.expect), std::string::npos) << "expected '" << c.expect << "' in: " << msg;
  } catch (const std::exception& e) {
    ADD_FAILURE() << c.file << ": not a SceneError: " << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadFiles, ::testing::ValuesIn(readTable()), [](const auto& info) {
  std::string n = info.param.file.substr(0, info.param.file.find('.'));
  for (auto& ch : n)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n;
});

TEST(BadFiles, EveryFileIsInTheTable) {
  std::set<std::string> listed;
  for (auto& b : readTable()) listed.insert(b.file);
  EXPECT_GE(listed.size(), 30u);
  for (auto& e : std::filesystem::directory_iterator(kDir))
    if (e.path().extension() == ".yaml")
      EXPECT_TRUE(listed.count(e.path().filename().string())) << e.path() << " is not in expected.tsv";
  for (auto& f : listed) EXPECT_TRUE(std::filesystem::exists(kDir + f)) << f << " is listed but missing";
}

// The memory refusal carries the estimate (and comes before anything is allocated).
TEST(BadFiles, GridTooLargeGivesTheEstimate) {
  try {
    loadAndSetUp(kDir + "grid_too_large.yaml");
    ADD_FAILURE() << "accepted";
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(" GiB but only "), std::string::npos) << msg;
    EXPECT_NE(msg.find(" GiB of memory is available"), std::string::npos) << msg;
  }
}

} // namespace
