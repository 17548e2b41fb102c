// Fast diagonalization of the exact projection operator at one density: see
// fast_diagonalization.hpp and kernels/fast_diag.hpp for the equations.
#include "solvers/fast_diagonalization.hpp"

#include <Teuchos_LAPACK.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/host_access.hpp"

namespace voigt {

namespace {

// Which velocity components are free at the owned nodes of one face (global node index
// `g` along axis e), away from the face's edges? Bit c set: component c free somewhere
// there. Local share; the caller reduces.
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
  int bits = 0;
  for (int c = 0; c < 3; ++c)
    if (fdFaceMax(coef, b, en, c) > 0) bits |= 1 << c;
  return bits;
}

// The 1-D factors along one axis of n cells: K = D1^T W^-1 D1 over the node rows where the
// axis' own velocity component is free (kK: the face nodes of a bounded axis, low and high),
// M = A1^T W^-1 A1 over those where the other two are (kM; a slip wall keeps them, a no-slip
// wall neither), E = M + K/4 (diagonal: interior nodes are in both sets, and a face node
// touches one cell), and V, lambda with K V = E V Lambda, V^T E V = I (LAPACK SYEV on
// E^-1/2 K E^-1/2). tri (bounded axes): K's diagonal and upper diagonal, M's the same (n each).
void axisFactors(int n, bool periodic, const bool kK[2], const bool kM[2], std::vector<double>& V,
                 std::vector<double>& lam, std::vector<double>& tri) {
  std::vector<double> K(n * n, 0.0), Md(n * n, 0.0);
  const int nodes = periodic ? n : n + 1;
  for (int a = 0; a < nodes; ++a) {
    const bool boundary = !periodic && (a == 0 || a == n);
    const bool inK = !boundary || kK[a == 0 ? 0 : 1], inM = !boundary || kM[a == 0 ? 0 : 1];
    if (!inK && !inM) continue;
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
          if (inK) K[cells[s] + n * cells[t]] += sd[s] * sd[t] / w;
          if (inM) Md[cells[s] + n * cells[t]] += 0.25 / w;
        }
  }
  std::vector<double> E(n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double e = Md[i + n * j] + 0.25 * K[i + n * j];
      if (i == j) {
        if (!(e > 0)) throw std::invalid_argument("fast diagonalization: a cell with no free node along an axis");
        E[i] = e;
      }
      else if (std::abs(e) > 1e-12) throw std::logic_error("fast diagonalization: E is not diagonal");
    }
  tri.assign(4 * n, 0.0); // M = E - K/4 with E diagonal: M's off-diagonals are -K's/4
  for (int i = 0; i < n; ++i) {
    tri[i] = K[i + n * i];
    tri[n + i] = i + 1 < n ? K[i + n * (i + 1)] : 0.0;
    tri[2 * n + i] = E[i] - 0.25 * K[i + n * i];
    tri[3 * n + i] = i + 1 < n ? -0.25 * K[i + n * (i + 1)] : 0.0;
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

namespace {
// Range [lo, lo + n) of part p of m items split over `size` parts as evenly as possible.
void split(int m, int size, int p, int& lo, int& n) {
  lo = int(1LL * m * p / size);
  n = int(1LL * m * (p + 1) / size) - lo;
}
} // namespace

std::array<int, 2> FastDiagonalization::pencilGrid(int size, const int n[3], int s, int c) {
  const int cap2 = std::min(n[s], n[c]), cap1 = std::min(n[0], n[c]);
  if (size <= std::min(cap2, kSlabRanks)) return {1, size};
  int best = 0; // the divisor nearest sqrt(size) that fits, the smaller of a pair
  for (int p1 = 1; p1 <= cap1 && p1 * p1 <= size; ++p1)
    if (size % p1 == 0 && size / p1 <= cap2) best = p1;
  if (best > 0) return {best, size / best};
  return {std::max(1, std::min(cap1, size / cap2)), cap2}; // no exact fit: the rest idle
}

FastDiagonalization::FastDiagonalization(const Grid& g, MPI_Comm comm, bool single, bool tridiagonal, int p1)
    : g_(g), single_(single), comm_(comm) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &size_);
  for (int d = 0; d < 3; ++d) n_[d] = g.n[d];
  // The solve axis: y or z (lines vectorise along x), bounded (a periodic K is cyclic), the
  // longer (its transforms cost the most); on a tie z, whose slabs are the layout's as before.
  if (tridiagonal)
    for (int e : {2, 1})
      if (!g.periodic[e] && n_[e] >= 2 && (s_ < 0 || n_[e] > n_[s_])) s_ = e;
  c_ = s_ == 1 ? 2 : 1;
  const int s = s_ >= 0 ? s_ : 2; // the pencils' third axis
  if (p1 > 0) p1_ = p1, p2_ = std::max(1, size_ / p1);
  else {
    const auto pg = pencilGrid(size_, n_, s, c_);
    p1_ = pg[0], p2_ = pg[1];
  }
  // Box of rank p in a layout whose axes e1, e2 are split p1 and p2 ways (p = a + p1 b).
  auto pencil = [&](int p, int e1, int e2) {
    Box b;
    b.n = {n_[0], n_[1], n_[2]};
    if (p >= p1_ * p2_) return Box{}; // idle in the passes
    split(n_[e1], p1_, p % p1_, b.lo[e1], b.n[e1]);
    split(n_[e2], p2_, p / p1_, b.lo[e2], b.n[e2]);
    if (b.size() == 0) b.n = {0, 0, 0};
    return b;
  };
  std::vector<Box> blocks(size_), outer(size_), mid(size_), inner(size_);
  const int mine[6] = {g.c0[0], g.c0[1], g.c0[2], g.ln[0], g.ln[1], g.ln[2]};
  std::vector<int> all(6 * size_);
  MPI_Allgather(mine, 6, MPI_INT, all.data(), 6, MPI_INT, comm_);
  for (int p = 0; p < size_; ++p) {
    blocks[p].lo = {all[6 * p], all[6 * p + 1], all[6 * p + 2]};
    blocks[p].n = {all[6 * p + 3], all[6 * p + 4], all[6 * p + 5]};
    outer[p] = pencil(p, c_, s);
    mid[p] = pencil(p, 0, s);
    inner[p] = pencil(p, 0, c_);
  }
  outer_ = outer[rank_];
  mid_ = mid[rank_];
  inner_ = inner[rank_];
  if (size_ > 1) {
    toOuter_ = std::make_unique<Redistribute>(comm_, blocks, outer);
    if (p1_ > 1) {
      toMid_ = std::make_unique<Redistribute>(comm_, outer, mid);
      toInner_ = std::make_unique<Redistribute>(comm_, mid, inner);
    } else {
      toInner_ = std::make_unique<Redistribute>(comm_, outer, inner);
    }
  }
  if (s_ >= 0) {
    cp_ = Grid3("fd_tri_c", inner_.n[0], inner_.n[1], inner_.n[2]);
    dp_ = Grid3("fd_tri_d", inner_.n[0], inner_.n[1], inner_.n[2]);
  }
  if (single_) allocate(f_);
  else allocate(d_);
}

void FastDiagonalization::findSingularLines(const Kokkos::View<double* [3], MemSpace>::HostMirror& lam, double cut) {
  // Lines (i, o) of the inner slab whose block T = sigma M_s + tau K_s has an eigenvalue at
  // or below the cut (fd_tridiagonal.hpp): A0's null modes, few (the constant and
  // checkerboard modes of the transformed axes).
  std::vector<int> found;
  const int no = inner_.n[c_], off = inner_.lo[c_], ni = inner_.n[0], offA = inner_.lo[0];
  for (int o = 0; o < no; ++o)
    for (int i = 0; i < ni; ++i) {
      double sigma, tau;
      fd_detail::lineCoef(lam(i + offA, 0), lam(o + off, c_), ih_[0], ih_[c_], ih_[s_], sigma, tau);
      double low = 1e300;
      for (int b = 0; b < n_[s_]; ++b) low = std::min(low, sigma * (1 - 0.25 * lam(b, s_)) + tau * lam(b, s_));
      if (low <= cut) found.insert(found.end(), {i, o});
    }
  const int nl = (int)found.size() / 2;
  lines_ = Lines2("fd_singular_lines", nl);
  auto h = hostMirror(lines_);
  for (int l = 0; l < nl; ++l) h(l, 0) = found[2 * l], h(l, 1) = found[2 * l + 1];
  toDevice(lines_, h, "solver_setup");
  lineWork_ = Kokkos::View<double**, Kokkos::LayoutRight, MemSpace>("fd_line_work", nl, 3 * n_[s_]);
}

void FastDiagonalization::setup(const VecField& coef) {
  const Grid& g = g_;
  int flags[6] = {0, 0, 0, 0, 0, 0}; // per axis and face: bits of the free components
  for (int e = 0; e < 3; ++e) {
    if (g.periodic[e]) continue;
    flags[2 * e] = faceFree(coef, g, e, 0);
    flags[2 * e + 1] = faceFree(coef, g, e, n_[e]);
  }
  MPI_Allreduce(MPI_IN_PLACE, flags, 6, MPI_INT, MPI_BOR, comm_);
  for (int e = 0; e < 3; ++e)
    for (int side = 0; side < 2; ++side) {
      const int f = flags[2 * e + side];
      keepK_[e][side] = (f >> e) & 1;
      keepM_[e][side] = (f & ~(1 << e)) != 0; // either tangential component free
    }
  // Every rank builds the 1-D factors (small dense eigenproblems, identical everywhere).
  Kokkos::View<double* [3], MemSpace> lam("fd_lambda", std::max(n_[0], std::max(n_[1], n_[2])));
  auto lamH = hostMirror(lam);
  std::vector<double> l[3];
  for (int e = 0; e < 3; ++e) {
    const int n = n_[e];
    std::vector<double> V, tri;
    axisFactors(n, g.periodic[e], keepK_[e], keepM_[e], V, l[e], tri);
    if (e == s_) { // the solve axis: its tridiagonal factors; not folded (its V serves the singular lines)
      tri_ = Table4("fd_tri", n, 4);
      auto th = hostMirror(tri_);
      for (int c = 0; c < 4; ++c)
        for (int q = 0; q < n; ++q) th(q, c) = tri[c * n + q];
      toDevice(tri_, th, "solver_setup");
    }
    // A mirror-symmetric axis (both faces of one kind) has even and odd eigenvectors: fold
    // it (fdFold) and keep V block diagonal, even modes first, to halve the transform.
    std::vector<int> order(n);
    for (int a = 0; a < n; ++a) order[a] = a;
    nb_[e] = n;
    if (e != s_ && !g.periodic[e] && keepK_[e][0] == keepK_[e][1] && keepM_[e][0] == keepM_[e][1] && n > 1) {
      std::vector<int> even, odd;
      bool clean = true;
      for (int a = 0; a < n && clean; ++a) {
        double sym = 0, anti = 0, big = 0;
        for (int q = 0; q < n; ++q) {
          const double v = V[q + n * a], w = V[n - 1 - q + n * a];
          sym = std::max(sym, std::abs(v - w));
          anti = std::max(anti, std::abs(v + w));
          big = std::max(big, std::abs(v));
        }
        if (sym <= 1e-9 * big) even.push_back(a);
        else if (anti <= 1e-9 * big) odd.push_back(a);
        else clean = false;
      }
      if (clean && (int)even.size() == (n + 1) / 2) {
        order = even;
        order.insert(order.end(), odd.begin(), odd.end());
        nb_[e] = (n + 1) / 2;
      }
    }
    V_[e] = Dense("fd_V", n, n);
    auto vh = hostMirror(V_[e]);
    Kokkos::deep_copy(vh, 0.0);
    const int h = nb_[e];
    for (int c = 0; c < n; ++c) {
      const int a = order[c];
      if (h == n) {
        for (int q = 0; q < n; ++q) vh(q, c) = V[q + n * a];
      } else if (c < h) { // even mode: rows 0 .. h-1 of the folded sums
        for (int q = 0; q < h; ++q) vh(q, c) = V[q + n * a];
      } else {            // odd mode: rows h .. of the folded differences
        for (int q = 0; q < n / 2; ++q) vh(h + q, c) = V[q + n * a];
      }
    }
    toDevice(V_[e], vh, "solver_setup");
    std::vector<double> lo(n);
    for (int c = 0; c < n; ++c) lo[c] = l[e][order[c]];
    l[e] = lo;
    for (int a = 0; a < n; ++a) lamH(a, e) = l[e][a];
    lam_[e] = Table("fd_lambda_axis", n);
    auto th = hostMirror(lam_[e]);
    for (int a = 0; a < n; ++a) th(a) = l[e][a];
    toDevice(lam_[e], th, "solver_setup");
  }
  toDevice(lam, lamH, "solver_setup");
  // Null modes of A0 (eigenvalue 0 up to round-off) get 0: A's own null space is removed
  // by the caller (ProjectedPrec), and a mode A0 lacks is never in range(A) exactly. The
  // largest eigenvalue is the largest of each 1-D factor's products (all factors >= 0).
  const double ih[3] = {1 / (g.h[0] * g.h[0]), 1 / (g.h[1] * g.h[1]), 1 / (g.h[2] * g.h[2])};
  double dmax = 0;
  for (double l0 : l[0])
    for (double l1 : l[1])
      for (double l2 : l[2]) {
        const double m0 = 1 - 0.25 * l0, m1 = 1 - 0.25 * l1, m2 = 1 - 0.25 * l2;
        dmax = std::max(dmax, ih[0] * l0 * m1 * m2 + ih[1] * m0 * l1 * m2 + ih[2] * m0 * m1 * l2);
      }
  for (int d = 0; d < 3; ++d) ih_[d] = ih[d];
  cut_ = 1e-10 * dmax;
  Grid3 inv;
  if (s_ < 0) {
    inv = Grid3("fd_inverse_eigenvalues", inner_.n[0], inner_.n[1], inner_.n[2]);
    fdInverseEigenvalues(inv, lam, ih[0], ih[1], ih[2], inner_.lo[1], cut_, inner_.lo[0]);
  } else {
    VsT_ = Dense("fd_VsT", n_[s_], n_[s_]);
    fdTransposeDense(V_[s_], VsT_);
    findSingularLines(lamH, cut_);
  }
  // The passes of one application (they depend on which axes are folded): built here, once.
  if (single_) build(f_, inv);
  else build(d_, inv);
}

} // namespace voigt
