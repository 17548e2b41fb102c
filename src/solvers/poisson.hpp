#pragma once
// Pressure Poisson solver behind a Trilinos-free interface (the Tpetra, Belos,
// Ifpack2 and MueLu headers stay in src/solvers/*.cpp).
//
// Exact operator A = D B D^T, B = diag(coef_d(n) / w_n) (27-point, consistent
// with divergence()/subtractGradient() in kernels/projection_ops.hpp, so that
// after u -= dt coef G dp one has D u = -dt (rhs - A dp) to round-off).
// Approximate operator: compact 7-point variable-coefficient Laplacian.
#include <array>
#include <memory>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "solvers/solver_settings.hpp"

namespace voigt {

struct PoissonStats {
  int iterations = 0;     // 0 when the solve was skipped (rhs at round-off, see solve())
  double relResidual = 0; // explicit ||b - A x|| / ||b|| after null-mode projection (0 when b = 0)
  bool converged = false;
  double seconds = 0;      // this solve
  // setCoefficients() since the previous solve: matrix fill, null space, preconditioner
  // (for multigrid the MueLu set-up, which projection.multigrid_reuse makes cheaper).
  double setupSeconds = 0;
  int nullModes = 0;      // dim null(A) (src/solvers/null_space.hpp)
  // ||P_N b|| / ||b|| of the rhs as given: its part in null(A), which no pressure
  // can remove (NUMERICS.md: compatible only when the prescribed velocities carry
  // no such component). Removed before the solve; > ~1e-12 means incompatible.
  double incompatibility = 0;
  int breakdowns = 0;     // CG breakdowns (p^T A p <= 0); converged then = relResidual <= 10 tol
};

class PoissonSolver {
 public:
  virtual ~PoissonSolver() = default;
  // coef: node vector field, coef_d(n) = 1/rho(n) where velocity component d at
  // node n is free, 0 where it is prescribed. Valid (halo-exchanged) at every
  // corner node of every owned cell. Refills matrix values (graph is fixed),
  // marks identity rows, recomputes the preconditioner (multigrid: keeping what
  // projection.multigrid_reuse says, rebuilt in full when the zero pattern changed or
  // every multigrid_refresh calls), and finds the null modes again when the zero
  // pattern of coef changed (null(A) depends on it only).
  virtual void setCoefficients(const VecField& coef) = 0;
  // rhs: owned cells (= -D u*/dt). x: initial guess in, solution out (owned
  // cells only are written). Null modes are projected out of rhs and solution;
  // identity rows get rhs 0 and solution 0. Not converging is reported, not thrown.
  // CG starts from x0 or 0, whichever has the smaller residual (x0 is often the
  // previous increment, far worse than 0 once the flow is at rest). When
  // ||b|| <= 1e-14 max(||A||_inf ||x||, ||b_given||) (b after projection, x that
  // start) b is below what double precision resolves: no CG, x is the start. The same
  // when ||b|| <= floor (the caller's absolute scale: projection.volume_tolerance / dt^2).
  virtual PoissonStats solve(const Field& rhs, const Field& x, double floor = 0) = 0;
  virtual void apply(const Field& x, const Field& y) = 0; // y = A x on owned cells
  virtual long long globalNonzeros() const = 0;
  virtual int nullModeCount() const = 0;
  // The fast diagonalization's rank grid p1 x p2 (fast_diagonalization.hpp); {0, 0}: none.
  virtual std::array<int, 2> fdRankGrid() const { return {0, 0}; }
};

// Collective over g.comm. The solver keeps its own duplicate of the communicator.
std::unique_ptr<PoissonSolver> makePoissonSolver(const Grid& g, const PoissonSettings& cfg);

} // namespace voigt
