#include "core/halo.hpp"

#include <mpi.h>

#include "core/host_access.hpp"
#include "kernels/box_copy.hpp"

namespace voigt {

namespace {
using Buf = Kokkos::View<double*, MemSpace>;

// Slab [b, e) along axis d, full extent along the others.
struct Slab {
  int b[3], e[3];
  long long size() const { return 1LL * (e[0] - b[0]) * (e[1] - b[1]) * (e[2] - b[2]); }
};

Slab slab(const Grid& g, int d, int from, int to) {
  Slab s;
  for (int a = 0; a < 3; ++a) {
    s.b[a] = 0;
    s.e[a] = g.ext[a];
  }
  s.b[d] = from;
  s.e[d] = to;
  return s;
}

void pack(const Field& f, const Slab& s, Buf buf, long long off) { copyBoxFlat<true>(f, s.b, s.e, buf, off); }
void unpack(const Field& f, const Slab& s, Buf buf, long long off) { copyBoxFlat<false>(f, s.b, s.e, buf, off); }
} // namespace

void Halo::exchange(const std::vector<Field>& fields, int depth) {
  const Grid& g = *g_;
  const double t0 = MPI_Wtime();
  const int nd = depth > 0 && depth < g.ng ? depth : g.ng; // layers next to the owned ones
  for (int d = 0; d < 3; ++d) {
    if (g.nbrLo[d] == MPI_PROC_NULL && g.nbrHi[d] == MPI_PROC_NULL) continue;
    const int ng = g.ng, ln = g.ln[d];
    Slab sLo = slab(g, d, ng, ng + nd), sHi = slab(g, d, ln + ng - nd, ln + ng);
    Slab rLo = slab(g, d, ng - nd, ng), rHi = slab(g, d, ln + ng, ln + ng + nd);
    const long long per = sLo.size(), total = per * (long long)fields.size();
    if ((long long)sendLo_.extent(0) < total) {
      sendLo_ = Buf("halo_sendLo", total);
      sendHi_ = Buf("halo_sendHi", total);
      recvLo_ = Buf("halo_recvLo", total);
      recvHi_ = Buf("halo_recvHi", total);
      guard(sendLo_), guard(sendHi_), guard(recvLo_), guard(recvHi_);
#if defined(KOKKOS_ENABLE_CUDA)
      hsLo_ = StageBuf("halo_stage_sendLo", total), hsHi_ = StageBuf("halo_stage_sendHi", total);
      hrLo_ = StageBuf("halo_stage_recvLo", total), hrHi_ = StageBuf("halo_stage_recvHi", total);
#else
      hsLo_ = hostMirror(sendLo_), hsHi_ = hostMirror(sendHi_);
      hrLo_ = hostMirror(recvLo_), hrHi_ = hostMirror(recvHi_);
#endif
    }
    const bool lo = g.nbrLo[d] != MPI_PROC_NULL, hi = g.nbrHi[d] != MPI_PROC_NULL;
    for (size_t f = 0; f < fields.size(); ++f) { // only what a neighbour receives
      if (lo) pack(fields[f], sLo, sendLo_, f * per);
      if (hi) pack(fields[f], sHi, sendHi_, f * per);
    }
    if (g.nbrLo[d] == g.rank && g.nbrHi[d] == g.rank) { // periodic on one rank: no MPI, no staging
      for (size_t f = 0; f < fields.size(); ++f) {
        unpack(fields[f], rHi, sendLo_, f * per);
        unpack(fields[f], rLo, sendHi_, f * per);
      }
      Kokkos::fence();
      continue;
    }
    Kokkos::fence();
    Kokkos::deep_copy(hsLo_, sendLo_); // staging: a copy on a device, an alias on the host
    Kokkos::deep_copy(hsHi_, sendHi_);
    host_access::countCopy("halo_staging", 2 * 8 * total);
    // Low slab goes down and fills the neighbour's high ghosts; and vice versa.
    MPI_Sendrecv(hsLo_.data(), (int)total, MPI_DOUBLE, g.nbrLo[d], 10 + d, hrHi_.data(), (int)total,
                 MPI_DOUBLE, g.nbrHi[d], 10 + d, g.comm, MPI_STATUS_IGNORE);
    MPI_Sendrecv(hsHi_.data(), (int)total, MPI_DOUBLE, g.nbrHi[d], 20 + d, hrLo_.data(), (int)total,
                 MPI_DOUBLE, g.nbrLo[d], 20 + d, g.comm, MPI_STATUS_IGNORE);
    Kokkos::deep_copy(recvLo_, hrLo_);
    Kokkos::deep_copy(recvHi_, hrHi_);
    host_access::countCopy("halo_staging", 2 * 8 * total);
    for (size_t f = 0; f < fields.size(); ++f) {
      if (lo) unpack(fields[f], rLo, recvLo_, f * per);
      if (hi) unpack(fields[f], rHi, recvHi_, f * per);
    }
    Kokkos::fence();
    bytes += 8 * total * (lo + hi);
    messages += 2;
  }
  seconds += MPI_Wtime() - t0;
}

} // namespace voigt
