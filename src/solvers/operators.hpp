#pragma once
// Small Tpetra operators the Poisson solver hands to Belos. Include only from
// src/solvers/*.cpp (Trilinos headers).
#include "core/halo.hpp"
#include "core/host_access.hpp"
#include "core/index_space.hpp"
#include "kernels/fast_diag.hpp"
#include "kernels/poisson_apply.hpp"
#include "solvers/fast_diagonalization.hpp"
#include "solvers/null_space.hpp"
#include "solvers/trilinos_types.hpp"

namespace voigt::tpetra {

// A for Belos, counting applications: the iteration count of a solve that
// threw (breakdown), where getNumIters() is stale.
struct CountedOperator final : Operator {
  explicit CountedOperator(Teuchos::RCP<const Operator> a) : A(a) {}
  Teuchos::RCP<const Map> getDomainMap() const override { return A->getDomainMap(); }
  Teuchos::RCP<const Map> getRangeMap() const override { return A->getRangeMap(); }
  void apply(const MV& X, MV& Y, Teuchos::ETransp mode, Scalar alpha, Scalar beta) const override {
    ++count;
    A->apply(X, Y, mode, alpha, beta);
  }
  Teuchos::RCP<const Operator> A;
  mutable long count = 0;
};

// A preconditioner followed by the null-space projection. SGS and multigrid do
// not map range(A) into itself; projecting keeps every Krylov direction in
// range(A), so round-off cannot feed the null directions (at an unreachable
// tolerance on 2 ranks CG then runs to its limit instead of breaking down).
// Iteration counts on the cavity are unchanged; the cost is one P_N a step.
struct ProjectedPrec final : Operator {
  ProjectedPrec(Teuchos::RCP<const Operator> m, const NullSpace* ns) : M(m), ns(ns) {}
  Teuchos::RCP<const Map> getDomainMap() const override { return M->getDomainMap(); }
  Teuchos::RCP<const Map> getRangeMap() const override { return M->getRangeMap(); }
  void apply(const MV& X, MV& Y, Teuchos::ETransp mode, Scalar alpha, Scalar beta) const override {
    M->apply(X, Y, mode, alpha, beta);
    if (ns->dimension() == 0) return;
    for (size_t c = 0; c < Y.getNumVectors(); ++c) {
      RowVector y = Kokkos::subview(Y.getLocalViewDevice(Tpetra::Access::ReadWrite), Kokkos::ALL(), c);
      ns->remove(y);
    }
  }
  Teuchos::RCP<const Operator> M;
  const NullSpace* ns;
};

// The fast-diagonalization preconditioner (fast_diagonalization.hpp) as a Tpetra operator:
// Y = alpha Z A0^+ Z X + beta Y, Z zeroing the identity rows (cells inside obstacles) on both
// sides, so that it stays symmetric whatever X holds there.
struct FastDiagPrec final : Operator {
  FastDiagPrec(Teuchos::RCP<const Map> m, const FastDiagonalization* fd, RowFlags ident)
      : map(m), fd(fd), ident(ident) {}
  Teuchos::RCP<const Map> getDomainMap() const override { return map; }
  Teuchos::RCP<const Map> getRangeMap() const override { return map; }
  void apply(const MV& X, MV& Y, Teuchos::ETransp, Scalar alpha, Scalar beta) const override {
    for (size_t c = 0; c < Y.getNumVectors(); ++c) {
      ConstRowVector x = Kokkos::subview(X.getLocalViewDevice(Tpetra::Access::ReadOnly), Kokkos::ALL(), c);
      RowVector y = Kokkos::subview(Y.getLocalViewDevice(Tpetra::Access::ReadWrite), Kokkos::ALL(), c);
      fd->applyMasked(x, ident, alpha, beta, y);
    }
  }
  Teuchos::RCP<const Map> map;
  const FastDiagonalization* fd;
  RowFlags ident;
};

// The exact operator without its matrix (kernels/poisson_apply.hpp): what CG multiplies by
// when projection.matrix_free (default with the exact operator). The CSR matrix is still
// filled: the null space, the identity rows and ||A|| come from it, and SGS and multigrid
// need it. Bit-identical on any decomposition (each sum in a fixed order); differs from the
// CSR product by round-off.
struct MatrixFreeOperator final : Operator {
  MatrixFreeOperator(const Grid& grid, Teuchos::RCP<const Map> m, RowFlags ident)
      : g(grid), halo(g), map(m), ident(ident), rw{g.ng, g.ln[0], g.ln[1]}, cells(cellRange(g)),
        corners(cellRange(g)), nrows(int(g.cellsOwned())), x("mf_x", g.ext[0], g.ext[1], g.ext[2]),
        t("mf_t", nrows) {
    for (int d = 0; d < 3; ++d) {
      corners.e[d] += 1; // every corner node of an owned cell
      s.c[d] = Field("mf_scale", g.ext[0], g.ext[1], g.ext[2]);
      q.c[d] = Field("mf_flux", g.ext[0], g.ext[1], g.ext[2]);
      guard(s.c[d]), guard(q.c[d]);
    }
    guard(x);
  }
  // coef valid at every corner node of every owned cell (PoissonSolver::setCoefficients).
  void setCoefficients(const VecField& coef) { poissonNodeScale(g, coef, s, corners); }
  Teuchos::RCP<const Map> getDomainMap() const override { return map; }
  Teuchos::RCP<const Map> getRangeMap() const override { return map; }
  void apply(const MV& X, MV& Y, Teuchos::ETransp, Scalar alpha, Scalar beta) const override {
    for (size_t c = 0; c < Y.getNumVectors(); ++c) {
      ConstRowVector xv = Kokkos::subview(X.getLocalViewDevice(Tpetra::Access::ReadOnly), Kokkos::ALL(), c);
      RowVector y = Kokkos::subview(Y.getLocalViewDevice(Tpetra::Access::ReadWrite), Kokkos::ALL(), c);
      rowsToField(xv, x, rw, cells);
      halo.exchange(x, 1);
      poissonNodeFlux(x, s, q, corners);
      if (alpha == 1 && beta == 0) {
        poissonCellSum(q, x, y, ident, rw, cells);
      } else {
        poissonCellSum(q, x, t, ident, rw, cells);
        fdAxpby(alpha, t, beta, y, nrows);
      }
    }
  }
  Grid g; // a copy (the halo keeps a pointer to it): messages on the grid's communicator
  mutable Halo halo;
  Teuchos::RCP<const Map> map;
  RowFlags ident;
  CellRows rw;
  Range3 cells, corners;
  int nrows;
  Field x; // owned cells and the ghosts the halo fills; those beyond a wall stay 0 (poissonNodeFlux)
  VecField s, q;
  RowVector t;
};

} // namespace voigt::tpetra
