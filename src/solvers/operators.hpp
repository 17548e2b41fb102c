#pragma once
// Small Tpetra operators the Poisson solver hands to Belos. Include only from
// src/solvers/*.cpp (Trilinos headers).
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
  FastDiagPrec(Teuchos::RCP<const Map> m, const FastDiagonalization* fd, RowFlags ident, int nrows)
      : map(m), fd(fd), ident(ident), nrows(nrows), t("fd_prec_t", nrows), xz("fd_prec_x", nrows) {}
  Teuchos::RCP<const Map> getDomainMap() const override { return map; }
  Teuchos::RCP<const Map> getRangeMap() const override { return map; }
  void apply(const MV& X, MV& Y, Teuchos::ETransp, Scalar alpha, Scalar beta) const override {
    for (size_t c = 0; c < Y.getNumVectors(); ++c) {
      ConstRowVector x = Kokkos::subview(X.getLocalViewDevice(Tpetra::Access::ReadOnly), Kokkos::ALL(), c);
      RowVector y = Kokkos::subview(Y.getLocalViewDevice(Tpetra::Access::ReadWrite), Kokkos::ALL(), c);
      Kokkos::deep_copy(xz, x);
      zeroIdentityRows(xz, ident, nrows);
      fd->apply(xz, t);
      zeroIdentityRows(t, ident, nrows);
      fdAxpby(alpha, t, beta, y, nrows);
    }
  }
  Teuchos::RCP<const Map> map;
  const FastDiagonalization* fd;
  RowFlags ident;
  int nrows;
  RowVector t, xz;
};

} // namespace voigt::tpetra
