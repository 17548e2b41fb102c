#pragma once
// The level set's mean curvature at one cell centre, central differences (psi > 0 inside: a
// sphere of radius R has kappa = 2/R, a cylinder 1/R):
//   kappa = -div(grad psi / |grad psi|)
//         = -[psi_xx (psi_y^2 + psi_z^2) + psi_yy (psi_x^2 + psi_z^2) + psi_zz (psi_x^2 + psi_y^2)
//             - 2 (psi_x psi_y psi_xy + psi_x psi_z psi_xz + psi_y psi_z psi_yz)] / |grad psi|^3
// 0 where |grad psi| < 0.5 (no interface shape to speak of), limited to |kappa| <= kmax (a
// radius below one cell). Used by surface tension (kernels/curvature.hpp) and by the level
// set's roughness diagnostic (kernels/levelset.hpp localPhaseMeasures). psi fresh on the 27
// cells around (i, j, k); ih = 1 / h per axis.
#include <Kokkos_Core.hpp>

#include "core/field.hpp"

namespace voigt {
namespace curvature {

KOKKOS_INLINE_FUNCTION double curvatureAt(const Field& psi, int i, int j, int k, double i0, double i1, double i2,
                                          double kmax) {
  const double c = psi(i, j, k);
  const double px = 0.5 * i0 * (psi(i + 1, j, k) - psi(i - 1, j, k));
  const double py = 0.5 * i1 * (psi(i, j + 1, k) - psi(i, j - 1, k));
  const double pz = 0.5 * i2 * (psi(i, j, k + 1) - psi(i, j, k - 1));
  const double pxx = i0 * i0 * (psi(i + 1, j, k) - 2 * c + psi(i - 1, j, k));
  const double pyy = i1 * i1 * (psi(i, j + 1, k) - 2 * c + psi(i, j - 1, k));
  const double pzz = i2 * i2 * (psi(i, j, k + 1) - 2 * c + psi(i, j, k - 1));
  const double pxy = 0.25 * i0 * i1 *
                     (psi(i + 1, j + 1, k) - psi(i + 1, j - 1, k) - psi(i - 1, j + 1, k) + psi(i - 1, j - 1, k));
  const double pxz = 0.25 * i0 * i2 *
                     (psi(i + 1, j, k + 1) - psi(i + 1, j, k - 1) - psi(i - 1, j, k + 1) + psi(i - 1, j, k - 1));
  const double pyz = 0.25 * i1 * i2 *
                     (psi(i, j + 1, k + 1) - psi(i, j + 1, k - 1) - psi(i, j - 1, k + 1) + psi(i, j - 1, k - 1));
  const double g2 = px * px + py * py + pz * pz;
  const double num = pxx * (py * py + pz * pz) + pyy * (px * px + pz * pz) + pzz * (px * px + py * py) -
                     2 * (px * py * pxy + px * pz * pxz + py * pz * pyz);
  const double kv = g2 > 0.25 ? -num / (g2 * km::sqrt(g2)) : 0.0;
  return maxOf(-kmax, minOf(kmax, kv));
}

} // namespace curvature
} // namespace voigt
