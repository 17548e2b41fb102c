#pragma once
// Pressure Poisson solver behind a Trilinos-free interface (the Tpetra, Belos,
// Ifpack2 and MueLu headers stay in src/solvers/*.cpp).
//
// Exact operator A = D B D^T, B = diag(coef_d(n) / w_n) (27-point, consistent
// with divergence()/subtractGradient() in kernels/projection_ops.hpp, so that
// after u -= dt coef G dp one has D u = -dt (rhs - A dp) to round-off).
// Approximate operator: compact 7-point variable-coefficient Laplacian.
#include <memory>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "scene/scene.hpp"

namespace voigt {

struct PoissonStats {
  int iterations = 0;
  double relResidual = 0; // explicit ||b - A x|| / ||b|| after null-mode projection
  bool converged = false;
  double seconds = 0;
  int nullModes = 0;
};

class PoissonSolver {
 public:
  virtual ~PoissonSolver() = default;
  // coef: node vector field, coef_d(n) = 1/rho(n) where velocity component d at
  // node n is free, 0 where it is prescribed. Valid (halo-exchanged) at every
  // corner node of every owned cell. Refills matrix values (graph is fixed),
  // marks identity rows, finds the null modes, recomputes the preconditioner.
  virtual void setCoefficients(const VecField& coef) = 0;
  // rhs: owned cells (= -D u*/dt). x: initial guess in, solution out (owned
  // cells only are written). Null modes are projected out of rhs and solution;
  // identity rows get rhs 0 and solution 0. Not converging is reported, not thrown.
  virtual PoissonStats solve(const Field& rhs, const Field& x) = 0;
  virtual void apply(const Field& x, const Field& y) = 0; // y = A x on owned cells
  virtual long long globalNonzeros() const = 0;
  virtual int nullModeCount() const = 0;
};

// Collective over g.comm. The solver keeps its own duplicate of the communicator.
std::unique_ptr<PoissonSolver> makePoissonSolver(const Grid& g, const ProjectionCfg& cfg);

} // namespace voigt
