#pragma once
// A preconditioner for the exact projection operator A = D B D^T (poisson.hpp): the exact
// inverse of the same operator at one density, A0^+, by fast diagonalization
// (kernels/fast_diag.hpp). Why it works where multigrid struggles: A's hard modes are the
// plane-modulated checkerboards near its three null lines and the fourth-order corner
// (perf/README.md, "Exact projection"), and A0 has exactly the same ones, so A0^+ A is
// close to the identity except where 1/rho differs from the reference; measured flat in n
// (perf/README.md, "Fast diagonalization").
//
// A0's boundary treatment is read off the coefficient pattern of the faces: per face, whether
// the normal and the tangential velocity components are free there (no-slip walls and
// inflow: neither; slip walls: tangential; outflow: both; periodic axes wrap). Exact at one
// density in a box with such faces (the two tangential components must agree, else both are
// taken as free); obstacles and density jumps are left to CG. A face is sampled away from
// its edges: a wall with an outflow patch reads as free, and then A0 is a preconditioner only.
//
// One axis s (y or z, bounded, the longer) is not transformed: per line along it A0 is
// tridiagonal in the two other axes' modes, solved directly (kernels/fd_tridiagonal.hpp):
// 2 n_s flops a cell less each way. With both y and z periodic, all three are transformed.
//
// MPI: the transforms and solves need whole grid lines, so the passes run on pencils, each
// whole along the axis it works on, over a p1 x p2 grid of ranks (p1 splits x or c, p2 s or c):
//   x pencils (x transform): c split p1, s split p2
//   c pencils (c transform): x split p1, s split p2
//   s pencils (the solve along s; with no solve axis, the z transform and the scaling):
//                            x split p1, c split p2
// (s = y or z the solve axis, c the other transformed one; with no solve axis s = z, c = y),
// with box-to-box moves (src/core/redistribute.hpp) each way: blocks -> x -> c -> s pencils.
// With p1 = 1 the x and c pencils are one slab (whole planes of x and c, a range of s) and the
// x and c transforms run there together (the fused x pass folds c too): the slab layout,
// used up to 8 ranks where they fit the planes (pencilGrid). Beyond that p1 > 1: up to
// min(n_x, n_c) min(n_s, n_c) ranks work, not min(n_s, n_c). Every line is transformed and
// solved alone, in the same order in every layout: the same bits at any p1 and rank count.
#include <mpi.h>

#include <array>
#include <functional>
#include <memory>
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/redistribute.hpp"
#include "kernels/fast_diag.hpp"
#include "kernels/fd_tridiagonal.hpp"
#include "kernels/poisson_rows.hpp"

namespace voigt {

using ConstRowVector = Kokkos::View<const double*, Kokkos::LayoutLeft, MemSpace>;

// Mixed precision (projection.fd_precision: single, the default): the passes run in float
// (half the bytes, twice the SIMD lanes) between two conversions; CG itself stays in double.
// A0^+ in float is A0^+ to about 1e-6 relative, which costs CG a few iterations at tight
// tolerances (perf/README.md, "The exact projection at a tolerance").
class FastDiagonalization {
 public:
  // tridiagonal false: transform all three axes (the form before 2026-12-05; tests compare).
  // p1: the rank grid's first extent (0: chosen, pencilGrid; tests force pencils with it).
  FastDiagonalization(const Grid& g, MPI_Comm comm, bool single = false, bool tridiagonal = true, int p1 = 0);
  // The rank grid p1 x p2 for `size` ranks on n cells with solve (layout) axis s and c:
  // slabs (p1 = 1) up to kSlabRanks ranks where they fit (size <= min(n_s, n_c)): one move
  // fewer each way, the fewest bytes; else p1 x p2 = size with p1 <= p2 as near sqrt(size)
  // as fits (p1 <= min(n_x, n_c), p2 <= min(n_s, n_c)): each rank then exchanges with about
  // 2 sqrt(size) others an application, not size (slabs: 159 messages against 53 at 64 ranks
  // on 75^3, perf/scaling/README.md "Traffic"); where no factorisation fits, the largest grid
  // that does (the other ranks idle in the passes).
  static constexpr int kSlabRanks = 8;
  static std::array<int, 2> pencilGrid(int size, const int n[3], int s, int c);
  // Reads which faces keep their node rows from coef (collective); builds the 1-D
  // eigenvectors and the eigenvalue table. Cheap (1-D eigenproblems): call when the
  // zero pattern of coef changes.
  void setup(const VecField& coef);
  // z = A0^+ r on this rank's rows (r: owned rows, i fastest). Collective.
  void apply(const ConstRowVector& r, const RowVector& z) const;
  // y = alpha Z A0^+ Z x + beta y, Z zeroing the rows where ident != 0 (the preconditioner of
  // CG, FastDiagPrec): the zeroing and conversions fused into the first and last passes.
  void applyMasked(const ConstRowVector& x, const Kokkos::View<int*, MemSpace>& ident, double alpha, double beta,
                   const RowVector& y) const;
  bool single() const { return single_; }
  int solveAxis() const { return s_; } // the axis solved by lines (1 or 2), -1: none
  int singularLines() const { return (int)lines_.extent(0); } // on this rank (after setup)
  std::array<int, 2> rankGrid() const { return {p1_, p2_}; }
  // Per application on this rank: messages sent and bytes sent (the moves both ways).
  std::array<long long, 2> traffic() const;

 private:
  template <class T>
  struct Passes { // one precision's passes and work arrays
    using Op = std::function<void(const CGrid3Of<T>&, const Grid3Of<T>&)>;
    // x pencils: the x transform (and with p1 = 1 the c transform); c pencils (p1 > 1): the c
    // transform; s pencils: the solve along s (or the third transform, the scaling and its
    // inverse); then back the same way.
    std::vector<Op> fwd, mid, inner, midBack, back, all;
    DenseOf<T> V[3];
    Grid3Of<T> inv;                 // no solve axis: 1/eigenvalue on this rank's inner slab of modes
    Grid3Of<T> o1, o2, m1, m2, i1, i2; // x, c and s pencils' work arrays (1 rank: the whole grid, all one)
    typename Grid3Of<T>::HostMirror oh, mh, ih;
    Kokkos::View<T*, Kokkos::LayoutLeft, MemSpace> r, x; // rows in T (applyMasked; apply in float)
    mutable std::vector<T> rowsH;
  };
  template <class T>
  void allocate(Passes<T>& P) const;
  template <class T>
  void build(Passes<T>& P, const Grid3& inv) const; // V, inv and the ops from V_, nb_ (setup)
  template <class T>
  void run(const Passes<T>& P, const Kokkos::View<const T*, Kokkos::LayoutLeft, MemSpace>& r,
           const Kokkos::View<T*, Kokkos::LayoutLeft, MemSpace>& z) const;
  void findSingularLines(const Kokkos::View<double* [3], MemSpace>::HostMirror& lam, double cut);
  Grid g_;                 // this rank's box (a copy; the communicator is comm_)
  int n_[3];
  bool single_;
  int s_ = -1;             // the solve axis, -1: none (all three transformed)
  int c_ = 1;              // the transformed axis other than x (2 when s_ = 1, else 1)
  bool keepK_[3][2] = {}, keepM_[3][2] = {}; // face node rows kept: normal / tangential components
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  int p1_ = 1, p2_ = 1;    // the rank grid of the pencils
  Box outer_, mid_, inner_; // this rank's x, c and s pencil (p1 = 1: mid_ = outer_, not used)
  std::unique_ptr<Redistribute> toOuter_, toMid_, toInner_; // blocks -> x -> (c ->) s pencils
  Dense V_[3];             // per axis: eigenvectors (block diagonal after folding), double
  int nb_[3] = {0, 0, 0};  // first block of V_ (n: not folded)
  // The solve (s_ >= 0): eigenvalues per axis, K_s and M_s's diagonals, the singular lines
  // (inner-slab indices) with the unfolded eigenvectors of s, and double work arrays.
  Table lam_[3];
  Table4 tri_;
  Dense VsT_;             // V_[s_] transposed (the singular lines read both)
  Lines2 lines_;
  Grid3 cp_, dp_;
  Kokkos::View<double**, Kokkos::LayoutRight, MemSpace> lineWork_;
  double ih_[3] = {0, 0, 0}, cut_ = 0;
  Passes<double> d_;
  Passes<float> f_;
};

} // namespace voigt
