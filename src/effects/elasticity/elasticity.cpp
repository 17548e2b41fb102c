// elasticity: scene section, fields, initial stress, time-step limit, summary.
// Scene:
//   materials.<solid>: shear_modulus, or youngs_modulus + poisson_ratio
//     (mu_S = E / (2 (1 + nu))); `viscosity` on it is the optional Kelvin-Voigt
//     solid viscosity (NOTES.md erratum 7; default 0), which enters through the
//     level set's mu blend H mu_solid + (1 - H) mu_L.
//   elasticity: {initial_stress: {xx, yy, zz, xy, yz, zx} (Pa, where psi > 0),
//                band: cells beyond H > 0 where the stress kernels run (default 3),
//                rotation: cayley | explicit (default cayley): how Eq. (16)'s half
//                  rotations are applied (kernels/elastic.hpp header),
//                model: hypoelastic | neo_hookean (default hypoelastic, the paper's),
//                fluid_side: integrate | extend | one_cell | blend (default extend): the
//                  stress of the band's fluid side (elasticity.hpp header)}
#include "effects/elasticity/elasticity.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>

#include "core/boundary.hpp"
#include "core/field_names.hpp"
#include "kernels/contact.hpp"
#include "levelset/params.hpp"
#include "scene/reader.hpp"

namespace voigt {

std::unique_ptr<Effect> makeElasticity() { return std::make_unique<Elasticity>(); }

SymTensorField solidStressField(const FieldStore& f) { return symTensorField(f, "solid_stress"); }

SymTensorField symTensorField(const FieldStore& f, const std::string& base) {
  VecField n = f.vector(base), s = f.vector(base + "_shear");
  SymTensorField t;
  VOIGT_UNROLL
  for (int c = 0; c < 3; ++c) {
    t.c[c] = n.c[c];
    t.c[3 + c] = s.c[c];
  }
  return t;
}

void Elasticity::configure(const Scene& s, const Published& pub) {
  scene_ = &s;
  const Section sec = topSection(s, "elasticity");
  // level_set: the solid's level set, or a list of them (bodies of one material that touch
  // without merging: the stress lives on their union, max psi; kernels/contact.hpp).
  const std::vector<LevelSetInfo> ls = pub.select(sec, true);
  phase_ = ls[0].phase; // validated by level_set
  geo_ = ls[0].geometry;
  psiFields_.clear();
  for (const LevelSetInfo& l : ls) {
    if (l.phase != phase_) sec.fail("level_set", "names level sets of different phases (" + phase_ + ", " + l.phase + "): one elastic material");
    if (l.geometry.kappaCells != geo_.kappaCells) sec.fail("level_set", "names level sets of different smoothing");
    psiFields_.push_back(l.field);
  }
  psiName_ = ls.size() == 1 ? ls[0].field : "psi_solid";
  if (!s.materials.count(phase_)) sec.fail("band", "needs level_set.phase to name the solid material");
  const Material& m = s.materials.at(phase_);
  if (!(m.shearModulus > 0)) {
    const Section mats = topSection(s, "materials");
    mats.section(phase_).fail("shear_modulus", "is required for the elastic solid '" + phase_ +
                                                   "' (level_set.phase): give shear_modulus, or "
                                                   "youngs_modulus and poisson_ratio");
  }
  mu_ = m.shearModulus;
  rho_ = m.density;
  etaKV_ = m.viscosity;
  bandCells_ = sec.number("band", 3, Range::nonNegative());
  rotation_ = sec.choice("rotation", "cayley", {"cayley", "explicit"}) == "explicit" ? elastic::Rotation::Explicit
                                                                                      : elastic::Rotation::Cayley;
  // model: the paper's hypoelastic solid (Jaumann rate, Eq. 13) or neo-Hookean, tau = mu_S (B - I)
  // (kernels/elastic.hpp, bensonUpdate; issue 53).
  neoHookean_ = sec.choice("model", "hypoelastic", {"hypoelastic", "neo_hookean"}) == "neo_hookean";
  side_ = sec.choice("fluid_side", "extend", {"integrate", "extend", "one_cell", "blend"});
  extend_ = side_ != "integrate";
  const Section is = sec.section("initial_stress");
  const char* keys[6] = {"xx", "yy", "zz", "xy", "yz", "zx"};
  VOIGT_UNROLL
  for (int c = 0; c < 6; ++c) tau0_[c] = is.number(keys[c], 0);
  is.finish();
  sec.finish();
  cfl_ = s.time.cfl;
  limiter_ = limiterNamed(s.advection.limiter);
}

void Elasticity::declareFields(FieldStore& f) const {
  const std::string me = name();
  for (const std::string& n : psiFields_) f.declare(n, Centring::Cell, 1, me);
  if (psiFields_.size() > 1) f.declareDerived(psiName_, Centring::Cell, 1, me); // their union
  f.declare(field::velocity, Centring::Node, 3, me);
  for (const char* n : {"solid_stress", "solid_stress_shear"}) f.declare(n, Centring::Cell, 3, me);
  // Runge-Kutta stage copies and diagnostics: derived (FieldStore::Decl::derived).
  for (const char* n : {"solid_stress_old", "solid_stress_old_shear"}) f.declareDerived(n, Centring::Cell, 3, me);
  f.declareDerived("S2", Centring::Cell, 1, me);
  f.declareDerived("log10_S2", Centring::Cell, 1, me);
}

Field Elasticity::solidPsi(State& st) const {
  Field psi = st.fields.scalar(psiName_);
  if (psiFields_.size() == 1) return psi;
  const Range3 all = cellRange(st.grid, st.grid.ng); // the level sets' ghosts are fresh
  Kokkos::deep_copy(psi, st.fields.scalar(psiFields_[0]));
  for (size_t i = 1; i < psiFields_.size(); ++i) // outside its box a body's psi is far below the others'
    maxInto(psi, st.fields.scalar(psiFields_[i]), within(st.activeBox(psiFields_[i]), st.grid.ng, all));
  return psi;
}

void Elasticity::refreshStress(State& st) const {
  refresh(st, solidStressField(st.fields));
  stressHalosCurrent_ = true;
}

void Elasticity::refreshBand(State& st) const { refresh(st, solidStressField(st.fields), &bandReads_); }

void Elasticity::refresh(State& st, const SymTensorField& t, const Range3* reads, int depth) const {
  st.halo->exchange(std::vector<Field>(t.c, t.c + 6), depth);
  VOIGT_UNROLL
  for (int c = 0; c < 6; ++c) {
    if (reads) fillCellGhostsEven(st.grid, t.c[c], *reads);
    else fillCellGhostsEven(st.grid, t.c[c]);
  }
}

void Elasticity::setup(State& st) {
  const Grid& g = st.grid;
  const LevelSetGeometry& geo = geo_;
  hmin_ = LevelSetGeometry::hMin(g);
  kappa_ = geo.kappa(g);
  threshold_ = -(kappa_ + bandCells_ * hmin_);
  // Where Eq. (13) stops and the extension starts (elasticity.hpp): blend -kappa, one_cell -h
  // (the fluid cells next to the interface keep their own stiffness), extend 0.
  below_ = side_ == "blend" ? -kappa_ : side_ == "one_cell" ? -hmin_ : 0.0;
  // Enough sweeps to cross the blend zone's fluid side (kappa) and one cell
  // more each step; the outer band continues the iteration over steps.
  sweeps_ = 2 * ((int(std::ceil(kappa_ / hmin_ - 1e-9)) + 2 + 1) / 2);
  owned_ = elastic::IntList("elastic_owned", size_t(g.cellsOwned()));
  owned_runs_ = elastic::IntList("elastic_owned_runs", size_t(g.cellsOwned()));
  prev_ = elastic::IntList("elastic_prev", size_t(g.cellsOwned()));
  if (extend_) side_cells_ = elastic::IntList("elastic_fluid_side", size_t(g.cellsOwned()));
  if (extend_) side_runs_ = elastic::IntList("elastic_fluid_side_runs", size_t(g.cellsOwned()));
  if (extend_) solid_cells_ = elastic::IntList("elastic_solid_side", size_t(g.cellsOwned()));
  grown_ = elastic::IntList("elastic_grown", size_t(cellRange(g, 1).size()));
  nOwned_ = nPrev_ = nGrown_ = 0;

  // Initial stress where psi > 0 (psi is set up: level_set runs first).
  const SymTensorField t = solidStressField(st.fields);
  Field psi = solidPsi(st);
  elastic::initialStress(g, psi, t, tau0_);
  const double floorLog = std::log10(1e-6 * mu_) * 2; // see diagnose(): log10 of (1e-6 mu_S)^2
  Kokkos::deep_copy(st.fields.scalar("S2"), 0.0);
  Kokkos::deep_copy(st.fields.scalar("log10_S2"), floorLog);
  buildLists(st);
  refreshStress(st);
  if (extend_) extend(st);
  // Time-series columns are fixed by the first row: declare ours now.
  diagnose(st);
  steps_ = 0;
  cellsTotal_ = 0;
}

void Elasticity::registerTasks(Pipeline& p) {
  p.add(Stage::Advection, name(), "tau_S: band list, SSP-RK2 + MUSCL/KT transport (erratum 3)",
        [this](State& st) { advect(st); });
  p.add(Stage::Stress, name(), "tau += H(psi) tau_S, Eq. (9)/(14)", [this](State& st) { addStress(st); });
  // After the interface is final for the step (re-initialised, volume-corrected):
  // the extension to psi <= below_ (fluid_side extend/one_cell/blend) uses the psi that the
  // next step's blend will see.
  const std::string model = neoHookean_ ? "neo-Hookean solid, tau_S = mu_S (B - I): upper-convected rate "
                                          "(Jaumann + S tau + tau S)"
                                        : "hypoelastic solid (the paper's): Jaumann rate";
  p.add(Stage::Corrections, name(), model + ", Benson half-step with u^{n+1}, Eq. (13)/(16); fluid side: " + side_,
        [this](State& st) { update(st); }, {"reinit", "level_set"});
  p.add(Stage::Diagnostics, name(), "S2, elastic energy, stress cells", [this](State& st) { diagnose(st); });
}

// Explicit elastic stress: shear-wave speed c = sqrt(mu_S / rho_S), dt <= cfl h_min / c (NUMERICS.md);
// the neo-Hookean solid's from its current stiffness, the last step's largest tension
// (currentWaveSpeed, elasticity.hpp).
DtLimit Elasticity::dtLimit(const State&) const { return {cfl_ * hmin_ / currentWaveSpeed(), "elastic wave"}; }

void Elasticity::saveState(nlohmann::json& j) const {
  j = {{"steps", steps_}, {"cells_total", cellsTotal_}, {"cells_last", cellsLast_}, {"energy", energy_},
       {"max_S2", maxS2_}, {"max_tension", maxTension_}, {"det_B_drift_max", detDrift_}};
}

void Elasticity::loadState(const nlohmann::json& j) {
  steps_ = j.at("steps").get<long>();
  cellsTotal_ = j.at("cells_total").get<double>();
  cellsLast_ = j.at("cells_last").get<long long>();
  energy_ = j.at("energy").get<double>();
  maxS2_ = j.at("max_S2").get<double>();
  maxTension_ = j.value("max_tension", 0.0); // the neo-Hookean dt (checkpoints before 2026-12-07: 0)
  detDrift_ = j.value("det_B_drift_max", 0.0);
}

// The next Advection stage rebuilds the band from psi and zeroes tau_S in the
// cells of the previous list that left it. That list is not in the checkpoint;
// the cells holding non-zero stress are exactly those of it that matter (the
// others hold zeros, and their S2 and log10_S2 hold the reset values), so it is
// rebuilt from the stress. The grown list is rebuilt from psi before use.
void Elasticity::restored(State& st) {
  nOwned_ = elastic::buildNonzeroList(st.grid, solidStressField(st.fields), owned_);
  ownedBox_ = elastic::listBox(st.grid, owned_, nOwned_);
  nGrown_ = elastic::buildActiveList(st.grid, solidPsi(st), threshold_, cellRange(st.grid, 1), grown_);
  refreshStress(st);
}

void Elasticity::summary(const State& st, nlohmann::json& j) const {
  const double mean = steps_ > 0 ? cellsTotal_ / double(steps_) : double(cellsLast_);
  j["elasticity"] = {{"solid", phase_},
                     {"shear_modulus", mu_},
                     {"solid_density", rho_},
                     {"wave_speed", waveSpeed()},
                     {"kelvin_voigt_viscosity", etaKV_},
                     {"band_cells", bandCells_},
                     {"rotation", rotation_ == elastic::Rotation::Explicit ? "explicit" : "cayley"},
                     {"model", neoHookean_ ? "neo_hookean" : "hypoelastic"},
                     {"fluid_side", side_},
                     {"steps", steps_},
                     {"stress_cells_mean", mean},
                     {"stress_cell_steps", cellsTotal_},
                     {"band_fraction_mean", mean / double(st.grid.cellsGlobal())},
                     {"elastic_energy", energy_},
                     {"max_S2", maxS2_}, {"max_tension", maxTension_}, {"det_B_drift_max", detDrift_}};
}

} // namespace voigt
