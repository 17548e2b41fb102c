#pragma once
// The elastic diagnostics (elasticity's Diagnostics stage, effects/elasticity/update.cpp):
// S2, log10 S2, the elastic energy, the largest S2 and tension, and (neo-Hookean) det B.
#include <Kokkos_Core.hpp>

#include "kernels/elastic.hpp"

namespace voigt {
namespace elastic {

// Per listed cell: S2 (secondInvariant) and log10 |S2| floored at (1e-6 mu_S)^2 (a strain of
// 1e-6, so that stress-free cells do not swamp a colour map with -infinity; the paper shades
// by "the magnitude of the logarithm", and S2 of a deviatoric stress can be negative). Local
// reductions (ElasticDiag):
//   energy = sum H(psi) w dV, w = tau_S:tau_S / (4 mu_S) (hypoelastic: mu_S gamma^2 / 2 in a
//     simple shear gamma) or, neoHookean, the incompressible neo-Hookean strain energy of the
//     isochoric part, w = mu_S (tr B / det(B)^(1/3) - 3) / 2 with B = I + tau_S / mu_S (=
//     tr(tau_S) / 2 where det B = 1; the isochoric form does not count the drift of det B,
//     which the projection's pressure absorbs and the stress does not act through);
//   maxS2 = max |S2| inside the solid (psi > 0);
//   tension = max over the solid of a bound on tau_S's largest eigenvalue (Gershgorin:
//     t_ii + sum |t_ij|), for the neo-Hookean wave speed (elasticity.cpp dtLimit);
//   detDrift = max over the solid of |det B - 1| (neoHookean; 0 otherwise).
struct ElasticDiag {
  double energy, maxS2, tension, detDrift;
  template <class D, class S>
  KOKKOS_INLINE_FUNCTION static void join(D& d, const S& s) {
    d.energy += s.energy;
    if (s.maxS2 > d.maxS2) d.maxS2 = s.maxS2;
    if (s.tension > d.tension) d.tension = s.tension;
    if (s.detDrift > d.detDrift) d.detDrift = s.detDrift;
  }
  KOKKOS_INLINE_FUNCTION static void init(ElasticDiag& v) { v.energy = 0, v.maxS2 = 0, v.tension = 0, v.detDrift = 0; }
};

inline ElasticDiag stressDiagnostics(const Grid& g, const SymTensorField& tau, const Field& psi, const Field& S2,
                                     const Field& lg, const IntList& cell, int n, double kappa, double mu,
                                     bool neoHookean = false) {
  // One pass, flat addressing (the packed entry is the offset): the sum in list order as
  // before; the maxima over the solid cells start at 0 (what an empty list reported).
  const FlatSym t = flatSym(tau);
  const FlatField t0 = t.c[0], t1 = t.c[1], t2 = t.c[2], t3 = t.c[3], t4 = t.c[4], t5 = t.c[5];
  const FlatField fpsi = flat(psi), fS2 = flat(S2), flg = flat(lg);
  const double dv = g.cellVolume(), inv4mu = 1 / (4 * mu), imu = 1 / mu;
  const double floorS2 = (1e-6 * mu) * (1e-6 * mu);
  ElasticDiag acc;
  Kokkos::parallel_reduce(
      "elastic_diagnose", Kokkos::RangePolicy<ExecSpace>(0, n),
      KOKKOS_LAMBDA(int q, ElasticDiag& v) {
        const int p = cell(q);
        const double xx = t0(p), yy = t1(p), zz = t2(p), xy = t3(p), yz = t4(p), zx = t5(p);
        const double s2 = secondInvariant(xx, yy, zz, xy, yz, zx);
        fS2(p) = s2;
        const double a = km::fabs(s2);
        flg(p) = km::log10(a > floorS2 ? a : floorS2);
        const double ps = fpsi(p);
        const double H = smoothedHeaviside(ps, kappa);
        double dd = 0;
        if (neoHookean) {
          const double bx = 1 + xx * imu, by = 1 + yy * imu, bz = 1 + zz * imu;
          const double cxy = xy * imu, cyz = yz * imu, czx = zx * imu;
          const double J = bx * (by * bz - cyz * cyz) - cxy * (cxy * bz - cyz * czx) + czx * (cxy * cyz - by * czx);
          const double w = J > 0 ? 0.5 * mu * ((bx + by + bz) / km::cbrt(J) - 3) : 0.0;
          v.energy += H * w * dv;
          dd = km::fabs(J - 1);
        } else {
          v.energy += H * (xx * xx + yy * yy + zz * zz + 2 * (xy * xy + yz * yz + zx * zx)) * inv4mu * dv;
        }
        const bool solid = ps > 0; // the maxima inside the solid only
        const double m = solid ? a : 0.0;
        if (m > v.maxS2) v.maxS2 = m;
        const double ax = km::fabs(xy), ay = km::fabs(yz), az = km::fabs(zx);
        const double tb = solid ? maxOf(xx + ax + az, maxOf(yy + ax + ay, zz + ay + az)) : 0.0;
        if (tb > v.tension) v.tension = tb;
        const double dm = solid ? dd : 0.0;
        if (dm > v.detDrift) v.detDrift = dm;
      },
      AccReducer<ElasticDiag>(acc));
  return acc;
}

} // namespace elastic
} // namespace voigt
