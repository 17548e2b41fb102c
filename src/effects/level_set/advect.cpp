// Level-set stages.
//   Advection, Eq. (1): dpsi/dt = -v . grad psi, in the conservative form
//     dpsi/dt = -[div(v psi) - psi div_h v]        (kernels/levelset.hpp)
//   with SSP-RK2 (Heun) and the velocity frozen at u^n:
//     psi1 = psi^n + dt R(psi^n);  psi^{n+1} = (psi^n + psi1 + dt R(psi1)) / 2
//   Properties, Eq. (2)-(4): rho = H rho_1 + (1 - H) rho_2, same for mu (several level sets:
//   each laid over the earlier ones, kernels/levelset.hpp blendOver); blended from psi^n
//   at the start of a step and again from psi^{n+1} after the advection, so the momentum
//   stage sees rho^{n+1}: interface displacement and velocity then form a symplectic-Euler
//   pair, stable for omega dt <= 2 (with rho^n, forward Euler: unstable at any dt; README,
//   "Gravity and rest").
#include <cmath>

#include "effects/level_set/level_set.hpp"
#include "effects/level_set/surface_velocity.hpp"
#include "core/field_names.hpp"
#include "kernels/advection_faces.hpp"
#include "kernels/levelset.hpp"
#include "kernels/multiphase.hpp"
#include "kernels/reductions.hpp"

namespace voigt {

void LevelSet::advect(State& st) {
  const Grid& g = st.grid;
  const Range3 cells = cellRange(g);
  Field old = st.fields.scalar("psi_old");
  VecField u = st.fields.vector(field::velocity);
  exchangeVelocity(st); // face speeds need the nodes on the owned cells' high faces
  const double dt = st.dt;
  updateBoxes(st, false); // several level sets: each on its own box
  int speeds = -1;        // whose face speeds flux_ holds: 0 the flow's, 1 a surface's
  for (auto& l : ls_) {
    Field psi = st.fields.scalar(l.info.field);
    // u is frozen: the flow's face speeds once for both stages and every fluid level set; a
    // solid's surface velocity (surface_velocity: solid) for its own.
    if (l.surfaceSolid) cellFaceSpeeds(g, surfaceVelocity(st, l), cells, flux_);
    else if (speeds != 0) cellFaceSpeeds(g, u, cells, flux_);
    speeds = l.surfaceSolid ? 1 : 0;
    const Range3* b = box(st, l);
    if (b) copyCells(old, psi, within(b, g.ng, cellRange(g, g.ng)));
    else Kokkos::deep_copy(old, psi);
    VOIGT_UNROLL
    for (int stage = 0; stage < 2; ++stage) {
      refreshGhosts(st, psi);
      advanceCellAdvection(g, psi, old, within(b, 0, cells), limiter_, dt, stage == 0 ? 1.0 : 0.5, false, flux_);
    }
    refreshGhosts(st, psi);
  }
  blend(st); // rho^{n+1}, mu^{n+1} for the momentum stage (header)
}

// surface_velocity: solid: the solid's velocity extended across the zone's fluid half
// (effects/level_set/surface_velocity.hpp).
VecField LevelSet::surfaceVelocity(State& st, const LevelSetInstance& l) {
  const Field psi = st.fields.scalar(l.info.field);
  refreshGhosts(st, psi); // reinit and the volume correction wrote psi since
  return solidSurfaceVelocity(st, psi, l.info.geometry.kappa(st.grid), layer_);
}

void LevelSet::blend(State& st) {
  if (!st.fields.allocated(field::density)) return; // kinematic scenes: nothing to blend
  const Grid& g = st.grid;
  const Field rho = st.fields.scalar(field::density), mu = st.fields.scalar(field::viscosity);
  for (size_t i = 0; i < ls_.size(); ++i) {
    const LevelSetInstance& l = ls_[i];
    const Field psi = st.fields.scalar(l.info.field);
    const double kappa = l.info.geometry.kappa(g);
    if (i == 0)
      blendProperties(psi, kappa, l.rho, rhoF_, l.mu, muF_, rho, mu, cellRange(g, g.ng), l.harmonicMu);
    else // outside its box H = 0: nothing to lay over
      blendOver(psi, kappa, l.rho, l.mu, rho, mu, within(box(st, l), g.ng, cellRange(g, g.ng)), l.harmonicMu);
  }
  st.propertiesChanged = true;
}

void LevelSet::diagnose(State& st) {
  const Grid& g = st.grid;
  double total = 1;
  VOIGT_UNROLL
  for (int d = 0; d < 3; ++d) total *= g.hi[d] - g.lo[d];
  double fluid = total;
  for (size_t i = 0; i < ls_.size(); ++i) {
    LevelSetInstance& l = ls_[i];
    const Field psi = st.fields.scalar(l.info.field);
    const double kappa = l.info.geometry.kappa(g);
    PhaseMeasures m = localPhaseMeasures(g, psi, kappa, box(st, l));
    if (covered(i)) { // the fluid's volume: what later level sets leave (multiphase.cpp)
      double dv;
      multiphase::localCoveredVolume(g, psi, kappa, cover(st, i), m.volume, dv, box(st, l));
    }
    double loc[4] = {m.volume, m.sharpVolume, m.area, m.curvature2}, glob[4];
    MPI_Allreduce(loc, glob, 4, MPI_DOUBLE, MPI_SUM, g.comm);
    l.volume = glob[0];
    l.sharpVolume = glob[1];
    l.area = glob[2];
    const double drift = l.volume0 != 0 ? l.volume / l.volume0 - 1 : 0;
    l.driftMax = std::max(l.driftMax, std::abs(drift));
    fluid -= l.volume;
    // One level set: volume_<phase>; several (two may share a phase): volume_<name>.
    st.diag["volume_" + (single() ? l.info.phase : l.info.name)] = l.volume;
    st.diag["volume_drift" + l.suffix()] = drift;
    st.diag["interface_area" + l.suffix()] = l.area;
    // rms mean curvature over the surface (1/m): a smooth body's stays near its shape's value,
    // cell-scale wrinkles raise it towards 1/h (issue 53; kernels/curvature_point.hpp).
    st.diag["interface_curvature_rms" + l.suffix()] = l.area > 0 ? std::sqrt(glob[3] / l.area) : 0.0;
  }
  st.diag["volume_" + scene_->fluid] = fluid;
}

} // namespace voigt
