// Stress, Corrections and Diagnostics stages of elasticity.
//   Stress (per Runge-Kutta substage of navier_stokes): tau += H(psi) tau_S,
//     Eq. (9)/(14). The viscous task ran first and filled tau = mu D with the
//     level set's blended mu = H mu_solid + (1 - H) mu_L (mu_solid = the
//     optional Kelvin-Voigt viscosity, 0 by default), so the sum is
//     tau = H tau_S + (1 - H) mu_L D [+ H eta_KV D]: Eq. (14) and, across the
//     interface, Eq. (15)'s Kelvin-Voigt blend. tau_S is the same in both
//     substages (it changes only in Corrections).
//   Corrections (after the projection, velocity u^{n+1}): Benson's half-step
//     Jaumann update, Eq. (16) with errata 1-2, half rotations by the scene's
//     `rotation` (Cayley by default; kernels/elastic.hpp). Momentum
//     used tau_S^n, the stress update uses u^{n+1}: the velocity/stress pair is
//     advanced like symplectic Euler, which is neutrally stable for elastic
//     waves below the elastic-wave dt limit (no amplitude growth or decay from
//     the time integration itself; test_shear_wave measures it).
//   Diagnostics: S2 and log10(S2) at the band cells, elastic energy
//     integral of H tau_S:tau_S / (4 mu_S) dV (= mu_S gamma^2 / 2 for a simple
//     shear gamma), max |S2| over the solid (psi > 0; the band's fluid side
//     also carries tau_S, as in the paper, where H ~ 0 makes it harmless) and
//     the number of cells the kernels touched.
#include <mpi.h>

#include <algorithm>
#include <cmath>

#include "effects/elasticity/elasticity.hpp"
#include "core/field_names.hpp"
#include "effects/navier_stokes/navier_stokes.hpp"
#include "kernels/elastic_diagnostics.hpp"
#include "kernels/extension.hpp"

namespace voigt {

void Elasticity::addStress(State& st) {
  elastic::addSolidStress(st.grid, psiField(st), kappa_, solidStressField(st.fields),
                          stressField(st.fields), grown_, nGrown_);
}

void Elasticity::update(State& st, double spinScale) {
  VecField u = st.fields.vector(field::velocity);
  exchangeVelocity(st); // the corners of the owned cells
  // fluid_side extend / one_cell / blend: Eq. (13) only where psi > below_ (0 / -h / -kappa),
  // then the cells below take the stress extended from above (elasticity.hpp).
  // The band's cells above below_ listed first (not masked in the kernel: the cells
  // below would cost as much as the rest, for nothing), in runs that vectorise.
  const elastic::IntList& cells = extend_ ? solid_cells_ : owned_;
  const int n = extend_ ? extension::fluidSide(solidPsi(st), st.grid, owned_, nOwned_, below_,
                                               solid_cells_, true)
                        : nOwned_;
  const int nRuns = listRuns(cells, n, owned_runs_);
  stressHalosCurrent_ = false;
  elastic::jaumannUpdate(st.grid, u, solidStressField(st.fields), mu_, st.dt, cells, n, owned_runs_, nRuns, spinScale,
                         rotation_, Field(), elastic::kAll, neoHookean_);
  if (extend_) extend(st);
}

void Elasticity::diagnose(State& st) {
  const Grid& g = st.grid;
  const SymTensorField t = solidStressField(st.fields);
  Field psi = psiField(st), S2 = st.fields.scalar("S2"), lg = st.fields.scalar("log10_S2");
  const elastic::ElasticDiag d = elastic::stressDiagnostics(g, t, psi, S2, lg, owned_, nOwned_, kappa_, mu_, neoHookean_);
  const double m[3] = {d.maxS2, d.tension, d.detDrift};
  double glob[4];
  MPI_Allreduce(&d.energy, &glob[0], 1, MPI_DOUBLE, MPI_SUM, g.comm);
  MPI_Allreduce(m, &glob[1], 3, MPI_DOUBLE, MPI_MAX, g.comm);
  long long n = nOwned_, ng = 0;
  MPI_Allreduce(&n, &ng, 1, MPI_LONG_LONG, MPI_SUM, g.comm);
  energy_ = glob[0];
  maxS2_ = glob[1];
  maxTension_ = glob[2];
  detDrift_ = std::max(detDrift_, glob[3]);
  cellsLast_ = ng;
  cellsTotal_ += double(ng);
  ++steps_;
  st.diag["elastic_energy"] = energy_;
  st.diag["max_S2"] = maxS2_;
  if (neoHookean_) st.diag["det_B_drift"] = glob[3]; // max |det B - 1| over the solid
  st.diag["stress_cells"] = double(ng);
}

} // namespace voigt
