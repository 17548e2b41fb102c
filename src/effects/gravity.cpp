// gravity: body force per unit mass, f/rho = g in Eq. (7), in balanced form.
//
// The predictor's acceleration is g - (1/rho_n) G p (navier_stokes/momentum.cpp). With
// projection.hydrostatic: balanced (the default) the stored pressure carries the discrete
// hydrostatic pressure of the current density, p_h (kernels/momentum.hpp, hydrostaticShift):
// before each predictor p += p_h(rho^{n+1}) - p_h(rho^n). G p_h = rho_n g exactly (to
// round-off) wherever rho varies only along g, so a resting stratification - a flat
// interface, with or without obstacles or a solid in equilibrium - is a fixed point of the
// step at any solver tolerance: the predictor gives u* = 0, the solve's right-hand side is
// round-off and the increment stays ~0. Elsewhere the solve finds only the departure from
// hydrostatics, so its relative tolerance applies to the dynamic pressure, not to rho g H.
// `none`: g as a plain body force, the hydrostatic part left to the solve (as before).
// The split is along the axis of g's largest component; it is off when that axis is
// periodic (a hydrostatic pressure is not periodic: the force drives a flow there).
#include <mpi.h>

#include <algorithm>
#include <cmath>

#include "core/field_names.hpp"
#include "core/halo.hpp"
#include "core/host_access.hpp"
#include "core/index_space.hpp"
#include "effects/effect.hpp"
#include "kernels/momentum.hpp"

namespace voigt {

namespace {
constexpr char kHydrostatic[] = "hydrostatic_pressure";

class Gravity : public Effect {
 public:
  std::string name() const override { return "gravity"; }
  std::vector<std::string> dependsOn() const override { return {"navier_stokes"}; }
  void configure(const Scene& s, const Published&) override {
    g_ = s.gravity;
    cfl_ = s.time.cfl;
    axis_ = 0;
    for (int d = 1; d < 3; ++d)
      if (std::abs(g_[d]) > std::abs(g_[axis_])) axis_ = d;
    balanced_ = s.projection.hydrostatic == "balanced" && g_[axis_] != 0 && !s.periodic(axis_);
  }
  void declareFields(FieldStore& f) const override {
    if (!balanced_) return;
    f.declare(kHydrostatic, Centring::Cell, 1, name());
    f.markOptionalOnRestart(kHydrostatic);
  }
  // A body starting from rest moves h in sqrt(2 h / |g|): limit dt to a CFL
  // fraction of that, so a scene at rest does not take one giant step.
  DtLimit dtLimit(const State& st) const override {
    const double gm = std::sqrt(g_[0] * g_[0] + g_[1] * g_[1] + g_[2] * g_[2]);
    if (gm == 0) return {};
    const double h = std::min({st.grid.h[0], st.grid.h[1], st.grid.h[2]});
    return {cfl_ * std::sqrt(2 * h / gm), "gravity"};
  }
  void registerTasks(Pipeline& p) override {
    const Vec3 g = g_;
    if (balanced_)
      p.add(Stage::Momentum, name(), "hydrostatic pressure of rho^{n+1} into p (balanced gravity)",
            [this](State& st) { shift(st); });
    p.add(Stage::Forces, name(), "uniform body force g", [g](State& st) {
      addBodyForce(st.evalRhs, g[0], g[1], g[2], nodeRange(st.grid));
    });
  }
  void summary(const State&, nlohmann::json& j) const override {
    j["gravity"] = {{"hydrostatic", balanced_ ? "balanced" : "none"}, {"axis", std::string(1, "xyz"[axis_])}};
  }
  void saveState(nlohmann::json& j) const override { j["hydrostatic_in_pressure"] = balanced_; }
  // A checkpoint from before the split: its pressure holds the hydrostatic part already,
  // so the first shift only fills p_h.
  void loadState(const nlohmann::json& j) override { resync_ = !j.value("hydrostatic_in_pressure", false); }

 private:
  void shift(State& st) {
    const Grid& gr = st.grid;
    const int a = axis_, b = a == 0 ? 1 : 0, c = a == 2 ? 1 : 2;
    Field ph = st.fields.scalar(kHydrostatic), p = st.fields.scalar(field::pressure);
    Field target = p;
    if (resync_) guard(target = Field("hydrostatic_resync", gr.ext[0], gr.ext[1], gr.ext[2]));
    if (top_.extent(0) != size_t(gr.ln[b]) || top_.extent(1) != size_t(gr.ln[c])) {
      top_ = Plane("hydrostatic_top", gr.ln[b], gr.ln[c]);
      last_ = Plane("hydrostatic_last", gr.ln[b], gr.ln[c]);
      guard(top_), guard(last_);
    }
    // The columns run from the top rank down, each rank after the one above it: the same
    // sums in the same order at any rank count (bit-identical results).
    const bool down = g_[a] < 0;
    const int above = down ? gr.nbrHi[a] : gr.nbrLo[a], below = down ? gr.nbrLo[a] : gr.nbrHi[a];
    const bool atTop = down ? gr.atHi(a) : gr.atLo(a);
    const int count = gr.ln[b] * gr.ln[c];
    if (!atTop) {
      auto topH = hostMirror(top_);
      MPI_Recv(topH.data(), count, MPI_DOUBLE, above, 71, gr.comm, MPI_STATUS_IGNORE);
      toDevice(top_, topH, "hydrostatic_columns");
    }
    hydrostaticShift(gr, a, g_[a], st.fields.scalar(field::density), ph, target, top_, atTop, last_);
    if (!(down ? gr.atLo(a) : gr.atHi(a))) {
      auto lastH = toHost(last_, "hydrostatic_columns");
      MPI_Send(lastH.data(), count, MPI_DOUBLE, below, 71, gr.comm);
    }
    resync_ = false;
    st.halo->exchange(p); // the predictor's G p reads the ghosts
  }

  Vec3 g_{0, 0, 0};
  double cfl_ = 0.5;
  int axis_ = 1;
  bool balanced_ = false, resync_ = false;
  Plane top_, last_;
};
} // namespace

std::unique_ptr<Effect> makeGravity() { return std::make_unique<Gravity>(); }

} // namespace voigt
