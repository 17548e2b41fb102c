// One application of the fast diagonalization, z = A0^+ r = V (Lambda3^+ (V^T r)): the passes of
// kernels/fast_diag.hpp in order, in double or (mixed precision) in float, and on more than one
// rank the moves between blocks, z-slabs and y-slabs (fast_diagonalization.hpp).
#include "solvers/fast_diagonalization.hpp"

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
    P.z1 = grid("z1", zs_);
    P.z2 = grid("z2", zs_);
    P.y1 = grid("y1", ys_);
    P.y2 = grid("y2", ys_);
    P.zh = Kokkos::create_mirror_view(P.z1);
    P.yh = Kokkos::create_mirror_view(P.y1);
    P.rowsH.resize(g_.cellsOwned());
  } else {
    P.z1 = grid("t1", zs_);
    P.z2 = grid("t2", zs_);
    P.y1 = P.z1;
    P.y2 = P.z2;
  }
  if (!std::is_same<T, double>::value) {
    P.r = Rows<T>(std::string(tag) + "rows_in", g_.cellsOwned());
    P.x = Rows<T>(std::string(tag) + "rows_out", g_.cellsOwned());
  }
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
  P.xy.clear();
  P.z.clear();
  P.yx.clear();
  if (nb0 < n0) P.xy.push_back([](const CG& i, const G& o) { fdFold<0>(i, o); });
  P.xy.push_back([=](const CG& i, const G& o) { fdTransform<0, false>(i, o, V0, nb0); });
  if (nb1 < n1) P.xy.push_back([](const CG& i, const G& o) { fdFold<1>(i, o); });
  P.xy.push_back([=](const CG& i, const G& o) { fdTransform<1, false>(i, o, V1, nb1); });
  if (nb2 < n2) P.z.push_back([](const CG& i, const G& o) { fdFold<2>(i, o); });
  P.z.push_back([=](const CG& i, const G& o) { fdTransform<2, false>(i, o, V2, nb2); });
  P.z.push_back([=](const CG& i, const G& o) { fdScale<T>(i, inverse, o); });
  P.z.push_back([=](const CG& i, const G& o) { fdTransform<2, true>(i, o, V2, nb2); });
  if (nb2 < n2) P.z.push_back([](const CG& i, const G& o) { fdUnfold<2>(i, o); });
  P.yx.push_back([=](const CG& i, const G& o) { fdTransform<1, true>(i, o, V1, nb1); });
  if (nb1 < n1) P.yx.push_back([](const CG& i, const G& o) { fdUnfold<1>(i, o); });
  P.yx.push_back([=](const CG& i, const G& o) { fdTransform<0, true>(i, o, V0, nb0); });
  if (nb0 < n0) P.yx.push_back([](const CG& i, const G& o) { fdUnfold<0>(i, o); });
  P.all = P.xy;
  P.all.insert(P.all.end(), P.z.begin(), P.z.end());
  P.all.insert(P.all.end(), P.yx.begin(), P.yx.end());
}

template <class T>
void FastDiagonalization::run(const Passes<T>& P, const Kokkos::View<const T*, Kokkos::LayoutLeft, MemSpace>& r,
                              const Rows<T>& z) const {
  if (size_ == 1) {
    const CGrid3Of<T> in(r.data(), n_[0], n_[1], n_[2]);
    const Grid3Of<T> out(z.data(), n_[0], n_[1], n_[2]);
    chain(P.all, in, out, P.z1, P.z2);
    return;
  }
  // Rows are this rank's block, i fastest: the block layout Redistribute expects.
  const Kokkos::View<T*, Kokkos::LayoutLeft, Kokkos::HostSpace, Kokkos::MemoryUnmanaged> rh(P.rowsH.data(),
                                                                                           P.rowsH.size());
  Kokkos::deep_copy(rh, r);
  toZ_->forward(P.rowsH.data(), P.zh.data());
  Kokkos::deep_copy(P.z1, P.zh);
  chain(P.xy, CGrid3Of<T>(P.z1), P.z2, P.z1, P.z2);
  Kokkos::deep_copy(P.zh, P.z2);
  zToY_->forward(P.zh.data(), P.yh.data());
  Kokkos::deep_copy(P.y1, P.yh);
  chain(P.z, CGrid3Of<T>(P.y1), P.y2, P.y1, P.y2);
  Kokkos::deep_copy(P.yh, P.y2);
  zToY_->backward(P.yh.data(), P.zh.data());
  Kokkos::deep_copy(P.z1, P.zh);
  chain(P.yx, CGrid3Of<T>(P.z1), P.z2, P.z1, P.z2);
  Kokkos::deep_copy(P.zh, P.z2);
  toZ_->backward(P.zh.data(), P.rowsH.data());
  Kokkos::deep_copy(z, rh);
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

} // namespace voigt
