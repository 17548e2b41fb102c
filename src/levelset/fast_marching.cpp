// Fast Marching signed distance (Sethian 1996/1999); design in the header.
#include "levelset/fast_marching.hpp"

#include <mpi.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <functional>
#include <queue>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/host_access.hpp"

namespace voigt {
namespace {

enum : std::uint8_t { kFar = 0, kTrial = 1, kKnown = 2 };
constexpr double kInf = std::numeric_limits<double>::infinity();

// The global grid on rank 0, x fastest. psi is the input; u receives |distance|.
struct Marcher {
  std::array<int, 3> n;
  std::array<double, 3> h;
  std::array<bool, 3> per;
  std::vector<double>& psi;
  std::vector<double>& u;
  std::vector<std::uint8_t> state;
  int order = 2; // upwind order of the march; 1 reproduces the first-order numbers in the tests
  long long stride[3];

  Marcher(const Grid& g, std::vector<double>& p, std::vector<double>& dist)
      : n(g.n), h(g.h), per(g.periodic), psi(p), u(dist), state(p.size(), kFar) {
    stride[0] = 1, stride[1] = n[0], stride[2] = 1LL * n[0] * n[1];
  }

  void coords(long long c, int* x) const {
    x[0] = int(c % n[0]);
    x[1] = int((c / n[0]) % n[1]);
    x[2] = int(c / stride[2]);
  }
  // Cell s steps from c along axis a (periodic axes wrap), or -1 outside the grid.
  long long nb(long long c, const int* x, int a, int s) const {
    int y = x[a] + s;
    if (y < 0 || y >= n[a]) {
      if (!per[a]) return -1;
      y = ((y % n[a]) + n[a]) % n[a];
    }
    return c + (y - x[a]) * stride[a];
  }

  // Cell at offset o from x (periodic axes wrap), or -1 outside the grid.
  long long at(const int* x, std::array<int, 3> o) const {
    long long c = 0;
    for (int a = 0; a < 3; ++a) {
      int y = x[a] + o[a];
      if (y < 0 || y >= n[a]) {
        if (!per[a]) return -1;
        y = ((y % n[a]) + n[a]) % n[a];
      }
      c += y * stride[a];
    }
    return c;
  }

  // Distance estimate of a cell next to the interface, or -1 if it is not.
  // Secant estimate dS: crossing axes by linear interpolation to the nearer
  // crossing, other axes by the minmod slope (robust at kinks of psi), i.e.
  // 1/dS^2 = sum 1/d_a^2 + sum (slope_a / psi)^2. It is O(h^2) but biased on
  // curved interfaces (the secant slope belongs to the face, not the cell), which
  // shows in integral measures such as the phase volume. So the curvature-aware
  // step of newton() is used when it lies within [dS/2, 2 dS]; outside that range
  // the local quadratic model is not trusted (kinks, thin features).
  double interfaceDistance(long long c, const int* x) const {
    const double p = psi[c];
    if (p == 0) return 0;
    double inv = 0;
    bool crossing = false;
    for (int a = 0; a < 3; ++a) {
      double da = kInf, slope[2] = {0, 0};
      int sides = 0;
      for (int s = -1; s <= 1; s += 2) {
        const long long m = nb(c, x, a, s);
        if (m < 0) continue;
        const double q = psi[m];
        if (q == 0 || (q > 0) != (p > 0)) da = std::min(da, h[a] * p / (p - q));
        slope[sides++] = s * (q - p) / h[a];
      }
      if (da < kInf) {
        inv += 1 / (da * da);
        crossing = true;
      } else if (sides > 0) {
        double gr = slope[0];
        if (sides == 2) gr = slope[0] * slope[1] <= 0 ? 0 : std::fabs(slope[0]) < std::fabs(slope[1]) ? slope[0] : slope[1];
        inv += (gr / p) * (gr / p);
      }
    }
    if (!crossing) return -1;
    const double dS = 1 / std::sqrt(inv), dN = newton(x, p);
    return dN >= 0.5 * dS && dN <= 2 * dS ? dN : dS;
  }

  // Distance to the zero of the quadratic model of psi along its normal,
  // psi(s) = p + |g| s + H_nn s^2 / 2, with g and the Hessian H by central
  // differences (one-sided g, no H at non-periodic edges of the grid). Exact for
  // a distance function of a sphere (H_nn = 0) and for R^2 - |x-c|^2; NaN when
  // the model has no root.
  double newton(const int* x, double p) const {
    double g[3] = {0, 0, 0}, H[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (int a = 0; a < 3; ++a) {
      std::array<int, 3> o{0, 0, 0};
      o[a] = -1;
      const long long lo = at(x, o);
      o[a] = 1;
      const long long hi = at(x, o);
      if (lo >= 0 && hi >= 0) {
        g[a] = (psi[hi] - psi[lo]) / (2 * h[a]);
        H[a][a] = (psi[hi] - 2 * p + psi[lo]) / (h[a] * h[a]);
      } else if (hi >= 0 || lo >= 0) {
        g[a] = hi >= 0 ? (psi[hi] - p) / h[a] : (p - psi[lo]) / h[a];
      }
      for (int b = 0; b < a; ++b) {
        long long q[4];
        for (int k = 0; k < 4; ++k) {
          std::array<int, 3> o2{0, 0, 0};
          o2[a] = k & 1 ? 1 : -1, o2[b] = k & 2 ? 1 : -1;
          q[k] = at(x, o2);
        }
        if (q[0] >= 0 && q[1] >= 0 && q[2] >= 0 && q[3] >= 0)
          H[a][b] = H[b][a] = (psi[q[3]] - psi[q[2]] - psi[q[1]] + psi[q[0]]) / (4 * h[a] * h[b]);
      }
    }
    const double g2 = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
    if (!(g2 > 0)) return std::nan("");
    double hnn = 0;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) hnn += g[a] * H[a][b] * g[b] / g2;
    const double disc = g2 - 2 * hnn * p;
    return disc >= 0 ? 2 * std::fabs(p) / (std::sqrt(g2) + std::sqrt(disc)) : std::nan("");
  }


  // Godunov upwind Eikonal update of cell c from its Known neighbours. Per axis
  // the upwind side is the smaller Known neighbour T1; with a Known T2 <= T1 two
  // cells out, Sethian's second-order difference (3T - 4T1 + T2)/(2h) replaces
  // (T - T1)/h, i.e. the term w (T - t)^2 with t = (4T1 - T2)/3, w = 9/(4h^2).
  // T2 is taken signed relative to c, so a stencil across the interface sees the
  // smooth signed distance, not its kinked absolute value.
  double update(long long c, const int* x) const {
    const bool pos = psi[c] > 0;
    double t[3], w[3];
    int m = 0;
    for (int a = 0; a < 3; ++a) {
      long long best = -1;
      int side = 0;
      for (int s = -1; s <= 1; s += 2) {
        const long long q = nb(c, x, a, s);
        if (q >= 0 && state[q] == kKnown && (best < 0 || u[q] < u[best])) best = q, side = s;
      }
      if (best < 0) continue;
      t[m] = u[best];
      w[m] = 1 / (h[a] * h[a]);
      const long long q2 = order == 2 ? nb(c, x, a, 2 * side) : -1;
      if (q2 >= 0 && q2 != c && state[q2] == kKnown) {
        const double t2 = (psi[q2] > 0) == pos || psi[q2] == 0 ? u[q2] : -u[q2];
        if (t2 <= t[m]) {
          t[m] = (4 * t[m] - t2) / 3;
          w[m] *= 2.25;
        }
      }
      ++m;
    }
    if (m == 0) return kInf; // not reached from any Known cell (callers relax neighbours of one)
    // Axes in increasing t; add the next one while the root lies beyond it.
    for (int i = 1; i < m; ++i)
      for (int j = i; j > 0 && t[j] < t[j - 1]; --j) std::swap(t[j], t[j - 1]), std::swap(w[j], w[j - 1]);
    double T = t[0] + 1 / std::sqrt(w[0]);
    double A = w[0], B = w[0] * t[0], C = w[0] * t[0] * t[0];
    for (int i = 1; i < m && T > t[i]; ++i) {
      A += w[i], B += w[i] * t[i], C += w[i] * t[i] * t[i];
      T = (B + std::sqrt(std::max(0.0, B * B - A * (C - 1)))) / A;
    }
    return T;
  }

  // Marches |psi| outward from the interface; returns {initial, accepted} cells.
  std::pair<long long, long long> run(double cap) {
    const long long N = (long long)psi.size();
    long long initial = 0, accepted = 0;
    int x[3], y[3];
    for (long long c = 0; c < N; ++c) {
      coords(c, x);
      const double d = interfaceDistance(c, x);
      u[c] = d >= 0 ? d : kInf;
      if (d >= 0) state[c] = kKnown, ++initial;
    }
    using Item = std::pair<double, long long>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap; // lazy deletion
    auto relax = [&](long long c, const int* xc) {
      for (int a = 0; a < 3; ++a)
        for (int s = -1; s <= 1; s += 2) {
          const long long q = nb(c, xc, a, s);
          if (q < 0 || state[q] == kKnown) continue;
          coords(q, y);
          const double T = update(q, y);
          if (T < u[q]) u[q] = T, state[q] = kTrial, heap.push({T, q});
        }
    };
    for (long long c = 0; c < N; ++c)
      if (state[c] == kKnown) coords(c, x), relax(c, x);
    while (!heap.empty()) {
      const auto [T, c] = heap.top();
      if (T > cap) break;
      heap.pop();
      if (state[c] == kKnown || T != u[c]) continue; // stale entry
      state[c] = kKnown;
      ++accepted;
      coords(c, x);
      relax(c, x);
    }
    return {initial, accepted};
  }

  // psi <- sign(psi) min(u, cap) where reached; unreached cells get sign * cap
  // (unchanged if the cap is infinite: psi has no interface then).
  void finish(double cap) {
    for (size_t c = 0; c < psi.size(); ++c) {
      const double s = psi[c] > 0 ? 1 : psi[c] < 0 ? -1 : 0;
      if (state[c] == kKnown) psi[c] = s * std::min(u[c], cap);
      else if (cap < kInf) psi[c] = s * cap;
    }
  }
};

// Owned block of a rank: {c0, ln} per axis; visits (offset in block, global index).
template <class F>
void forBlock(const int* meta, const std::array<int, 3>& n, F f) {
  long long o = 0;
  for (int k = 0; k < meta[5]; ++k)
    for (int j = 0; j < meta[4]; ++j)
      for (int i = 0; i < meta[3]; ++i, ++o)
        f(o, meta[0] + i + 1LL * n[0] * (meta[1] + j + 1LL * n[1] * (meta[2] + k)));
}

} // namespace

FastMarchingStats fastMarching(const Grid& g, const Field& psi, double maxDistance) {
  const double t0 = MPI_Wtime();
  if (g.cellsGlobal() > INT_MAX) throw std::runtime_error("fastMarching: more than 2^31 cells (gathered on one rank)");
  const bool root = g.rank == 0;
  const int ng = g.ng;

  // Pack the owned block (x fastest) from a host copy of psi.
  auto hpsi = toHost(psi, "fast_marching");
  const int meta[6] = {g.c0[0], g.c0[1], g.c0[2], g.ln[0], g.ln[1], g.ln[2]};
  std::vector<double> block(size_t(g.cellsOwned()));
  for (int k = 0; k < g.ln[2]; ++k)
    for (int j = 0; j < g.ln[1]; ++j)
      for (int i = 0; i < g.ln[0]; ++i) block[i + size_t(g.ln[0]) * (j + size_t(g.ln[1]) * k)] = hpsi(ng + i, ng + j, ng + k);

  std::vector<int> metas(root ? 6 * g.size : 0), counts(root ? g.size : 0), displs(root ? g.size : 0);
  MPI_Gather(meta, 6, MPI_INT, metas.data(), 6, MPI_INT, 0, g.comm);
  for (int r = 0, off = 0; root && r < g.size; ++r) {
    counts[r] = metas[6 * r + 3] * metas[6 * r + 4] * metas[6 * r + 5];
    displs[r] = off;
    off += counts[r];
  }
  // Rank 0: `packed` holds the blocks in rank order; it doubles as the distance
  // array during the march and as the scatter buffer after (17 bytes per cell).
  std::vector<double> packed(root ? size_t(g.cellsGlobal()) : 0);
  MPI_Gatherv(block.data(), int(block.size()), MPI_DOUBLE, packed.data(), counts.data(), displs.data(), MPI_DOUBLE, 0,
              g.comm);

  long long stats[2] = {0, 0};
  if (root) {
    std::vector<double> gpsi(packed.size());
    for (int r = 0; r < g.size; ++r)
      forBlock(&metas[6 * r], g.n, [&](long long o, long long c) { gpsi[c] = packed[displs[r] + o]; });
    Marcher m(g, gpsi, packed);
    const auto [init, acc] = m.run(maxDistance);
    stats[0] = init, stats[1] = acc;
    m.finish(maxDistance);
    for (int r = 0; r < g.size; ++r)
      forBlock(&metas[6 * r], g.n, [&](long long o, long long c) { packed[displs[r] + o] = gpsi[c]; });
  }
  MPI_Scatterv(packed.data(), counts.data(), displs.data(), MPI_DOUBLE, block.data(), int(block.size()), MPI_DOUBLE, 0,
               g.comm);
  MPI_Bcast(stats, 2, MPI_LONG_LONG, 0, g.comm);

  for (int k = 0; k < g.ln[2]; ++k)
    for (int j = 0; j < g.ln[1]; ++j)
      for (int i = 0; i < g.ln[0]; ++i) hpsi(ng + i, ng + j, ng + k) = block[i + size_t(g.ln[0]) * (j + size_t(g.ln[1]) * k)];
  toDevice(psi, hpsi, "fast_marching");

  FastMarchingStats st;
  st.initialCells = stats[0];
  st.acceptedCells = stats[1];
  st.seconds = MPI_Wtime() - t0;
  return st;
}

} // namespace voigt
