#pragma once
// Advection kernel family, face-flux form: the schemes of advection.hpp and
// levelset.hpp (MUSCL + Kurganov-Tadmor, dq/dt = -[div(v q) - q div_h v]) with
// every face flux computed once, not twice (once by each point beside it). Axes
// are template parameters and each field has its own kernels (a runtime axis or
// component index was slower, perf/README.md). One pass per axis fills the faces
// (FluxScratch), one pass over the points takes the differences in the same
// order and with the same operations as the point-wise kernels, so the results
// are bit-identical to them (tests/flow/test_advection_faces.cpp).
// Face i along an axis lies between points i-1 and i.
#include <type_traits>

#include "core/field.hpp"
#include "core/index_space.hpp"
#include "kernels/advection.hpp"

namespace voigt {
namespace faces {

// Points [b, e) need faces [b, e] along axis d.
inline Range3 faceRange(const Range3& r, int d) {
  Range3 f = r;
  f.e[d] += 1;
  return f;
}

// Face speed of a primary cell face: the mean of its 4 nodes (levelset.hpp's order).
KOKKOS_INLINE_FUNCTION double cellFaceSpeed(const Field& vd, int d, int i, int j, int k) {
  if (d == 0) return 0.25 * (vd(i, j, k) + vd(i, j + 1, k) + vd(i, j, k + 1) + vd(i, j + 1, k + 1));
  if (d == 1) return 0.25 * (vd(i, j, k) + vd(i + 1, j, k) + vd(i, j, k + 1) + vd(i + 1, j, k + 1));
  return 0.25 * (vd(i, j, k) + vd(i + 1, j, k) + vd(i, j + 1, k) + vd(i + 1, j + 1, k));
}

// Momentum face fluxes along axis D (compile-time: the offsets fold into the
// addressing): slots 4 D + {0: F_rho, 1..3: F_m}. The face speed is not stored: the
// sum pass recomputes it from the velocity it reads anyway (same expression, same
// bits), which saves writing and reading three slots a node.
template <int D, int LIM>
void momentumFaces(const Field& rho, const VecField& v, Range3 nodes,
                   const Kokkos::View<double****, Kokkos::LayoutLeft, MemSpace>& F) {
  constexpr int di = D == 0, dj = D == 1, dk = D == 2, s0 = 4 * D - 1;
  const Field vx = v.c[0], vy = v.c[1], vz = v.c[2], vd = v.c[D];
  for_each3(
      "momentum_advection_faces", faceRange(nodes, D), KOKKOS_LAMBDA(int i, int j, int k) {
        const double a = 0.5 * (vd(i - di, j - dj, k - dk) + vd(i, j, k));
        double rL, rR, uL, uR;
        musclStatesT<LIM>(rho(i - 2 * di, j - 2 * dj, k - 2 * dk), rho(i - di, j - dj, k - dk), rho(i, j, k),
                    rho(i + di, j + dj, k + dk), rL, rR);
        F(i, j, k, s0 + 1) = ktFlux(a, rL, rR);
        musclStatesT<LIM>(vx(i - 2 * di, j - 2 * dj, k - 2 * dk), vx(i - di, j - dj, k - dk), vx(i, j, k),
                    vx(i + di, j + dj, k + dk), uL, uR);
        F(i, j, k, s0 + 2) = ktFlux(a, rL * uL, rR * uR);
        musclStatesT<LIM>(vy(i - 2 * di, j - 2 * dj, k - 2 * dk), vy(i - di, j - dj, k - dk), vy(i, j, k),
                    vy(i + di, j + dj, k + dk), uL, uR);
        F(i, j, k, s0 + 3) = ktFlux(a, rL * uL, rR * uR);
        musclStatesT<LIM>(vz(i - 2 * di, j - 2 * dj, k - 2 * dk), vz(i - di, j - dj, k - dk), vz(i, j, k),
                    vz(i + di, j + dj, k + dk), uL, uR);
        F(i, j, k, s0 + 4) = ktFlux(a, rL * uL, rR * uR);
      });
}
// One axis of the momentum face differences, unrolled (a runtime axis or
// component index keeps the compiler from holding the views in registers).
template <int D>
KOKKOS_FORCEINLINE_FUNCTION void momentumSum(const Kokkos::View<double****, Kokkos::LayoutLeft, MemSpace>& F,
                                             const Field& vd, int i, int j, int k, double r0, double u0, double u1,
                                             double u2, double hinv, double& tr, double* tm) {
  constexpr int s0 = 4 * D - 1, di = D == 0, dj = D == 1, dk = D == 2;
  const int ip = i + di, jp = j + dj, kp = k + dk;
  const double vc = vd(i, j, k);
  const double ap = 0.5 * (vc + vd(ip, jp, kp)), am = 0.5 * (vd(i - di, j - dj, k - dk) + vc); // as momentumFaces
  tr -= (F(ip, jp, kp, s0 + 1) - F(i, j, k, s0 + 1) - r0 * (ap - am)) * hinv;
  tm[0] -= (F(ip, jp, kp, s0 + 2) - F(i, j, k, s0 + 2) - r0 * u0 * (ap - am)) * hinv;
  tm[1] -= (F(ip, jp, kp, s0 + 3) - F(i, j, k, s0 + 3) - r0 * u1 * (ap - am)) * hinv;
  tm[2] -= (F(ip, jp, kp, s0 + 4) - F(i, j, k, s0 + 4) - r0 * u2 * (ap - am)) * hinv;
}
} // namespace faces

// Conservative momentum advection, as addMomentumAdvection (advection.hpp).
// assign: rhs = the tendency, as += onto a zeroed rhs would give (0 + x, bit for bit),
// without the zeroing pass and the read of rhs.
inline void addMomentumAdvectionFaces(const Grid& g, const Field& rho, const VecField& v, const Field& rhoRef,
                                      const Field& rhsRho, const VecField& rhs, Range3 nodes, Limiter limiter,
                                      FluxScratch& scratch, bool assign = false) {
  scratch.reserve(g, 12);
  auto F = scratch.F;
  auto vx = v.c[0], vy = v.c[1], vz = v.c[2];
  withLimiter(limiter, [&](auto L) {
    faces::momentumFaces<0, decltype(L)::value>(rho, v, nodes, F);
    faces::momentumFaces<1, decltype(L)::value>(rho, v, nodes, F);
    faces::momentumFaces<2, decltype(L)::value>(rho, v, nodes, F);
  });
  const double ih0 = 1 / g.h[0], ih1 = 1 / g.h[1], ih2 = 1 / g.h[2];
  auto rx = rhs.c[0], ry = rhs.c[1], rz = rhs.c[2];
  for_each3(
      "momentum_advection_sum", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
        const double r0 = rho(i, j, k);
        const double u0 = vx(i, j, k), u1 = vy(i, j, k), u2 = vz(i, j, k);
        double tr = 0, tm[3] = {0, 0, 0};
        faces::momentumSum<0>(F, vx, i, j, k, r0, u0, u1, u2, ih0, tr, tm);
        faces::momentumSum<1>(F, vy, i, j, k, r0, u0, u1, u2, ih1, tr, tm);
        faces::momentumSum<2>(F, vz, i, j, k, r0, u0, u1, u2, ih2, tr, tm);
        rhsRho(i, j, k) = tr;
        const double inv = 1 / rhoRef(i, j, k);
        rx(i, j, k) = (assign ? 0.0 : rx(i, j, k)) + tm[0] * inv;
        ry(i, j, k) = (assign ? 0.0 : ry(i, j, k)) + tm[1] * inv;
        rz(i, j, k) = (assign ? 0.0 : rz(i, j, k)) + tm[2] * inv;
      });
}

// rhs.c[c] += -(advection of v.c[c] by v): the three calls of addNodeAdvection,
// one component at a time (a kernel per component beats one over all three,
// perf/README.md). Slots per axis d: 2 d + {0: speed, 1: F}.
namespace faces {
// Face fluxes of one field q along axis D. Node fields (dual cells): the face
// speed is the mean of the two nodes; cell fields: the mean of the face's 4 nodes.
template <int D, bool CellField, int LIM>
void scalarFaces(const Field& q, const Field& vd, Range3 r,
                 const Kokkos::View<double****, Kokkos::LayoutLeft, MemSpace>& F) {
  constexpr int di = D == 0, dj = D == 1, dk = D == 2, s0 = 2 * D;
  for_each3(
      CellField ? "cell_advection_faces" : "node_advection_faces", faceRange(r, D),
      KOKKOS_LAMBDA(int i, int j, int k) {
        const double a = CellField ? cellFaceSpeed(vd, D, i, j, k) : 0.5 * (vd(i - di, j - dj, k - dk) + vd(i, j, k));
        F(i, j, k, s0) = a;
        F(i, j, k, s0 + 1) = centralFluxT<LIM>(q(i - 2 * di, j - 2 * dj, k - 2 * dk), q(i - di, j - dj, k - dk),
                                         q(i, j, k), q(i + di, j + dj, k + dk), a);
      });
}
template <int D>
KOKKOS_FORCEINLINE_FUNCTION void scalarSum(const Kokkos::View<double****, Kokkos::LayoutLeft, MemSpace>& F, int i,
                                           int j, int k, double q0, double h, double& tend) {
  constexpr int s0 = 2 * D;
  const int ip = i + (D == 0), jp = j + (D == 1), kp = k + (D == 2);
  const double ap = F(ip, jp, kp, s0), am = F(i, j, k, s0);
  tend -= (F(ip, jp, kp, s0 + 1) - F(i, j, k, s0 + 1) - q0 * (ap - am)) / h;
}
// The face fluxes of q along the three axes into the scratch's slots (Cell: q at cell
// centres); returns the flux view.
template <bool Cell>
inline auto scalarFacesXYZ(const Grid& g, const Field& q, const VecField& v, Range3 r, Limiter limiter,
                           FluxScratch& scratch) {
  scratch.reserve(g, 6);
  auto F = scratch.F;
  withLimiter(limiter, [&](auto L) {
    scalarFaces<0, Cell, decltype(L)::value>(q, v.c[0], r, F);
    scalarFaces<1, Cell, decltype(L)::value>(q, v.c[1], r, F);
    scalarFaces<2, Cell, decltype(L)::value>(q, v.c[2], r, F);
  });
  return F;
}

// The advective tendency of q at (i, j, k) from the three axes' face fluxes.
template <class Flux>
KOKKOS_FORCEINLINE_FUNCTION double scalarTendency(const Flux& F, int i, int j, int k, double q0, double h0, double h1,
                                             double h2) {
  double tend = 0;
  scalarSum<0>(F, i, j, k, q0, h0, tend);
  scalarSum<1>(F, i, j, k, q0, h1, tend);
  scalarSum<2>(F, i, j, k, q0, h2, tend);
  return tend;
}
} // namespace faces

inline void addNodeAdvectionFaces(const Grid& g, const Field& q, const VecField& v, const Field& rhs, Range3 nodes,
                                  Limiter limiter, FluxScratch& scratch, bool assign = false) {
  const auto F = faces::scalarFacesXYZ<false>(g, q, v, nodes, limiter, scratch);
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  for_each3(
      "node_advection_sum", nodes, KOKKOS_LAMBDA(int i, int j, int k) {
        const double tend = faces::scalarTendency(F, i, j, k, q(i, j, k), h0, h1, h2);
        rhs(i, j, k) = (assign ? 0.0 : rhs(i, j, k)) + tend; // assign: as addMomentumAdvectionFaces
      });
}

inline void addVelocityAdvectionFaces(const Grid& g, const VecField& v, const VecField& rhs, Range3 nodes,
                                      Limiter limiter, FluxScratch& scratch, bool assign = false) {
#if defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL)
  // On a GPU the point-wise form (one launch a component, no face scratch) is faster:
  // 1.94 against 2.91 ms at 256^3, 0.043 against 0.078 at 64^3 on an H200
  // (perf/portability/device_check_h200.md, NodeAdvection[Pointwise]). Plain `if`: nvcc
  // refuses a lambda's first capture inside `if constexpr`.
  if (kOnDevice) {
    for (int c = 0; c < 3; ++c) {
      const Field r = rhs.c[c];
      if (assign) // as the face form's rhs = 0 + tend: zero the nodes it writes, no others
        for_each3("node_advection_zero", nodes, KOKKOS_LAMBDA(int i, int j, int k) { r(i, j, k) = 0; });
      addNodeAdvection(g, v.c[c], v, r, nodes, limiter);
    }
  } else // (not `return`: nvcc would call the loop below unreachable)
#endif
  {
    VOIGT_UNROLL
    for (int c = 0; c < 3; ++c) addNodeAdvectionFaces(g, v.c[c], v, rhs.c[c], nodes, limiter, scratch, assign);
  }
}

// One cell field advected by the node velocity (addCellAdvection of
// levelset.hpp) and advanced by one SSP-RK2 (Heun) stage in the same pass, as
// the callers did with a zeroed rhs r:
//   q <- (1 - a) o + a (q + dt r),   a = 1 (stage 1) or 1/2 (stage 2);
// storeOld: stage 1 also sets o = q^n. The velocity is frozen over a step's stages and
// the same for every field, so its face speeds are computed once (cellFaceSpeeds,
// slots 0-2) and each field's pass writes only its fluxes (slots 3-5): a field's face
// pass then reads q and one speed and writes one slot, not four velocity nodes and two
// slots. Several fields: one call each (faster than one kernel over all of them,
// perf/README.md).
namespace faces {
template <int D>
void cellSpeeds(const Field& vd, Range3 r, const Kokkos::View<double****, Kokkos::LayoutLeft, MemSpace>& F) {
  for_each3(
      "cell_face_speeds", faceRange(r, D), KOKKOS_LAMBDA(int i, int j, int k) { F(i, j, k, D) = cellFaceSpeed(vd, D, i, j, k); });
}
template <int D, int LIM>
void cellFluxes(const Field& q, Range3 r, const Kokkos::View<double****, Kokkos::LayoutLeft, MemSpace>& F) {
  constexpr int di = D == 0, dj = D == 1, dk = D == 2;
  for_each3(
      "cell_advection_faces", faceRange(r, D), KOKKOS_LAMBDA(int i, int j, int k) {
        F(i, j, k, 3 + D) = centralFluxT<LIM>(q(i - 2 * di, j - 2 * dj, k - 2 * dk), q(i - di, j - dj, k - dk),
                                              q(i, j, k), q(i + di, j + dj, k + dk), F(i, j, k, D));
      });
}
template <int D>
KOKKOS_FORCEINLINE_FUNCTION void cellSum(const Kokkos::View<double****, Kokkos::LayoutLeft, MemSpace>& F, int i, int j,
                                         int k, double q0, double h, double& tend) {
  const int ip = i + (D == 0), jp = j + (D == 1), kp = k + (D == 2);
  const double ap = F(ip, jp, kp, D), am = F(i, j, k, D);
  tend -= (F(ip, jp, kp, 3 + D) - F(i, j, k, 3 + D) - q0 * (ap - am)) / h;
}
} // namespace faces

// The face speeds of v for cell fields on `cells` into the scratch's slots 0-2.
inline void cellFaceSpeeds(const Grid& g, const VecField& v, Range3 cells, FluxScratch& scratch) {
  scratch.reserve(g, 6);
  faces::cellSpeeds<0>(v.c[0], cells, scratch.F);
  faces::cellSpeeds<1>(v.c[1], cells, scratch.F);
  faces::cellSpeeds<2>(v.c[2], cells, scratch.F);
}

// One stage for q with the speeds cellFaceSpeeds left in `speeds` (same cells).
inline void advanceCellAdvection(const Grid& g, const Field& q, const Field& o, Range3 cells, Limiter limiter, double dt,
                                 double a, bool storeOld, const FluxScratch& speeds) {
  const auto F = speeds.F;
  withLimiter(limiter, [&](auto L) {
    faces::cellFluxes<0, decltype(L)::value>(q, cells, F);
    faces::cellFluxes<1, decltype(L)::value>(q, cells, F);
    faces::cellFluxes<2, decltype(L)::value>(q, cells, F);
  });
  const double h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
  for_each3(
      "cell_advection_rk2", cells, KOKKOS_LAMBDA(int i, int j, int k) {
        const double q0 = q(i, j, k);
        double tend = 0; // the same order as scalarTendency
        faces::cellSum<0>(F, i, j, k, q0, h0, tend);
        faces::cellSum<1>(F, i, j, k, q0, h1, tend);
        faces::cellSum<2>(F, i, j, k, q0, h2, tend);
        double r = 0; // as the zeroed rhs the callers used: 0 + (-0) is +0, bit for bit
        r += tend;
        if (storeOld) o(i, j, k) = q0;
        const double old = storeOld ? q0 : o(i, j, k);
        q(i, j, k) = (1 - a) * old + a * (q0 + dt * r);
      });
}

// One field, one stage: the speeds, then the stage.
inline void advanceCellAdvection(const Grid& g, const Field& q, const Field& o, const VecField& v, Range3 cells,
                                 Limiter limiter, double dt, double a, bool storeOld, FluxScratch& scratch) {
  cellFaceSpeeds(g, v, cells, scratch);
  advanceCellAdvection(g, q, o, cells, limiter, dt, a, storeOld, scratch);
}

} // namespace voigt
