#pragma once
// A one-process MPI for the programs of tests/device (issue 25), so that the binaries packed
// for a GPU machine (perf/portability/device-check) need no Open MPI there (its libraries and
// run-time plugins). Only what grid.cpp, halo.cpp, kernels/ and perf/ call, with one rank's
// meaning: rank 0 of 1, a Cartesian communicator remembers its periodic axes (a periodic
// neighbour is the rank itself, else MPI_PROC_NULL), a message to oneself is a copy.
// Used with -DVOIGT_MPI_STUB=ON (tests/device/CMakeLists.txt); never by the main build.
#include <chrono>
#include <cstring>

typedef int MPI_Comm;
typedef int MPI_Datatype;
typedef int MPI_Op;
struct MPI_Status {
  int MPI_SOURCE, MPI_TAG, MPI_ERROR;
};
#define MPI_SUCCESS 0
#define MPI_COMM_NULL 0
#define MPI_COMM_WORLD 1
#define MPI_COMM_SELF 2
#define MPI_PROC_NULL (-2)
#define MPI_STATUS_IGNORE ((MPI_Status*)0)
#define MPI_IN_PLACE ((void*)1)
#define MPI_INT 4
#define MPI_DOUBLE 8
#define MPI_LONG_LONG 9
#define MPI_SUM 1
#define MPI_MAX 2
#define MPI_MIN 3

namespace voigt_mpi_stub {
constexpr int kCart = 16; // a Cartesian communicator: kCart | periodic bits (1 << axis)
inline int bytes(MPI_Datatype t) { return t == MPI_INT ? 4 : 8; }
} // namespace voigt_mpi_stub

inline int MPI_Init(int*, char***) { return MPI_SUCCESS; }
inline int MPI_Finalize() { return MPI_SUCCESS; }
inline int MPI_Comm_rank(MPI_Comm, int* r) { return *r = 0, MPI_SUCCESS; }
inline int MPI_Comm_size(MPI_Comm, int* s) { return *s = 1, MPI_SUCCESS; }
inline int MPI_Comm_free(MPI_Comm* c) { return *c = MPI_COMM_NULL, MPI_SUCCESS; }
inline int MPI_Comm_split(MPI_Comm, int, int, MPI_Comm* c) { return *c = 1, MPI_SUCCESS; } // Grid::io
inline int MPI_Dims_create(int, int nd, int* dims) {
  for (int d = 0; d < nd; ++d)
    if (dims[d] <= 0) dims[d] = 1;
  return MPI_SUCCESS;
}
inline int MPI_Cart_create(MPI_Comm, int nd, const int*, const int* periods, int, MPI_Comm* c) {
  *c = voigt_mpi_stub::kCart;
  for (int d = 0; d < nd && d < 3; ++d)
    if (periods[d]) *c |= 1 << d;
  return MPI_SUCCESS;
}
inline int MPI_Cart_coords(MPI_Comm, int, int nd, int* coords) {
  for (int d = 0; d < nd; ++d) coords[d] = 0;
  return MPI_SUCCESS;
}
inline int MPI_Cart_shift(MPI_Comm c, int d, int, int* src, int* dst) {
  *src = *dst = (c & (1 << d)) ? 0 : MPI_PROC_NULL;
  return MPI_SUCCESS;
}
inline int MPI_Allreduce(const void* s, void* r, int n, MPI_Datatype t, MPI_Op, MPI_Comm) {
  if (s != MPI_IN_PLACE && s != r) std::memcpy(r, s, size_t(n) * voigt_mpi_stub::bytes(t));
  return MPI_SUCCESS;
}
inline int MPI_Sendrecv(const void* sb, int sc, MPI_Datatype st, int dest, int, void* rb, int, MPI_Datatype,
                        int source, int, MPI_Comm, MPI_Status*) {
  if (dest == 0 && source == 0) std::memcpy(rb, sb, size_t(sc) * voigt_mpi_stub::bytes(st)); // to oneself
  return MPI_SUCCESS;
}
inline double MPI_Wtime() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
