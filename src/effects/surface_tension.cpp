// surface_tension: the continuum surface force (Brackbill et al. 1992) on the level set's
// interface, f = sigma kappa grad H(psi), in balanced form (Francois et al. 2006): on the
// pressure gradient's own node stencil and coefficient, with kappa evaluated at the
// interface and carried along the normals over the smoothing zone (kernels/curvature.hpp).
// A drop at rest with one curvature is then a fixed point once p = sigma kappa H + const:
// the predictor's coef (sigma kappa G H - G p) is zero to round-off.
// `form: csf` is the plain force for comparison: sigma kappa(psi) H'(psi) grad psi at the
// nodes from the cell curvature where it is, without the pressure's stencil.
// Scene section `surface_tension`: sigma (N/m, required), form (balanced | csf), curvature
// (level_set | height_function: kernels/height_function.hpp).
// Time step (Brackbill): dt <= sqrt(rho_mean h^3 / (2 pi sigma)), rho_mean the phases' mean.
#include <cmath>

#include "core/boundary.hpp"
#include "core/field_names.hpp"
#include "core/halo.hpp"
#include "effects/effect.hpp"
#include "kernels/curvature.hpp"
#include "kernels/height_function.hpp"
#include "scene/reader.hpp"

namespace voigt {

namespace {
constexpr char kCurvature[] = "curvature";

class SurfaceTension : public Effect {
 public:
  std::string name() const override { return "surface_tension"; }
  std::vector<std::string> dependsOn() const override { return {"navier_stokes", "level_set"}; }
  void configure(const Scene& s, const Published& pub) override {
    const Section sec = topSection(s, "surface_tension");
    sigma_ = sec.requireNumber("sigma", Range::nonNegative());
    balanced_ = sec.choice("form", "balanced", {"balanced", "csf"}) == "balanced";
    heights_ = sec.choice("curvature", "level_set", {"level_set", "height_function"}) == "height_function";
    const LevelSetInfo ls = pub.one(sec); // the interface that carries sigma (level_set: NAME)
    sec.finish();
    geo_ = ls.geometry;
    psiName_ = ls.field;
    rhoMean_ = 0.5 * (s.materials.at(ls.phase).density + s.fluidMaterial().density);
    // projection.variable_density: split lags part of the pressure gradient, which capillary
    // waves feel too: a resting drop at ratio 1000 grew above 0.39-0.58 of the capillary dt
    // (32^3; at ratio 100 no worse than the solve at the full dt), so the limit is scaled by
    // 6 sqrt(rho_min / rho_max), half the lower threshold (perf/README.md, "The one-density split").
    if (s.projection.variableDensity == "split") {
      const double a = s.materials.at(ls.phase).density, b = s.fluidMaterial().density;
      splitFactor_ = std::min(1.0, 6 * std::sqrt(std::min(a, b) / std::max(a, b)));
    }
  }
  void declareFields(FieldStore& f) const override {
    f.declare(psiName_, Centring::Cell, 1, name());
    f.declareDerived(kCurvature, Centring::Cell, 1, name());
    if (heights_) {
      for (const char* n : {"curvature_heights", "curvature_heights_ok"}) f.declareDerived(n, Centring::Cell, 1, name());
      f.declareDerived("curvature_crossings", Centring::Cell, 3, name());
    }
    if (!balanced_) return; // the plain CSF needs the cell curvature only
    for (const char* n : {"capillary_H", "curvature_cell", "curvature_known", "curvature_tmp", "curvature_tmp_known"})
      f.declareDerived(n, Centring::Cell, 1, name());
  }
  // Brackbill et al. (1992), Eq. (61): the capillary wave of the shortest length must not
  // travel more than a cell in a step.
  DtLimit dtLimit(const State& st) const override {
    if (sigma_ <= 0) return {};
    const double h = std::min({st.grid.h[0], st.grid.h[1], st.grid.h[2]});
    const double dt = std::sqrt(rhoMean_ * h * h * h / (2 * M_PI * sigma_));
    if (splitFactor_ < 1) return {splitFactor_ * dt, "capillary (split)"};
    return {dt, "capillary"};
  }
  void registerTasks(Pipeline& p) override {
    // psi^{n+1} is fixed over the predictor's two stages: kappa once, before them.
    p.add(Stage::Momentum, name(), "interface curvature of psi^{n+1}, extended over the zone",
          [this](State& st) { curvature(st); });
    p.add(Stage::Forces, name(), balanced_ ? "sigma kappa G H on the pressure's stencil (balanced CSF)"
                                           : "sigma kappa H'(psi) grad psi (plain CSF)",
          [this](State& st) { force(st); });
  }
  static double counter(const State& st, const char* k) {
    auto it = st.counters.find(k);
    return it == st.counters.end() ? 0.0 : it->second;
  }
  void summary(const State& st, nlohmann::json& j) const override {
    j["surface_tension"] = {{"sigma", sigma_},
                            {"form", balanced_ ? "balanced" : "csf"},
                            {"curvature", heights_ ? "height_function" : "level_set"}};
    if (heights_) j["surface_tension"]["height_function_fallbacks"] = counter(st, "height_function_fallbacks");
  }

 private:
  double reach(const Grid& g) const { return geo_.kappa(g) + std::min({g.h[0], g.h[1], g.h[2]}); }

  void curvature(State& st) {
    const Grid& g = st.grid;
    // psi's ghosts (halos and walls) are fresh: the level set's Advection stage ends refreshing them.
    const Field psi = st.fields.scalar(psiName_);
    Field ext = st.fields.scalar(kCurvature);
    if (!balanced_) { // the plain CSF uses the cell curvature where it is
      cellCurvature(st, psi, ext);
      return;
    }
    Field kc = st.fields.scalar("curvature_cell"), known = st.fields.scalar("curvature_known");
    Field tmp = st.fields.scalar("curvature_tmp"), tmpKnown = st.fields.scalar("curvature_tmp_known");
    cellCurvature(st, psi, kc);
    curvature::heavisideField(psi, st.fields.scalar("capillary_H"), geo_.kappa(g), cellRange(g, 2));
    curvature::interfaceCurvature(psi, kc, ext, known, cellRange(g));
    // Each sweep reaches one more layer: the zone plus one cell, on both sides.
    const double r = reach(g), hmin = std::min({g.h[0], g.h[1], g.h[2]});
    const int sweeps = int(std::ceil(r / hmin)) + 1;
    for (int s = 0; s < sweeps; ++s) {
      st.halo->exchange(std::vector<Field>{ext, known}, 1);
      fillCellGhostsEven(g, ext);
      fillCellGhostsEven(g, known);
      curvature::extendSweep(g, psi, ext, known, tmp, tmpKnown, r, cellRange(g));
      std::swap(ext, tmp);
      std::swap(known, tmpKnown);
    }
    if (sweeps % 2 == 1) Kokkos::deep_copy(st.fields.scalar(kCurvature), ext); // the named field holds it
    st.halo->exchange(st.fields.scalar(kCurvature), 1);
    fillCellGhostsEven(g, st.fields.scalar(kCurvature));
  }

  // kappa at the owned cells and one layer beyond: of psi, and with curvature: height_function
  // the heights' value at the interface cells (kernels/height_function.hpp).
  void cellCurvature(State& st, const Field& psi, const Field& kap) {
    const Grid& g = st.grid;
    curvature::cellCurvature(g, psi, kap, cellRange(g, 1));
    if (!heights_) return;
    Field hk = st.fields.scalar("curvature_heights"), ok = st.fields.scalar("curvature_heights_ok");
    const VecField rec = st.fields.vector("curvature_crossings");
    // Records beyond walls stay 0 (none): only owned cells are computed, the halo fills the rest.
    for (int d = 0; d < 3; ++d) Kokkos::deep_copy(rec.c[d], 0.0);
    curvature::columnCrossings(psi, rec, cellRange(g));
    st.halo->exchange(rec); // two layers: a column reads records 2 cells along its axis
    Kokkos::deep_copy(hk, kap);
    const double local = curvature::heightCurvature(g, psi, rec, hk, ok, cellRange(g));
    double global = 0;
    MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, g.comm);
    st.counters["height_function_fallbacks"] += global;
    st.halo->exchange(std::vector<Field>{hk, ok}, 1);
    fillCellGhostsEven(g, hk);
    fillCellGhostsEven(g, ok);
    curvature::fallbackCurvature(hk, ok, kap, cellRange(g));
    st.halo->exchange(kap, 1);
    fillCellGhostsEven(g, kap);
  }

  void force(State& st) {
    const Grid& g = st.grid;
    const Field psi = st.fields.scalar(psiName_), kap = st.fields.scalar(kCurvature);
    const VecField coef = st.fields.vector("proj_coef");
    if (balanced_)
      curvature::addCapillaryForce(g, psi, st.fields.scalar("capillary_H"), kap, coef, sigma_, reach(g), st.evalRhs,
                                   nodeRange(g));
    else
      curvature::addPlainCsf(g, psi, kap, coef, sigma_, geo_.kappa(g), st.evalRhs, nodeRange(g));
  }

  double sigma_ = 0, rhoMean_ = 1;
  double splitFactor_ = 1; // projection.variable_density: split (configure)
  bool balanced_ = true;
  bool heights_ = false; // curvature: height_function
  LevelSetGeometry geo_;
  std::string psiName_ = field::psi;
};
} // namespace

std::unique_ptr<Effect> makeSurfaceTension() { return std::make_unique<SurfaceTension>(); }

} // namespace voigt
