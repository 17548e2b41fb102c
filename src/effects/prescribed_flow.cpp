// prescribed_flow: a kinematic velocity field given in closed form, for
// verification of transport (level set, stress) without the momentum
// equation. It replaces navier_stokes, so the two cannot be combined.
//   rotation:      v = omega x (x - center)           (rigid body)
//   single_vortex: v = (d psi_s/dy, -d psi_s/dx) cos(pi t / T) with
//                  psi_s = sin^2(pi x') sin^2(pi y') / pi in the x-y plane
//                  mapped to the unit square (LeVeque 1996; Rider & Kothe 1998);
//                  the flow reverses at T/2 and the exact shape returns at T
//   uniform:       v = velocity
// The velocity is set at t + dt/2 before advection, so frozen-velocity RK2
// stays second order in time.
#include <cmath>

#include "core/field_names.hpp"
#include "core/index_space.hpp"
#include "effects/effect.hpp"
#include "kernels/prescribed_flow.hpp"
#include "scene/reader.hpp"

namespace voigt {

namespace {

class PrescribedFlow : public Effect {
 public:
  std::string name() const override { return "prescribed_flow"; }
  std::vector<std::string> setupAfter() const override { return {}; } // first: the velocity others read
  void configure(const Scene& s, const Published&) override {
    const Section sec = topSection(s, "prescribed_flow");
    for (auto& e : s.effects)
      if (e == "navier_stokes")
        sec.fail("type", "prescribed_flow sets the velocity itself: remove navier_stokes from effects");
    if (!sec.has("type")) sec.fail("type", "is required (rotation, single_vortex or uniform)");
    const std::string t = sec.choice("type", "", {"rotation", "single_vortex", "uniform"});
    p_.type = t == "rotation" ? 0 : t == "single_vortex" ? 1 : 2;
    auto need = [&](const char* k) {
      if (!sec.has(k)) sec.fail(k, std::string("is required for type ") + t);
      return sec.vec3(k, {});
    };
    if (p_.type == 0) {
      auto c = need("center"), w = need("omega");
      for (int d = 0; d < 3; ++d) p_.c[d] = c[d], p_.w[d] = w[d];
    } else if (p_.type == 1) {
      p_.period = sec.requireNumber("period", Range::positive());
      for (int d = 0; d < 2; ++d) p_.lo[d] = s.lo[d], p_.len[d] = s.hi[d] - s.lo[d];
    } else {
      auto v = need("velocity");
      for (int d = 0; d < 3; ++d) p_.v[d] = v[d];
    }
    cfl_ = s.time.cfl;
    sec.finish();
  }
  void declareFields(FieldStore& f) const override { f.declare(field::velocity, Centring::Node, 3, name()); }
  void setup(State& st) override { fill(st, st.t); }
  void registerTasks(Pipeline& pl) override {
    pl.add(Stage::Properties, name(), "velocity at t + dt/2 from the closed form",
           [this](State& st) { fill(st, st.t + 0.5 * st.dt); });
  }
  // Advective CFL with the flow's largest speed over all times (|cos| <= 1).
  DtLimit dtLimit(const State& st) const override {
    const Grid& g = st.grid;
    double inv = prescribedFlowRate(g, p_);
    MPI_Allreduce(MPI_IN_PLACE, &inv, 1, MPI_DOUBLE, MPI_MAX, g.comm);
    if (inv == 0) return {};
    return {cfl_ / inv, "advective CFL (prescribed flow)"};
  }

 private:
  void fill(State& st, double t) const {
    fillPrescribedFlow(st.grid, p_, t, st.fields.vector(field::velocity));
    st.velocityHalosCurrent = false;
  }
  FlowParams p_;
  double cfl_ = 0.5;
};

} // namespace

std::unique_ptr<Effect> makePrescribedFlow() { return std::make_unique<PrescribedFlow>(); }

} // namespace voigt
