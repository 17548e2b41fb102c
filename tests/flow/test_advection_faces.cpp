// The face-flux advection kernels (kernels/advection_faces.hpp) against the
// point-wise ones they replace in the step (kernels/advection.hpp,
// kernels/levelset.hpp): same operations in the same order, so the results must
// be equal bit for bit (tolerance 0), for every limiter, on rough fields (random
// values: every limiter branch is taken), a non-cubic grid and sub-ranges.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/grid.hpp"
#include "kernels/advection_faces.hpp"
#include "kernels/levelset.hpp"

using namespace voigt;

namespace {

struct Fixture {
  Grid g;
  Field rho, rhoRef, rr1, rr2;
  VecField u, a1, a2;
  Field cq[6], co1[6], co2[6], cq2[6];
  Fixture() {
    g = makeGrid(MPI_COMM_WORLD, {12, 9, 7}, {0, 0, 0}, {1.2, 0.8, 0.9}, {false, false, false}, {0, 0, 0});
    auto mk = [&](const char* n) { return Field(std::string(n), g.ext[0], g.ext[1], g.ext[2]); };
    rho = mk("rho"), rhoRef = mk("rhoRef"), rr1 = mk("rr1"), rr2 = mk("rr2");
    for (int c = 0; c < 3; ++c) u.c[c] = mk("u"), a1.c[c] = mk("a1"), a2.c[c] = mk("a2");
    for (int c = 0; c < 6; ++c) cq[c] = mk("q"), co1[c] = mk("o1"), co2[c] = mk("o2"), cq2[c] = mk("q2");
    // Deterministic pseudo-random values (an LCG per point): sign changes and
    // extrema everywhere, so MinMod/MC/van Leer take all their branches.
    auto fill = [&](const Field& f, double lo, double hi, unsigned seed) {
      const int e0 = g.ext[0], e1 = g.ext[1];
      Kokkos::parallel_for(
          "fill", Policy3({0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}), KOKKOS_LAMBDA(int i, int j, int k) {
            unsigned x = seed * 2654435761u + unsigned(i + e0 * (j + e1 * k)) * 40503u;
            x ^= x >> 13;
            x *= 1274126177u;
            x ^= x >> 16;
            f(i, j, k) = lo + (hi - lo) * double(x % 100000) / 100000.0;
          });
    };
    fill(rho, 1, 1000, 1), fill(rhoRef, 1, 1000, 2);
    for (int c = 0; c < 3; ++c) fill(u.c[c], -1, 1, 3 + c), fill(a1.c[c], -1, 1, 9 + c);
    for (int c = 0; c < 6; ++c) fill(cq[c], -2, 2, 20 + c), fill(co1[c], -2, 2, 30 + c);
    for (int c = 0; c < 3; ++c) Kokkos::deep_copy(a2.c[c], a1.c[c]);
    for (int c = 0; c < 6; ++c) Kokkos::deep_copy(cq2[c], cq[c]), Kokkos::deep_copy(co2[c], co1[c]);
  }
  ~Fixture() { freeGrid(g); }
};

// Largest |a - b| over the range (0 when bit-identical, but for signed zeros).
double maxDiff(const Field& a, const Field& b, Range3 r) {
  double m = 0;
  Kokkos::parallel_reduce(
      "maxdiff", r.policy(),
      KOKKOS_LAMBDA(int i, int j, int k, double& acc) {
        const double x = a(i, j, k), y = b(i, j, k);
        const double d = x == y ? 0.0 : (x - y != x - y ? 1e300 : Kokkos::Experimental::fabs(x - y));
        if (d > acc) acc = d;
      },
      Kokkos::Max<double>(m));
  return m;
}

const Limiter kLimiters[] = {Limiter::MinMod, Limiter::VanLeer, Limiter::MC, Limiter::None};

} // namespace

TEST(AdvectionFaces, MomentumBitIdentical) {
  Fixture s;
  FluxScratch scratch;
  for (Limiter lim : kLimiters) {
    const Range3 nodes = nodeRange(s.g);
    addMomentumAdvection(s.g, s.rho, s.u, s.rhoRef, s.rr1, s.a1, nodes, lim);
    addMomentumAdvectionFaces(s.g, s.rho, s.u, s.rhoRef, s.rr2, s.a2, nodes, lim, scratch);
    EXPECT_EQ(maxDiff(s.rr1, s.rr2, nodes), 0.0) << "limiter " << int(lim);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(maxDiff(s.a1.c[c], s.a2.c[c], nodes), 0.0) << "limiter " << int(lim);
  }
}

TEST(AdvectionFaces, VelocityBitIdentical) {
  Fixture s;
  FluxScratch scratch;
  for (Limiter lim : kLimiters) {
    const Range3 nodes = nodeRange(s.g);
    for (int c = 0; c < 3; ++c) addNodeAdvection(s.g, s.u.c[c], s.u, s.a1.c[c], nodes, lim);
    addVelocityAdvectionFaces(s.g, s.u, s.a2, nodes, lim, scratch);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(maxDiff(s.a1.c[c], s.a2.c[c], nodes), 0.0) << "limiter " << int(lim);
  }
}

// Both RK stages as elasticity and the level set ran them: o = q, r = 0,
// r += advection, q = (1 - a) o + a (q + dt r); on all cells and on a box.
TEST(AdvectionFaces, CellRk2StagesBitIdentical) {
  Fixture s;
  FluxScratch scratch;
  Range3 box = cellRange(s.g);
  box.b[0] += 2, box.e[1] -= 3, box.b[2] += 1;
  for (Range3 r : std::vector<Range3>{cellRange(s.g), box}) {
    for (Limiter lim : kLimiters) {
      const double dt = 0.013;
      Field rr = s.rr1;
      for (int stage = 0; stage < 2; ++stage) {
        const double a = stage == 0 ? 1.0 : 0.5;
        for (int c = 0; c < 6; ++c) {
          Field q = s.cq[c], o = s.co1[c];
          if (stage == 0) Kokkos::deep_copy(o, q);
          Kokkos::deep_copy(rr, 0.0);
          addCellAdvection(s.g, q, s.u, rr, r, lim);
          Kokkos::parallel_for(
              "rk2", r.policy(), KOKKOS_LAMBDA(int i, int j, int k) {
                q(i, j, k) = (1 - a) * o(i, j, k) + a * (q(i, j, k) + dt * rr(i, j, k));
              });
        }
        for (int c = 0; c < 6; ++c) advanceCellAdvection(s.g, s.cq2[c], s.co2[c], s.u, r, lim, dt, a, stage == 0, scratch);
        for (int c = 0; c < 6; ++c) {
          EXPECT_EQ(maxDiff(s.cq[c], s.cq2[c], r), 0.0) << "stage " << stage << " limiter " << int(lim);
          EXPECT_EQ(maxDiff(s.co1[c], s.co2[c], r), 0.0) << "stage " << stage << " limiter " << int(lim);
        }
      }
    }
  }
}
