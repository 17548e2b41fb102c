#pragma once
// Moves a whole-grid cell array from one box decomposition over the ranks to another (e.g.
// Voigt's blocks to z-slabs): each rank holds one box, stored i fastest (LayoutLeft) with
// the box's own extents; what moves is the intersection of a source box with each
// destination box, in one MPI_Neighbor_alltoallv over a graph of the ranks that exchange
// cells (both directions built once), through host buffers made once: a rank's cost follows
// its partners, not the communicator's size (an MPI_Alltoallv over all ranks passes P counts
// and, in Open MPI's pairwise algorithm, P steps). The fast diagonalization's transposes
// (src/solvers/fast_diagonalization.cpp) are built on it.
#include <mpi.h>

#include <array>
#include <vector>

namespace voigt {

struct Box {
  std::array<int, 3> lo{}, n{}; // global first cell and extent per axis (n 0: empty)
  long long size() const { return 1LL * n[0] * n[1] * n[2]; }
};

class Redistribute {
 public:
  // src[p], dst[p]: every rank's box before and after (the same lists on every rank).
  Redistribute(MPI_Comm comm, const std::vector<Box>& src, const std::vector<Box>& dst);
  ~Redistribute();
  Redistribute(const Redistribute&) = delete;
  Redistribute& operator=(const Redistribute&) = delete;
  // out (this rank's dst box) = in (this rank's src box) moved. Host pointers. Collective.
  // T: double or float.
  template <class T>
  void forward(const T* in, T* out) const { move(in, out, false); }
  // The reverse move: in (dst layout) -> out (src layout).
  template <class T>
  void backward(const T* in, T* out) const { move(in, out, true); }
  // What one move (reverse: the backward one) sends from this rank to others: messages and
  // cells (the part kept by the rank itself is a copy, not counted).
  std::array<long long, 2> sent(bool reverse) const;

 private:
  struct Part {
    Box box;      // intersection, global cells
    int rank;
  };
  template <class T>
  void move(const T* in, T* out, bool reverse) const;
  MPI_Comm comm_;
  MPI_Comm graph_[2] = {MPI_COMM_NULL, MPI_COMM_NULL}; // forward, backward: edges where cells move
  Box mySrc_, myDst_;
  // Forward direction, partners only (the rank itself included when it keeps cells): what
  // this rank sends and receives, and the counts and displacements in partner order.
  std::vector<Part> sends_, recvs_;
  std::vector<int> sendCount_, sendDispl_, recvCount_, recvDispl_;
  mutable std::vector<double> sendBuf_, recvBuf_; // also hold floats (half the bytes)
};

} // namespace voigt
