#pragma once
// Shared pieces of the device check (kernels_all.cpp, kernels_effects.cpp): the checksum
// list, the reductions that make a field a checksum, and the fields every part works on.
#include <Kokkos_Core.hpp>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/host_access.hpp"
#include "core/index_space.hpp"
#include "kernels/fast_diag.hpp"
#include "kernels/reinit.hpp"
#include "kernels/stress.hpp"

namespace voigt {
namespace check {

inline std::vector<std::pair<std::string, double>> gSums; // name, checksum, in call order
inline void put(const std::string& name, double v) { gSums.emplace_back(name, v); }

inline double sumAbs(const Field& f, Range3 r) {
  double s = 0;
  Kokkos::parallel_reduce(
      "check_sum_abs", r.policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& acc) { acc += Kokkos::Experimental::fabs(f(i, j, k)); }, s);
  return s;
}
inline double sumAbs(const VecField& v, Range3 r) { return sumAbs(v.c[0], r) + sumAbs(v.c[1], r) + sumAbs(v.c[2], r); }
inline double sumAbs(const SymTensorField& t, Range3 r) {
  double s = 0;
  for (int c = 0; c < 6; ++c) s += sumAbs(t.c[c], r);
  return s;
}
inline double sumList(const IntList& l, int n) {
  double s = 0;
  Kokkos::parallel_reduce(
      "check_sum_list", Kokkos::RangePolicy<ExecSpace>(0, n),
      KOKKOS_LAMBDA(int q, double& acc) { acc += double(l(q)) * double(q % 7 + 1); }, s);
  return s;
}

inline double sumBand(const reinit::BandViews& b, int n) {
  double s = 0;
  const auto sg = b.sgn, di = b.dist, co = b.coef;
  Kokkos::parallel_reduce(
      "check_sum_band", Kokkos::RangePolicy<ExecSpace>(0, n),
      KOKKOS_LAMBDA(int q, double& acc) {
        acc += Kokkos::Experimental::fabs(sg(q)) + Kokkos::Experimental::fabs(di(q)) + Kokkos::Experimental::fabs(co(q));
      },
      s);
  return s;
}

struct Fields {
  VecField u, u2, rhs, coef;
  Field p, psi, rho, mu, q, o, rhsCell, div, dH, gm, psi1, psiT;
  SymTensorField tau, tauS, tau2;
};

inline Field mk(const Grid& g, const char* name) { return Field(std::string(name), g.ext[0], g.ext[1], g.ext[2]); }

// A dense n x n test matrix for the fast-diagonalization passes (not orthogonal: a checksum).
inline Dense denseOf(int n) {
  Dense V("V", n, n);
  auto h = hostMirror(V); // core/host_access.hpp, compiled for the device here too
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < n; ++a) h(i, a) = std::cos(0.1 * (i + 1) * (a + 1)) / n;
  toDevice(V, h, "test_matrix");
  return V;
}

// The parts in kernels_effects.cpp (the effects' kernels), run after the others.
void effects(const Grid& g, Fields& f);
// kernels_capillary.cpp (surface tension), after effects().
void capillary(const Grid& g, Fields& f);
// kernels_viscous.cpp (semi-implicit viscosity), after capillary().
void viscous(const Grid& g, Fields& f);
// kernels_multiphase.cpp (several level sets), after viscous().
void multiphase(const Grid& g, Fields& f);

} // namespace check
} // namespace voigt
