// Output layer: HDF5/XDMF round trip and probe interpolation of linear fields.
#include "io/checkpoint.hpp"
#include "io/fields_out.hpp"
#include "io/probes.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <hdf5.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace voigt;
namespace fs = std::filesystem;

namespace {

struct Lin {
  double a, b, c, d;
};

// Shared by the fill kernel and the checks so both round identically.
KOKKOS_INLINE_FUNCTION double evalAt(Lin f, const Grid& g, int i, int j, int k, double off) {
  const double x = g.lo[0] + (i + off) * g.h[0];
  const double y = g.lo[1] + (j + off) * g.h[1];
  const double z = g.lo[2] + (k + off) * g.h[2];
  return f.a + f.b * x + f.c * y + f.d * z;
}

// Fills the whole local array, ghosts included, so no halo exchange is needed.
Field fill(const Grid& g, Lin f, Centring c) {
  Field v("v", g.ext[0], g.ext[1], g.ext[2]);
  const double off = c == Centring::Cell ? 0.5 : 0.0;
  const Grid gg = g;
  Kokkos::parallel_for(Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}), KOKKOS_LAMBDA(int i, int j, int k) {
    v(i, j, k) = evalAt(f, gg, gg.global(0, i), gg.global(1, j), gg.global(2, k), off);
  });
  return v;
}

const Lin kP{1.5, 2.0, -3.0, 0.75}, kPhi{-0.25, 0.5, 1.25, -2.0};
const Lin kU[3] = {{1, 1, 0, 0}, {0.5, -2, 3, 1}, {-1, 0.25, 0.5, 4}};

std::vector<OutField> makeFields(const Grid& g) {
  return {{"pressure", Centring::Cell, {fill(g, kP, Centring::Cell)}},
          {"phi", Centring::Node, {fill(g, kPhi, Centring::Node)}},
          {"velocity", Centring::Node,
           {fill(g, kU[0], Centring::Node), fill(g, kU[1], Centring::Node), fill(g, kU[2], Centring::Node)}},
          {"cellvec", Centring::Cell,
           {fill(g, kU[0], Centring::Cell), fill(g, kU[1], Centring::Cell), fill(g, kU[2], Centring::Cell)}}};
}

int worldRank() {
  int r;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

// A fresh directory shared by all ranks, removed on destruction.
struct TempDir {
  std::string path;
  TempDir() {
    char buf[4096] = {};
    if (worldRank() == 0) {
      std::string t = (fs::temp_directory_path() / "voigt_io_XXXXXX").string();
      std::snprintf(buf, sizeof buf, "%s", t.c_str());
      if (!mkdtemp(buf)) buf[0] = 0;
    }
    MPI_Bcast(buf, sizeof buf, MPI_CHAR, 0, MPI_COMM_WORLD);
    path = buf;
  }
  ~TempDir() {
    MPI_Barrier(MPI_COMM_WORLD);
    if (worldRank() == 0 && !path.empty()) fs::remove_all(path);
  }
};

Grid testGrid(std::array<int, 3> dims = {0, 0, 0}) {
  return makeGrid(MPI_COMM_WORLD, {8, 6, 5}, {0.5, -1.0, 2.0}, {2.5, 1.0, 3.25}, {false, true, false}, dims);
}

// Serial read of one dataset; checks its shape and every value (global indices).
void checkDataset(hid_t file, const Grid& g, const std::string& name, const std::vector<Lin>& f, Centring c) {
  const int e = c == Centring::Node ? 1 : 0, nc = int(f.size());
  hid_t ds = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  ASSERT_GE(ds, 0) << name;
  hid_t sp = H5Dget_space(ds);
  hsize_t dims[4] = {};
  const int rank = H5Sget_simple_extent_dims(sp, dims, nullptr);
  H5Sclose(sp);
  ASSERT_EQ(rank, nc == 1 ? 3 : 4) << name;
  EXPECT_EQ(dims[0], hsize_t(g.n[2] + e));
  EXPECT_EQ(dims[1], hsize_t(g.n[1] + e));
  EXPECT_EQ(dims[2], hsize_t(g.n[0] + e));
  if (nc == 3) {
    EXPECT_EQ(dims[3], 3u);
  }
  std::vector<double> v(dims[0] * dims[1] * dims[2] * nc);
  ASSERT_GE(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
  H5Dclose(ds);
  const double off = c == Centring::Cell ? 0.5 : 0.0;
  int bad = 0;
  size_t p = 0;
  for (int k = 0; k < g.n[2] + e; ++k)
    for (int j = 0; j < g.n[1] + e; ++j)
      for (int i = 0; i < g.n[0] + e; ++i)
        for (int m = 0; m < nc; ++m, ++p)
          if (v[p] != evalAt(f[m], g, i, j, k, off) && bad++ < 5)
            ADD_FAILURE() << name << " at (" << i << "," << j << "," << k << ")[" << m << "]: " << v[p]
                          << " != " << evalAt(f[m], g, i, j, k, off);
  EXPECT_EQ(bad, 0) << name;
}

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

void writerRoundTrip(std::array<int, 3> dims) {
  TempDir tmp;
  Grid g = testGrid(dims);
  {
    FieldWriter w(g, tmp.path);
    auto fields = makeFields(g);
    w.write(0, 0.0, fields);
    const std::string h5 = w.write(3, 0.25, fields);
    EXPECT_EQ(h5, tmp.path + "/fields_000003.h5");
  }
  if (g.rank == 0) {
    hid_t f = H5Fopen((tmp.path + "/fields_000003.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    double t = -1;
    hid_t at = H5Aopen(f, "time", H5P_DEFAULT);
    EXPECT_GE(H5Aread(at, H5T_NATIVE_DOUBLE, &t), 0);
    H5Aclose(at);
    EXPECT_EQ(t, 0.25);
    checkDataset(f, g, "pressure", {kP}, Centring::Cell);
    checkDataset(f, g, "phi", {kPhi}, Centring::Node);
    checkDataset(f, g, "velocity", {kU[0], kU[1], kU[2]}, Centring::Node);
    checkDataset(f, g, "cellvec", {kU[0], kU[1], kU[2]}, Centring::Cell);
    H5Fclose(f);

    std::ifstream in(tmp.path + "/fields.xdmf");
    ASSERT_TRUE(in.good());
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string x = ss.str();
    EXPECT_FALSE(fs::exists(tmp.path + "/fields.xdmf.tmp"));
    EXPECT_EQ(x.rfind("<?xml", 0), 0u);
    EXPECT_EQ(count(x, "<Grid "), 3u);
    EXPECT_EQ(count(x, "</Grid>"), 3u);
    EXPECT_EQ(count(x, "<Attribute "), count(x, "</Attribute>"));
    EXPECT_EQ(count(x, "CollectionType=\"Temporal\""), 1u);
    EXPECT_EQ(count(x, "<Time Value=\"0\"/>"), 1u);
    EXPECT_EQ(count(x, "<Time Value=\"0.25\"/>"), 1u);
    EXPECT_EQ(count(x, "TopologyType=\"3DCoRectMesh\" Dimensions=\"6 7 9\""), 2u);
    EXPECT_EQ(count(x, "Center=\"Node\""), 4u);
    EXPECT_EQ(count(x, "Center=\"Cell\""), 4u);
    EXPECT_EQ(count(x, "AttributeType=\"Vector\""), 4u);
    EXPECT_EQ(count(x, "Dimensions=\"5 6 8\""), 2u);    // scalar cell
    EXPECT_EQ(count(x, "Dimensions=\"6 7 9 3\""), 2u);  // vector node
    EXPECT_EQ(count(x, "fields_000003.h5:/velocity"), 1u);
    EXPECT_NE(x.find(">2 -1 0.5</DataItem>"), std::string::npos); // origin, z y x
    EXPECT_NE(x.find("</Xdmf>"), std::string::npos);
  }
  freeGrid(g);
}

TEST(FieldWriter, LinearRoundTripAutoDecomposition) { writerRoundTrip({0, 0, 0}); }

TEST(FieldWriter, LinearRoundTripSplitYandZ) {
  int size;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size != 2) GTEST_SKIP() << "needs 2 ranks";
  writerRoundTrip({1, 2, 1}); // splits the periodic axis
  writerRoundTrip({1, 1, 2});
}

std::vector<std::vector<double>> readCsv(const std::string& path, std::string& header) {
  std::ifstream in(path);
  std::getline(in, header);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<double> r;
    std::stringstream ls(line);
    for (std::string c; std::getline(ls, c, ',');) r.push_back(std::stod(c));
    rows.push_back(r);
  }
  return rows;
}

double lin(Lin f, double x, double y, double z) { return f.a + f.b * x + f.c * y + f.d * z; }

void expectSample(const std::vector<double>& r, size_t off, double x, double y, double z) {
  ASSERT_GE(r.size(), off + 4);
  for (int m = 0; m < 3; ++m) EXPECT_NEAR(r[off + m], lin(kU[m], x, y, z), 1e-12) << "velocity " << m;
  EXPECT_NEAR(r[off + 3], lin(kP, x, y, z), 1e-12) << "pressure";
}

void probeLinear(std::array<int, 3> dims) {
  TempDir tmp;
  Grid g = testGrid(dims);
  auto fields = makeFields(g);
  Probe pt, onFace, nearPeriodic, line;
  pt.name = "pt";
  pt.a = {1.234, 0.1, 2.61};
  onFace.name = "face"; // on a cell face/rank boundary: must be counted once
  onFace.a = {0.5 + 4 * 0.25, 0.0, 2.0 + 2 * 0.25};
  nearPeriodic.name = "per"; // reads the periodic ghost cell centre
  nearPeriodic.a = {1.1, -0.95, 2.4};
  line.name = "line";
  line.kind = Probe::Kind::Line;
  line.a = {0.7, -0.8, 2.2};
  line.b = {2.3, 0.9, 3.1};
  line.points = 7;
  ProbeSet probes(g, {pt, onFace, nearPeriodic, line}, tmp.path);
  probes.sample(0.0, fields);
  probes.sample(0.5, fields);
  if (g.rank == 0) {
    std::string h;
    for (const Probe* p : {&pt, &onFace, &nearPeriodic}) {
      auto rows = readCsv(tmp.path + "/probe_" + p->name + ".csv", h);
      EXPECT_EQ(h, "t,velocity_x,velocity_y,velocity_z,pressure");
      ASSERT_EQ(rows.size(), 2u) << p->name;
      EXPECT_EQ(rows[1][0], 0.5);
      for (const auto& r : rows) expectSample(r, 1, p->a[0], p->a[1], p->a[2]);
    }
    auto rows = readCsv(tmp.path + "/probe_line.csv", h);
    EXPECT_EQ(h, "t,s,x,y,z,velocity_x,velocity_y,velocity_z,pressure");
    ASSERT_EQ(rows.size(), 14u);
    const double len = std::sqrt(1.6 * 1.6 + 1.7 * 1.7 + 0.9 * 0.9);
    for (int q = 0; q < 14; ++q) {
      const auto& r = rows[q];
      ASSERT_EQ(r.size(), 9u);
      EXPECT_EQ(r[0], q < 7 ? 0.0 : 0.5);
      EXPECT_NEAR(r[1], len * (q % 7) / 6.0, 1e-12);
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(r[2 + d], line.a[d] + (line.b[d] - line.a[d]) * (q % 7) / 6.0, 1e-12);
      expectSample(r, 5, r[2], r[3], r[4]);
    }
  }
  freeGrid(g);
}

// A checkpoint whose metadata differs between ranks (wall_seconds_total, the level set's
// fm_seconds: each rank's clock). HDF5 metadata writes are collective with identical arguments;
// an 'effects' attribute 300 kB longer on rank 1 hangs H5Fclose without the broadcast (checked:
// killed after 60 s), as a 48^3 falling block hung at its first checkpoint at 2 ranks
// (2026-12-03). The file holds rank 0's metadata.
TEST(Checkpoint, RankDependentMetadata) {
  Grid g = testGrid();
  TempDir dir;
  FieldStore fs;
  for (int i = 0; i < 12; ++i) fs.declare("f" + std::to_string(i), i % 2 ? Centring::Cell : Centring::Node, i % 3 ? 1 : 3, "test");
  fs.allocate(g);
  const int r = worldRank();
  nlohmann::json meta = {{"t", 0.5}, {"wall_seconds_total", 1.0 + 0.123456789 * r}, {"note", std::string(5 + 7 * r, 'x')},
                         {"effects", {{"state", std::string(10 + 300000 * r, 'y')}}}}; // an attribute: metadata
  const std::string path = Checkpointer(g, dir.path, 2).write(7, fs, meta);
  if (r == 0) {
    hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(f, 0) << path;
    hid_t ds = H5Dopen2(f, "meta", H5P_DEFAULT);
    hid_t sp = H5Dget_space(ds);
    hsize_t n = 0;
    H5Sget_simple_extent_dims(sp, &n, nullptr);
    std::string text(n, ' ');
    H5Dread(ds, H5T_NATIVE_CHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data());
    H5Sclose(sp);
    H5Dclose(ds);
    H5Fclose(f);
    const auto j = nlohmann::json::parse(text);
    EXPECT_EQ(j["note"].get<std::string>(), "xxxxx");
    EXPECT_EQ(j["wall_seconds_total"].get<double>(), 1.0);
    EXPECT_EQ(j["effects"]["state"].get<std::string>().size(), 10u);
  }
}

TEST(ProbeSet, LinearFieldsAreExact) { probeLinear({0, 0, 0}); }

TEST(ProbeSet, LinearFieldsAreExactSplitYandZ) {
  int size;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size != 2) GTEST_SKIP() << "needs 2 ranks";
  probeLinear({1, 2, 1}); // the periodic axis: ghost cell centres across ranks
  probeLinear({1, 1, 2});
}

TEST(ProbeSet, IntervalForceAndMissingField) {
  TempDir tmp;
  Grid g = testGrid();
  auto fields = makeFields(g);
  Probe p;
  p.name = "p";
  p.a = {1.0, 0.0, 2.5};
  p.fields = {"pressure"};
  p.interval = 0.1;
  Probe missing = p;
  missing.name = "m";
  missing.fields = {"pressure", "temperature"};
  {
    ProbeSet probes(g, {p}, tmp.path);
    for (double t : {0.0, 0.05, 0.1, 0.15, 0.2}) probes.sample(t, fields);
    probes.sample(0.2, fields, true); // forced at the time just sampled: no second row
    probes.sample(0.23, fields, true);
  }
  if (g.rank == 0) {
    std::string h;
    auto rows = readCsv(tmp.path + "/probe_p.csv", h);
    EXPECT_EQ(h, "t,pressure");
    ASSERT_EQ(rows.size(), 4u);
    const double ts[] = {0.0, 0.1, 0.2, 0.23};
    for (int i = 0; i < 4; ++i) EXPECT_EQ(rows[i][0], ts[i]);
  }
  ProbeSet bad(g, {missing}, tmp.path);
  try {
    bad.sample(0.0, fields);
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'m'"), std::string::npos) << m;
    EXPECT_NE(m.find("temperature"), std::string::npos) << m;
  }
  freeGrid(g);
}

} // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  Kokkos::initialize(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  if (worldRank() != 0) { // one report, from rank 0
    auto& l = ::testing::UnitTest::GetInstance()->listeners();
    delete l.Release(l.default_result_printer());
  }
  int rc = RUN_ALL_TESTS(), worst = 0;
  MPI_Allreduce(&rc, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  Kokkos::finalize();
  MPI_Finalize();
  return worst;
}
