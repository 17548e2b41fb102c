#include "levelset/reinit.hpp"

#include <mpi.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/boundary.hpp"
#include "core/host_access.hpp"
#include "kernels/levelset.hpp"
#include "kernels/reductions.hpp"

namespace voigt {

Reinitializer::Reinitializer(const Grid& g, ReinitParams p) : g_(&g), p_(p) {
  if (p_.iterations < 0) throw std::invalid_argument("reinit: iterations must be >= 0");
  if (!(p_.dtauCells > 0 && p_.dtauCells <= 1)) throw std::invalid_argument("reinit: dtau must be in (0, 1] cells");
  if (!(p_.band > 0)) throw std::invalid_argument("reinit: band must be > 0");
  if (!(p_.zoneTolerance >= 0)) throw std::invalid_argument("reinit: zone_tolerance must be >= 0");
  // band >= kappa keeps H'(psi0) = 0 on every frozen cell, so the Eq. (21)
  // integrals see only cells that the constraint also corrects.
  if (p_.volumeConstraint && !(p_.kappa > 0 && p_.kappa <= p_.band))
    throw std::invalid_argument("reinit: the volume constraint needs 0 < kappa <= band");
  psi1_ = Field("reinit_psi1", g.ext[0], g.ext[1], g.ext[2]);
  psiT_ = Field("reinit_psiT", g.ext[0], g.ext[1], g.ext[2]);
  dH_ = Field("reinit_dH", g.ext[0], g.ext[1], g.ext[2]);
  if (p_.volumeConstraint) gm_ = Field("reinit_grad_mag", g.ext[0], g.ext[1], g.ext[2]);
  for (const Field& f : {psi1_, psiT_, dH_, gm_}) guard(f); // the host-touch check's too
  const size_t cap = size_t(g.cellsOwned());
  band_.cell = reinit::IntList("reinit_band", cap);
  band_.flags = reinit::IntList("reinit_flags", cap);
  band_.sgn = reinit::RealList("reinit_sgn", cap);
  band_.dist = reinit::RealList("reinit_dist", cap);
  band_.coef = reinit::RealList("reinit_coef", cap);
  band_.runs = reinit::IntList("reinit_runs", cap);
}

void Reinitializer::refresh(Halo& halo, const Field& f, const Range3* reads, int depth) const {
  halo.exchange(f, depth);
  if (reads) fillCellGhostsEven(*g_, f, *reads);
  else fillCellGhostsEven(*g_, f);
}

void Reinitializer::setBand(double kappa, double band) {
  if (!(band > 0) || (p_.volumeConstraint && !(kappa > 0 && kappa <= band)))
    throw std::invalid_argument("reinit: the volume constraint needs 0 < kappa <= band");
  p_.kappa = kappa;
  p_.band = band;
}

ReinitStats Reinitializer::run(Halo& halo, const Field& psi, const Range3* box) {
  using namespace reinit;
  const Grid& g = *g_;
  Kokkos::fence();
  const double t0 = MPI_Wtime();
  const double hmin = std::min({g.h[0], g.h[1], g.h[2]});
  const double dtau = p_.dtauCells * hmin;
  const bool con = p_.volumeConstraint;

  // psi0 = psi. The stage fields start as copies, so the stencils read the frozen
  // values wherever the band kernels do not write.
  // With a box the copies cover it and its ghost layers: all that the stencils read.
  const Range3 all{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}}, copied = within(box, g.ng, all);
  auto copy = [&](const Field& dst, const Field& src) {
    if (box) copyCells(dst, src, copied);
    else Kokkos::deep_copy(dst, src);
  };
  refresh(halo, psi);
  if (p_.boundFarField) { // kernels/reinit.hpp: no cell near the interface stays outside the band
    copy(psi1_, psi);
    boundFarField(g, psi, psi1_, p_.kappa, box);
    copy(psi, psi1_);
    refresh(halo, psi);
  }
  const double zt = p_.zoneTolerance;
  const int n = buildBandList(g, psi, p_.band, band_.cell, p_.kappa, zt, p_.zoneCurvature, box);
  band_.nRuns = listRuns(band_.cell, n, band_.runs);
  copy(psi1_, psi);
  if (con) {
    copy(psiT_, psi);
    deltaField(g, psi, dH_, p_.kappa, box);
    if (zt > 0) unsettleDelta(g, psi, dH_, p_.kappa, zt, p_.zoneCurvature, box);
  }
  prepareBand(g, band_, n, psi, dH_, gm_, p_.band, con, box);

  // Inside the loop the kernels read the band cells and 2 layers around them:
  // the wall ghosts are filled there only; the last refresh of psi is whole.
  const Range3 reads = grown(listBox(g, band_.cell, n), 2);
  for (int m = 0; m < p_.iterations; ++m) {
    // psi (= psi^m) is fresh here.
    eikonalStage(g, band_, n, psi, psi, psi1_, 0.0, dtau, p_.subcellFix);
    refresh(halo, psi1_, &reads);
    if (!con) {
      eikonalStage(g, band_, n, psi1_, psi, psi, 0.5, dtau, p_.subcellFix);
    } else {
      eikonalStage(g, band_, n, psi1_, psi, psiT_, 0.5, dtau, p_.subcellFix);
      refresh(halo, psiT_, &reads, 1); // the constraint reads one layer (27 neighbours)
      applyConstraint(g, band_, n, psiT_, psi, dH_, psi1_); // psi1 is free again
      copyBand(g, band_, n, psi1_, psi);
    }
    refresh(halo, psi, m + 1 < p_.iterations ? &reads : nullptr);
  }

  ReinitStats st;
  long long local = n;
  MPI_Allreduce(&local, &st.bandCells, 1, MPI_LONG_LONG, MPI_SUM, g.comm);
  double ge = maxGradError(g, band_, n, psi, p_.band);
  MPI_Allreduce(&ge, &st.maxGradError, 1, MPI_DOUBLE, MPI_MAX, g.comm);
  Kokkos::fence();
  st.seconds = MPI_Wtime() - t0;
  return st;
}

} // namespace voigt
