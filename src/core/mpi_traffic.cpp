// The PMPI wrappers behind mpi_traffic.hpp: each counts and calls the PMPI_ entry point.
// Defined in the executable, they take the place of the MPI library's for every caller,
// the shared Trilinos libraries included (the dynamic linker binds to the first definition).
#include "core/mpi_traffic.hpp"

#include <mpi.h>

#include <algorithm>
#include <vector>

namespace voigt::mpi_traffic {
namespace {
Counts totals;
long long bytesOf(int count, MPI_Datatype t) {
  int size = 0;
  if (count <= 0 || t == MPI_DATATYPE_NULL) return 0;
  PMPI_Type_size(t, &size);
  return 1LL * count * size;
}
void send(int dest, int count, MPI_Datatype t) {
  if (dest == MPI_PROC_NULL) return;
  ++totals.messages[PointToPoint];
  totals.bytes[PointToPoint] += bytesOf(count, t);
}
void collective(int count, MPI_Datatype t) {
  ++totals.messages[Collective];
  totals.bytes[Collective] += bytesOf(count, t);
}
void allToAll(const int* counts, MPI_Datatype t, MPI_Comm c) {
  int rank = 0, size = 1;
  PMPI_Comm_rank(c, &rank);
  PMPI_Comm_size(c, &size);
  for (int p = 0; p < size; ++p)
    if (p != rank && counts[p] > 0) ++totals.messages[AllToAll], totals.bytes[AllToAll] += bytesOf(counts[p], t);
}
} // namespace

Counts now() { return totals; }
const char* name(Kind k) {
  return k == PointToPoint ? "point_to_point" : k == AllToAll ? "all_to_all" : "collective";
}

} // namespace voigt::mpi_traffic

using namespace voigt::mpi_traffic;

extern "C" {
int MPI_Send(const void* b, int n, MPI_Datatype t, int dest, int tag, MPI_Comm c) {
  send(dest, n, t);
  return PMPI_Send(b, n, t, dest, tag, c);
}
int MPI_Ssend(const void* b, int n, MPI_Datatype t, int dest, int tag, MPI_Comm c) {
  send(dest, n, t);
  return PMPI_Ssend(b, n, t, dest, tag, c);
}
int MPI_Rsend(const void* b, int n, MPI_Datatype t, int dest, int tag, MPI_Comm c) {
  send(dest, n, t);
  return PMPI_Rsend(b, n, t, dest, tag, c);
}
int MPI_Isend(const void* b, int n, MPI_Datatype t, int dest, int tag, MPI_Comm c, MPI_Request* r) {
  send(dest, n, t);
  return PMPI_Isend(b, n, t, dest, tag, c, r);
}
int MPI_Issend(const void* b, int n, MPI_Datatype t, int dest, int tag, MPI_Comm c, MPI_Request* r) {
  send(dest, n, t);
  return PMPI_Issend(b, n, t, dest, tag, c, r);
}
int MPI_Irsend(const void* b, int n, MPI_Datatype t, int dest, int tag, MPI_Comm c, MPI_Request* r) {
  send(dest, n, t);
  return PMPI_Irsend(b, n, t, dest, tag, c, r);
}
int MPI_Sendrecv(const void* sb, int sn, MPI_Datatype st, int dest, int stag, void* rb, int rn, MPI_Datatype rt,
                 int src, int rtag, MPI_Comm c, MPI_Status* s) {
  send(dest, sn, st);
  return PMPI_Sendrecv(sb, sn, st, dest, stag, rb, rn, rt, src, rtag, c, s);
}
int MPI_Alltoall(const void* sb, int sn, MPI_Datatype st, void* rb, int rn, MPI_Datatype rt, MPI_Comm c) {
  int size = 1;
  PMPI_Comm_size(c, &size);
  totals.messages[AllToAll] += size - 1;
  totals.bytes[AllToAll] += (size - 1) * bytesOf(sn, st);
  return PMPI_Alltoall(sb, sn, st, rb, rn, rt, c);
}
int MPI_Alltoallv(const void* sb, const int sc[], const int sd[], MPI_Datatype st, void* rb, const int rc[],
                  const int rd[], MPI_Datatype rt, MPI_Comm c) {
  allToAll(sc, st, c);
  return PMPI_Alltoallv(sb, sc, sd, st, rb, rc, rd, rt, c);
}
int MPI_Neighbor_alltoallv(const void* sb, const int sc[], const int sd[], MPI_Datatype st, void* rb, const int rc[],
                           const int rd[], MPI_Datatype rt, MPI_Comm c) {
  int in = 0, out = 0, weighted = 0, rank = 0;
  PMPI_Dist_graph_neighbors_count(c, &in, &out, &weighted);
  std::vector<int> srcs(std::max(in, 1)), dsts(std::max(out, 1));
  PMPI_Dist_graph_neighbors(c, in, srcs.data(), MPI_UNWEIGHTED, out, dsts.data(), MPI_UNWEIGHTED);
  PMPI_Comm_rank(c, &rank);
  for (int q = 0; q < out; ++q)
    if (dsts[q] != rank && sc[q] > 0) ++totals.messages[AllToAll], totals.bytes[AllToAll] += bytesOf(sc[q], st);
  return PMPI_Neighbor_alltoallv(sb, sc, sd, st, rb, rc, rd, rt, c);
}
int MPI_Allreduce(const void* sb, void* rb, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c) {
  collective(n, t);
  return PMPI_Allreduce(sb, rb, n, t, op, c);
}
int MPI_Iallreduce(const void* sb, void* rb, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c, MPI_Request* r) {
  collective(n, t);
  return PMPI_Iallreduce(sb, rb, n, t, op, c, r);
}
int MPI_Reduce(const void* sb, void* rb, int n, MPI_Datatype t, MPI_Op op, int root, MPI_Comm c) {
  collective(n, t);
  return PMPI_Reduce(sb, rb, n, t, op, root, c);
}
int MPI_Scan(const void* sb, void* rb, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c) {
  collective(n, t);
  return PMPI_Scan(sb, rb, n, t, op, c);
}
int MPI_Exscan(const void* sb, void* rb, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c) {
  collective(n, t);
  return PMPI_Exscan(sb, rb, n, t, op, c);
}
int MPI_Bcast(void* b, int n, MPI_Datatype t, int root, MPI_Comm c) {
  collective(n, t);
  return PMPI_Bcast(b, n, t, root, c);
}
int MPI_Allgather(const void* sb, int sn, MPI_Datatype st, void* rb, int rn, MPI_Datatype rt, MPI_Comm c) {
  collective(sn, st);
  return PMPI_Allgather(sb, sn, st, rb, rn, rt, c);
}
int MPI_Allgatherv(const void* sb, int sn, MPI_Datatype st, void* rb, const int rc[], const int rd[],
                   MPI_Datatype rt, MPI_Comm c) {
  collective(sn, st);
  return PMPI_Allgatherv(sb, sn, st, rb, rc, rd, rt, c);
}
int MPI_Gather(const void* sb, int sn, MPI_Datatype st, void* rb, int rn, MPI_Datatype rt, int root, MPI_Comm c) {
  collective(sn, st);
  return PMPI_Gather(sb, sn, st, rb, rn, rt, root, c);
}
int MPI_Gatherv(const void* sb, int sn, MPI_Datatype st, void* rb, const int rc[], const int rd[], MPI_Datatype rt,
                int root, MPI_Comm c) {
  collective(sn, st);
  return PMPI_Gatherv(sb, sn, st, rb, rc, rd, rt, root, c);
}
int MPI_Barrier(MPI_Comm c) {
  collective(0, MPI_DATATYPE_NULL);
  return PMPI_Barrier(c);
}
} // extern "C"
