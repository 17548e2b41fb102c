#pragma once
// Semi-implicit viscosity (navier_stokes.viscous: semi_implicit): the implicit half of each
// predictor stage, (M - dt K) d = dt K q, solved by CG with Jacobi on the three velocity
// components at once (kernels/viscous_implicit.hpp has the scheme and why it is stable).
#include <string>

#include "core/field.hpp"
#include "core/state.hpp"

namespace voigt {

class ImplicitViscosity {
 public:
  static void declareFields(FieldStore& f, const std::string& owner);
  // Once a step, after the properties (mu, rho at the cells, ghosts fresh) and dt are set.
  void prepare(State& st);
  // q: the stage's increment at the owned nodes (its ghosts are refreshed here); u += d.
  // Counts iterations in st.counters (viscous_*); a solve at its cap is counted, not thrown.
  void correct(State& st, const VecField& q, const VecField& u);
  // The scratch vector a stage's increment is built in.
  static VecField increment(State& st);

  static constexpr double kTolerance = 1e-8; // relative 2-norm of the residual
  static constexpr int kMaxIterations = 1000;

 private:
  bool zeroed_ = false; // the scratch's wall ghosts set to 0 (prepare)
};

} // namespace voigt
