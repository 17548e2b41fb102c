#pragma once
// Shared set-up for the perf programs: MPI + Kokkos (common_kokkos.hpp), scenes from strings.
#include <algorithm>
#include <string>

#include "common_kokkos.hpp"

#include "app/simulation.hpp"
#include "scene/load.hpp"

namespace voigt::perf {

inline Scene scene(const std::string& yaml) {
  return loadSceneWithEffectsFromString(yaml, "perf");
}

// Lid-driven cavity at Re = 100 on n^3 cells.
inline std::string cavity(int n, const std::string& op, const std::string& pc, const std::string& tol) {
  const std::string c = std::to_string(n);
  return "name: cavity\ndomain: {lo: [0,0,0], hi: [1,1,1], cells: [" + c + "," + c + "," + c + "]}\n"
         "boundaries: {default: {type: no_slip}, y+: {type: no_slip, velocity: [1,0,0]}}\n"
         "materials: {fluid: {density: 1, viscosity: 0.01}}\neffects: [navier_stokes]\n"
         "time: {end: 100, cfl: 0.5}\n"
         "projection: {operator: " + op + ", preconditioner: " + pc + ", tolerance: " + tol +
         ", max_iterations: 20000}\noutput: {enabled: false}\n";
}

} // namespace voigt::perf
