#pragma once
// What this rank sends through MPI, counted by the code itself: every MPI call of the
// process (Voigt's halos and transposes, Tpetra's and Belos' messages and reductions)
// passes through the wrappers of mpi_traffic.cpp (MPI's profiling interface, PMPI), which
// count and forward. Exact at any rank count, oversubscribed or not, so a scaling model
// can be built from counts measured on one machine (perf/scaling/README.md).
#include <array>

namespace voigt::mpi_traffic {

enum Kind { PointToPoint, AllToAll, Collective, kKinds };
// Per kind: messages (point to point: sends; all-to-all: destinations other than this rank
// with data; collective: calls) and bytes sent (a collective: its payload on this rank).
struct Counts {
  std::array<long long, kKinds> messages{}, bytes{};
  Counts operator-(const Counts& o) const {
    Counts d;
    for (int k = 0; k < kKinds; ++k) d.messages[k] = messages[k] - o.messages[k], d.bytes[k] = bytes[k] - o.bytes[k];
    return d;
  }
  Counts& operator+=(const Counts& o) {
    for (int k = 0; k < kKinds; ++k) messages[k] += o.messages[k], bytes[k] += o.bytes[k];
    return *this;
  }
};

Counts now(); // totals since the process started
const char* name(Kind k); // "point_to_point", "all_to_all", "collective"

} // namespace voigt::mpi_traffic
