#pragma once
// Static-drop helpers shared by test_surface_tension.cpp and test_height_function.cpp: the
// pressure jump and capillary number of a finished run, and the cylinder scene.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "kernels/reductions.hpp"
#include "support/flow.hpp"

namespace voigt::capillary_test {
using namespace voigt;
struct Drop {
  double jump, ca;
};

// The jump between the mean pressures beyond the smoothing zone (4 cells) inside and outside,
// and Ca = max|u| mu / sigma, of a finished static-drop run (mu = 0.1, sigma = 1).
inline Drop measure(const Simulation& sim) {
  const State& st = sim.state();
  const Grid& G = st.grid;
  auto p = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.fields.scalar("pressure"));
  auto psi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.fields.scalar("psi"));
  const double far = 4 * G.h[0]; // beyond the smoothing zone (2 cells) on either side
  double s[4] = {0, 0, 0, 0};    // sum and count inside, outside
  auto r = cellRange(G);
  for (int k = r.b[2]; k < r.e[2]; ++k)
    for (int j = r.b[1]; j < r.e[1]; ++j)
      for (int i = r.b[0]; i < r.e[0]; ++i) {
        if (psi(i, j, k) > far) s[0] += p(i, j, k), s[1] += 1;
        if (psi(i, j, k) < -far) s[2] += p(i, j, k), s[3] += 1;
      }
  MPI_Allreduce(MPI_IN_PLACE, s, 4, MPI_DOUBLE, MPI_SUM, G.comm);
  double u = 0;
  for (int c = 0; c < 3; ++c) u = std::max(u, globalMaxAbs(G, st.fields.vector("velocity").c[c], nodeRange(G)));
  return {s[0] / s[1] - s[2] / s[3], u * 0.1 / 1.0};
}

inline std::string materials(double rhoIn, double rhoOut) {
  return "materials: {drop: {density: " + std::to_string(rhoIn) + ", viscosity: 0.1}, out: {density: " +
         std::to_string(rhoOut) + ", viscosity: 0.1}}\nfluid: out\n"
         "effects: [navier_stokes, level_set, reinit, surface_tension]\noutput: {enabled: false}\n";
}

// A cylinder: R = 0.25 in the unit square on n^2 cells (n = 64: 16 cells per radius), 2
// periodic cells along z, no-slip walls; `steps` steps from rest.
inline std::string cylinderScene(int n, double rhoIn, double rhoOut, const std::string& form, int steps,
                          const std::string& curvature = "level_set") {
  const double h = 1.0 / n;
  return "domain: {lo: [0,0,0], hi: [1,1," + std::to_string(2 * h) + "], cells: [" + std::to_string(n) + "," +
         std::to_string(n) + ",2], ranks: [0,0,1]}\n"
         "boundaries: {default: {type: no_slip}, z-: {type: periodic}, z+: {type: periodic}}\n"
         "time: {end: 100, max_steps: " + std::to_string(steps) + "}\n" + materials(rhoIn, rhoOut) +
         "level_set: {phase: drop, fast_marching: false, shape: {type: cylinder, center: [0.5, 0.5, 0], radius: 0.25, axis: z}}\n"
         "surface_tension: {sigma: 1, form: " + form + ", curvature: " + curvature + "}\n";
}

inline Drop staticDrop(int n, double rhoIn, double rhoOut, const std::string& form, int steps,
                const std::string& curvature = "level_set") {
  return measure(*test::runScene(test::scene(cylinderScene(n, rhoIn, rhoOut, form, steps, curvature))));
}
} // namespace voigt::capillary_test
