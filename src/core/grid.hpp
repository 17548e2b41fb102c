#pragma once
// Structured grid and its block decomposition over MPI ranks.
//
// Semi-staggered layout (paper, "Numerical methodology"): cell fields live at
// cell centres, velocity at cell corners (nodes). Node (i,j,k) is the low
// corner of cell (i,j,k), so both share one local index space:
//   local l = global g - c0 + ng,  arrays of extent ln + 2 ng + 1 per axis.
// A rank owns cells [c0, c1) and nodes [c0, c1), plus node n on the last rank
// of a non-periodic axis. Ghost layers are ng wide (MUSCL needs 2).
#include <array>
#include <mpi.h>

namespace voigt {

constexpr int kGhost = 2;

struct Grid {
  std::array<int, 3> n{};          // global cells per axis
  std::array<double, 3> lo{}, hi{}; // physical extent
  std::array<double, 3> h{};       // cell size
  std::array<bool, 3> periodic{};
  int ng = kGhost;

  // Decomposition.
  MPI_Comm comm = MPI_COMM_NULL;   // Cartesian communicator
  // The same ranks in the same order without the topology, for parallel HDF5: Open MPI's
  // default MPI-IO (OMPIO, 4.1) corrupts collective writes over a Cartesian communicator
  // (open-mpi/ompi#12718; seen here at 8 ranks: another rank's data in a dataset).
  MPI_Comm io = MPI_COMM_NULL;
  int rank = 0, size = 1;
  std::array<int, 3> dims{1, 1, 1}, coords{};
  std::array<int, 3> nbrLo{}, nbrHi{}; // MPI_PROC_NULL at physical faces
  std::array<int, 3> c0{}, c1{};   // owned cells [c0, c1)
  std::array<int, 3> ln{};         // owned cells per axis
  std::array<int, 3> ext{};        // array extent per axis

  // Node index range owned by this rank along axis d: [c0, nodeHi(d)).
  int nodeHi(int d) const { return c1[d] + ((!periodic[d] && c1[d] == n[d]) ? 1 : 0); }
  bool atLo(int d) const { return !periodic[d] && c0[d] == 0; }
  bool atHi(int d) const { return !periodic[d] && c1[d] == n[d]; }
  int local(int d, int g) const { return g - c0[d] + ng; }
  int global(int d, int l) const { return l - ng + c0[d]; }
  // Number of nodes along an axis globally (periodic axes wrap node n to 0).
  int nodes(int d) const { return periodic[d] ? n[d] : n[d] + 1; }
  long long cellsGlobal() const { return 1LL * n[0] * n[1] * n[2]; }
  long long cellsOwned() const { return 1LL * ln[0] * ln[1] * ln[2]; }
  long long arrayPoints() const { return 1LL * ext[0] * ext[1] * ext[2]; }
  double cellVolume() const { return h[0] * h[1] * h[2]; }
};

// Builds the decomposition. dims: requested ranks per axis (0 = let MPI choose).
Grid makeGrid(MPI_Comm world, std::array<int, 3> cells, std::array<double, 3> lo,
              std::array<double, 3> hi, std::array<bool, 3> periodic,
              std::array<int, 3> dims = {0, 0, 0});
void freeGrid(Grid& g);

} // namespace voigt
