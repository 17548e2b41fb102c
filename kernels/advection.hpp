#pragma once
// Advection kernel family: MUSCL reconstruction with a slope limiter and the
// semi-discrete central (Kurganov-Tadmor 2000) flux, the non-staggered
// descendant of Nessyahu-Tadmor (NUMERICS.md). Second order in space away from
// extrema; paired with SSP-RK2 in time by the caller.
//   dq/dt = -[div(v q) - q div_h(v)]
// The q div_h(v) term removes the compression of the dual-cell divergence,
// which the projection does not zero (it zeroes D, a different stencil), so a
// uniform q stays uniform.
#include <string>
#include <type_traits>

#include "core/field.hpp"
#include "core/index_space.hpp"

namespace voigt {

enum class Limiter { MinMod = 0, VanLeer = 1, MC = 2, None = 3 };

// The scene's advection.limiter (validated by the loader: minmod, van_leer, mc, none).
inline Limiter limiterNamed(const std::string& l) {
  return l == "van_leer" ? Limiter::VanLeer : l == "mc" ? Limiter::MC : l == "none" ? Limiter::None : Limiter::MinMod;
}

KOKKOS_INLINE_FUNCTION double limitedSlope(int lim, double a, double b) {
  if (lim == 3) return 0.5 * (a + b); // unlimited central slope (Fromm)
  if (a * b <= 0) return 0;
  const double sgn = a > 0 ? 1 : -1;
  const double aa = a * sgn, bb = b * sgn;
  if (lim == 0) return sgn * (aa < bb ? aa : bb);
  if (lim == 1) return 2 * a * b / (a + b);
  const double m = 2 * (aa < bb ? aa : bb), c = 0.5 * (aa + bb);
  return sgn * (m < c ? m : c);
}

// The same limiters with the choice fixed at compile time and no branches: every
// expression is evaluated and the result selected, so a loop over faces has no
// control flow and vectorises (advection_faces.hpp). Same operations, same bits.
template <int LIM>
KOKKOS_FORCEINLINE_FUNCTION double limitedSlopeT(double a, double b) {
  if constexpr (LIM == 3) {
    return 0.5 * (a + b);
  } else if constexpr (LIM == 0) {
    // minmod: sgn min(a sgn, b sgn) is the argument of smaller magnitude (a*sgn*sgn = a
    // exactly, ties give b either way): two selects instead of three products.
    const double r = km::fabs(a) < km::fabs(b) ? a : b;
    return a * b <= 0 ? 0.0 : r;
  } else {
    const double sgn = a > 0 ? 1.0 : -1.0;
    const double aa = a * sgn, bb = b * sgn;
    const double mn = aa < bb ? aa : bb;
    double r;
    if constexpr (LIM == 0) {
      r = sgn * mn;
    } else if constexpr (LIM == 1) {
      r = 2 * a * b / (a + b);
    } else {
      const double m = 2 * mn, c = 0.5 * (aa + bb);
      r = sgn * (m < c ? m : c);
    }
    return a * b <= 0 ? 0.0 : r;
  }
}
template <int LIM>
KOKKOS_FORCEINLINE_FUNCTION void musclStatesT(double qm1, double q0, double q1, double q2, double& qL, double& qR) {
  qL = q0 + 0.5 * limitedSlopeT<LIM>(q0 - qm1, q1 - q0);
  qR = q1 - 0.5 * limitedSlopeT<LIM>(q1 - q0, q2 - q1);
}
// Calls f(std::integral_constant<int, LIM>) for the run-time limiter.
template <class F>
inline void withLimiter(Limiter l, const F& f) {
  switch (l) {
    case Limiter::MinMod: f(std::integral_constant<int, 0>()); break;
    case Limiter::VanLeer: f(std::integral_constant<int, 1>()); break;
    case Limiter::MC: f(std::integral_constant<int, 2>()); break;
    default: f(std::integral_constant<int, 3>()); break;
  }
}

// Face-flux scratch of the advection kernels (advection_faces.hpp): slot s of
// the face between points i-1 and i along an axis lives at F(i, j, k, s).
// Grown on demand, owned by the caller so that steps do not allocate.
struct FluxScratch {
  Kokkos::View<double****, Kokkos::LayoutLeft, MemSpace> F;
  void reserve(const Grid& g, int slots) {
    if ((int)F.extent(0) != g.ext[0] || (int)F.extent(1) != g.ext[1] || (int)F.extent(2) != g.ext[2] ||
        (int)F.extent(3) < slots)
      F = decltype(F)(Kokkos::view_alloc(std::string("advection_face_flux"), Kokkos::WithoutInitializing), g.ext[0],
                      g.ext[1], g.ext[2], slots);
  }
};

// MUSCL states either side of the face between q(-1..2) positions 0|1.
KOKKOS_FORCEINLINE_FUNCTION void musclStates(int lim, double qm1, double q0, double q1, double q2, double& qL,
                                        double& qR) {
  qL = q0 + 0.5 * limitedSlope(lim, q0 - qm1, q1 - q0);
  qR = q1 - 0.5 * limitedSlope(lim, q1 - q0, q2 - q1);
}

// Kurganov-Tadmor flux of states qL|qR at a face moving at speed a.
KOKKOS_FORCEINLINE_FUNCTION double ktFlux(double a, double qL, double qR) {
  const double aa = a < 0 ? -a : a;
  return 0.5 * a * (qL + qR) - 0.5 * aa * (qR - qL);
}

template <int LIM>
KOKKOS_FORCEINLINE_FUNCTION double centralFluxT(double qm1, double q0, double q1, double q2, double a) {
  double qL, qR;
  musclStatesT<LIM>(qm1, q0, q1, q2, qL, qR);
  return ktFlux(a, qL, qR);
}

// Flux through the face between q(-1..2) positions 0|1, advecting speed a.
KOKKOS_FORCEINLINE_FUNCTION double centralFlux(int lim, double qm1, double q0, double q1, double q2, double a) {
  double qL, qR;
  musclStates(lim, qm1, q0, q1, q2, qL, qR);
  return ktFlux(a, qL, qR);
}

// rhs += -(advection of node field q by node velocity v) over the given nodes.
// Dual-cell face speed: mean of the two nodes' normal velocities.
inline void addNodeAdvection(const Grid& g, const Field& q, const VecField& v, const Field& rhs,
                             Range3 nodes, Limiter limiter) {
  const int lim = static_cast<int>(limiter);
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  auto vx = v.c[0], vy = v.c[1], vz = v.c[2];
  Kokkos::parallel_for(
      "node_advection", nodes.policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        double tend = 0;
        const double q0 = q(i, j, k);
        {
          const double ap = 0.5 * (vx(i, j, k) + vx(i + 1, j, k)), am = 0.5 * (vx(i - 1, j, k) + vx(i, j, k));
          const double fp = centralFlux(lim, q(i - 1, j, k), q0, q(i + 1, j, k), q(i + 2, j, k), ap);
          const double fm = centralFlux(lim, q(i - 2, j, k), q(i - 1, j, k), q0, q(i + 1, j, k), am);
          tend -= (fp - fm - q0 * (ap - am)) / h0;
        }
        {
          const double ap = 0.5 * (vy(i, j, k) + vy(i, j + 1, k)), am = 0.5 * (vy(i, j - 1, k) + vy(i, j, k));
          const double fp = centralFlux(lim, q(i, j - 1, k), q0, q(i, j + 1, k), q(i, j + 2, k), ap);
          const double fm = centralFlux(lim, q(i, j - 2, k), q(i, j - 1, k), q0, q(i, j + 1, k), am);
          tend -= (fp - fm - q0 * (ap - am)) / h1;
        }
        {
          const double ap = 0.5 * (vz(i, j, k) + vz(i, j, k + 1)), am = 0.5 * (vz(i, j, k - 1) + vz(i, j, k));
          const double fp = centralFlux(lim, q(i, j, k - 1), q0, q(i, j, k + 1), q(i, j, k + 2), ap);
          const double fm = centralFlux(lim, q(i, j, k - 2), q(i, j, k - 1), q0, q(i, j, k + 1), am);
          tend -= (fp - fm - q0 * (ap - am)) / h2;
        }
        rhs(i, j, k) += tend;
      });
}

// Mass-consistent momentum advection (Rudman 1998; Raessi & Pitsch 2012). The
// node density rho and the momentum m = rho u cross each face with one KT flux,
//   F_rho = KT(a; rho_L, rho_R),   F_m = KT(a; rho_L u_L, rho_R u_R),
// so F_m = u F_rho when u is uniform: a light fluid's speed is not carried
// into heavy nodes (the velocity form does that at density ratio 1000 and
// creates kinetic energy). With the same compression correction as above:
//   rhsRho = -[div F_rho - rho div_h v],
//   rhs_c += -[div F_m,c - rho u_c div_h v] / rhoRef   (a momentum rate per rhoRef)
inline void addMomentumAdvection(const Grid& g, const Field& rho, const VecField& v, const Field& rhoRef,
                                 const Field& rhsRho, const VecField& rhs, Range3 nodes, Limiter limiter) {
  const int lim = static_cast<int>(limiter);
  const double ih0 = 1 / g.h[0], ih1 = 1 / g.h[1], ih2 = 1 / g.h[2];
  auto vx = v.c[0], vy = v.c[1], vz = v.c[2];
  auto rx = rhs.c[0], ry = rhs.c[1], rz = rhs.c[2];
  Kokkos::parallel_for(
      "momentum_advection", nodes.policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        const double r0 = rho(i, j, k);
        const double u0[3] = {vx(i, j, k), vy(i, j, k), vz(i, j, k)};
        double tr = 0, tm[3] = {0, 0, 0};
        VOIGT_UNROLL
        for (int d = 0; d < 3; ++d) {
          const int di = d == 0, dj = d == 1, dk = d == 2;
          const double hinv = d == 0 ? ih0 : d == 1 ? ih1 : ih2;
          auto at = [&](const Field& f, int s) { return f(i + s * di, j + s * dj, k + s * dk); };
          const Field& vd = d == 0 ? vx : d == 1 ? vy : vz;
          const double ap = 0.5 * (u0[d] + at(vd, 1)), am = 0.5 * (at(vd, -1) + u0[d]);
          double rLp, rRp, rLm, rRm; // density states at the + and - faces
          musclStates(lim, at(rho, -1), r0, at(rho, 1), at(rho, 2), rLp, rRp);
          musclStates(lim, at(rho, -2), at(rho, -1), r0, at(rho, 1), rLm, rRm);
          tr -= (ktFlux(ap, rLp, rRp) - ktFlux(am, rLm, rRm) - r0 * (ap - am)) * hinv;
          VOIGT_UNROLL
          for (int c = 0; c < 3; ++c) {
            const Field& q = c == 0 ? vx : c == 1 ? vy : vz;
            double uLp, uRp, uLm, uRm;
            musclStates(lim, at(q, -1), u0[c], at(q, 1), at(q, 2), uLp, uRp);
            musclStates(lim, at(q, -2), at(q, -1), u0[c], at(q, 1), uLm, uRm);
            tm[c] -= (ktFlux(ap, rLp * uLp, rRp * uRp) - ktFlux(am, rLm * uLm, rRm * uRm) - r0 * u0[c] * (ap - am)) *
                     hinv;
          }
        }
        rhsRho(i, j, k) = tr;
        const double inv = 1 / rhoRef(i, j, k);
        rx(i, j, k) += tm[0] * inv;
        ry(i, j, k) += tm[1] * inv;
        rz(i, j, k) += tm[2] * inv;
      });
}

} // namespace voigt
