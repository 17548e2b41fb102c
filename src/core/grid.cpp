#include "core/grid.hpp"

#include <stdexcept>
#include <string>

namespace voigt {

Grid makeGrid(MPI_Comm world, std::array<int, 3> cells, std::array<double, 3> lo,
              std::array<double, 3> hi, std::array<bool, 3> periodic, std::array<int, 3> dims) {
  Grid g;
  g.n = cells;
  g.lo = lo;
  g.hi = hi;
  g.periodic = periodic;
  for (int d = 0; d < 3; ++d) g.h[d] = (hi[d] - lo[d]) / cells[d];

  int size = 1;
  MPI_Comm_size(world, &size);
  int req[3] = {dims[0], dims[1], dims[2]};
  MPI_Dims_create(size, 3, req);
  int per[3] = {periodic[0], periodic[1], periodic[2]};
  MPI_Cart_create(world, 3, req, per, 0, &g.comm);
  MPI_Comm_rank(g.comm, &g.rank);
  MPI_Comm_size(g.comm, &g.size);
  int crd[3];
  MPI_Cart_coords(g.comm, g.rank, 3, crd);
  for (int d = 0; d < 3; ++d) {
    g.dims[d] = req[d];
    g.coords[d] = crd[d];
    MPI_Cart_shift(g.comm, d, 1, &g.nbrLo[d], &g.nbrHi[d]);
    // Even split, remainder to the first ranks.
    int base = cells[d] / req[d], rem = cells[d] % req[d];
    g.c0[d] = crd[d] * base + std::min(crd[d], rem);
    g.ln[d] = base + (crd[d] < rem ? 1 : 0);
    g.c1[d] = g.c0[d] + g.ln[d];
    if (g.ln[d] < g.ng)
      throw std::runtime_error("grid: " + std::to_string(cells[d]) + " cells on axis " +
                               std::to_string(d) + " cannot be split over " + std::to_string(req[d]) +
                               " ranks (each needs at least " + std::to_string(g.ng) + " cells)");
    g.ext[d] = g.ln[d] + 2 * g.ng + 1;
  }
  return g;
}

void freeGrid(Grid& g) {
  if (g.comm != MPI_COMM_NULL) MPI_Comm_free(&g.comm);
  g.comm = MPI_COMM_NULL;
}

} // namespace voigt
