#pragma once
// The elasticity effect: the paper's hypoelastic solid, Eq. (9)-(16), with
// NOTES.md errata 1-3, or (scene key `model: neo_hookean`) a neo-Hookean solid, tau_S =
// mu_S (B - I) with the upper-convected rate (kernels/elastic_stretch.hpp). The solid is the
// level set's phase (psi > 0); its deviatoric stress tau_S lives at cell centres (six components) and is
//   advected with the material, erratum 3 (Advection stage, advect.cpp): the
//     level set's own scheme, kernels/levelset.hpp addCellAdvection (KT/MUSCL,
//     scene limiter), SSP-RK2, velocity frozen at u^n;
//   added to the momentum stress as H(psi) tau_S, Eq. (9)/(14) (Stress stage,
//     once per Runge-Kutta substage, update.cpp);
//   updated with the Jaumann rate by Benson's half-step scheme, Eq. (13)/(16)
//     with errata 1-2 (Corrections stage, after the projection, so with u^{n+1};
//     kernels/elastic.hpp); scene key `rotation`: each half rotation by the
//     orthogonal Cayley transform of the half-step spin (default, `cayley`:
//     keeps |tau| under rotation) or explicitly as erratum 2 prints it
//     (`explicit`: the amplitude grows by 1 + (w dt)^2 per step).
// Fluid side of the band (scene key `fluid_side`); measurements in
// cases/falling_block/NOTEBOOK.md, "Stress on the fluid side" and "A smooth surface":
//   integrate (the paper's): Eq. (13) on the whole band, so the fluid side stores mu_S times
//     the integrated *fluid* shear; where air is squeezed past a solid, transport and
//     re-initialisation carry it into H > 0: an energy source (falling block 48^3, energy
//     ratio 1.47).
//   extend (default since 2026-12-03): Eq. (13) only where psi > 0, the cells with psi <= 0
//     take the solid's stress extended along the normal (kernels/extension.hpp). No source, but
//     the fluid half of the blend zone (0 < H < 1/2) has no stiffness of its own: cell-scale
//     wrinkles grow on a body's surface from an impact on (falling block: rms curvature +30 %).
//   one_cell: Eq. (13) on the solid and on the fluid cells next to the interface (psi > -h),
//     extension beyond: the zone keeps its stiffness where H matters (H(-h) = 0.09 at
//     kappa = 2h). Smooth (+4.5 %), no source on the falling block (ratio <= 1.00, free fall
//     elastic / kinetic 2e-4), dissipative (a free oscillation keeps 0.80 of its energy after
//     0.1 s at 48^3, extend 0.90). Not the default: where bodies pack (the porous bed's throats,
//     two cells wide) those cells integrate the gas's shear, and the bed holds 40x the elastic
//     energy it holds with extend (half grid, t = 0.34 s).
//   blend: as one_cell to psi > -kappa (Eq. 15 exact on the whole zone): smooth, no source on
//     the block, but the zone's outer half stores the air's shear (free fall 2.4e-3).
// Stress kernels run on a packed list of cells with psi > -(kappa + band h):
// cells far from any solid cost nothing; tau_S is zero outside the band.
// One file per stage: elasticity.cpp (scene, fields, set-up, dt, summary),
// advect.cpp (band list + transport), update.cpp (stress, Jaumann update, diagnostics).
#include <algorithm>
#include <cmath>
#include <string>

#include "core/field_names.hpp"
#include "effects/effect.hpp"
#include "kernels/advection.hpp"
#include "kernels/elastic.hpp"
#include "kernels/stress.hpp"

namespace voigt {

// The solid stress tau_S (xx, yy, zz, xy, yz, zx). Stored as two 3-component
// cell fields, so that `output.fields` can name them: `solid_stress` holds
// (xx, yy, zz) and `solid_stress_shear` holds (xy, yz, zx).
SymTensorField solidStressField(const FieldStore& f);
// The same pairing for any `<base>` / `<base>_shear` pair (the RK buffer solid_stress_old).
SymTensorField symTensorField(const FieldStore& f, const std::string& base);

class Elasticity : public Effect {
 public:
  std::string name() const override { return "elasticity"; }
  std::vector<std::string> dependsOn() const override { return {"level_set"}; }
  // psi and the face masks exist; reinit (a default effect) comes after.
  std::vector<std::string> setupAfter() const override {
    return {"navier_stokes", "prescribed_flow", "level_set", "obstacles"};
  }
  void configure(const Scene& s, const Published& pub) override;
  void declareFields(FieldStore& f) const override;
  void setup(State& st) override;
  void registerTasks(Pipeline& p) override;
  DtLimit dtLimit(const State& st) const override;
  void summary(const State& st, nlohmann::json& j) const override;
  // Checkpoint/restart: counters in the JSON; the band list is rebuilt from
  // the restored stress (restored()), so the continued run is bit-identical.
  void saveState(nlohmann::json& j) const override;
  void loadState(const nlohmann::json& j) override;
  void restored(State& st) override;

  double shearModulus() const { return mu_; }
  double solidDensity() const { return rho_; }
  double kelvinVoigtViscosity() const { return etaKV_; }
  elastic::Rotation rotation() const { return rotation_; }
  double waveSpeed() const { return std::sqrt(mu_ / rho_); }
  // The neo-Hookean solid stiffens in tension: a shear wave along n in a stretched state has
  // rho c^2 = mu_S (n.B n) = mu_S + n.tau_S n <= mu_S + the largest eigenvalue of tau_S.
  double currentWaveSpeed() const {
    return neoHookean_ ? std::sqrt((mu_ + std::max(0.0, maxTension_)) / rho_) : waveSpeed();
  }

  // Stages (public so tests can drive them one at a time).
  void advect(State& st);     // Advection: band list + transport of tau_S
  void addStress(State& st);  // Stress: tau += H(psi) tau_S
  void update(State& st, double spinScale = 0.5); // Corrections: Benson/Jaumann
  void diagnose(State& st);   // Diagnostics: S2, energy, counts
  int activeCells() const { return nOwned_; } // this rank's cells in the band

 private:
  void buildLists(State& st);
  void refreshStress(State& st) const; // every ghost; sets stressHalosCurrent_
  // Rank ghosts, and wall ghosts only within bandReads_ (every cell the band's readers touch).
  void refreshBand(State& st) const;
  // Halo exchange and wall ghosts; with `reads`, wall ghosts only where those cells lie.
  void refresh(State& st, const SymTensorField& t, const Range3* reads = nullptr, int depth = 0) const;
  void extend(State& st);

  const Scene* scene_ = nullptr;
  // The solid's psi: its level set's field, or with several the union refreshed by solidPsi()
  // when the level sets have moved (setup, Advection, Corrections, restart) and read after.
  Field solidPsi(State& st) const;
  Field psiField(const State& st) const { return st.fields.scalar(psiName_); }
  std::string phase_;
  std::vector<std::string> psiFields_{field::psi};
  std::string psiName_ = field::psi;
  LevelSetGeometry geo_; // level_set's smoothing and band (Published)
  double mu_ = 0, rho_ = 1, etaKV_ = 0;
  elastic::Rotation rotation_ = elastic::Rotation::Cayley;
  bool neoHookean_ = false; // elasticity.model: neo_hookean
  double tau0_[6] = {0, 0, 0, 0, 0, 0};
  double bandCells_ = 3, kappa_ = 0, threshold_ = 0, cfl_ = 0.5, hmin_ = 1;
  Limiter limiter_ = Limiter::MinMod;
  FluxScratch flux_; // face fluxes of the transport (kernels/advection_faces.hpp)
  std::string side_ = "extend"; // fluid_side (header)
  bool extend_ = true;             // extend or blend: cells with psi <= below_ are extended
  double below_ = 0;               // extend: 0; blend: -kappa
  int sweeps_ = 4;     // extension sweeps per step (even: the result lands in tau_S)
  // True while tau_S's ghosts (rank and wall) match the owned cells: set by a whole refresh,
  // cleared where tau_S is written (the transport's stages, the Jaumann update). The same
  // on every rank (set and cleared outside any band test), so the collective skip agrees.
  mutable bool stressHalosCurrent_ = false;

  elastic::IntList owned_, prev_, grown_;
  elastic::IntList side_cells_; // extend: the listed cells the extension sweeps write
  elastic::IntList side_runs_;  // ... and where their runs of consecutive cells start
  elastic::IntList solid_cells_; // extend: the listed cells the Jaumann update writes (psi > below_)
  elastic::IntList owned_runs_;  // where the updated cells' runs of consecutive cells start (listRuns)
  int nOwned_ = 0, nPrev_ = 0, nGrown_ = 0;
  Range3 ownedBox_{{0, 0, 0}, {0, 0, 0}}; // listBox(owned_), set with the list (buildLists)
  // ownedBox_ grown by the transport's 2 layers, joined with the grown list's box (the
  // Stress stage reads tau_S there, ghosts included); empty without band cells.
  Range3 bandReads_{{0, 0, 0}, {0, 0, 0}};

  // Diagnostics and counters for summary.json.
  // elastic_diagnostics.hpp; detDrift_: the run's largest |det B - 1| (neo-Hookean)
  double energy_ = 0, maxS2_ = 0, maxTension_ = 0, detDrift_ = 0;
  long long cellsLast_ = 0;
  double cellsTotal_ = 0; // sum over steps of global stress cells
  long steps_ = 0;
};

} // namespace voigt
