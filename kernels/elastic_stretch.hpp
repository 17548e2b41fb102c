#pragma once
// The neo-Hookean solid's stretching terms (elasticity.model: neo_hookean, issue 53), for
// bensonUpdate (kernels/elastic.hpp). tau = mu_S (B - I) with B, the left Cauchy-Green
// tensor, carried by the upper-convected derivative, dB/dt = L B + B L^T, so
//   dtau/dt = (W tau - tau W) + mu_S (L + L^T) + (S tau + tau S),   S = (L + L^T) / 2:
// the paper's Jaumann rate (Eq. 13) plus S tau + tau S. In simple shear gamma it gives
// tau_xy = mu_S gamma and tau_xx = mu_S gamma^2, where the hypoelastic solid gives
// mu_S sin(gamma) and mu_S (1 - cos(gamma)) (Dienes 1979).
#include <Kokkos_Core.hpp>

#include "core/index_space.hpp"

namespace voigt {
namespace elastic {

// (S t + t S) for symmetric t (xx, yy, zz, xy, yz, zx) and S = (L + L^T) / 2.
KOKKOS_INLINE_FUNCTION void stretching(const double s[6], const double L[3][3], double out[6]) {
  const double t[3][3] = {{s[0], s[3], s[5]}, {s[3], s[1], s[4]}, {s[5], s[4], s[2]}};
  double S[3][3];
  VOIGT_UNROLL
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q) S[p][q] = 0.5 * (L[p][q] + L[q][p]);
  const int ip[6] = {0, 1, 2, 0, 1, 2}, iq[6] = {0, 1, 2, 1, 2, 0};
  VOIGT_UNROLL
  for (int c = 0; c < 6; ++c) {
    const int p = ip[c], q = iq[c];
    out[c] = S[p][0] * t[0][q] + S[p][1] * t[1][q] + S[p][2] * t[2][q] + t[p][0] * S[0][q] + t[p][1] * S[1][q] +
             t[p][2] * S[2][q];
  }
}

// s += dt (S m + m S) with m the midpoint of the middle increment, m = s + (dt/2) (mu (L + L^T)
// + S s + s S): with the caller's s += dt mu (L + L^T), the increment by the midpoint rule, so
// that between the half rotations the whole step stays second order in dt.
KOKKOS_INLINE_FUNCTION void addStretching(double s[6], const double L[3][3], double mu, double dt) {
  double st[6], m[6];
  stretching(s, L, st);
  const double e[6] = {2 * L[0][0], 2 * L[1][1], 2 * L[2][2], L[0][1] + L[1][0], L[1][2] + L[2][1], L[2][0] + L[0][2]};
  VOIGT_UNROLL
  for (int c = 0; c < 6; ++c) m[c] = s[c] + 0.5 * dt * (mu * e[c] + st[c]);
  stretching(m, L, st);
  VOIGT_UNROLL
  for (int c = 0; c < 6; ++c) s[c] += dt * st[c];
}

} // namespace elastic
} // namespace voigt
