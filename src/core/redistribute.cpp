// Box-to-box redistribution of a cell array: see redistribute.hpp.
#include "core/redistribute.hpp"

#include <Kokkos_Core.hpp>

#include <algorithm>
#include <climits>
#include <stdexcept>
#include <utility>

namespace voigt {

namespace {

Box intersect(const Box& a, const Box& b) {
  Box r;
  for (int d = 0; d < 3; ++d) {
    r.lo[d] = std::max(a.lo[d], b.lo[d]);
    const int hi = std::min(a.lo[d] + a.n[d], b.lo[d] + b.n[d]);
    r.n[d] = std::max(0, hi - r.lo[d]);
  }
  if (r.size() == 0) r.n = {0, 0, 0};
  return r;
}

// Copies the part `p` between a box array (LayoutLeft in `owner`'s extents) and a packed
// buffer (LayoutLeft in p's extents). toBuf: array -> buffer.
template <class T>
void copyPart(const Box& owner, const Box& p, T* arr, T* buf, bool toBuf) {
  using HostGrid = Kokkos::View<T***, Kokkos::LayoutLeft, Kokkos::HostSpace, Kokkos::MemoryUnmanaged>;
  const HostGrid A(arr, owner.n[0], owner.n[1], owner.n[2]), B(buf, p.n[0], p.n[1], p.n[2]);
  auto range = [&](int d) {
    const int o = p.lo[d] - owner.lo[d];
    return std::make_pair(o, o + p.n[d]);
  };
  const auto sub = Kokkos::subview(A, range(0), range(1), range(2));
  if (toBuf) Kokkos::deep_copy(B, sub);
  else Kokkos::deep_copy(sub, B);
}

} // namespace

Redistribute::Redistribute(MPI_Comm comm, const std::vector<Box>& src, const std::vector<Box>& dst) : comm_(comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  mySrc_ = src[rank];
  myDst_ = dst[rank];
  std::vector<int> to, from; // partners, in rank order
  for (int p = 0; p < size; ++p) {
    const Box s = intersect(mySrc_, dst[p]);
    const Box r = intersect(src[p], myDst_);
    if (s.size() > INT_MAX || r.size() > INT_MAX) throw std::overflow_error("Redistribute: a part of over 2^31 cells");
    if (s.size() > 0) sends_.push_back({s, p}), sendCount_.push_back((int)s.size()), to.push_back(p);
    if (r.size() > 0) recvs_.push_back({r, p}), recvCount_.push_back((int)r.size()), from.push_back(p);
  }
  auto displ = [](const std::vector<int>& count, std::vector<int>& d) {
    d.assign(count.size(), 0);
    for (size_t p = 1; p < count.size(); ++p) {
      if (1LL * d[p - 1] + count[p - 1] > INT_MAX)
        throw std::overflow_error("Redistribute: more than 2^31 cells a rank (MPI int counts)");
      d[p] = d[p - 1] + count[p - 1];
    }
    return count.empty() ? 0 : size_t(d.back()) + size_t(count.back());
  };
  sendBuf_.resize(std::max<size_t>(1, displ(sendCount_, sendDispl_)));
  recvBuf_.resize(std::max<size_t>(1, displ(recvCount_, recvDispl_)));
  // Forward: this rank receives from `from`, sends to `to`; backward the reverse. Not
  // reordered: the graph's ranks are comm's.
  auto graph = [&](const std::vector<int>& in, const std::vector<int>& out, MPI_Comm* g) {
    MPI_Dist_graph_create_adjacent(comm, (int)in.size(), in.empty() ? MPI_WEIGHTS_EMPTY : in.data(), MPI_UNWEIGHTED,
                                   (int)out.size(), out.empty() ? MPI_WEIGHTS_EMPTY : out.data(), MPI_UNWEIGHTED,
                                   MPI_INFO_NULL, 0, g);
  };
  graph(from, to, &graph_[0]);
  graph(to, from, &graph_[1]);
}

Redistribute::~Redistribute() {
  for (MPI_Comm& g : graph_)
    if (g != MPI_COMM_NULL) MPI_Comm_free(&g);
}

std::array<long long, 2> Redistribute::sent(bool reverse) const {
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  const auto& parts = reverse ? recvs_ : sends_;
  std::array<long long, 2> t{0, 0};
  for (const Part& p : parts)
    if (p.rank != rank) ++t[0], t[1] += p.box.size();
  return t;
}

template <class T>
void Redistribute::move(const T* in, T* out, bool reverse) const {
  // Reverse: the roles of the send and receive lists swap (same counts, same buffers).
  const auto& sends = reverse ? recvs_ : sends_;
  const auto& recvs = reverse ? sends_ : recvs_;
  const auto& sc = reverse ? recvCount_ : sendCount_;
  const auto& sd = reverse ? recvDispl_ : sendDispl_;
  const auto& rc = reverse ? sendCount_ : recvCount_;
  const auto& rd = reverse ? sendDispl_ : recvDispl_;
  auto& sb = reverse ? recvBuf_ : sendBuf_;
  auto& rb = reverse ? sendBuf_ : recvBuf_;
  const Box& from = reverse ? myDst_ : mySrc_;
  const Box& to = reverse ? mySrc_ : myDst_;
  for (size_t p = 0; p < sends.size(); ++p)
    copyPart(from, sends[p].box, const_cast<T*>(in), reinterpret_cast<T*>(sb.data()) + sd[p], true);
  const MPI_Datatype type = sizeof(T) == sizeof(float) ? MPI_FLOAT : MPI_DOUBLE;
  MPI_Neighbor_alltoallv(sb.data(), sc.data(), sd.data(), type, rb.data(), rc.data(), rd.data(), type,
                         graph_[reverse ? 1 : 0]);
  for (size_t p = 0; p < recvs.size(); ++p)
    copyPart(to, recvs[p].box, out, reinterpret_cast<T*>(rb.data()) + rd[p], false);
}
template void Redistribute::move(const double*, double*, bool) const;
template void Redistribute::move(const float*, float*, bool) const;

} // namespace voigt
