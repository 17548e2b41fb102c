// Global volume correction (level_set.volume_correction: global, the default).
//   The model's phase-1 volume is V = INT H(psi) dV (Eq. 4), and its mass is
//   INT rho dV = rho_2 |Omega| + (rho_1 - rho_2) V (Eq. 2): holding V holds both
//   phases' mass. Advection (Eq. 1, not conservative in H) and the
//   re-initialisation (Eq. 17, with or without the local constraint of
//   Eq. 18-21) change V; after them, once per step,
//     psi <- psi + s,   s: INT H(psi + s) dV = V_target   (one Newton step)
//   V_target = V(t = 0) minus the outflow of H through open (inflow/outflow)
//   faces, INT dt SUM H (u.n) dA. A uniform shift moves the interface by s along
//   its normal everywhere and keeps |grad psi| (a distance stays a distance), so
//   it neither undoes the re-initialisation nor adds a time scale; measured
//   by the next step's V, nothing accumulates: every step corrects against the
//   target, not against the previous step. One step's residual is
//   V'' s^2 / 2, round-off for the per-step drifts seen (s ~ 1e-4 cells).
//   |s| is capped at 0.1 cell per step, so a restart from a drifted state is
//   corrected over a few steps rather than in one jump.
#include <mpi.h>

#include <algorithm>
#include <cmath>

#include "effects/level_set/level_set.hpp"
#include "core/field_names.hpp"
#include "kernels/levelset.hpp"
#include "kernels/multiphase.hpp"

namespace voigt {

void LevelSet::correctVolume(State& st) {
  for (size_t i = 0; i < ls_.size(); ++i)
    if (ls_[i].globalCorrection) correctVolume(st, i);
}

// Several level sets: a fluid's target is its covered volume (multiphase.cpp), and so is
// its derivative: the shift moves only the part of the interface that is seen.
void LevelSet::correctVolume(State& st, size_t i) {
  LevelSetInstance& l = ls_[i];
  const Grid& g = st.grid;
  Field psi = st.fields.scalar(l.info.field);
  const double kappa = l.info.geometry.kappa(g), hmin = LevelSetGeometry::hMin(g);
  double loc[3] = {0, 0, 0}, glob[3];
  const Range3* b = box(st, l); // several level sets: outside it H = H' = 0
  if (covered(i))
    multiphase::localCoveredVolume(g, psi, kappa, cover(st, i), loc[0], loc[1], b);
  else
    localVolumeAndDerivative(g, psi, kappa, loc[0], loc[1], b);
  if (std::any_of(open_, open_ + 6, [](bool b) { return b; }) && st.fields.allocated(field::velocity))
    loc[2] = localOpenBoundaryFlux(g, psi, st.fields.vector(field::velocity), kappa, open_);
  MPI_Allreduce(loc, glob, 3, MPI_DOUBLE, MPI_SUM, g.comm);
  l.target -= st.dt * glob[2];
  double s = 0;
  if (glob[1] > 0) s = std::clamp((l.target - glob[0]) / glob[1], -0.1 * hmin, 0.1 * hmin);
  if (s != 0) shiftField(g, psi, s, b);
  l.shiftTotal += std::abs(s);
  // Volume the correction put back or took away so far (|s| times the smoothed
  // interface area), relative: what the numerics moved, for energy budgets.
  l.movedTotal += std::abs(s) * glob[1];
  st.diag["volume_shift_cells" + l.suffix()] = s / hmin;
  st.diag["volume_corrected" + l.suffix()] = l.volume0 != 0 ? l.movedTotal / l.volume0 : 0.0;
}

} // namespace voigt
