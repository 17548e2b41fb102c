// The host-touch check (core/host_access.hpp) on the Serial build: armed, a field is
// reachable from kernels, deep copies and toHost/toDevice, and host code that dereferences
// it anywhere else kills the process with kHostTouchExit and the field's name. The whole
// program runs armed (its own executable), as `VOIGT_HOST_TOUCH_CHECK=1 voigt` does.
#include <gtest/gtest.h>
#include <mpi.h>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/host_access.hpp"

using namespace voigt;

namespace {

struct Armed : ::testing::Test {
  static void SetUpTestSuite() { host_access::arm(); }
  Grid g = makeGrid(MPI_COMM_SELF, {24, 24, 24}, {0, 0, 0}, {1, 1, 1}, {false, false, false}, {0, 0, 0});
  FieldStore fs;
  void SetUp() override {
    fs.declare("probe", Centring::Cell, 1, "test");
    fs.declare("vel", Centring::Node, 3, "test");
    fs.allocate(g);
  }
  void TearDown() override { freeGrid(g); }
};

TEST_F(Armed, FieldsAreRegisteredAndKernelsReachThem) {
  const Field f = fs.scalar("probe");
  EXPECT_TRUE(host_access::isField(f.data()));
  EXPECT_TRUE(host_access::isField(fs.vector("vel").c[2].data() + 5));
  EXPECT_FALSE(host_access::isField(&g)); // host memory
  const long long k0 = host_access::kernels(), c0 = host_access::deepCopies();
  Kokkos::parallel_for(
      "fill", Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}),
      KOKKOS_LAMBDA(int i, int j, int k) { f(i, j, k) = i + 100.0 * j + 1e4 * k; });
  double sum = 0;
  Kokkos::parallel_reduce(
      "sum", Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}),
      KOKKOS_LAMBDA(int i, int j, int k, double& s) { s += f(i, j, k); }, sum);
  EXPECT_GT(sum, 0);
  const Field v = fs.vector("vel").c[0];
  Kokkos::deep_copy(v, f); // field to field: a deep copy opens the pages too
  Kokkos::deep_copy(fs.vector("vel").c[1], 2.5);
  EXPECT_GE(host_access::kernels() - k0, 2); // and whatever deep_copy launched
  EXPECT_GE(host_access::deepCopies() - c0, 2);
}

TEST_F(Armed, ToHostCopiesAndToDeviceWritesBack) {
  const Field f = fs.scalar("probe");
  Kokkos::deep_copy(f, 3.0);
  host_access::reset();
  auto h = toHost(f, "test_read");
  EXPECT_NE(h.data(), f.data()); // armed: a copy, as on a device
  EXPECT_EQ(h(3, 4, 5), 3.0);
  h(3, 4, 5) = -1.0;
  double seen = 0;
  Kokkos::parallel_reduce(
      "read", 1, KOKKOS_LAMBDA(int, double& s) { s += f(3, 4, 5); }, seen);
  EXPECT_EQ(seen, 3.0); // the host copy is not the field
  toDevice(f, h, "test_write");
  Kokkos::parallel_reduce(
      "read", 1, KOKKOS_LAMBDA(int, double& s) { s += f(3, 4, 5); }, seen = 0);
  EXPECT_EQ(seen, -1.0);
  const auto& c = host_access::copies();
  ASSERT_EQ(c.count("test_read"), 1u);
  EXPECT_EQ(c.at("test_read").count, 1);
  EXPECT_EQ(c.at("test_read").bytes, (long long)f.span() * 8);
  EXPECT_EQ(c.at("test_write").count, 1);
}

// The point of the check: a host read or write of a field outside the allowed paths.
TEST_F(Armed, HostTouchOfAFieldDies) {
  const Field f = fs.scalar("probe");
  const int mid = g.ext[0] / 2;
  EXPECT_EXIT({ f(mid, mid, mid) = 1.0; }, ::testing::ExitedWithCode(host_access::kHostTouchExit),
              "host code touched field 'probe'");
  const Field w = fs.vector("vel").c[1];
  EXPECT_EXIT(
      {
        volatile double x = w(mid, mid, mid);
        (void)x;
      },
      ::testing::ExitedWithCode(host_access::kHostTouchExit), "touched field 'vel_y'");
}

// Kokkos frees a field: its pages open again before the allocator reuses them.
TEST_F(Armed, FreedFieldsAreForgotten) {
  const void* p = nullptr;
  {
    FieldStore tmp;
    tmp.declare("short_lived", Centring::Cell, 1, "test");
    tmp.allocate(g);
    p = tmp.scalar("short_lived").data();
    EXPECT_TRUE(host_access::isField(p));
  }
  EXPECT_FALSE(host_access::isField(p));
  std::vector<double> reuse(size_t(g.ext[0]) * g.ext[1] * g.ext[2], 1.0); // may land on those pages
  EXPECT_EQ(reuse.back(), 1.0);
}

} // namespace
