#include "io/probes.hpp"

#include <filesystem>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "core/host_access.hpp"

namespace voigt {

namespace {
// The one rule for when a probe samples (interval 0: every call).
bool probeDue(const Probe& p, bool sampled, double next, double t) {
  return !sampled || p.interval <= 0 || t >= next - 1e-9 * p.interval;
}
} // namespace

bool ProbeSet::due(double t) const {
  for (auto& s : probes_)
    if (probeDue(s.probe, s.sampled, s.next, t)) return true;
  return false;
}
namespace {

// Shortest text that reads back to the same double.
void put(std::ostream& o, double v) {
  char b[32];
  auto r = std::to_chars(b, b + sizeof b, v);
  o.write(b, r.ptr - b);
}

} // namespace

ProbeSet::ProbeSet(const Grid& g, const std::vector<Probe>& probes, std::string dir, double resumeAt)
    : g_(g), dir_(std::move(dir)) {
  int ok = 1;
  std::string bad;
  for (const auto& p : probes) {
    State s;
    s.probe = p;
    const int np = p.kind == Probe::Kind::Line ? std::max(p.points, 1) : 1;
    for (int i = 0; i < np; ++i) {
      const double f = np > 1 ? double(i) / (np - 1) : 0.0;
      Vec3 x;
      for (int d = 0; d < 3; ++d) x[d] = p.a[d] + f * (p.b[d] - p.a[d]);
      s.pts.push_back(x);
    }

    // Owner: the rank whose owned cells contain the (clamped) point. Node
    // stencil: nodes ci, ci+1. Cell stencil: centres j0, j0+1 with j0 in
    // {ci-1, ci}, so every read stays inside owned + one ghost layer.
    std::vector<std::array<int, 9>> idx;
    std::vector<std::array<double, 6>> w;
    for (int i = 0; i < np; ++i) {
      std::array<int, 9> id{};
      std::array<double, 6> wt{};
      bool mine = true;
      for (int d = 0; d < 3; ++d) {
        const int n = g.n[d];
        const double u = (std::clamp(s.pts[i][d], g.lo[d], g.hi[d]) - g.lo[d]) / g.h[d];
        const int ci = std::clamp(int(std::floor(u)), 0, n - 1);
        mine = mine && ci >= g.c0[d] && ci < g.c1[d];
        id[d] = g.local(d, ci);
        wt[d] = std::clamp(u - ci, 0.0, 1.0);

        double uc = u - 0.5;
        int j0 = int(std::floor(uc)), step = 1;
        if (!g.periodic[d]) { // clamp to the first/last cell centre
          uc = std::clamp(uc, 0.0, double(n - 1));
          j0 = std::min(int(std::floor(uc)), std::max(n - 2, 0));
          if (n == 1) step = 0;
        }
        id[3 + d] = g.local(d, j0);
        id[6 + d] = step;
        wt[3 + d] = step ? std::clamp(uc - j0, 0.0, 1.0) : 0.0;
      }
      if (mine) {
        s.local.push_back(i);
        idx.push_back(id);
        w.push_back(wt);
      }
    }
    const int nl = int(s.local.size());
    s.idx = IdxView("probe::idx", nl);
    s.w = WView("probe::w", nl);
    auto hi = hostMirror(s.idx);
    auto hw = hostMirror(s.w);
    for (int p2 = 0; p2 < nl; ++p2) {
      for (int c = 0; c < 9; ++c) hi(p2, c) = idx[p2][c];
      for (int c = 0; c < 6; ++c) hw(p2, c) = w[p2][c];
    }
    toDevice(s.idx, hi, "setup");
    toDevice(s.w, hw, "setup");

    if (g.rank == 0 && ok) {
      const std::string path = dir_ + "/probe_" + p.name + ".csv";
      s.out = std::make_unique<std::ofstream>(path, resumeAt >= 0 ? std::ios::app : std::ios::trunc);
      if (!*s.out) ok = 0, bad = path;
    }
    if (resumeAt >= 0) {
      std::error_code ec;
      const std::string path = dir_ + "/probe_" + p.name + ".csv";
      s.headerDone = std::filesystem::exists(path, ec) && std::filesystem::file_size(path, ec) > 0;
      s.sampled = true;
      if (p.interval > 0) s.next = (std::floor(resumeAt / p.interval + 1e-9) + 1) * p.interval;
    }
    probes_.push_back(std::move(s));
  }
  // Fail on every rank, not just rank 0, so nobody waits in a collective.
  MPI_Bcast(&ok, 1, MPI_INT, 0, g.comm);
  if (!ok) throw std::runtime_error("cannot open probe file " + (g.rank == 0 ? bad : std::string("(see rank 0)")));
}

void ProbeSet::sample(double t, const std::vector<OutField>& available, bool force) {
  for (auto& s : probes_) {
    const Probe& p = s.probe;
    if (!(force || probeDue(p, s.sampled, s.next, t))) continue;
    // The run's final forced sample lands on the last interval sample when the
    // end time is a multiple of the interval: one row per time.
    if (s.sampled && t == s.lastT) continue;
    s.sampled = true;
    s.lastT = t;
    if (p.interval > 0) s.next = (std::floor(t / p.interval + 1e-9) + 1) * p.interval;

    std::vector<const OutField*> fs;
    int ncols = 0;
    for (const auto& name : p.fields) {
      auto it = std::find_if(available.begin(), available.end(),
                             [&](const OutField& f) { return f.name == name; });
      if (it == available.end())
        throw std::runtime_error("probe '" + p.name + "': field '" + name + "' is not available");
      fs.push_back(&*it);
      ncols += int(it->comps.size());
    }

    // Sample owned points on the execution space: one column per component.
    const int nl = int(s.local.size());
    ProbeValues res("probe::res", nl, ncols);
    const auto idx = s.idx;
    const auto w = s.w;
    int col = 0;
    for (const OutField* f : fs) {
      const int o = f->centring == Centring::Node ? 0 : 3;
      for (const Field& v : f->comps) sampleProbes(v, idx, w, o, nl, res, col++);
    }
    auto hres = toHost(res, "probes");

    // Each point has exactly one owner, so a sum over ranks gathers it.
    const int np = int(s.pts.size());
    std::vector<double> mine(size_t(np) * ncols, 0.0), all(g_.rank == 0 ? mine.size() : 0);
    for (int q = 0; q < nl; ++q)
      for (int c = 0; c < ncols; ++c) mine[size_t(s.local[q]) * ncols + c] = hres(q, c);
    MPI_Reduce(mine.data(), all.data(), int(mine.size()), MPI_DOUBLE, MPI_SUM, 0, g_.comm);
    if (g_.rank == 0) writeRows(s, t, fs, all);
  }
}

void ProbeSet::writeRows(State& s, double t, const std::vector<const OutField*>& fs,
                         const std::vector<double>& vals) {
  std::ofstream& o = *s.out;
  const bool line = s.probe.kind == Probe::Kind::Line;
  if (!s.headerDone) {
    o << (line ? "t,s,x,y,z" : "t");
    for (const OutField* f : fs) {
      if (f->comps.size() == 1) o << ',' << f->name;
      else
        for (size_t c = 0; c < f->comps.size(); ++c) o << ',' << f->name << '_' << char('x' + c);
    }
    o << '\n';
    s.headerDone = true;
  }
  const size_t ncols = s.pts.empty() ? 0 : vals.size() / s.pts.size();
  for (size_t q = 0; q < s.pts.size(); ++q) {
    put(o, t);
    if (line) {
      const Vec3& x = s.pts[q];
      const Vec3& a = s.probe.a;
      o << ',';
      put(o, std::sqrt((x[0] - a[0]) * (x[0] - a[0]) + (x[1] - a[1]) * (x[1] - a[1]) +
                       (x[2] - a[2]) * (x[2] - a[2])));
      for (int d = 0; d < 3; ++d) {
        o << ',';
        put(o, x[d]);
      }
    }
    for (size_t c = 0; c < ncols; ++c) {
      o << ',';
      put(o, vals[q * ncols + c]);
    }
    o << '\n';
  }
  o.flush(); // a crashed run keeps every sample taken so far
  if (!o) throw std::runtime_error("probe '" + s.probe.name + "': write to " + dir_ + " failed");
}

} // namespace voigt
