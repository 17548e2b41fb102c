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
#include "kernels/curvature_point.hpp"
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
// On host backends a piece of 8 cells none of which lies in the band |psi| <= kappa takes
// H = 0 or 1 without the polynomial (smoothedHeaviside's own branches, the same bits;
// NaN counts as in the band): on the falling block most cells, and the polynomial,
// vectorised, costs more than their memory traffic.
// harmonic: mu = 1 / (H / mu1 + (1 - H) / mu2) instead (level_set.viscosity_blend; both > 0).
inline void blendProperties(const Field& psi, double kappa, double rho1, double rho2, double mu1, double mu2,
                            const Field& rho, const Field& mu, Range3 cells, bool harmonic = false) {
  const double r1 = harmonic ? 1 / mu1 : 0, r2 = harmonic ? 1 / mu2 : 0;
  auto point = KOKKOS_LAMBDA(int i, int j, int k, double H) {
    rho(i, j, k) = H * rho1 + (1 - H) * rho2;
    mu(i, j, k) = harmonic ? 1 / (H * r1 + (1 - H) * r2) : H * mu1 + (1 - H) * mu2;
  };
  if constexpr (!kOnDevice) {
    const int b0 = cells.b[0], e0 = cells.e[0], b1 = cells.b[1], b2 = cells.b[2], nj = cells.e[1] - cells.b[1];
    const long long rows = 1LL * nj * (cells.e[2] - cells.b[2]);
    if (rows <= 0 || e0 <= b0) return;
    const long long chunks = hostChunks(rows);
    Kokkos::parallel_for(
        "blend_properties", Kokkos::RangePolicy<ExecSpace, Kokkos::IndexType<long long>>(0, chunks),
        KOKKOS_LAMBDA(long long c) {
          const auto pt = point; // a copy per chunk, as for_each3 (index_space.hpp)
          const long long q1 = rows * (c + 1) / chunks;
          for (long long q = rows * c / chunks; q < q1; ++q) {
            const int j = b1 + int(q % nj), k = b2 + int(q / nj);
            for (int i0 = b0; i0 < e0; i0 += 8) { // pieces of 8 cells (two AVX2 vectors)
              const int i1 = i0 + 8 < e0 ? i0 + 8 : e0;
              int band = 0;
              for (int i = i0; i < i1; ++i) band |= !(psi(i, j, k) < -kappa || psi(i, j, k) > kappa);
              if (band) {
#pragma GCC ivdep
                for (int i = i0; i < i1; ++i) pt(i, j, k, smoothedHeaviside(psi(i, j, k), kappa));
              } else {
#pragma GCC ivdep
                for (int i = i0; i < i1; ++i) pt(i, j, k, psi(i, j, k) > kappa ? 1.0 : 0.0);
              }
            }
          }
        });
    return;
  }
  for_each3("blend_properties", cells, KOKKOS_LAMBDA(int i, int j, int k) {
        point(i, j, k, smoothedHeaviside(psi(i, j, k), kappa));
      });
}

// Several level sets (level_sets:): each after the first is laid over the properties the
// earlier ones left, rho <- H rho_i + (1 - H) rho (same for mu, or its inverse with harmonic),
// so where two overlap the later one's phase wins (the priority order) and where one
// alone is positive this is Eq. (2) between its phase and what lies beneath.
inline void blendOver(const Field& psi, double kappa, double rho1, double mu1, const Field& rho, const Field& mu,
                      Range3 cells, bool harmonic = false) {
  const double r1 = harmonic ? 1 / mu1 : 0;
  for_each3("blend_over", cells, KOKKOS_LAMBDA(int i, int j, int k) {
        const double H = smoothedHeaviside(psi(i, j, k), kappa);
        rho(i, j, k) = H * rho1 + (1 - H) * rho(i, j, k);
        mu(i, j, k) = harmonic ? 1 / (H * r1 + (1 - H) / mu(i, j, k)) : H * mu1 + (1 - H) * mu(i, j, k);
      });
}

struct PhaseMeasures {
  double volume = 0;      // integral of H(psi): phase 1 volume
  double sharpVolume = 0; // cells with psi > 0 (sharp Heaviside)
  double area = 0;        // integral of delta(psi) |grad psi|: interface area
  double curvature2 = 0;  // integral of delta(psi) |grad psi| kappa^2: over area, the mean square
                          // curvature (roughness: grid-scale wrinkles raise it, issue 53)
};

// Local (this rank's owned cells) sums; the caller reduces over ranks.
// Needs psi on one ghost layer (edges too) for the central gradient and the curvature. box:
// only there (core/index_space.hpp, within: several level sets; psi <= -kappa outside it adds
// nothing).
inline PhaseMeasures localPhaseMeasures(const Grid& g, const Field& psi, double kappa, const Range3* box = nullptr) {
  const double dv = g.cellVolume();
  const double i0 = 0.5 / g.h[0], i1 = 0.5 / g.h[1], i2 = 0.5 / g.h[2];
  const double kmax = 1 / minOf(g.h[0], minOf(g.h[1], g.h[2]));
  double vol = 0, sharp = 0, area = 0, curv2 = 0;
  Kokkos::parallel_reduce(
      "phase_measures", within(box, 0, cellRange(g)).policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& v, double& s, double& a, double& c2) {
        const double p = psi(i, j, k);
        v += smoothedHeaviside(p, kappa) * dv;
        s += sharpHeaviside(p) * dv;
        const double d = smoothedDelta(p, kappa);
        if (d > 0) {
          const double gx = (psi(i + 1, j, k) - psi(i - 1, j, k)) * i0;
          const double gy = (psi(i, j + 1, k) - psi(i, j - 1, k)) * i1;
          const double gz = (psi(i, j, k + 1) - psi(i, j, k - 1)) * i2;
          const double da = d * km::sqrt(gx * gx + gy * gy + gz * gz) * dv;
          const double kv = curvature::curvatureAt(psi, i, j, k, 2 * i0, 2 * i1, 2 * i2, kmax);
          a += da;
          c2 += da * kv * kv;
        }
      },
      vol, sharp, area, curv2);
  return {vol, sharp, area, curv2};
}

// Global volume correction (level_set.volume_correction, effects/level_set/volume.cpp).
// Local sums over owned cells of H(psi) dv and dH/dpsi(psi) dv: the phase-1
// volume and its derivative with respect to a uniform shift of psi (Newton's step).
inline void localVolumeAndDerivative(const Grid& g, const Field& psi, double kappa, double& vol, double& dvol,
                                     const Range3* box = nullptr) {
  const double dv = g.cellVolume();
  double v = 0, d = 0;
  Kokkos::parallel_reduce(
      "volume_and_derivative", within(box, 0, cellRange(g)).policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& va, double& da) {
        const double p = psi(i, j, k);
        va += smoothedHeaviside(p, kappa);
        da += smoothedDelta(p, kappa);
      },
      v, d);
  vol = v * dv;
  dvol = d * dv;
}

// psi += s on every cell, ghosts included: s is the same on every rank and a
// uniform shift commutes with the even (mirror) ghost fill, so no exchange.
// box: only there and its ghost layers (several level sets: the far field is left as it is).
inline void shiftField(const Grid& g, const Field& psi, double s, const Range3* box = nullptr) {
  for_each3("shift_psi", within(box, g.ng, Range3{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}}),
      KOKKOS_LAMBDA(int i, int j, int k) { psi(i, j, k) += s; });
}

// dst = src on r.
inline void copyCells(const Field& dst, const Field& src, Range3 r) {
  for_each3("copy_cells", r, KOKKOS_LAMBDA(int i, int j, int k) { dst(i, j, k) = src(i, j, k); });
}

// Outward flux of the phase-1 volume through the open faces of the domain
// (open[f], f = 2 axis + side): sum over this rank's boundary cells of
// H(psi_c) (u.n) dA, u.n the mean of the face's 4 node velocities, as in the
// advection's face speed. Needs u on the boundary nodes.
inline double localOpenBoundaryFlux(const Grid& g, const Field& psi, const VecField& u, double kappa,
                                    const bool open[6]) {
  double total = 0;
  for (int f = 0; f < 6; ++f) {
    const int d = f / 2, side = f % 2;
    if (!open[f] || !(side == 0 ? g.atLo(d) : g.atHi(d))) continue;
    Range3 r = cellRange(g);
    const int cell = side == 0 ? g.ng : g.ng + g.ln[d] - 1;
    r.b[d] = cell;
    r.e[d] = cell + 1;
    const int a = (d + 1) % 3, b = (d + 2) % 3;
    const double area = g.h[a] * g.h[b], sign = side == 0 ? -1.0 : 1.0;
    const int node = cell + side; // the face's node layer along d
    const auto ud = u.c[d];
    double sum = 0;
    Kokkos::parallel_reduce(
        "open_boundary_flux", r.policy(),
        KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
          int n0[3] = {i, j, k};
          n0[d] = node;
          double un = 0;
          VOIGT_UNROLL
          for (int c = 0; c < 4; ++c) {
            int n[3] = {n0[0], n0[1], n0[2]};
            n[a] += c & 1;
            n[b] += (c >> 1) & 1;
            un += 0.25 * ud(n[0], n[1], n[2]);
          }
          acc += smoothedHeaviside(psi(i, j, k), kappa) * sign * un * area;
        },
        sum);
    total += sum;
  }
  return total;
}

} // namespace voigt
