#pragma once
// Null space of the exact projection operator A = D_free B D_free^T (poisson.hpp),
// represented implicitly. No Trilinos here: rows are plain Kokkos views.
//
// null(A) = null(D_free^T) (B > 0 diagonal): the cell vectors whose gradient G p
// vanishes at every free node component. It depends on the zero pattern of the
// coefficients only, not on their values. Besides the constant, G kills every
// MODULATED alternating mode, one per plane q along each axis c:
//   m_{c,q} = (-1)^(i_a + i_b) [i_c == q]      (a, b: the two other axes)
// At an interior node the x pair differences cancel across j, the y ones across
// i, and the z sum of (-1)^(i+j) over the 2x2 (i,j) block vanishes; so does any
// (-1)^(i+j) f(k). The three families share (-1)^(i+j+k), hence in a closed box
// dim null(A) = n_x + n_y + n_z - 1, not the 5 global modes.
//
// Measured (dense A assembled through PoissonSolver::apply, LAPACK dsyev,
// |lambda| < 1e-10 max with the next one > 2e-2 max; exact operator, 1 rank;
// tests/solvers/test_poisson.cpp NullSpaceDimension re-measures some of them):
//   no-slip walls 4^3 11, 6^3 17, 7^3 20, 8^3 23, 6x7x8 20   (sum n - 1)
//   walls 8^3 + obstacle nodes [3,5]^3 (8 identity rows) 23; 10^3 + [2,5]^3 29
//   periodic 8^3 23, 6^3 17, 6x2x6 13; periodic x + walls 8^3 23
//   periodic 7^3 1 (odd n breaks the alternation), periodic 8x7x8 8
//   outflow x+ 8^3 8, 7^3 7 (the (-1)^(j+k)[i==q] family), outflow x+ and y+ 0
//   walls 8^3 + obstacle + outflow x+ 8; channel in x-/out x+, no-slip walls 8
//   slip walls everywhere 1; slip x,y + walls z 1; periodic x + slip y + walls z 9;
//   channel in x-/out x+ with slip walls 0.
// In every case the candidates below that pass the test span null(A) exactly.
//
// Representation: basis M = [1, m_{0,0..n0-1}, m_{1,0..n1-1}, m_{2,0..n2-1}]
// (nb = 1 + n0 + n1 + n2 columns, zero on identity rows), never stored. M^T v is
// one pass of signed plane sums (+ MPI_Allreduce of nb numbers), M a one pass.
// The kept candidates K = M C overlap, so their Gram H = C^T (M^T M) C is
// singular: P_N = M C H^+ C^T M^T with H^+ from a symmetric eigen-decomposition,
// stored as Z = C V_+ Lambda_+^{-1/2} (nb x dim): P_N v = M Z Z^T M^T v and
// ||P_N v|| = ||Z^T M^T v||.
#include <mpi.h>

#include <functional>
#include <vector>

#include "core/field.hpp"
#include "kernels/poisson_rows.hpp"
#include "kernels/projection_ops.hpp"

namespace voigt {

class NullSpace {
 public:
  using Apply = std::function<void(const RowVector& x, const RowVector& y)>; // y = A x (collective)

  // Collective over comm (which must outlive this object).
  NullSpace(const GridGeom& G, const CellRows& rows, int nrows, MPI_Comm comm);

  // Tests the candidates 1, m_{c,q} and the 4 global alternating modes (zero on
  // identity rows; kept when ||A v|| <= 1e-10 ||v|| scale, scale ~ ||A||_inf)
  // and builds the projector. About 20 applications of A: the m_{c,q} are
  // tested a colour at a time (planes 3 apart), as A m_{c,q} lives on planes
  // q-1..q+1. Call when the coefficient pattern changes.
  void rebuild(const RowFlags& ident, const Apply& apply, double scale);

  // v -= P_N v (orthogonal projection onto range(A)); returns ||P_N v||_2 as it
  // was before. Two passes over the rows and one MPI_Allreduce of nb doubles.
  double remove(const RowVector& v) const;

  int dimension() const { return dim_; }
  int candidatesKept() const { return kept_; }

 private:
  void analyze(const RowVector& v, double* s) const;                          // s = M^T v (global)
  void synthesize(const double* a, const RowVector& v, bool subtract) const; // v = M a or v -= M a
  void planeNorms(const RowVector& y, int axis, double* ps) const;           // per-plane sum of y^2
  double norm2(const RowVector& v) const;
  NullBasis basis() const { return NullBasis{G_, rows_, off_[0], off_[1], off_[2]}; }

  GridGeom G_;
  CellRows rows_;
  int nrows_ = 0, nb_ = 1, off_[3] = {1, 1, 1};
  MPI_Comm comm_;
  RowFlags ident_;
  int dim_ = 0, kept_ = 0;
  bool constantOnly_ = false;             // Z is zero but for the constant: plain sums do
  std::vector<double> Z_;                 // nb x dim, column-major
  Kokkos::View<double*, MemSpace> coef_;  // a = Z Z^T M^T v on the device
  mutable std::vector<double> s_;         // host work, nb
};

} // namespace voigt
