// reinit: Sussman re-initialisation of psi with the local volume constraint,
// paper Eq. (17)-(21), on the level set's narrow band (levelset/reinit.hpp).
// Scene section `reinit`: interval (steps), iterations, dtau (cells),
// volume_constraint, subcell_fix (Russo & Smereka; off by default, see
// kernels/reinit.hpp), far_bound, zone_curvature and zone_tolerance (settled smoothing-zone cells keep their
// advected values: kernels/reinit.hpp, settledCell), level_set (a name or a list: the level sets it
// runs on; default every one). kappa and band come from each level set's section.
#include <algorithm>
#include <memory>

#include "core/field_names.hpp"
#include "effects/effect.hpp"
#include "levelset/params.hpp"
#include "levelset/reinit.hpp"
#include "scene/reader.hpp"

namespace voigt {

namespace {
class Reinit : public Effect {
 public:
  std::string name() const override { return "reinit"; }
  std::vector<std::string> dependsOn() const override { return {"level_set"}; }
  void configure(const Scene& s, const Published& pub) override {
    const Section r = topSection(s, "reinit");
    ls_ = pub.select(r, true, true);
    interval_ = r.integer("interval", 1, 1, 1000000);
    p_.iterations = int(r.integer("iterations", 2, 1, 1000));
    p_.dtauCells = r.number("dtau", 0.5, {0, 1, true, false});
    p_.volumeConstraint = r.boolean("volume_constraint", true);
    p_.subcellFix = r.boolean("subcell_fix", false);
    // 1e-6: settles a zone that is a distance to round-off (a flat or planar interface at rest);
    // larger values settle more of a moving flow and cost CG iterations there (dam break 64^3:
    // 57.4 its a step at 0, 58.2 at 1e-6, 63.4 at 1e-3, 73.2 at 0.01; README, "Re-initialisation
    // and rest").
    p_.zoneTolerance = r.number("zone_tolerance", 1e-6, {0, 1, false, true});
    // zone_curvature: the tolerance also allows the central differences' error on a resolved
    // curved distance (kernels/reinit.hpp, settledCell), so a drop at rest is settled and its
    // capillary currents decay (tests/levelset/test_surface_tension.cpp). On by default with
    // surface tension only: in a shearing flow it costs shape (single vortex T = 2 at 128^2:
    // E 0.166 h against 0.149 h; README, "Re-initialisation and rest").
    // far_bound: |psi| outside the smoothing zone bounded by its neighbours' + h before each call
    // (kernels/reinit.hpp, boundFarField), so that no cell near the interface is left outside the band.
    p_.boundFarField = r.boolean("far_bound", true);
    const bool capillary = std::count(s.effects.begin(), s.effects.end(), "surface_tension") > 0;
    p_.zoneCurvature = r.boolean("zone_curvature", capillary);
    r.finish();
  }
  void declareFields(FieldStore& f) const override {
    for (const LevelSetInfo& l : ls_) f.declare(l.field, Centring::Cell, 1, name());
  }
  void setup(State& st) override {
    // One Reinitializer (its scratch) for every level set: each call sets its band; with
    // several level sets each runs on its box (State::activeBoxes).
    p_.kappa = ls_[0].geometry.kappa(st.grid);
    p_.band = ls_[0].geometry.band(st.grid);
    re_ = std::make_unique<Reinitializer>(st.grid, p_);
    // Time-series columns are fixed at the first row: declare ours now.
    st.diag["reinit_band_cells"] = 0.0;
    st.diag["reinit_grad_error"] = 0.0;
  }
  void registerTasks(Pipeline& p) override {
    // The step counter increments after the stages, so step + 1 steps have
    // been advected when this runs: re-initialise after every interval-th step.
    p.add(Stage::Corrections, name(), "Eikonal + local volume constraint, Eq. (17)-(21)", [this](State& st) {
      if ((st.step + 1) % interval_ != 0) return;
      ReinitStats s;
      for (size_t i = 0; i < ls_.size(); ++i) { // band cells summed, gradient error the largest
        re_->setBand(ls_[i].geometry.kappa(st.grid), ls_[i].geometry.band(st.grid));
        const ReinitStats si = re_->run(*st.halo, st.fields.scalar(ls_[i].field), st.activeBox(ls_[i].field));
        if (i == 0) {
          s = si;
          continue;
        }
        s.bandCells += si.bandCells;
        s.maxGradError = std::max(s.maxGradError, si.maxGradError);
      }
      ++calls_;
      bandTotal_ += double(s.bandCells);
      st.diag["reinit_band_cells"] = double(s.bandCells);
      st.diag["reinit_grad_error"] = s.maxGradError;
      st.counters["reinit_calls"] += 1;
      st.counters["reinit_band_cells_total"] += double(s.bandCells);
    });
  }
  void saveState(nlohmann::json& j) const override { j = {{"calls", calls_}, {"band_total", bandTotal_}}; }
  void loadState(const nlohmann::json& j) override {
    calls_ = j.at("calls").get<long long>();
    bandTotal_ = j.at("band_total").get<double>();
  }
  void summary(const State& st, nlohmann::json& j) const override {
    const double mean = calls_ ? bandTotal_ / double(calls_) : 0.0;
    j["reinit"] = {{"calls", calls_},
                   {"band_cells_mean", mean},
                   {"band_fraction_mean", mean / double(st.grid.cellsGlobal())},
                   {"interval", interval_},
                   {"iterations", p_.iterations},
                   {"dtau", p_.dtauCells},
                   {"volume_constraint", p_.volumeConstraint},
                   {"subcell_fix", p_.subcellFix},
                   {"zone_tolerance", p_.zoneTolerance},
                   {"zone_curvature", p_.zoneCurvature},
                   {"far_bound", p_.boundFarField}};
  }

 private:
  std::vector<LevelSetInfo> ls_;
  ReinitParams p_;
  long interval_ = 1;
  long long calls_ = 0;
  double bandTotal_ = 0;
  std::unique_ptr<Reinitializer> re_;
};
} // namespace

std::unique_ptr<Effect> makeReinit() { return std::make_unique<Reinit>(); }

} // namespace voigt
