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
// MPI: the transforms need whole grid lines. The x and y transforms run on z-slabs (each
// rank a range of k with whole x-y planes), the z transform and the scaling on y-slabs;
// three box-to-box moves (src/core/redistribute.hpp) each way: blocks -> z-slabs -> y-slabs.
#include <mpi.h>

#include <functional>
#include <memory>
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"
#include "core/redistribute.hpp"
#include "kernels/fast_diag.hpp"
#include "kernels/poisson_rows.hpp"

namespace voigt {

using ConstRowVector = Kokkos::View<const double*, Kokkos::LayoutLeft, MemSpace>;

class FastDiagonalization {
 public:
  FastDiagonalization(const Grid& g, MPI_Comm comm);
  // Reads which faces keep their node rows from coef (collective); builds the 1-D
  // eigenvectors and the eigenvalue table. Cheap (1-D eigenproblems): call when the
  // zero pattern of coef changes.
  void setup(const VecField& coef);
  // z = A0^+ r on this rank's rows (r: owned rows, i fastest). Collective.
  void apply(const ConstRowVector& r, const RowVector& z) const;

 private:
  using Op = std::function<void(const CGrid3&, const Grid3&)>;
  std::vector<Op> forwardXY() const; // z-slab: (fold) x, (fold) y forward
  std::vector<Op> zAndScale() const; // y-slab: (fold) z forward, scale, z back (unfold)
  std::vector<Op> backYX() const;    // z-slab: y back (unfold), x back (unfold)
  void chain(const std::vector<Op>& ops, const CGrid3& src, const Grid3& dst, const Grid3& A, const Grid3& B) const;
  std::vector<Op> opsXY_, opsZ_, opsYX_, opsAll_; // the three parts and all in order (setup)
  Grid g_;                 // this rank's box (a copy; the communicator is comm_)
  int n_[3];
  bool keepK_[3][2] = {}, keepM_[3][2] = {}; // face node rows kept: normal / tangential components
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  Box zs_, ys_;            // this rank's z-slab and y-slab
  std::unique_ptr<Redistribute> toZ_, zToY_; // blocks -> z-slabs, z-slabs -> y-slabs
  Dense V_[3];             // per axis: eigenvectors (block diagonal after folding)
  int nb_[3] = {0, 0, 0};  // first block of V_ (n: not folded)
  Grid3 inv_;              // 1/eigenvalue on this rank's y-slab of modes
  Grid3 z1_, z2_, y1_, y2_; // z-slab and y-slab work arrays (1 rank: the whole grid, z == y)
  Grid3::HostMirror zh_, yh_;
  mutable std::vector<double> rowsH_;
};

} // namespace voigt
