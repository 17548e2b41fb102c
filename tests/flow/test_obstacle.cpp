// Flow past a fixed cylinder (cases/cylinder): mass is conserved to solver
// tolerance and nothing flows through the obstacle.
#include <gtest/gtest.h>

#include <cmath>

#include "support/flow.hpp"

using namespace voigt;

namespace {
// Volume flux through the node plane at global index ip (normal x): the
// discrete D telescopes, so F(ip) - F(0) = sum of D u over the cells between.
double planeFlux(const Grid& g, const VecField& u, int ip) {
  const int ic = std::min(ip, g.n[0] - 1), face = ip == g.n[0] ? 1 : 0;
  if (ic < g.c0[0] || ic >= g.c1[0]) return 0; // MPI_Allreduce below still runs
  const int li = g.local(0, ic) + face;
  const double area = g.h[1] * g.h[2];
  auto ux = u.c[0];
  double f = 0;
  Kokkos::parallel_reduce(
      "plane_flux", Kokkos::MDRangePolicy<ExecSpace, Kokkos::Rank<2>>({g.ng, g.ng}, {g.ng + g.ln[1], g.ng + g.ln[2]}),
      KOKKOS_LAMBDA(int j, int k, double& acc) {
        acc += 0.25 * area * (ux(li, j, k) + ux(li, j + 1, k) + ux(li, j, k + 1) + ux(li, j + 1, k + 1));
      },
      f);
  return f;
}
} // namespace

TEST(Obstacle, CylinderConservesMass) {
  auto s = test::scene(
      "name: cyl\ndomain: {lo: [0,0,0], hi: [1.6,0.4,0.05], cells: [64,16,2]}\n"
      "boundaries: {x-: {type: inflow, velocity: [1,0,0]}, x+: {type: outflow}, y-: {type: slip}, y+: {type: slip},"
      " z-: {type: periodic}, z+: {type: periodic}}\n"
      "materials: {water: {density: 1000, viscosity: 1.0}}\n"
      "effects: [navier_stokes, obstacles]\n"
      "obstacles: [{type: cylinder, center: [0.3, 0.2, 0.025], radius: 0.06, axis: z}]\n"
      "initial: {velocity: uniform, uniform: [1,0,0]}\n"
      "time: {end: 1, cfl: 0.5, max_steps: 10}\n"
      "projection: {operator: exact, tolerance: 1e-10, max_iterations: 5000}\n"
      "output: {enabled: false}\n");
  auto sim = test::runScene(s);
  const Grid& g = sim->state().grid;
  VecField u = sim->state().fields.vector("velocity");
  const double inflow = 1.0 * 0.4 * 0.05;
  double worst = 0;
  for (int ip = 0; ip <= g.n[0]; ++ip) {
    double f = planeFlux(g, u, ip);
    MPI_Allreduce(MPI_IN_PLACE, &f, 1, MPI_DOUBLE, MPI_SUM, g.comm);
    worst = std::max(worst, std::abs(f - inflow) / inflow);
  }
  // Each cell's D u is at most tol * ||b|| * dt (see test_projection); summed
  // over the 1024 cells that is far below 1e-6 of the inflow.
  EXPECT_LT(worst, 1e-6);
  EXPECT_LT(sim->state().diag.at("poisson_residual"), 1e-9);
  // Nodes inside the cylinder hold zero velocity.
  auto ux = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), u.c[0]);
  for (int li = g.ng; li < g.ng + g.ln[0]; ++li)
    for (int lj = g.ng; lj < g.ng + g.ln[1]; ++lj) {
      const Vec3 x = test::nodePos(g, li, lj, g.ng);
      if ((x[0] - 0.3) * (x[0] - 0.3) + (x[1] - 0.2) * (x[1] - 0.2) <= 0.06 * 0.06) EXPECT_EQ(ux(li, lj, g.ng), 0.0);
    }
}
