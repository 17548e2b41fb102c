#pragma once
// Initial velocity and pressure of the navier_stokes effect (scene `initial:`), in closed
// form at every node (velocity) and cell (pressure) of the array, ghosts included:
//   zero; uniform U; taylor_green: u = A sin(kx x) cos(ky y), v = -A (kx/ky) cos(kx x)
//   sin(ky y), p = p0 + rho A^2 / 4 (cos(2 kx x) + (kx/ky)^2 cos(2 ky y)) at cell centres
//   (the exact Navier-Stokes solution in x-y); couette: the linear profile between the
//   y walls' x velocities; poiseuille: u = 4 A y (Ly - y) / Ly^2.
#include <cmath>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/index_space.hpp"

namespace voigt {

struct InitialFlow {
  int mode = 0; // 0 zero, 1 uniform, 2 taylor_green, 3 couette, 4 poiseuille
  double A = 0, rho = 0, p0 = 0, U[3] = {0, 0, 0}, wLo = 0, wHi = 0;
};

inline void fillInitialFlow(const Grid& g, const InitialFlow& f, const VecField& u, const Field& p) {
  const int mode = f.mode;
  const double A = f.A, rho = f.rho, p0 = f.p0, U0 = f.U[0], U1 = f.U[1], U2 = f.U[2];
  const double kx = 2 * M_PI / (g.hi[0] - g.lo[0]), ky = 2 * M_PI / (g.hi[1] - g.lo[1]);
  const double lo0 = g.lo[0], lo1 = g.lo[1], Ly = g.hi[1] - g.lo[1];
  const double h0 = g.h[0], h1 = g.h[1];
  const double wLo = f.wLo, wHi = f.wHi;
  const int ng = g.ng, c00 = g.c0[0], c01 = g.c0[1];
  Kokkos::parallel_for(
      "initial_velocity", Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}),
      KOKKOS_LAMBDA(int i, int j, int k) {
        const double x = lo0 + (i - ng + c00) * h0, y = lo1 + (j - ng + c01) * h1;
        const double xc = x + 0.5 * h0, yc = y + 0.5 * h1; // cell centre
        double v[3] = {0, 0, 0}, pc = p0;
        if (mode == 1) {
          v[0] = U0; v[1] = U1; v[2] = U2;
        } else if (mode == 2) {
          v[0] = A * km::sin(kx * (x - lo0)) * km::cos(ky * (y - lo1));
          v[1] = -A * (kx / ky) * km::cos(kx * (x - lo0)) * km::sin(ky * (y - lo1));
          pc += 0.25 * rho * A * A *
                (km::cos(2 * kx * (xc - lo0)) + (kx * kx) / (ky * ky) * km::cos(2 * ky * (yc - lo1)));
        } else if (mode == 3) {
          v[0] = wLo + (wHi - wLo) * (y - lo1) / Ly;
        } else if (mode == 4) {
          v[0] = 4 * A * (y - lo1) * (Ly - (y - lo1)) / (Ly * Ly);
        }
        VOIGT_UNROLL
        for (int c = 0; c < 3; ++c) u.c[c](i, j, k) = v[c];
        p(i, j, k) = pc;
      });
}

} // namespace voigt
