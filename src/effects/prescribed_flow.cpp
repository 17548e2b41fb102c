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

#include "core/index_space.hpp"
#include "effects/effect.hpp"
#include "kernels/reductions.hpp"
#include "scene/reader.hpp"

namespace voigt {

namespace {

struct FlowParams {
  int type = 0; // 0 rotation, 1 single_vortex, 2 uniform
  double c[3] = {0, 0, 0}, w[3] = {0, 0, 0}, v[3] = {0, 0, 0};
  double period = 1, lo[2] = {0, 0}, len[2] = {1, 1};
};

KOKKOS_INLINE_FUNCTION void flowAt(const FlowParams& p, const double x[3], double t, double out[3]) {
  if (p.type == 0) {
    const double r[3] = {x[0] - p.c[0], x[1] - p.c[1], x[2] - p.c[2]};
    out[0] = p.w[1] * r[2] - p.w[2] * r[1];
    out[1] = p.w[2] * r[0] - p.w[0] * r[2];
    out[2] = p.w[0] * r[1] - p.w[1] * r[0];
  } else if (p.type == 1) {
    const double xs = (x[0] - p.lo[0]) / p.len[0], ys = (x[1] - p.lo[1]) / p.len[1];
    const double f = std::cos(M_PI * t / p.period);
    const double sx = std::sin(M_PI * xs), sy = std::sin(M_PI * ys);
    out[0] = -2 * sx * sx * sy * std::cos(M_PI * ys) * f * p.len[0];
    out[1] = 2 * sy * sy * sx * std::cos(M_PI * xs) * f * p.len[1];
    out[2] = 0;
  } else {
    out[0] = p.v[0];
    out[1] = p.v[1];
    out[2] = p.v[2];
  }
}

class PrescribedFlow : public Effect {
 public:
  std::string name() const override { return "prescribed_flow"; }
  int setupOrder() const override { return 0; }
  void configure(const Scene& s) override {
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
  void declareFields(FieldStore& f) const override { f.declare("velocity", Centring::Node, 3, name()); }
  void setup(State& st) override { fill(st, st.t); }
  void registerTasks(Pipeline& pl) override {
    pl.add(Stage::Properties, name(), "velocity at t + dt/2 from the closed form",
           [this](State& st) { fill(st, st.t + 0.5 * st.dt); });
  }
  // Advective CFL with the flow's largest speed over all times (|cos| <= 1).
  DtLimit dtLimit(const State& st) const override {
    const Grid& g = st.grid;
    const FlowParams p = p_;
    const double lo0 = g.lo[0], lo1 = g.lo[1], lo2 = g.lo[2], h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
    const int ng = g.ng, c0 = g.c0[0], c1 = g.c0[1], c2 = g.c0[2];
    double inv = 0;
    Kokkos::parallel_reduce(
        "prescribed_cfl", nodeRange(g).policy(),
        KOKKOS_LAMBDA(int i, int j, int k, double& m) {
          const double x[3] = {lo0 + (i - ng + c0) * h0, lo1 + (j - ng + c1) * h1, lo2 + (k - ng + c2) * h2};
          double v[3];
          flowAt(p, x, 0.0, v);
          const double s = std::fabs(v[0]) / h0 + std::fabs(v[1]) / h1 + std::fabs(v[2]) / h2;
          if (s > m) m = s;
        },
        Kokkos::Max<double>(inv));
    MPI_Allreduce(MPI_IN_PLACE, &inv, 1, MPI_DOUBLE, MPI_MAX, g.comm);
    if (inv == 0) return {};
    return {cfl_ / inv, "advective CFL (prescribed flow)"};
  }

 private:
  void fill(State& st, double t) const {
    const Grid& g = st.grid;
    VecField u = st.fields.vector("velocity");
    const FlowParams p = p_;
    const double lo0 = g.lo[0], lo1 = g.lo[1], lo2 = g.lo[2], h0 = g.h[0], h1 = g.h[1], h2 = g.h[2];
    const int ng = g.ng, c0 = g.c0[0], c1 = g.c0[1], c2 = g.c0[2];
    Kokkos::parallel_for(
        "prescribed_flow", Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}), KOKKOS_LAMBDA(int i, int j, int k) {
          const double x[3] = {lo0 + (i - ng + c0) * h0, lo1 + (j - ng + c1) * h1, lo2 + (k - ng + c2) * h2};
          double v[3];
          flowAt(p, x, t, v);
          for (int d = 0; d < 3; ++d) u.c[d](i, j, k) = v[d];
        });
  }
  FlowParams p_;
  double cfl_ = 0.5;
};

} // namespace

std::unique_ptr<Effect> makePrescribedFlow() { return std::make_unique<PrescribedFlow>(); }

} // namespace voigt
