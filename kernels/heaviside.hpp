#pragma once
// Smoothed Heaviside and delta of the level set, Eq. (4).
// Sign convention (NOTES.md erratum 4), used everywhere in Voigt:
//   psi > 0  is phase 1 (the level set's material; later the solid), H = 1;
//   psi < 0  is phase 2 (the scene's `fluid`), H = 0.
// kappa is the smoothing half-width in length units (paper: 2 cells).
#include <cmath>

#include "core/field.hpp" // km:: math

namespace voigt {

// sin(pi t) for |t| <= 1: the argument reduced to |r| <= 1/2 (sin(pi a) = sin(pi (1 - a)),
// exact for a >= 1/2), then the Taylor series of sin to x^21 (within 3 ulp of glibc's sin
// on the whole range, 3.3e-16 absolute). Branch-free, so the kernels that evaluate H and
// H' vectorise (a libm call kept them scalar), and the same bits on every backend (CUDA's
// sin and glibc's differ in the last place).
KOKKOS_INLINE_FUNCTION double sinPi(double t) {
  const double a = t < 0 ? -t : t;
  const double r = a > 0.5 ? 1 - a : a;
  const double x = M_PI * r, x2 = x * x;
  double p = 1.0 / 51090942171709440000.0;  // 1/21!
  p = p * x2 - 1.0 / 121645100408832000.0;  // 1/19!
  p = p * x2 + 1.0 / 355687428096000.0;     // 1/17!
  p = p * x2 - 1.0 / 1307674368000.0;       // 1/15!
  p = p * x2 + 1.0 / 6227020800.0;          // 1/13!
  p = p * x2 - 1.0 / 39916800.0;            // 1/11!
  p = p * x2 + 1.0 / 362880.0;              // 1/9!
  p = p * x2 - 1.0 / 5040.0;                // 1/7!
  p = p * x2 + 1.0 / 120.0;                 // 1/5!
  p = p * x2 - 1.0 / 6.0;                   // 1/3!
  p = p * x2 + 1.0;
  const double v = x * p;
  return t < 0 ? -v : v;
}

// cos(pi t) for |t| <= 1 = sin(pi (1/2 - |t|)).
KOKKOS_INLINE_FUNCTION double cosPi(double t) { return sinPi(0.5 - (t < 0 ? -t : t)); }

KOKKOS_INLINE_FUNCTION double smoothedHeaviside(double psi, double kappa) {
  if (psi < -kappa) return 0;
  if (psi > kappa) return 1;
  const double t = psi / kappa;
  return 0.5 * (1 + t + sinPi(t) / M_PI);
}

// dH/dpsi of Eq. (4): (1 + cos(pi psi / kappa)) / (2 kappa) inside the band.
KOKKOS_INLINE_FUNCTION double smoothedDelta(double psi, double kappa) {
  if (psi < -kappa || psi > kappa) return 0;
  return 0.5 * (1 + cosPi(psi / kappa)) / kappa;
}

// Sharp Heaviside of Eq. (3), for shape-error measures.
KOKKOS_INLINE_FUNCTION double sharpHeaviside(double psi) { return psi > 0 ? 1.0 : psi < 0 ? 0.0 : 0.5; }

} // namespace voigt
