#pragma once
// Level-set kernel family: advection of a cell-centred field by the node
// velocity (Eq. 1), property blending (Eq. 2, 4) and phase diagnostics.
//
// Advection: the semi-discrete central scheme of advection.hpp (Kurganov-
// Tadmor with MUSCL/MinMod reconstruction, the non-staggered descendant of
// Nessyahu-Tadmor) on the primary cells, in the paper's conservative form
//   dq/dt = -[div(v q) - q div_h(v)].
// The face speed is the mean of the 4 node velocities of the face, so
// div_h is exactly the projection's D (NUMERICS.md): the correction term
// vanishes where the exact projection holds and keeps a uniform q uniform
// where it does not (prescribed, approximately projected or compressive
// velocity fields).
#include "core/field.hpp"
#include "core/index_space.hpp"
#include "kernels/advection.hpp"
#include "kernels/heaviside.hpp"

namespace voigt {

// rhs += -(advection of cell field q by node velocity v) over the given cells.
// Needs q on 2 ghost layers and v on the nodes of the cells' faces.
inline void addCellAdvection(const Grid& g, const Field& q, const VecField& v, const Field& rhs, Range3 cells,
                             Limiter limiter) {
  const int lim = static_cast<int>(limiter);
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  auto vx = v.c[0], vy = v.c[1], vz = v.c[2];
  Kokkos::parallel_for(
      "cell_advection", cells.policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        const double q0 = q(i, j, k);
        // Face speeds: the face at the cell's low side along x holds nodes
        // (i, j..j+1, k..k+1); the high side the same at i+1.
        auto fx = [&](int a) { return 0.25 * (vx(a, j, k) + vx(a, j + 1, k) + vx(a, j, k + 1) + vx(a, j + 1, k + 1)); };
        auto fy = [&](int b) { return 0.25 * (vy(i, b, k) + vy(i + 1, b, k) + vy(i, b, k + 1) + vy(i + 1, b, k + 1)); };
        auto fz = [&](int c) { return 0.25 * (vz(i, j, c) + vz(i + 1, j, c) + vz(i, j + 1, c) + vz(i + 1, j + 1, c)); };
        double tend = 0;
        {
          const double am = fx(i), ap = fx(i + 1);
          const double fp = centralFlux(lim, q(i - 1, j, k), q0, q(i + 1, j, k), q(i + 2, j, k), ap);
          const double fm = centralFlux(lim, q(i - 2, j, k), q(i - 1, j, k), q0, q(i + 1, j, k), am);
          tend -= (fp - fm - q0 * (ap - am)) / h0;
        }
        {
          const double am = fy(j), ap = fy(j + 1);
          const double fp = centralFlux(lim, q(i, j - 1, k), q0, q(i, j + 1, k), q(i, j + 2, k), ap);
          const double fm = centralFlux(lim, q(i, j - 2, k), q(i, j - 1, k), q0, q(i, j + 1, k), am);
          tend -= (fp - fm - q0 * (ap - am)) / h1;
        }
        {
          const double am = fz(k), ap = fz(k + 1);
          const double fp = centralFlux(lim, q(i, j, k - 1), q0, q(i, j, k + 1), q(i, j, k + 2), ap);
          const double fm = centralFlux(lim, q(i, j, k - 2), q(i, j, k - 1), q0, q(i, j, k + 1), am);
          tend -= (fp - fm - q0 * (ap - am)) / h2;
        }
        rhs(i, j, k) += tend;
      });
}

// Eq. (2) with the smoothed Heaviside of Eq. (4): phase 1 where psi > 0.
inline void blendProperties(const Field& psi, double kappa, double rho1, double rho2, double mu1, double mu2,
                            const Field& rho, const Field& mu, Range3 cells) {
  for_each3("blend_properties", cells, KOKKOS_LAMBDA(int i, int j, int k) {
        const double H = smoothedHeaviside(psi(i, j, k), kappa);
        rho(i, j, k) = H * rho1 + (1 - H) * rho2;
        mu(i, j, k) = H * mu1 + (1 - H) * mu2;
      });
}

struct PhaseMeasures {
  double volume = 0;      // integral of H(psi): phase 1 volume
  double sharpVolume = 0; // cells with psi > 0 (sharp Heaviside)
  double area = 0;        // integral of delta(psi) |grad psi|: interface area
};

// Local (this rank's owned cells) sums; the caller reduces over ranks.
// Needs psi on one ghost layer for the central gradient.
inline PhaseMeasures localPhaseMeasures(const Grid& g, const Field& psi, double kappa) {
  const double dv = g.cellVolume();
  const double i0 = 0.5 / g.h[0], i1 = 0.5 / g.h[1], i2 = 0.5 / g.h[2];
  double vol = 0, sharp = 0, area = 0;
  Kokkos::parallel_reduce(
      "phase_measures", cellRange(g).policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& v, double& s, double& a) {
        const double p = psi(i, j, k);
        v += smoothedHeaviside(p, kappa) * dv;
        s += sharpHeaviside(p) * dv;
        const double d = smoothedDelta(p, kappa);
        if (d > 0) {
          const double gx = (psi(i + 1, j, k) - psi(i - 1, j, k)) * i0;
          const double gy = (psi(i, j + 1, k) - psi(i, j - 1, k)) * i1;
          const double gz = (psi(i, j, k + 1) - psi(i, j, k - 1)) * i2;
          a += d * std::sqrt(gx * gx + gy * gy + gz * gz) * dv;
        }
      },
      vol, sharp, area);
  return {vol, sharp, area};
}

} // namespace voigt
