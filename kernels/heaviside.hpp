#pragma once
// Smoothed Heaviside and delta of the level set, Eq. (4).
// Sign convention (NOTES.md erratum 4), used everywhere in Voigt:
//   psi > 0  is phase 1 (the level set's material; later the solid), H = 1;
//   psi < 0  is phase 2 (the scene's `fluid`), H = 0.
// kappa is the smoothing half-width in length units (paper: 2 cells).
#include <cmath>

#include "core/field.hpp" // km:: math

namespace voigt {

KOKKOS_INLINE_FUNCTION double smoothedHeaviside(double psi, double kappa) {
  if (psi < -kappa) return 0;
  if (psi > kappa) return 1;
  return 0.5 * (1 + psi / kappa + km::sin(M_PI * psi / kappa) / M_PI);
}

// dH/dpsi of Eq. (4): (1 + cos(pi psi / kappa)) / (2 kappa) inside the band.
KOKKOS_INLINE_FUNCTION double smoothedDelta(double psi, double kappa) {
  if (psi < -kappa || psi > kappa) return 0;
  return 0.5 * (1 + km::cos(M_PI * psi / kappa)) / kappa;
}

// Sharp Heaviside of Eq. (3), for shape-error measures.
KOKKOS_INLINE_FUNCTION double sharpHeaviside(double psi) { return psi > 0 ? 1.0 : psi < 0 ? 0.0 : 0.5; }

} // namespace voigt
