// Fast diagonalization of the exact projection operator at one density: see
// fast_diagonalization.hpp and kernels/fast_diag.hpp for the equations.
#include "solvers/fast_diagonalization.hpp"

#include <Teuchos_LAPACK.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace voigt {

namespace {

// Is any velocity component free at the owned nodes of one face (global node index
// `g` along axis e), away from the face's edges? Local share; the caller reduces.
int faceFree(const VecField& coef, const Grid& G, int e, int g) {
  int b[3], en[3];
  for (int d = 0; d < 3; ++d) {
    int lo = G.c0[d], hi = G.nodeHi(d);                       // owned nodes [lo, hi)
    if (d == e) {
      lo = g;
      hi = g + 1;
    } else if (!G.periodic[d]) {
      lo = std::max(lo, 1);
      hi = std::min(hi, G.n[d]);                                // face interior: 1 .. n - 1
    }
    if (d == e && (g < G.c0[d] || g >= G.nodeHi(d))) return 0;  // face not on this rank
    b[d] = G.local(d, lo);
    en[d] = G.local(d, hi);
    if (en[d] <= b[d]) return 0;
  }
  const double m = fdFaceMax(coef, b, en);
  return m > 0 ? 1 : 0;
}

// The 1-D factors along one axis of n cells: node rows kept (keepLo/keepHi for the face
// nodes of a bounded axis), K = D1^T W^-1 D1, E = A1^T W^-1 A1 + K/4 (diagonal), and
// V, lambda with K V = E V Lambda, V^T E V = I (LAPACK SYEV on E^-1/2 K E^-1/2).
void axisFactors(int n, bool periodic, bool keepLo, bool keepHi, std::vector<double>& V,
                 std::vector<double>& lam) {
  std::vector<double> K(n * n, 0.0), Md(n * n, 0.0);
  const int nodes = periodic ? n : n + 1;
  for (int a = 0; a < nodes; ++a) {
    const bool boundary = !periodic && (a == 0 || a == n);
    if (boundary && !((a == 0 && keepLo) || (a == n && keepHi))) continue;
    const double w = boundary ? 0.5 : 1.0;
    int cells[2] = {a - 1, a};        // node a sits between cells a - 1 and a
    const double sd[2] = {-1.0, 1.0};
    bool ex[2];
    for (int s = 0; s < 2; ++s) {
      if (periodic) cells[s] = (cells[s] + n) % n;
      ex[s] = periodic || (cells[s] >= 0 && cells[s] < n);
    }
    for (int s = 0; s < 2; ++s)
      for (int t = 0; t < 2; ++t)
        if (ex[s] && ex[t]) {
          K[cells[s] + n * cells[t]] += sd[s] * sd[t] / w;
          Md[cells[s] + n * cells[t]] += 0.25 / w;
        }
  }
  std::vector<double> E(n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double e = Md[i + n * j] + 0.25 * K[i + n * j];
      if (i == j) E[i] = e;
      else if (std::abs(e) > 1e-12) throw std::logic_error("fast diagonalization: E is not diagonal");
    }
  std::vector<double> C(n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) C[i + n * j] = K[i + n * j] / std::sqrt(E[i] * E[j]);
  lam.assign(n, 0.0);
  int lwork = std::max(1, 3 * n), info = 0;
  std::vector<double> work(lwork);
  Teuchos::LAPACK<int, double>().SYEV('V', 'U', n, C.data(), n, lam.data(), work.data(), lwork, &info);
  if (info != 0) throw std::runtime_error("fast diagonalization: LAPACK SYEV failed, info " + std::to_string(info));
  V.resize(n * n);
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < n; ++a) V[i + n * a] = C[i + n * a] / std::sqrt(E[i]);
}

} // namespace

FastDiagonalization::FastDiagonalization(const Grid& g, MPI_Comm comm) : g_(g), comm_(comm) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &size_);
  for (int d = 0; d < 3; ++d) n_[d] = g.n[d];
  const int mine[6] = {g.c0[0], g.c0[1], g.c0[2], g.ln[0], g.ln[1], g.ln[2]};
  if (rank_ == 0) boxes_.resize(6 * size_);
  MPI_Gather(mine, 6, MPI_INT, boxes_.data(), 6, MPI_INT, 0, comm_);
  if (rank_ == 0) {
    inv_ = Grid3("fd_inverse_eigenvalues", n_[0], n_[1], n_[2]);
    t1_ = Grid3("fd_t1", n_[0], n_[1], n_[2]);
    t2_ = Grid3("fd_t2", n_[0], n_[1], n_[2]);
    if (size_ > 1) {
      all_ = Grid3("fd_all", n_[0], n_[1], n_[2]);
      hostAll_ = Kokkos::create_mirror_view(all_);
    }
  }
}

void FastDiagonalization::setup(const VecField& coef) {
  const Grid& g = g_;
  int flags[6] = {0, 0, 0, 0, 0, 0};
  for (int e = 0; e < 3; ++e) {
    if (g.periodic[e]) continue;
    flags[2 * e] = faceFree(coef, g, e, 0);
    flags[2 * e + 1] = faceFree(coef, g, e, n_[e]);
  }
  MPI_Allreduce(MPI_IN_PLACE, flags, 6, MPI_INT, MPI_MAX, comm_);
  for (int e = 0; e < 3; ++e) {
    keep_[e][0] = flags[2 * e] != 0;
    keep_[e][1] = flags[2 * e + 1] != 0;
  }
  if (rank_ != 0) return;
  Kokkos::View<double* [3], MemSpace> lam("fd_lambda", std::max(n_[0], std::max(n_[1], n_[2])));
  auto lamH = Kokkos::create_mirror_view(lam);
  for (int e = 0; e < 3; ++e) {
    std::vector<double> V, l;
    axisFactors(n_[e], g.periodic[e], keep_[e][0], keep_[e][1], V, l);
    V_[e] = Dense("fd_V", n_[e], n_[e]);
    auto vh = Kokkos::create_mirror_view(V_[e]);
    for (int i = 0; i < n_[e]; ++i)
      for (int a = 0; a < n_[e]; ++a) vh(i, a) = V[i + n_[e] * a];
    Kokkos::deep_copy(V_[e], vh);
    for (int a = 0; a < n_[e]; ++a) lamH(a, e) = l[a];
  }
  Kokkos::deep_copy(lam, lamH);
  // Null modes of A0 (eigenvalue 0 up to round-off) get 0: A's own null space is removed
  // by the caller (ProjectedPrec), and a mode A0 lacks is never in range(A) exactly.
  fdInverseEigenvalues(inv_, lam, 1 / (g.h[0] * g.h[0]), 1 / (g.h[1] * g.h[1]), 1 / (g.h[2] * g.h[2]), 1e-10);
}

void FastDiagonalization::transform(const CGrid3& in, const Grid3& out) const {
  fdTransform<0, false>(in, t1_, V_[0]);
  fdTransform<1, false>(t1_, t2_, V_[1]);
  fdTransform<2, false>(t2_, t1_, V_[2]);
  fdScale(t1_, inv_, t2_);
  fdTransform<2, true>(t2_, t1_, V_[2]);
  fdTransform<1, true>(t1_, t2_, V_[1]);
  fdTransform<0, true>(t2_, out, V_[0]);
  Kokkos::fence();
}

void FastDiagonalization::apply(const ConstRowVector& r, const RowVector& z) const {
  if (size_ == 1) {
    const CGrid3 in(r.data(), n_[0], n_[1], n_[2]);
    const Grid3 out(z.data(), n_[0], n_[1], n_[2]);
    transform(in, out);
    return;
  }
  const int nloc = (int)g_.cellsOwned();
  Kokkos::View<double*, Kokkos::LayoutLeft, Kokkos::HostSpace> rh("fd_rows_host", nloc);
  Kokkos::deep_copy(rh, r);
  std::vector<int> counts, displs;
  if (rank_ == 0) {
    counts.resize(size_);
    displs.resize(size_);
    int off = 0;
    for (int p = 0; p < size_; ++p) {
      counts[p] = boxes_[6 * p + 3] * boxes_[6 * p + 4] * boxes_[6 * p + 5];
      displs[p] = off;
      off += counts[p];
    }
    recvBuf_.resize(off);
  }
  MPI_Gatherv(rh.data(), nloc, MPI_DOUBLE, recvBuf_.data(), counts.data(), displs.data(), MPI_DOUBLE, 0, comm_);
  if (rank_ == 0) {
    // Unpack every rank's box (rows i fastest) into the whole grid, transform, pack back.
    auto unpack = [&](bool in) {
      for (int p = 0; p < size_; ++p) {
        const int* b = &boxes_[6 * p];
        double* buf = recvBuf_.data() + displs[p];
        for (int k = 0; k < b[5]; ++k)
          for (int j = 0; j < b[4]; ++j)
            for (int i = 0; i < b[3]; ++i) {
              double& g = hostAll_(b[0] + i, b[1] + j, b[2] + k);
              double& l = buf[i + b[3] * (j + b[4] * k)];
              if (in) g = l;
              else l = g;
            }
      }
    };
    unpack(true);
    Kokkos::deep_copy(all_, hostAll_);
    transform(all_, all_);
    Kokkos::deep_copy(hostAll_, all_);
    unpack(false);
  }
  MPI_Scatterv(recvBuf_.data(), counts.data(), displs.data(), MPI_DOUBLE, rh.data(), nloc, MPI_DOUBLE, 0, comm_);
  Kokkos::deep_copy(z, rh);
}

} // namespace voigt
