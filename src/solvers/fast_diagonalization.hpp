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

// Mixed precision (projection.fd_precision: single, the default): the passes run in float
// (half the bytes, twice the SIMD lanes) between two conversions; CG itself stays in double.
// A0^+ in float is A0^+ to about 1e-6 relative, which costs CG a few iterations at tight
// tolerances (perf/README.md, "The exact projection at a tolerance").
class FastDiagonalization {
 public:
  FastDiagonalization(const Grid& g, MPI_Comm comm, bool single = false);
  // Reads which faces keep their node rows from coef (collective); builds the 1-D
  // eigenvectors and the eigenvalue table. Cheap (1-D eigenproblems): call when the
  // zero pattern of coef changes.
  void setup(const VecField& coef);
  // z = A0^+ r on this rank's rows (r: owned rows, i fastest). Collective.
  void apply(const ConstRowVector& r, const RowVector& z) const;
  bool single() const { return single_; }

 private:
  template <class T>
  struct Passes { // one precision's passes and work arrays
    using Op = std::function<void(const CGrid3Of<T>&, const Grid3Of<T>&)>;
    std::vector<Op> xy, z, yx, all; // z-slab: x, y forward; y-slab: z, scale, z back; z-slab: y, x back
    DenseOf<T> V[3];
    Grid3Of<T> inv;                 // 1/eigenvalue on this rank's y-slab of modes
    Grid3Of<T> z1, z2, y1, y2;      // z-slab and y-slab work arrays (1 rank: the whole grid, z == y)
    typename Grid3Of<T>::HostMirror zh, yh;
    Kokkos::View<T*, Kokkos::LayoutLeft, MemSpace> r, x; // rows in T (float only)
    mutable std::vector<T> rowsH;
  };
  template <class T>
  void allocate(Passes<T>& P) const;
  template <class T>
  void build(Passes<T>& P, const Grid3& inv) const; // V, inv and the ops from V_, nb_ (setup)
  template <class T>
  void run(const Passes<T>& P, const Kokkos::View<const T*, Kokkos::LayoutLeft, MemSpace>& r,
           const Kokkos::View<T*, Kokkos::LayoutLeft, MemSpace>& z) const;
  Grid g_;                 // this rank's box (a copy; the communicator is comm_)
  int n_[3];
  bool single_;
  bool keepK_[3][2] = {}, keepM_[3][2] = {}; // face node rows kept: normal / tangential components
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  Box zs_, ys_;            // this rank's z-slab and y-slab
  std::unique_ptr<Redistribute> toZ_, zToY_; // blocks -> z-slabs, z-slabs -> y-slabs
  Dense V_[3];             // per axis: eigenvectors (block diagonal after folding), double
  int nb_[3] = {0, 0, 0};  // first block of V_ (n: not folded)
  Passes<double> d_;
  Passes<float> f_;
};

} // namespace voigt
