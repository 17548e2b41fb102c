// Level-set stages.
//   Advection, Eq. (1): dpsi/dt = -v . grad psi, in the conservative form
//     dpsi/dt = -[div(v psi) - psi div_h v]        (kernels/levelset.hpp)
//   with SSP-RK2 (Heun) and the velocity frozen at u^n:
//     psi1 = psi^n + dt R(psi^n);  psi^{n+1} = (psi^n + psi1 + dt R(psi1)) / 2
//   Properties, Eq. (2)-(4): rho = H rho_1 + (1 - H) rho_2, same for mu; blended from psi^n
//   at the start of a step and again from psi^{n+1} after the advection, so the momentum
//   stage sees rho^{n+1}: interface displacement and velocity then form a symplectic-Euler
//   pair, stable for omega dt <= 2 (with rho^n, forward Euler: unstable at any dt; README,
//   "Gravity and rest").
#include <cmath>

#include "effects/level_set/level_set.hpp"
#include "core/field_names.hpp"
#include "kernels/advection_faces.hpp"
#include "kernels/levelset.hpp"
#include "kernels/reductions.hpp"

namespace voigt {

void LevelSet::advect(State& st) {
  const Grid& g = st.grid;
  const Range3 cells = cellRange(g);
  Field psi = st.fields.scalar(field::psi), old = st.fields.scalar("psi_old");
  VecField u = st.fields.vector(field::velocity);
  exchangeVelocity(st); // face speeds need the nodes on the owned cells' high faces
  const double dt = st.dt;
  Kokkos::deep_copy(old, psi);
  cellFaceSpeeds(g, u, cells, flux_); // u is frozen: once for both stages
  VOIGT_UNROLL
  for (int stage = 0; stage < 2; ++stage) {
    refreshGhosts(st, psi);
    advanceCellAdvection(g, psi, old, cells, limiter_, dt, stage == 0 ? 1.0 : 0.5, false, flux_);
  }
  refreshGhosts(st, psi);
  blend(st); // rho^{n+1}, mu^{n+1} for the momentum stage (header)
}

void LevelSet::blend(State& st) {
  if (!st.fields.allocated(field::density)) return; // kinematic scenes: nothing to blend
  const Grid& g = st.grid;
  blendProperties(st.fields.scalar(field::psi), geo_.kappa(g), rho1_, rho2_, mu1_, mu2_, st.fields.scalar(field::density),
                  st.fields.scalar(field::viscosity), cellRange(g, g.ng), harmonicMu_);
  st.propertiesChanged = true;
}

void LevelSet::diagnose(State& st) {
  const Grid& g = st.grid;
  PhaseMeasures m = localPhaseMeasures(g, st.fields.scalar(field::psi), geo_.kappa(g));
  double loc[3] = {m.volume, m.sharpVolume, m.area}, glob[3];
  MPI_Allreduce(loc, glob, 3, MPI_DOUBLE, MPI_SUM, g.comm);
  volume_ = glob[0];
  sharpVolume_ = glob[1];
  area_ = glob[2];
  double total = 1;
  VOIGT_UNROLL
  for (int d = 0; d < 3; ++d) total *= g.hi[d] - g.lo[d];
  const double drift = volume0_ != 0 ? volume_ / volume0_ - 1 : 0;
  driftMax_ = std::max(driftMax_, std::abs(drift));
  st.diag["volume_" + phase_] = volume_;
  st.diag["volume_" + scene_->fluid] = total - volume_;
  st.diag["volume_drift"] = drift;
  st.diag["interface_area"] = area_;
}

} // namespace voigt
