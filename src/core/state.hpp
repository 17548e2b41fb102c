#pragma once
// Everything a time step reads and writes. Effects find their fields by name
// in `fields`; nothing here is physics.
#include <map>
#include <memory>
#include <string>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/halo.hpp"
#include "core/index_space.hpp"
#include "scene/scene.hpp"

namespace voigt {

// A time-step limit and the reason, e.g. {2.1e-4, "advective CFL"}.
struct DtLimit {
  double dt = std::numeric_limits<double>::infinity();
  std::string reason = "none";
};

struct State {
  const Scene* scene = nullptr;
  Grid grid;
  FieldStore fields;
  std::unique_ptr<Halo> halo;

  double t = 0, dt = 0;
  long step = 0;
  std::string dtReason;
  bool propertiesChanged = true; // set by whoever changes rho/mu; projection refills its matrix
  // True while the velocity's rank and periodic ghosts hold the neighbours' current values:
  // set by an exchange of it (exchangeVelocity), cleared by whoever writes it (the momentum
  // stages, the projection's correction, prescribed_flow, a restore). A reader after the
  // projection (level set, elasticity, the next predictor) then skips a redundant exchange.
  bool velocityHalosCurrent = false;

  // Velocity a Stress/Forces task evaluates and the acceleration it adds to.
  VecField evalU, evalRhs;

  // Scalar diagnostics of the last step (max divergence, energies, ...), and
  // running counters, for summary.json and the time-series CSV.
  std::map<std::string, double> diag;
  std::map<std::string, double> counters;

  // Where a cell field can be active, by field name (local owned-cell indices): outside the box
  // the field holds values its kernels may skip (several level sets: psi_NAME <= -reach there,
  // effects/level_set/level_set.hpp). A field without an entry is active everywhere.
  std::map<std::string, Range3> activeBoxes;
  const Range3* activeBox(const std::string& field) const {
    auto it = activeBoxes.find(field);
    return it == activeBoxes.end() ? nullptr : &it->second;
  }

  // Set by a task that asks the run to stop after this step (the same on every
  // rank): Simulation::advance stops the run as a failure with this message.
  std::string stopRequest;
};

// The velocity's halo exchange, skipped while it is current (State::velocityHalosCurrent).
void exchangeVelocity(State& st);
// f's halo exchange, with the velocity's in the same message when that is stale.
void exchangeWithVelocity(State& st, const Field& f);

} // namespace voigt
