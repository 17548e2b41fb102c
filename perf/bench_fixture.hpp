#pragma once
// perf_kernels' fixture (bench_kernels.cpp): a 64^3 periodic grid (VOIGT_BENCH_N) with a
// sphere of radius 0.3 (psi > 0 inside: the solid; |psi| the distance), a smooth flow, and
// the band lists the band kernels run over, built once.
#include <cmath>
#include <cstdlib>
#include <string>

#include "core/grid.hpp"
#include "core/index_space.hpp"
#include "kernels/elastic.hpp"
#include "kernels/extension.hpp"
#include "kernels/reductions.hpp"
#include "kernels/reinit.hpp"

namespace voigt {
namespace bench {

// A sphere of radius 0.3 (psi > 0 inside: the solid; |psi| the distance) and a smooth flow.
// A free function: nvcc allows no device lambda in a constructor (tests/device).
inline void fillSphereAndFlow(const Grid& g, const VecField& u, const Field& psi, const Field& p) {
  auto uu = u;
  auto ps = psi, pp = p;
  const int ng = g.ng;
  const double hh = g.h[0];
  Kokkos::parallel_for(
      Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}), KOKKOS_LAMBDA(int i, int j, int k) {
        uu.c[0](i, j, k) = std::sin(0.1 * i) * std::cos(0.2 * j);
        uu.c[1](i, j, k) = std::cos(0.1 * i) * std::sin(0.3 * k);
        uu.c[2](i, j, k) = std::sin(0.2 * j + 0.1 * k);
        const double x = (i - ng + 0.5) * hh - 0.5, y = (j - ng + 0.5) * hh - 0.5, z = (k - ng + 0.5) * hh - 0.5;
        ps(i, j, k) = 0.3 - std::sqrt(x * x + y * y + z * z);
        pp(i, j, k) = std::cos(6.0 * x) * std::sin(4.0 * y + z);
      });
}

struct Fixture {
  Grid g;
  VecField u, rhs, coef;
  Field p, div, mu, psi, rhsCell, psi1, psiT, dH, gm, old;
  SymTensorField tau, tauS;
  IntList owned, grown; // elastic band (psi > -(kappa + 3 h)): owned cells, one ghost layer more
  int nOwned = 0, nGrown = 0;
  IntList ownedRuns; // where the runs of consecutive cells in `owned` start (listRuns)
  int nOwnedRuns = 0;
  IntList side; // the band's fluid side (psi <= 0): the cells the stress extension sweeps
  int nSide = 0;
  IntList sideRuns; // where the runs of consecutive cells in `side` start (listRuns)
  int nSideRuns = 0;
  reinit::BandViews band; // reinit band |psi| < 6 h
  int nBand = 0;
  double h = 0;
  Fixture() {
    const int n = getenv("VOIGT_BENCH_N") ? atoi(getenv("VOIGT_BENCH_N")) : 64;
    g = makeGrid(MPI_COMM_SELF, {n, n, n}, {0, 0, 0}, {1, 1, 1}, {true, true, true});
    h = g.h[0];
    auto mk = [&](const char* name) { return Field(std::string(name), g.ext[0], g.ext[1], g.ext[2]); };
    for (int c = 0; c < 3; ++c) {
      u.c[c] = mk("u");
      rhs.c[c] = mk("rhs");
      coef.c[c] = mk("coef");
      Kokkos::deep_copy(coef.c[c], 1.0);
    }
    for (int c = 0; c < 6; ++c) {
      tau.c[c] = mk("tau");
      tauS.c[c] = mk("tau_S");
      Kokkos::deep_copy(tauS.c[c], c < 3 ? 1.0 : 0.1);
    }
    p = mk("p"), div = mk("div"), mu = mk("mu"), psi = mk("psi"), rhsCell = mk("rhs_cell");
    psi1 = mk("psi1"), psiT = mk("psiT"), dH = mk("dH"), gm = mk("gm"), old = mk("old");
    Kokkos::deep_copy(mu, 1e-3);
    fillSphereAndFlow(g, u, psi, p);
    const size_t cap = size_t(g.cellsOwned());
    const size_t capG = size_t(cellRange(g, 1).size());
    owned = IntList("owned", cap), grown = IntList("grown", capG);
    nOwned = elastic::buildActiveList(g, psi, -5 * h, cellRange(g), owned);
    nGrown = elastic::buildActiveList(g, psi, -5 * h, cellRange(g, 1), grown);
    ownedRuns = IntList("owned_runs", cap);
    nOwnedRuns = listRuns(owned, nOwned, ownedRuns);
    side = IntList("side", cap);
    nSide = extension::fluidSide(psi, g, owned, nOwned, 0.0, side);
    sideRuns = IntList("side_runs", cap);
    nSideRuns = listRuns(side, nSide, sideRuns);
    band.cell = IntList("band", cap), band.flags = IntList("flags", cap);
    band.sgn = reinit::RealList("sgn", cap), band.dist = reinit::RealList("dist", cap);
    band.coef = reinit::RealList("coef", cap);
    nBand = reinit::buildBandList(g, psi, 6 * h, band.cell);
    band.runs = IntList("runs", cap);
    band.nRuns = listRuns(band.cell, nBand, band.runs);
    Kokkos::deep_copy(psi1, psi), Kokkos::deep_copy(psiT, psi);
    reinit::deltaField(g, psi, dH, 2 * h);
    reinit::prepareBand(g, band, nBand, psi, dH, gm, 6 * h, true);
    Kokkos::fence();
  }
};
inline Fixture* gFixture = nullptr; // freed before Kokkos::finalize
inline Fixture& fx() {
  if (!gFixture) gFixture = new Fixture;
  return *gFixture;
}


} // namespace bench
} // namespace voigt
