// One application of the fast diagonalization, z = A0^+ r = V (Lambda3^+ (V^T r)), or with a
// solve axis s (V_a (x) V_c) T^-1 (V_a^T (x) V_c^T) r: the passes of kernels/fast_diag.hpp and
// fd_tridiagonal.hpp in order, in double or (mixed precision) in float, and on more than one
// rank the moves between blocks, outer and inner slabs (fast_diagonalization.hpp).
#include "solvers/fast_diagonalization.hpp"

#include "core/host_access.hpp"

#include <string>
#include <type_traits>

namespace voigt {

namespace {

template <class T>
using Rows = Kokkos::View<T*, Kokkos::LayoutLeft, MemSpace>;

// Runs ops one after another from src to dst through the work buffers A and B (each op
// reads one array and writes another; src and dst may be A or B).
template <class T, class Op>
void chain(const std::vector<Op>& ops, const CGrid3Of<T>& src, const Grid3Of<T>& dst, const Grid3Of<T>& A,
           const Grid3Of<T>& B) {
  const T* cur = src.data();
  CGrid3Of<T> in = src;
  for (size_t i = 0; i < ops.size(); ++i) {
    Grid3Of<T> out = i + 1 == ops.size() ? dst : (cur == A.data() ? B : A);
    const bool alias = out.data() == cur;
    if (alias) out = cur == A.data() ? B : A;
    ops[i](in, out);
    if (alias) Kokkos::deep_copy(dst, out), out = dst;
    in = out;
    cur = out.data();
  }
  Kokkos::fence();
}

} // namespace

template <class T>
void FastDiagonalization::allocate(Passes<T>& P) const {
  const char* tag = sizeof(T) == sizeof(float) ? "fd_f_" : "fd_";
  auto grid = [&](const char* name, const Box& b) {
    return Grid3Of<T>(std::string(tag) + name, b.n[0], b.n[1], b.n[2]);
  };
  if (size_ > 1) {
    P.o1 = grid("o1", outer_);
    P.o2 = grid("o2", outer_);
    P.i1 = grid("i1", inner_);
    P.i2 = grid("i2", inner_);
    for (const auto& v : {P.o1, P.o2, P.i1, P.i2}) guard(v);
    P.oh = hostMirror(P.o1);
    P.ih = hostMirror(P.i1);
    if (toMid_) {
      P.m1 = grid("m1", mid_);
      P.m2 = grid("m2", mid_);
      guard(P.m1), guard(P.m2);
      P.mh = hostMirror(P.m1);
    }
    P.rowsH.resize(g_.cellsOwned());
  } else {
    P.o1 = grid("t1", outer_);
    P.o2 = grid("t2", outer_);
    P.i1 = P.o1;
    P.i2 = P.o2;
    guard(P.o1), guard(P.o2);
  }
  P.r = Rows<T>(std::string(tag) + "rows_in", g_.cellsOwned());
  P.x = Rows<T>(std::string(tag) + "rows_out", g_.cellsOwned());
  guard(P.r), guard(P.x);
}

template <class T>
void FastDiagonalization::build(Passes<T>& P, const Grid3& inv) const {
  if constexpr (std::is_same<T, double>::value) { // the double passes use them as they are
    for (int e = 0; e < 3; ++e) P.V[e] = V_[e];
    P.inv = inv;
  } else {
    for (int e = 0; e < 3; ++e) {
      P.V[e] = DenseOf<T>("fd_V", n_[e], n_[e]);
      fdConvertDense<T>(V_[e], P.V[e]);
    }
    P.inv = Grid3Of<T>("fd_inverse_eigenvalues", inv.extent(0), inv.extent(1), inv.extent(2));
    fdConvert<double, T>(inv, P.inv);
    Kokkos::fence();
  }
  using CG = CGrid3Of<T>;
  using G = Grid3Of<T>;
  const int nb0 = nb_[0], nb1 = nb_[1], nb2 = nb_[2], n0 = n_[0], n1 = n_[1], n2 = n_[2];
  const DenseOf<T> V0 = P.V[0], V1 = P.V[1], V2 = P.V[2];
  const CG inverse = P.inv;
  for (auto* ops : {&P.fwd, &P.mid, &P.inner, &P.midBack, &P.back}) ops->clear();
  const bool foldX = nb0 < n0;
  const bool pencils = p1_ > 1; // the c transform on its own pencils (mid, midBack)
#if !(defined(KOKKOS_ENABLE_CUDA) || defined(KOKKOS_ENABLE_HIP) || defined(KOKKOS_ENABLE_SYCL))
  // Host backends: the x transform and the folds around it as one pass (fdLinePairs); on
  // slabs the fold along c too.
  if (!kOnDevice && n0 <= kFdLineMax) {
    const DenseOf<T> fw = fdPadRows(fdTransposed(V0), nb0), bw = fdPadRows(V0, nb0);
    if (s_ == 1) { // x and z on y-slabs; y solved on z-slabs
      const bool foldC = nb2 < n2 && !pencils;
      P.fwd.push_back([=](const CG& i, const G& o) { fdLinePairs<2, false>(i, o, fw, nb0, foldX, foldC); });
      P.back.push_back([=](const CG& i, const G& o) { fdLinePairs<2, true>(i, o, bw, nb0, foldX, foldC); });
    } else {
      const bool foldC = nb1 < n1 && !pencils;
      P.fwd.push_back([=](const CG& i, const G& o) { fdLinePairs<1, false>(i, o, fw, nb0, foldX, foldC); });
      P.back.push_back([=](const CG& i, const G& o) { fdLinePairs<1, true>(i, o, bw, nb0, foldX, foldC); });
    }
    if (!pencils) { // the c transform next to it, on the same slab
      if (s_ == 1) {
        P.mid.push_back([=](const CG& i, const G& o) { fdTransform<2, false>(i, o, V2, nb2); });
        P.midBack.push_back([=](const CG& i, const G& o) { fdTransform<2, true>(i, o, V2, nb2); });
      } else {
        P.mid.push_back([=](const CG& i, const G& o) { fdTransform<1, false>(i, o, V1, nb1); });
        P.midBack.push_back([=](const CG& i, const G& o) { fdTransform<1, true>(i, o, V1, nb1); });
      }
    }
  }
#endif
  if (P.fwd.empty()) { // device backends: one pass each
    if (foldX) P.fwd.push_back([](const CG& i, const G& o) { fdFold<0>(i, o); });
    P.fwd.push_back([=](const CG& i, const G& o) { fdTransform<0, false>(i, o, V0, nb0); });
    P.back.push_back([=](const CG& i, const G& o) { fdTransform<0, true>(i, o, V0, nb0); });
    if (foldX) P.back.push_back([](const CG& i, const G& o) { fdUnfold<0>(i, o); });
  }
  if (P.mid.empty()) { // the c transform with its folds
    if (s_ == 1) { // x and z transformed; y solved
      if (nb2 < n2) P.mid.push_back([](const CG& i, const G& o) { fdFold<2>(i, o); });
      P.mid.push_back([=](const CG& i, const G& o) { fdTransform<2, false>(i, o, V2, nb2); });
      P.midBack.push_back([=](const CG& i, const G& o) { fdTransform<2, true>(i, o, V2, nb2); });
      if (nb2 < n2) P.midBack.push_back([](const CG& i, const G& o) { fdUnfold<2>(i, o); });
    } else {       // x and y transformed; z solved, or transformed and scaled
      if (nb1 < n1) P.mid.push_back([](const CG& i, const G& o) { fdFold<1>(i, o); });
      P.mid.push_back([=](const CG& i, const G& o) { fdTransform<1, false>(i, o, V1, nb1); });
      P.midBack.push_back([=](const CG& i, const G& o) { fdTransform<1, true>(i, o, V1, nb1); });
      if (nb1 < n1) P.midBack.push_back([](const CG& i, const G& o) { fdUnfold<1>(i, o); });
    }
  }
  if (!pencils) { // one slab: x then c forward, c then x back
    P.fwd.insert(P.fwd.end(), P.mid.begin(), P.mid.end());
    P.back.insert(P.back.begin(), P.midBack.begin(), P.midBack.end());
    P.mid.clear();
    P.midBack.clear();
  }
  if (s_ < 0) {
    if (nb2 < n2) P.inner.push_back([](const CG& i, const G& o) { fdFold<2>(i, o); });
    P.inner.push_back([=](const CG& i, const G& o) { fdTransform<2, false>(i, o, V2, nb2); });
    P.inner.push_back([=](const CG& i, const G& o) { fdScale<T>(i, inverse, o); });
    P.inner.push_back([=](const CG& i, const G& o) { fdTransform<2, true>(i, o, V2, nb2); });
    if (nb2 < n2) P.inner.push_back([](const CG& i, const G& o) { fdUnfold<2>(i, o); });
  } else {
    const Grid3 cp = cp_, dp = dp_;
    const Table4 tri = tri_;
    const Table la = lam_[0], lc = lam_[c_], ls = lam_[s_];
    const Lines2 lines = lines_;
    const Dense Vs = V_[s_], VsT = VsT_; // the solve axis is not folded: V_[s_] is its whole eigenvector matrix
    const auto work = lineWork_;
    const double iha = ih_[0], ihc = ih_[c_], ihs = ih_[s_], cut = cut_;
    const int off = inner_.lo[c_], offA = inner_.lo[0];
    if (s_ == 1)
      P.inner.push_back([=](const CG& i, const G& o) {
        fdTridiagonal<1, T>(i, o, cp, dp, tri, la, lc, iha, ihc, ihs, off, offA);
        fdDenseLines<1, T>(i, o, lines, Vs, VsT, ls, la, lc, iha, ihc, ihs, off, cut, work, offA);
      });
    else
      P.inner.push_back([=](const CG& i, const G& o) {
        fdTridiagonal<2, T>(i, o, cp, dp, tri, la, lc, iha, ihc, ihs, off, offA);
        fdDenseLines<2, T>(i, o, lines, Vs, VsT, ls, la, lc, iha, ihc, ihs, off, cut, work, offA);
      });
  }
  P.all = P.fwd;
  for (const auto* ops : {&P.mid, &P.inner, &P.midBack, &P.back}) P.all.insert(P.all.end(), ops->begin(), ops->end());
}

template <class T>
void FastDiagonalization::run(const Passes<T>& P, const Kokkos::View<const T*, Kokkos::LayoutLeft, MemSpace>& r,
                              const Rows<T>& z) const {
  if (size_ == 1) {
    const CGrid3Of<T> in(r.data(), n_[0], n_[1], n_[2]);
    const Grid3Of<T> out(z.data(), n_[0], n_[1], n_[2]);
    chain(P.all, in, out, P.o1, P.o2);
    return;
  }
  // Rows are this rank's block, i fastest: the block layout Redistribute expects.
  const Kokkos::View<T*, Kokkos::LayoutLeft, Kokkos::HostSpace, Kokkos::MemoryUnmanaged> rh(P.rowsH.data(),
                                                                                           P.rowsH.size());
  // Every move goes through host memory (MPI here is not device-aware): on a device each
  // deep_copy below crosses the bus; counted as what it would move.
  auto stage = [](const auto& dst, const auto& src) {
    host_access::countCopy("fd_transpose_staging", dst.span() * sizeof(T));
    Kokkos::deep_copy(dst, src);
  };
  stage(rh, r);
  toOuter_->forward(P.rowsH.data(), P.oh.data());
  stage(P.o1, P.oh);
  chain(P.fwd, CGrid3Of<T>(P.o1), P.o2, P.o1, P.o2);
  stage(P.oh, P.o2);
  if (toMid_) { // x pencils -> c pencils, the c transform
    toMid_->forward(P.oh.data(), P.mh.data());
    stage(P.m1, P.mh);
    chain(P.mid, CGrid3Of<T>(P.m1), P.m2, P.m1, P.m2);
    stage(P.mh, P.m2);
  }
  toInner_->forward(toMid_ ? P.mh.data() : P.oh.data(), P.ih.data());
  stage(P.i1, P.ih);
  chain(P.inner, CGrid3Of<T>(P.i1), P.i2, P.i1, P.i2);
  stage(P.ih, P.i2);
  if (toMid_) {
    toInner_->backward(P.ih.data(), P.mh.data());
    stage(P.m1, P.mh);
    chain(P.midBack, CGrid3Of<T>(P.m1), P.m2, P.m1, P.m2);
    stage(P.mh, P.m2);
    toMid_->backward(P.mh.data(), P.oh.data());
  } else {
    toInner_->backward(P.ih.data(), P.oh.data());
  }
  stage(P.o1, P.oh);
  chain(P.back, CGrid3Of<T>(P.o1), P.o2, P.o1, P.o2);
  stage(P.oh, P.o2);
  toOuter_->backward(P.oh.data(), P.rowsH.data());
  stage(z, rh);
}

std::array<long long, 2> FastDiagonalization::traffic() const {
  std::array<long long, 2> t{0, 0};
  const long long bytes = single_ ? sizeof(float) : sizeof(double);
  for (const auto* m : {toOuter_.get(), toMid_.get(), toInner_.get()})
    if (m) {
      const auto f = m->sent(false), b = m->sent(true);
      t[0] += f[0] + b[0];
      t[1] += (f[1] + b[1]) * bytes;
    }
  return t;
}

// Used by setup and the constructor (fast_diagonalization.cpp).
template void FastDiagonalization::allocate(Passes<double>&) const;
template void FastDiagonalization::allocate(Passes<float>&) const;
template void FastDiagonalization::build(Passes<double>&, const Grid3&) const;
template void FastDiagonalization::build(Passes<float>&, const Grid3&) const;

void FastDiagonalization::apply(const ConstRowVector& r, const RowVector& z) const {
  if (!single_) return run(d_, r, z);
  const size_t n = g_.cellsOwned();
  fdConvertRows<double, float>(r, f_.r, n);
  run(f_, Kokkos::View<const float*, Kokkos::LayoutLeft, MemSpace>(f_.r), f_.x);
  fdConvertRows<float, double>(f_.x, z, n);
  Kokkos::fence();
}

void FastDiagonalization::applyMasked(const ConstRowVector& x, const Kokkos::View<int*, MemSpace>& ident, double alpha,
                                      double beta, const RowVector& y) const {
  const int n = int(g_.cellsOwned());
  auto ends = [&](const auto& P) {
    using T = typename std::remove_reference_t<decltype(P.r)>::value_type;
    fdMaskIn<T>(x, ident, P.r, n);
    run(P, Kokkos::View<const T*, Kokkos::LayoutLeft, MemSpace>(P.r), P.x);
    fdMaskOut<T>(alpha, Kokkos::View<const T*, Kokkos::LayoutLeft, MemSpace>(P.x), ident, beta, y, n);
  };
  if (single_) ends(f_);
  else ends(d_);
}

} // namespace voigt
