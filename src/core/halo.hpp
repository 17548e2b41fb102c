#pragma once
// Ghost-layer exchange between neighbouring ranks (and periodic images).
// Axis by axis, each pass over the full extent of the other axes, so edge and
// corner ghosts arrive without diagonal messages. Physical faces are left to
// the boundary conditions (boundary.hpp).
#include <vector>

#include "core/field.hpp"
#include "core/grid.hpp"

namespace voigt {

class Halo {
 public:
  explicit Halo(const Grid& g) : g_(&g) {}
  // depth: the ghost layers to fill next to a neighbour rank (0: all g.ng); a caller
  // whose next stencil reads one layer passes 1 and sends half the bytes.
  void exchange(const std::vector<Field>& fields, int depth = 0);
  void exchange(const VecField& v) { exchange(std::vector<Field>{v.c[0], v.c[1], v.c[2]}); }
  void exchange(const Field& f, int depth = 0) { exchange(std::vector<Field>{f}, depth); }

  // Totals since construction, for the cost model in perf/.
  double seconds = 0;
  long long bytes = 0;
  long long messages = 0;

 private:
  const Grid* g_;
  // Message buffers, kept across calls and grown on demand, and the host buffers
  // MPI reads and writes: the same memory on a host backend; on CUDA, page-locked
  // (pinned) host memory, created once, so the device copies run at full PCIe speed
  // (Debian's Open MPI is not CUDA-aware: no device pointers to MPI).
  using Buf = Kokkos::View<double*, MemSpace>;
#if defined(KOKKOS_ENABLE_CUDA)
  using StageBuf = Kokkos::View<double*, Kokkos::CudaHostPinnedSpace>;
#else
  using StageBuf = Buf::HostMirror;
#endif
  Buf sendLo_, sendHi_, recvLo_, recvHi_;
  StageBuf hsLo_, hsHi_, hrLo_, hrHi_;
};

} // namespace voigt
