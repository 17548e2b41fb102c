// The stress jump at a solid's edge under rigid rotation (issue 21 item 3: "a
// transport of tau_S that keeps the jump within 2 cells under rigid rotation").
//
// The pre-stressed disk of test_objectivity.cpp (rotating_disk.hpp) turns through
// 90 and 360 degrees at 64 cells. In a rigid rotation every cell holds
// s(x) M tau0 (M the Jaumann map, the same everywhere), so s = zz / zz0 is the
// transported solid stress relative to the solid's, and the stress the flow
// sees, H(psi) tau_S (Eq. 5), is H s times the solid's.
// Width of a 0-to-1 profile q: the area where 0.1 < q < 0.9 over the disk's
// perimeter, in cells. A sine-smoothed H (Eq. 4, kappa = 2 cells) has
// u + sin(pi u) / pi = 0.8 at u = 0.491, so width(H) = 0.98 kappa = 1.96 cells.
//
// fluid_side: extend (the default): the band's fluid side is rebuilt every step
// as the solid stress extended along the normal (kernels/extension.hpp), a
// weighted mean of equal values here, so the transport never sees a jump: s = 1
// to round-off wherever H > 0, and the blended stress's width is that of H
// alone, independent of the limiter. fluid_side: integrate (the paper's): s
// itself carries the jump and MUSCL smears it. Measured (90 / 360 degrees):
//   width of s:   MinMod 4.7 / 6.7 cells, MC 3.2 / 4.6;
//   width of H s: MinMod 2.7 / 4.1 cells, MC 1.94 / 2.7 (extend: 1.91 / 1.80-1.91).
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <string>

#include "core/field_names.hpp"
#include "effects/elasticity/elasticity.hpp"
#include "elasticity/rotating_disk.hpp"
#include "kernels/heaviside.hpp"
#include "support/flow.hpp"

using namespace voigt;
using namespace rotating_disk;

namespace {

struct Jump {
  double widthS = 0, widthHS = 0, widthH = 0; // cells
  double maxDevInBand = 0;                   // max |s - 1| where H(psi) > 0
};

Jump measureJump(const Simulation& sim) {
  const State& st = sim.state();
  const Grid& g = st.grid;
  const SymTensorField t = solidStressField(st.fields);
  auto zz = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t.c[2]);
  auto psi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.fields.scalar(field::psi));
  const double h = g.h[0], kappa = 2 * h;
  double zone[3] = {0, 0, 0}; // cell areas with 0.1 < q < 0.9 for q = s, H s, H (one z layer)
  Jump j;
  const Range3 r = cellRange(g);
  for (int k = r.b[2]; k < r.e[2]; ++k) {
    if (g.global(2, k) != 0) continue;
    for (int jj = r.b[1]; jj < r.e[1]; ++jj)
      for (int i = r.b[0]; i < r.e[0]; ++i) {
        const double s = zz(i, jj, k) / kTau0[2], H = smoothedHeaviside(psi(i, jj, k), kappa);
        const double q[3] = {s, H * s, H};
        for (int c = 0; c < 3; ++c) zone[c] += (q[c] > 0.1 && q[c] < 0.9) ? h * h : 0;
        if (H > 0) j.maxDevInBand = std::max(j.maxDevInBand, std::abs(s - 1));
      }
  }
  MPI_Allreduce(MPI_IN_PLACE, zone, 3, MPI_DOUBLE, MPI_SUM, g.comm);
  MPI_Allreduce(MPI_IN_PLACE, &j.maxDevInBand, 1, MPI_DOUBLE, MPI_MAX, g.comm);
  const double perimeter = 2 * M_PI * kR;
  j.widthS = zone[0] / perimeter / h;
  j.widthHS = zone[1] / perimeter / h;
  j.widthH = zone[2] / perimeter / h;
  return j;
}

// Turns the disk through each angle and returns the measures; tag_* reported.
std::vector<Jump> turn(const std::string& fluidSide, const std::string& limiter, const std::string& tag) {
  Simulation sim(test::scene(rotating_disk::scene(64, 0.5, "", fluidSide, limiter)), MPI_COMM_WORLD, RunOptions{});
  sim.initialize();
  std::vector<Jump> out;
  for (double deg : {90.0, 360.0}) {
    const double theta = deg * M_PI / 180;
    sim.advanceTo(theta / kOmega);
    const Jump j = measureJump(sim);
    const std::string key = tag + "_" + std::to_string(int(deg)) + "deg";
    test::report(key + "_width_s_cells", j.widthS);
    test::report(key + "_width_Hs_cells", j.widthHS);
    test::report(key + "_width_H_cells", j.widthH);
    test::report(key + "_max_abs_s_minus_1_where_H_positive", j.maxDevInBand);
    out.push_back(j);
  }
  return out;
}

} // namespace

// The default: the blended stress's jump is H's own, within 2 cells, after a
// quarter and a whole turn, with either limiter.
TEST(StressJump, ExtendKeepsTheJumpToTheBand) {
  for (const char* lim : {"minmod", "mc"}) {
    const std::vector<Jump> js = turn("extend", lim, std::string("extend_") + lim);
    for (const Jump& j : js) {
      // A weighted mean of equal values and the transport of a uniform field.
      // Measured 1e-15 (MC) and 1e-10 (MinMod: what the transport left beyond
      // the layers the extension reaches creeps back); a smeared jump is O(0.1-1).
      EXPECT_LT(j.maxDevInBand, 1e-8) << lim;
      // The stress adds nothing to H's width. H's own is 1.80-1.91 cells here
      // (0.98 kappa = 1.96 for a signed distance; the scene has no reinit, so
      // |grad psi| drifts above 1 and the cell count samples the annulus).
      EXPECT_NEAR(j.widthHS, j.widthH, 1e-6) << lim;
      EXPECT_LT(j.widthHS, 2.0) << lim;
    }
  }
}

// The paper's model: the transported stress carries the jump and MUSCL widens
// it beyond the band (so the measure above sees smearing when there is some).
TEST(StressJump, IntegrateSmearsTheJump) {
  const std::vector<Jump> mm = turn("integrate", "minmod", "integrate_minmod");
  const std::vector<Jump> mc = turn("integrate", "mc", "integrate_mc");
  for (size_t a = 0; a < mm.size(); ++a) {
    EXPECT_GT(mm[a].widthHS, 2.5);          // measured 2.7 / 4.1 cells (header)
    EXPECT_LT(mc[a].widthS, mm[a].widthS);  // the compressive limiter smears less
  }
  EXPECT_GT(mm[1].widthS, mm[0].widthS); // and the smearing grows with the distance carried
}
