// Advection stage of elasticity: the band list, then transport of tau_S with
// the material (NOTES.md erratum 3: Eq. (12)'s partial derivative becomes a
// material one in the Eulerian frame). Each component is advected by exactly
// the level set's scheme (kernels/levelset.hpp addCellAdvection: Kurganov-
// Tadmor central flux with MUSCL and the scene's limiter, in the form
// dq/dt = -[div(v q) - q div_h v]), SSP-RK2 with the velocity frozen at u^n:
//   q1 = q^n + dt R(q^n);  q^{n+1} = (q^n + q1 + dt R(q1)) / 2
// over the bounding box of the band's cells on this rank. Cells outside the
// band (psi <= -(kappa + band h)) hold tau_S = 0.
#include <algorithm>

#include "core/boundary.hpp"
#include "core/field_names.hpp"
#include "effects/elasticity/elasticity.hpp"
#include "kernels/advection_faces.hpp"
#include "kernels/extension.hpp"
#include "kernels/levelset.hpp"

namespace voigt {

void Elasticity::buildLists(State& st) {
  const Grid& g = st.grid;
  Field psi = solidPsi(st); // the level sets have moved (Advection stage, setup)
  std::swap(owned_, prev_);
  nPrev_ = nOwned_;
  nOwned_ = elastic::buildActiveList(g, psi, threshold_, cellRange(g), owned_);
  ownedBox_ = elastic::listBox(g, owned_, nOwned_);
  // Owned cells and one ghost layer: the stress divergence at the owned nodes
  // reads the cells around them (navier_stokes fills tau on cellRange(g, 1)).
  nGrown_ = elastic::buildActiveList(g, psi, threshold_, cellRange(g, 1), grown_);
  Range3 r{{0, 0, 0}, {0, 0, 0}};
  bool have = false;
  auto join = [&](const Range3& b) {
    for (int d = 0; d < 3; ++d) {
      r.b[d] = have ? std::min(r.b[d], b.b[d]) : b.b[d];
      r.e[d] = have ? std::max(r.e[d], b.e[d]) : b.e[d];
    }
    have = true;
  };
  if (nOwned_ > 0) join(grown(ownedBox_, 2));
  if (nGrown_ > 0) join(elastic::listBox(g, grown_, nGrown_));
  bandReads_ = r;
}

void Elasticity::advect(State& st) {
  const Grid& g = st.grid;
  buildLists(st); // psi is already at t^{n+1} (level_set advects first)
  const SymTensorField t = solidStressField(st.fields);
  VecField u = st.fields.vector(field::velocity);
  Field psi = psiField(st);
  VecField on = st.fields.vector("solid_stress_old"), os = st.fields.vector("solid_stress_old_shear");
  const Field o[6] = {on.c[0], on.c[1], on.c[2], os.c[0], os.c[1], os.c[2]};
  const Range3 box = ownedBox_;
  const bool any = nOwned_ > 0;
  const double dt = st.dt;
  exchangeVelocity(st); // face speeds need the nodes on the owned cells' high faces
  if (any) cellFaceSpeeds(g, u, box, flux_); // u is frozen: once for 6 components x 2 stages
  for (int stage = 0; stage < 2; ++stage) {
    // Collective: every rank, band or not. Stage 0 skips it after the last step's
    // extension (its whole refresh), when nothing has written tau_S since. Wall
    // ghosts only where the band is read: whole fills of six components were half
    // of all wall-ghost fills on the falling block (perf/README.md, ninth part).
    if (stage > 0 || !stressHalosCurrent_) refreshBand(st);
    stressHalosCurrent_ = false; // the stage writes tau_S
    if (!any) continue;
    // Face fluxes once each, RK update fused (kernels/advection_faces.hpp).
    VOIGT_UNROLL
    for (int c = 0; c < 6; ++c)
      advanceCellAdvection(g, t.c[c], o[c], box, limiter_, dt, stage == 0 ? 1.0 : 0.5, stage == 0, flux_);
  }
  // tau_S = 0 outside the band: in the box, and where the band was last step.
  elastic::zeroOutsideBand(g, psi, threshold_, t, box, any, prev_, nPrev_, st.fields.scalar("S2"),
                           st.fields.scalar("log10_S2"), 2 * std::log10(1e-6 * mu_));
  refreshBand(st); // the Stress stage reads one ghost layer (bandReads_)
}

// tau_S where psi <= below_ (extend: 0, one_cell: -h, blend: -kappa) = the stress above it,
// extended along the normal (kernels/extension.hpp), after the Jaumann update, so that the next
// transport carries a field that is smooth across psi = 0 (a uniform solid
// stress stays uniform). Jacobi sweeps between tau_S and the RK buffer (free
// outside the transport), ghosts refreshed before each.
void Elasticity::extend(State& st) {
  const SymTensorField t = solidStressField(st.fields), b = symTensorField(st.fields, "solid_stress_old");
  Field psi = psiField(st);
  // Only the fluid-side cells change; both buffers hold the others' values.
  const int nSide = extension::fluidSide(psi, st.grid, owned_, nOwned_, below_, side_cells_);
  const int nRuns = listRuns(side_cells_, nSide, side_runs_);
  extension::copySolidSide(st.grid, psi, t, b, owned_, nOwned_, below_);
  const Range3 reads = grown(ownedBox_, 1); // the sweeps read the band box and 1 layer
  for (int s = 0; s < sweeps_; ++s) {
    const SymTensorField& from = s % 2 == 0 ? t : b;
    const SymTensorField& to = s % 2 == 0 ? b : t;
    refresh(st, from, &reads, 1); // collective; the sweep reads one layer (27 neighbours)
    extension::sweep(st.grid, psi, from, to, side_cells_, nSide, side_runs_, nRuns, below_);
  }
  refresh(st, t); // sweeps_ is even: the result is in tau_S
  stressHalosCurrent_ = true;
}

} // namespace voigt
