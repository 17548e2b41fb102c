// The velocity a solid's surface moves with (level_set.surface_velocity: solid,
// kernels/surface_velocity.hpp), on a plane: psi = 0.5 - y, the solid below.
// The grid's velocity is the solid's, u_s = (1 + 0.5 x, -0.2, 0.3 z) (tangentially varying, so
// a mean over neighbours must reproduce a linear field), below the plane, and above it the
// gas's, u_s plus a slip that grows away from the surface and a normal velocity varying along
// x: what drags psi = 0 with it when the surface moves with the grid's velocity.
// Asserted, by the weights' symmetry (a plane normal to y: each node averages the nodes one
// layer down, symmetrically in x and z, so a linear field is reproduced to round-off):
//  - every listed node (lo < psi_n <= 0) holds
//    u_s to 1e-12 (here the planes psi_n = 0, -h, -2h);
//  - nodes further out keep the gas's velocity, nodes in the solid the solid's (unchanged bits);
//  - a node's prescribed component (fix_mask) keeps the grid's value.
// At 1 and 2 ranks (the decomposition along x: a rank boundary crosses the layer; the sweeps are
// Jacobi with ghosts exchanged before each, so the result is the same).
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>

#include "core/grid.hpp"
#include "core/halo.hpp"
#include "core/host_access.hpp"
#include "kernels/surface_velocity.hpp"
#include "support/flow.hpp"

using namespace voigt;

TEST(SurfaceVelocity, ThePlaneLayerTakesTheSolidsVelocity) {
  std::array<bool, 3> per{false, false, false};
  Grid g = makeGrid(MPI_COMM_WORLD, {24, 24, 24}, {0, 0, 0}, {1, 1, 1}, per, {0, 0, 0});
  Halo halo(g);
  const double h = g.h[0], lo = -2.5 * h; // between node planes: no ties in the test
  Field psi("psi", g.ext[0], g.ext[1], g.ext[2]), pn("pn", g.ext[0], g.ext[1], g.ext[2]);
  IntField mask("mask", g.ext[0], g.ext[1], g.ext[2]);
  VecField u, v, w;
  for (int c = 0; c < 3; ++c) {
    u.c[c] = Field("u", g.ext[0], g.ext[1], g.ext[2]);
    v.c[c] = Field("v", g.ext[0], g.ext[1], g.ext[2]);
    w.c[c] = Field("w", g.ext[0], g.ext[1], g.ext[2]);
  }
  const int ng = g.ng, c0 = g.c0[0], c1 = g.c0[1], c2 = g.c0[2];
  // The node (12, 14, 12) (global) is in the layer's last plane (psi_n = -2h, read by no listed node): its x component is
  // prescribed at 7.
  Kokkos::parallel_for(
      "sv_init", Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}), KOKKOS_LAMBDA(int i, int j, int k) {
        const double xc = (i - ng + c0 + 0.5) * h, yc = (j - ng + c1 + 0.5) * h;
        psi(i, j, k) = 0.5 - yc;
        (void)xc;
        const int gi = i - ng + c0, gj = j - ng + c1, gk = k - ng + c2;
        const double x = gi * h, y = gj * h, z = gk * h; // the node
        const double us[3] = {1 + 0.5 * x, -0.2, 0.3 * z};
        const double slip = y > 0.5 ? 4 * (y - 0.5) : 0.0, wave = y > 0.5 ? 0.3 * std::sin(8 * M_PI * x) : 0.0;
        u.c[0](i, j, k) = us[0] + slip;
        u.c[1](i, j, k) = us[1] + wave;
        u.c[2](i, j, k) = us[2] + 0.5 * slip;
        mask(i, j, k) = gi == 12 && gj == 14 && gk == 12 ? 1 : 0;
        if (mask(i, j, k)) u.c[0](i, j, k) = 7;
      });
  surface_velocity::nodeLevels(psi, pn, nodeRange(g, 1));
  IntList list("layer", size_t(g.ext[0]) * g.ext[1] * g.ext[2]);
  const int n = surface_velocity::listLayer(g, pn, lo, nodeRange(g), list);
  for (int c = 0; c < 3; ++c) Kokkos::deep_copy(v.c[c], u.c[c]), Kokkos::deep_copy(w.c[c], u.c[c]);
  for (int s = 0; s < 4; ++s) {
    const VecField& from = s % 2 == 0 ? v : w;
    halo.exchange(from);
    surface_velocity::sweep(g, pn, mask, from, s % 2 == 0 ? w : v, list, n);
  }
  auto vh = toHost(v.c[0], "test"), vy = toHost(v.c[1], "test"), vz = toHost(v.c[2], "test");
  auto uh = toHost(u.c[0], "test"), uy = toHost(u.c[1], "test"), uz = toHost(u.c[2], "test");
  const Range3 r = nodeRange(g);
  double errLayer = 0, changedOutside = 0;
  int layerNodes = 0, fixedSeen = 0;
  for (int k = r.b[2]; k < r.e[2]; ++k)
    for (int j = r.b[1]; j < r.e[1]; ++j)
      for (int i = r.b[0]; i < r.e[0]; ++i) {
        const int gi = i - ng + c0, gj = j - ng + c1, gk = k - ng + c2;
        // Nodes next to the walls read mirrored ghosts that are not the linear field: skip them.
        if (gi < 2 || gi > 22 || gk < 2 || gk > 22) continue;
        const double x = gi * h, z = gk * h, pnode = 0.5 - gj * h;
        const double us[3] = {1 + 0.5 * x, -0.2, 0.3 * z};
        if (gi == 12 && gj == 14 && gk == 12) {
          ++fixedSeen;
          EXPECT_EQ(vh(i, j, k), 7.0);                  // prescribed: kept
          EXPECT_NEAR(vy(i, j, k), us[1], 1e-12);       // free: extended
          continue;
        }
        if (pnode <= 1e-12 && pnode > lo + 1e-12) {
          ++layerNodes;
          errLayer = std::max({errLayer, std::abs(vh(i, j, k) - us[0]), std::abs(vy(i, j, k) - us[1]),
                               std::abs(vz(i, j, k) - us[2])});
        } else {
          changedOutside = std::max({changedOutside, std::abs(vh(i, j, k) - uh(i, j, k)),
                                     std::abs(vy(i, j, k) - uy(i, j, k)), std::abs(vz(i, j, k) - uz(i, j, k))});
        }
      }
  int tot[2] = {layerNodes, fixedSeen}, all[2];
  MPI_Allreduce(tot, all, 2, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  double e[2] = {errLayer, changedOutside}, emax[2];
  MPI_Allreduce(e, emax, 2, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  EXPECT_EQ(all[0], 3 * 21 * 21 - 1); // psi_n = 0, -h, -2h: three node planes (the fixed node apart)
  EXPECT_EQ(all[1], 1);
  EXPECT_LT(emax[0], 1e-12); // linear fields, symmetric weights: round-off
  EXPECT_EQ(emax[1], 0.0);   // not listed: untouched
}
