// Implicit null space of the exact projection operator (null_space.hpp).
#include "solvers/null_space.hpp"

#include <Teuchos_LAPACK.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/host_access.hpp"

namespace voigt {
namespace {

constexpr double kNullTol = 1e-10; // ||A v|| <= kNullTol ||v|| ||A||: v is null
constexpr double kRankTol = 1e-9;  // Gram eigenvalues below kRankTol * max are dependencies

// Colour of plane q along an axis with n planes: planes of one colour are >= 3
// apart (cyclically on a periodic axis), so their A-images do not overlap.
int colourOf(int q, int n, bool per) {
  if (!per) return q % 3;
  const int full = 3 * (n / 3);
  return q < full ? q % 3 : (full ? 3 : 0) + (q - full);
}
int colourCount(int n, bool per) {
  if (!per) return std::min(n, 3);
  return (n >= 3 ? 3 : 0) + (n - 3 * (n / 3));
}

using Column = std::vector<std::pair<int, double>>; // sparse column of C

} // namespace

NullSpace::NullSpace(const GridGeom& G, const CellRows& rows, int nrows, MPI_Comm comm)
    : G_(G), rows_(rows), nrows_(nrows), comm_(comm) {
  off_[0] = 1;
  off_[1] = 1 + G.n[0];
  off_[2] = 1 + G.n[0] + G.n[1];
  nb_ = 1 + G.n[0] + G.n[1] + G.n[2];
  s_.assign(nb_, 0.0);
  coef_ = Kokkos::View<double*, MemSpace>("nullspace_coef", nb_);
  ident_ = RowFlags("nullspace_ident", nrows_); // no identity rows until rebuild()
}

void NullSpace::analyze(const RowVector& v, double* s) const {
  if (constantOnly_) { // the 7-point operator's case: one plain sum, same order as below
    double sum = rowSum(v, ident_, nrows_);
    MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, comm_);
    std::fill(s, s + nb_, 0.0);
    s[0] = sum;
    return;
  }
  nullAnalyze(basis(), nb_, v, ident_, nrows_, s);
  MPI_Allreduce(MPI_IN_PLACE, s, nb_, MPI_DOUBLE, MPI_SUM, comm_);
}

void NullSpace::synthesize(const double* a, const RowVector& v, bool subtract) const {
  if (constantOnly_) { // the other coefficients are zero (remove()): nothing to copy
    nullSynthesizeConstant(a[0], v, ident_, nrows_, subtract);
    return;
  }
  auto ha = hostMirror(coef_);
  for (int m = 0; m < nb_; ++m) ha(m) = a[m];
  toDevice(coef_, ha, "null_space");
  nullSynthesize(basis(), coef_, v, ident_, nrows_, subtract);
}

void NullSpace::planeNorms(const RowVector& y, int axis, double* ps) const {
  planeSquares(G_, rows_, axis, y, nrows_, ps);
  MPI_Allreduce(MPI_IN_PLACE, ps, G_.n[axis], MPI_DOUBLE, MPI_SUM, comm_);
}

double NullSpace::norm2(const RowVector& v) const {
  double s = rowSquares(v, nrows_);
  MPI_Allreduce(MPI_IN_PLACE, &s, 1, MPI_DOUBLE, MPI_SUM, comm_);
  return std::sqrt(s);
}

void NullSpace::rebuild(const RowFlags& ident, const Apply& apply, double scale) {
  constantOnly_ = false; // the candidate tests below synthesize general modes
  ident_ = ident;
  const int nb = nb_;
  // Gram of the basis, Gm = M^T M: each live row is in 4 basis modes.
  std::vector<double> Gm((size_t)nb * nb, 0.0);
  {
    auto hid = toHost(ident, "solver_setup");
    const NullBasis B = basis();
    for (int r = 0; r < nrows_; ++r) {
      if (hid(r)) continue;
      int idx[4];
      double sg[4];
      B.at(r, idx, sg);
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) Gm[(size_t)idx[a] * nb + idx[b]] += sg[a] * sg[b];
    }
    MPI_Allreduce(MPI_IN_PLACE, Gm.data(), nb * nb, MPI_DOUBLE, MPI_SUM, comm_);
  }
  auto gram = [&](const Column& c) { // c^T Gm c
    double s = 0;
    for (auto& [i, x] : c)
      for (auto& [j, y] : c) s += x * y * Gm[(size_t)i * nb + j];
    return s;
  };

  RowVector x("nullspace_x", nrows_), y("nullspace_y", nrows_);
  std::vector<double> a(nb);
  auto applyColumn = [&](const Column& c) {
    std::fill(a.begin(), a.end(), 0.0);
    for (auto& [i, v] : c) a[i] += v;
    synthesize(a.data(), x, false);
    apply(x, y);
  };
  std::vector<Column> kept;
  const double tol = kNullTol * scale;

  // Constant.
  const Column one{{0, 1.0}};
  if (Gm[0] > 0) {
    applyColumn(one);
    if (norm2(y) <= tol * std::sqrt(Gm[0])) kept.push_back(one);
  }
  // Plane modes, a colour at a time; mode q owns the residual on planes q-1..q+1.
  bool whole[3]; // every nonzero plane mode of the family kept
  for (int c = 0; c < 3; ++c) {
    const int n = G_.n[c];
    const bool per = G_.per[c];
    whole[c] = true;
    std::vector<double> ps(n);
    for (int col = 0; col < colourCount(n, per); ++col) {
      Column sum;
      for (int q = 0; q < n; ++q)
        if (colourOf(q, n, per) == col) sum.push_back({off_[c] + q, 1.0});
      applyColumn(sum);
      planeNorms(y, c, ps.data());
      for (const auto& e : sum) {
        const int i = e.first, q = i - off_[c];
        const double nv2 = Gm[(size_t)i * nb + i];
        if (nv2 == 0) continue;
        int pl[3] = {q - 1, q, q + 1}, np = 0, uniq[3];
        for (int p : pl) {
          if (per) p = (p + n) % n;
          else if (p < 0 || p >= n) continue;
          if (std::find(uniq, uniq + np, p) == uniq + np) uniq[np++] = p;
        }
        double r2 = 0;
        for (int t = 0; t < np; ++t) r2 += ps[uniq[t]];
        if (std::sqrt(r2) <= tol * std::sqrt(nv2)) kept.push_back({{i, 1.0}});
        else whole[c] = false;
      }
    }
  }
  // Global alternating modes (-1)^(j+k), (-1)^(k+i), (-1)^(i+j), (-1)^(i+j+k):
  // sums over a family, tested only when the family's members are not all kept
  // (a sum can be null when its members are not; never seen, but cheap).
  for (int g = 0; g < 4; ++g) {
    const int c = g < 3 ? g : 2;
    if (whole[c]) continue;
    Column col;
    for (int q = 0; q < G_.n[c]; ++q) col.push_back({off_[c] + q, (g == 3 && (q & 1)) ? -1.0 : 1.0});
    const double nv2 = gram(col);
    if (nv2 <= 0) continue;
    applyColumn(col);
    if (norm2(y) <= tol * std::sqrt(nv2)) kept.push_back(col);
  }
  kept_ = (int)kept.size();

  // H = C^T Gm C, its eigen-decomposition, Z = C V_+ Lambda_+^{-1/2}.
  const int nk = kept_;
  Z_.clear();
  dim_ = 0;
  constantOnly_ = false;
  if (nk == 0) return;
  std::vector<double> GC((size_t)nb * nk, 0.0), H((size_t)nk * nk);
  for (int k = 0; k < nk; ++k)
    for (auto& [i, v] : kept[k])
      for (int r = 0; r < nb; ++r) GC[(size_t)k * nb + r] += v * Gm[(size_t)i * nb + r];
  for (int k = 0; k < nk; ++k)
    for (int l = 0; l < nk; ++l) {
      double s = 0;
      for (auto& [i, v] : kept[l]) s += v * GC[(size_t)k * nb + i];
      H[(size_t)l * nk + k] = s;
    }
  std::vector<double> w(nk);
  Teuchos::LAPACK<int, double> lapack;
  int info = 0, lwork = -1;
  double q = 0;
  lapack.SYEV('V', 'U', nk, H.data(), nk, w.data(), &q, lwork, &info);
  lwork = std::max(1, (int)q);
  std::vector<double> work(lwork);
  lapack.SYEV('V', 'U', nk, H.data(), nk, w.data(), work.data(), lwork, &info);
  if (info != 0) throw std::runtime_error("NullSpace: LAPACK SYEV failed, info " + std::to_string(info));
  const double wmax = *std::max_element(w.begin(), w.end());
  for (int t = 0; t < nk; ++t) {
    if (!(w[t] > kRankTol * wmax)) continue;
    const double f = 1 / std::sqrt(w[t]);
    std::vector<double> z(nb, 0.0);
    for (int k = 0; k < nk; ++k)
      for (auto& [i, v] : kept[k]) z[i] += v * H[(size_t)t * nk + k] * f;
    Z_.insert(Z_.end(), z.begin(), z.end());
    ++dim_;
  }
  constantOnly_ = true;
  for (int t = 0; t < dim_; ++t)
    for (int i = 1; i < nb; ++i) constantOnly_ = constantOnly_ && Z_[(size_t)t * nb + i] == 0.0;
}

double NullSpace::remove(const RowVector& v) const {
  if (dim_ == 0) return 0;
  const int nb = nb_;
  analyze(v, s_.data());
  std::vector<double> yt(dim_), a(nb, 0.0);
  double n2 = 0;
  for (int t = 0; t < dim_; ++t) {
    const double* z = &Z_[(size_t)t * nb];
    double s = 0;
    for (int i = 0; i < nb; ++i) s += z[i] * s_[i];
    yt[t] = s;
    n2 += s * s;
  }
  for (int t = 0; t < dim_; ++t) {
    const double* z = &Z_[(size_t)t * nb];
    for (int i = 0; i < nb; ++i) a[i] += z[i] * yt[t];
  }
  synthesize(a.data(), v, true);
  return std::sqrt(n2);
}

} // namespace voigt
