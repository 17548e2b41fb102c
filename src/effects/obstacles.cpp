// obstacles: rigid bodies as prescribed node velocities (paper: "cells within
// the cylinder set to zero velocity each step"). Their nodes join the fixed
// mask, so the projection gives them no correction and no mass leaks through.
#include "core/boundary.hpp"
#include "core/field_names.hpp"
#include "effects/effect.hpp"
#include "kernels/reductions.hpp"

namespace voigt {

namespace {
class Obstacles : public Effect {
 public:
  std::string name() const override { return "obstacles"; }
  std::vector<std::string> dependsOn() const override { return {"navier_stokes"}; }
  // navier_stokes built the face mask this extends.
  std::vector<std::string> setupAfter() const override { return {"navier_stokes", "prescribed_flow"}; }
  void configure(const Scene& s, const Published&) override { obstacles_ = s.obstacles; }
  void setup(State& st) override {
    IntField mask = st.fields.integer(field::fixMask);
    addObstacleMask(st.grid, obstacles_, mask, st.fields.vector(field::fixValue));
    applyFixed(mask, st.fields.vector(field::fixValue), st.fields.vector(field::velocity),
               Range3{{0, 0, 0}, {st.grid.ext[0], st.grid.ext[1], st.grid.ext[2]}});
    // Count the fully fixed owned nodes for the summary.
    long long n = countFullyFixed(mask, nodeRange(st.grid));
    long long tot = 0;
    MPI_Allreduce(&n, &tot, 1, MPI_LONG_LONG, MPI_SUM, st.grid.comm);
    fixedNodes_ = tot;
    st.propertiesChanged = true;
  }
  void registerTasks(Pipeline&) override {} // all work is in the mask
  void summary(const State&, nlohmann::json& j) const override {
    j["obstacles"] = {{"count", obstacles_.size()}, {"fixed_nodes_incl_walls", fixedNodes_}};
  }

 private:
  std::vector<Obstacle> obstacles_;
  long long fixedNodes_ = 0;
};
} // namespace

std::unique_ptr<Effect> makeObstacles() { return std::make_unique<Obstacles>(); }

} // namespace voigt
