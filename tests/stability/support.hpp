#pragma once
// Helpers for the checkpoint/restart and output-safety tests.
#include <gtest/gtest.h>
#include <mpi.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "app/simulation.hpp"
#include "core/index_space.hpp"
#include "scene/load.hpp"
#include "scene/reader.hpp"

namespace voigt::test {

inline int worldRank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
inline int worldSize() {
  int s = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

// A case scene with --set style overrides, loaded as `voigt run` loads it.
inline Scene caseScene(const std::string& rel, std::vector<std::string> sets) {
  return loadSceneWithEffects(std::string(VOIGT_SOURCE_DIR) + "/cases/" + rel, std::move(sets));
}

// A fresh empty directory, the same path on every rank of comm; removed by the destructor.
struct TempDir {
  std::string path;
  MPI_Comm comm;
  explicit TempDir(MPI_Comm c = MPI_COMM_WORLD) : comm(c) {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    char buf[256] = {0};
    if (rank == 0) {
      const char* base = std::getenv("TMPDIR");
      std::string tmpl = std::string(base && *base ? base : "/tmp") + "/voigt_stability_XXXXXX";
      std::strncpy(buf, tmpl.c_str(), sizeof buf - 1);
      if (!mkdtemp(buf)) buf[0] = 0;
    }
    MPI_Bcast(buf, sizeof buf, MPI_CHAR, 0, comm);
    path = buf;
  }
  ~TempDir() {
    MPI_Barrier(comm);
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    std::error_code ec;
    if (rank == 0 && !path.empty()) std::filesystem::remove_all(path, ec);
  }
  std::string sub(const std::string& name) const { return path + "/" + name; }
};

inline RunOptions runOpts(const std::string& dir, long steps, const std::string& restart = "") {
  RunOptions o;
  o.outDir = dir;
  o.maxSteps = steps;
  o.progress = false;
  o.restart = restart;
  return o;
}

// Owned values of every allocated field of two simulations on the same
// decomposition. Returns the number of points (over all ranks) whose bits
// differ, or, with tol > 0, whose values differ by more than tol relative to
// max(1, the field's max |value|) (fields that are round-off noise, such as
// the divergence, compare absolutely). `worst` gets the largest relative difference.
inline long long compareFields(Simulation& a, Simulation& b, double tol, double* worst = nullptr,
                               std::string* firstBad = nullptr) {
  const Grid& g = a.state().grid;
  long long bad = 0;
  double w = 0;
  for (auto& name : a.state().fields.allocatedNames()) {
    const auto& d = a.state().fields.decls().at(name);
    const Range3 r = d.centring == Centring::Cell ? cellRange(g) : nodeRange(g);
    std::vector<std::pair<std::vector<double>, std::vector<double>>> comps;
    auto collect = [&](auto fa, auto fb) {
      auto ha = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), fa);
      auto hb = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), fb);
      std::vector<double> va, vb;
      for (int k = r.b[2]; k < r.e[2]; ++k)
        for (int j = r.b[1]; j < r.e[1]; ++j)
          for (int i = r.b[0]; i < r.e[0]; ++i) {
            va.push_back(double(ha(i, j, k)));
            vb.push_back(double(hb(i, j, k)));
          }
      comps.emplace_back(std::move(va), std::move(vb));
    };
    const auto& fa = a.state().fields;
    const auto& fb = b.state().fields;
    if (d.isInt) collect(fa.integer(name), fb.integer(name));
    else if (d.components == 1) collect(fa.scalar(name), fb.scalar(name));
    else
      for (int c = 0; c < 3; ++c) collect(fa.vector(name).c[c], fb.vector(name).c[c]);
    for (auto& [va, vb] : comps) {
      double scale = 0;
      for (double v : va) scale = std::max(scale, std::abs(v));
      MPI_Allreduce(MPI_IN_PLACE, &scale, 1, MPI_DOUBLE, MPI_MAX, g.comm);
      long long nb = 0;
      for (size_t q = 0; q < va.size(); ++q) {
        const double rel = std::abs(va[q] - vb[q]) / std::max(scale, 1.0);
        w = std::max(w, rel);
        const bool differ = tol > 0 ? rel > tol : std::memcmp(&va[q], &vb[q], sizeof(double)) != 0;
        nb += differ;
      }
      MPI_Allreduce(MPI_IN_PLACE, &nb, 1, MPI_LONG_LONG, MPI_SUM, g.comm);
      if (nb && firstBad) *firstBad += name + " ";
      bad += nb;
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, &w, 1, MPI_DOUBLE, MPI_MAX, g.comm);
  if (worst) *worst = w;
  return bad;
}

} // namespace voigt::test
