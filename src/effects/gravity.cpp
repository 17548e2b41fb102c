// gravity: body force per unit mass, f/rho = g in Eq. (7).
#include <algorithm>
#include <cmath>

#include "core/index_space.hpp"
#include "effects/effect.hpp"
#include "kernels/momentum.hpp"

namespace voigt {

namespace {
class Gravity : public Effect {
 public:
  std::string name() const override { return "gravity"; }
  std::vector<std::string> dependsOn() const override { return {"navier_stokes"}; }
  void configure(const Scene& s, const Published&) override {
    g_ = s.gravity;
    cfl_ = s.time.cfl;
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
    p.add(Stage::Forces, name(), "uniform body force g", [g](State& st) {
      addBodyForce(st.evalRhs, g[0], g[1], g[2], nodeRange(st.grid));
    });
  }

 private:
  Vec3 g_{0, 0, 0};
  double cfl_ = 0.5;
};
} // namespace

std::unique_ptr<Effect> makeGravity() { return std::make_unique<Gravity>(); }

} // namespace voigt
