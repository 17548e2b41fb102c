// Every launcher of kernels/*.hpp called once (issue 25): compiled with nvcc against a
// Kokkos-CUDA (tests/device/CMakeLists.txt) each kernel lambda becomes device code, so
// host-only code in a kernel fails to compile there; compiled in the host build (CTest
// device.kernels_all, Serial) it proves the calls themselves run. Each call's result is
// reduced to a checksum (sum of |x| over the range it wrote, or the value it returns).
//   voigt_kernels_all [--out FILE]                 print (and write) "name value" lines
//   voigt_kernels_all --compare REF [--rtol R]     also compare with REF (default 1e-9):
//                                                  a GPU run against the Serial reference
//   --config                                       print Kokkos's configuration first
// The launcher list is checked at configure time (tests/device/launchers.cmake): a new
// `inline` function in kernels/ must be called here or in kernels_effects.cpp (the
// effects' kernels); check.hpp holds what both share.
#include <Kokkos_Core.hpp>
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "kernels/advection.hpp"
#include "kernels/advection_faces.hpp"
#include "kernels/boundary.hpp"
#include "kernels/elastic.hpp"
#include "kernels/extension.hpp"
#include "kernels/fast_diag.hpp"
#include "kernels/heaviside.hpp"
#include "kernels/levelset.hpp"
#include "kernels/poisson_rows.hpp"
#include "kernels/projection_ops.hpp"
#include "kernels/reductions.hpp"
#include "kernels/reinit.hpp"
#include "kernels/stress.hpp"

#include "check.hpp"

using namespace voigt;
using namespace voigt::check;

namespace {
// Smooth data over the whole array, ghosts included (no halo exchange needed): a sphere
// of radius 0.3 for psi (> 0 inside), trigonometric velocity, density and viscosity.
void fill(const Grid& g, Fields& f) {
  const GridGeom G(g);
  const double lo0 = g.lo[0], lo1 = g.lo[1], lo2 = g.lo[2];
  const Field p = f.p, psi = f.psi, rho = f.rho, mu = f.mu, q = f.q, o = f.o;
  const VecField u = f.u, u2 = f.u2, coef = f.coef;
  const SymTensorField tS = f.tauS;
  Kokkos::parallel_for(
      "check_fill", Range3{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}}.policy(), KOKKOS_LAMBDA(int i, int j, int k) {
        const double x = lo0 + (G.glob(0, i) + 0.5) * G.h[0], y = lo1 + (G.glob(1, j) + 0.5) * G.h[1],
                     z = lo2 + (G.glob(2, k) + 0.5) * G.h[2];
        const double X = x - 0.5, Y = y - 0.5, Z = z - 0.5, r = Kokkos::Experimental::sqrt(X * X + Y * Y + Z * Z);
        const double s1 = Kokkos::Experimental::sin(6.0 * x), c1 = Kokkos::Experimental::cos(5.0 * y),
                     s2 = Kokkos::Experimental::sin(4.0 * z + x);
        u.c[0](i, j, k) = s1 * c1;
        u.c[1](i, j, k) = c1 * s2 - 0.3;
        u.c[2](i, j, k) = s2 + 0.2 * s1;
        VOIGT_UNROLL
        for (int d = 0; d < 3; ++d) {
          u2.c[d](i, j, k) = u.c[d](i, j, k);
          coef.c[d](i, j, k) = 1.0 + 0.1 * d;
        }
        psi(i, j, k) = 0.3 - r;
        q(i, j, k) = 0.3 - r + 0.05 * s1;
        o(i, j, k) = q(i, j, k);
        p(i, j, k) = Kokkos::Experimental::cos(6.0 * X) * Kokkos::Experimental::sin(4.0 * Y + Z);
        rho(i, j, k) = 1.0 + 0.5 * s2;
        mu(i, j, k) = 1e-3 * (1.0 + 0.5 * c1);
        VOIGT_UNROLL
        for (int c = 0; c < 6; ++c) tS.c[c](i, j, k) = r < 0.3 ? (c < 3 ? 1.0 : 0.1) * (1.0 + X) : 0.0;
      });
}

void advection(const Grid& g, Fields& f, FluxScratch& scratch) {
  const Range3 nodes = nodeRange(g), cells = cellRange(g);
  const Limiter lims[4] = {Limiter::MinMod, Limiter::VanLeer, Limiter::MC, Limiter::None};
  for (int l = 0; l < 4; ++l) {
    const std::string L = std::to_string(l);
    Kokkos::deep_copy(f.rhs.c[0], 0.0);
    addNodeAdvection(g, f.u.c[0], f.u, f.rhs.c[0], nodes, lims[l]);
    put("addNodeAdvection." + L, sumAbs(f.rhs.c[0], nodes));
    Kokkos::deep_copy(f.rhs.c[0], 0.0);
    addNodeAdvectionFaces(g, f.u.c[0], f.u, f.rhs.c[0], nodes, lims[l], scratch);
    put("addNodeAdvectionFaces." + L, sumAbs(f.rhs.c[0], nodes));
    for (int c = 0; c < 3; ++c) Kokkos::deep_copy(f.rhs.c[c], 0.0);
    addVelocityAdvectionFaces(g, f.u, f.rhs, nodes, lims[l], scratch);
    put("addVelocityAdvectionFaces." + L, sumAbs(f.rhs, nodes));
    for (int c = 0; c < 3; ++c) Kokkos::deep_copy(f.rhs.c[c], 0.0);
    addMomentumAdvection(g, f.rho, f.u, f.rho, f.div, f.rhs, nodes, lims[l]);
    put("addMomentumAdvection." + L, sumAbs(f.rhs, nodes) + sumAbs(f.div, nodes));
    for (int c = 0; c < 3; ++c) Kokkos::deep_copy(f.rhs.c[c], 0.0);
    addMomentumAdvectionFaces(g, f.rho, f.u, f.rho, f.div, f.rhs, nodes, lims[l], scratch);
    put("addMomentumAdvectionFaces." + L, sumAbs(f.rhs, nodes) + sumAbs(f.div, nodes));
    Kokkos::deep_copy(f.rhsCell, 0.0);
    addCellAdvection(g, f.q, f.u, f.rhsCell, cells, lims[l]);
    put("addCellAdvection." + L, sumAbs(f.rhsCell, cells));
    Kokkos::deep_copy(f.psi1, f.q);
    advanceCellAdvection(g, f.psi1, f.o, f.u, cells, lims[l], 1e-3, 1.0, true, scratch);
    advanceCellAdvection(g, f.psi1, f.o, f.u, cells, lims[l], 1e-3, 0.5, false, scratch);
    put("advanceCellAdvection." + L, sumAbs(f.psi1, cells));
    Kokkos::deep_copy(f.psi1, f.q); // the face speeds once for both stages, as the effects run it
    cellFaceSpeeds(g, f.u, cells, scratch);
    advanceCellAdvection(g, f.psi1, f.o, cells, lims[l], 1e-3, 1.0, true, scratch);
    advanceCellAdvection(g, f.psi1, f.o, cells, lims[l], 1e-3, 0.5, false, scratch);
    put("advanceCellAdvection.shared." + L, sumAbs(f.psi1, cells));
  }
  put("faceRange", double(faces::faceRange(cells, 1).size()));
}

void levelSet(const Grid& g, Fields& f) {
  const Range3 cells = cellRange(g);
  const double kappa = 2 * g.h[0];
  Field rho2 = f.rhsCell, mu2 = f.gm;
  blendProperties(f.psi, kappa, 1000.0, 1.0, 0.1, 1e-3, rho2, mu2, cells);
  put("blendProperties", sumAbs(rho2, cells) + sumAbs(mu2, cells));
  const PhaseMeasures m = localPhaseMeasures(g, f.psi, kappa);
  put("localPhaseMeasures.volume", m.volume);
  put("localPhaseMeasures.sharp", m.sharpVolume);
  put("localPhaseMeasures.area", m.area);
  double vol = 0, dvol = 0;
  localVolumeAndDerivative(g, f.psi, kappa, vol, dvol);
  put("localVolumeAndDerivative.vol", vol);
  put("localVolumeAndDerivative.dvol", dvol);
  Kokkos::deep_copy(f.psi1, f.q);
  shiftField(g, f.psi1, 0.01);
  put("shiftField", sumAbs(f.psi1, cells));
  const bool open[6] = {true, true, true, true, true, true};
  put("localOpenBoundaryFlux", localOpenBoundaryFlux(g, f.q, f.u, 0.2, open));
}

void projectionStressReductions(const Grid& g, Fields& f) {
  const Range3 nodes = nodeRange(g), cells = cellRange(g);
  divergence(g, f.u, f.div, cells);
  put("divergence", sumAbs(f.div, cells));
  subtractGradient(g, f.p, f.coef, 1e-2, f.u2, nodes);
  put("subtractGradient", sumAbs(f.u2, nodes));
  viscousStress(g, f.u, f.mu, f.tau, cellRange(g, 1));
  put("viscousStress", sumAbs(f.tau, cellRange(g, 1)));
  for (int c = 0; c < 3; ++c) Kokkos::deep_copy(f.rhs.c[c], 0.0);
  addStressDivergence(g, f.tau, f.coef, f.rhs, nodes);
  put("addStressDivergence", sumAbs(f.rhs, nodes));
  put("globalMaxAbs", globalMaxAbs(g, f.p, cells));
  put("localMaxAbs", localMaxAbs(f.u.c[1], nodeRange(g)));
  put("countNonFinite", double(countNonFinite(f.p, cells)));
  { // the fused count over several arrays: one planted Inf in a copy of p, none in u.x
    Field q("q", g.ext[0], g.ext[1], g.ext[2]);
    Kokkos::deep_copy(q, f.p);
    Kokkos::deep_copy(Kokkos::subview(q, cells.b[0] + 1, cells.b[1] + 2, cells.b[2] + 1), 1.0 / 0.0);
    put("countNonFiniteAll", double(countNonFinite(arrayBoxes({q, f.u.c[0]}, {cells, nodes}))));
  }
  put("globalSum", globalSum(g, 0.25));
  put("kineticEnergy", kineticEnergy(g, f.u, f.rho));
}

// The fast-diagonalization passes (kernels/fast_diag.hpp) on a whole-grid array taken from p.
double sumAbs3(const Grid3& a) {
  double s = 0;
  Kokkos::parallel_reduce(
      "sum_abs3", Kokkos::RangePolicy<ExecSpace>(0, (int)a.size()),
      KOKKOS_LAMBDA(int p, double& t) { t += std::fabs(a.data()[p]); }, s);
  return s;
}

void fastDiagonalization(const Grid& g, Fields& f) {
  const Range3 cells = cellRange(g);
  const int n0 = g.ln[0], n1 = g.ln[1], n2 = g.ln[2];
  Grid3 a("a", n0, n1, n2), b("b", n0, n1, n2), inv("inv", n0, n1, n2);
  Kokkos::deep_copy(a, Kokkos::subview(f.p, std::make_pair(cells.b[0], cells.e[0]),
                                       std::make_pair(cells.b[1], cells.e[1]), std::make_pair(cells.b[2], cells.e[2])));
  const Dense V0 = denseOf(n0), V1 = denseOf(n1), V2 = denseOf(n2);
  fdTransform<0, false>(a, b, V0, n0);
  fdTransform<1, true>(b, a, V1, n1);
  fdTransform<2, false>(a, b, V2, n2);
  put("fdTransform", sumAbs3(b));
  Grid3 c("c", n0, n1, n2);
  fdFold<1>(b, c);
  put("fdFold", sumAbs3(c));
  fdTransform<1, false>(c, a, V1, (n1 + 1) / 2); // block-diagonal use (V1 not block diagonal: a checksum)
  fdUnfold<2>(a, c);
  put("fdUnfold", sumAbs3(c));
  Kokkos::View<double* [3], MemSpace> lam("lam", 20);
  auto lh = Kokkos::create_mirror_view(lam);
  for (int q = 0; q < 20; ++q)
    for (int d = 0; d < 3; ++d) lh(q, d) = 0.2 * q / (d + 1);
  Kokkos::deep_copy(lam, lh);
  fdInverseEigenvalues(inv, lam, 1.0, 2.0, 3.0, 0, 1e-10);
  put("fdInverseEigenvalues", sumAbs3(inv));
  fdScale(b, inv, a);
  put("fdScale", sumAbs3(a));
  const int lo[3] = {g.ng, g.ng + 1, g.ng}, hi[3] = {g.ng + 1, g.ng + n1, g.ng + n2};
  put("fdFaceMax", fdFaceMax(f.coef, lo, hi, 1));
  RowVector x("x", n0), y("y", n0);
  Kokkos::deep_copy(x, Kokkos::subview(a, Kokkos::ALL(), 1, 2));
  Kokkos::deep_copy(y, Kokkos::subview(b, Kokkos::ALL(), 2, 1));
  fdAxpby(0.5, x, -2.0, y, n0);
  auto yh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), y);
  double sy = 0;
  for (int i = 0; i < n0; ++i) sy += std::fabs(yh(i));
  put("fdAxpby", sy);
  const Dense WT = fdTransposed(V0), Wp = fdPadRows(V0, (n0 + 1) / 2); // the x-line matrices
  auto wt = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), WT);
  auto wp = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), Wp);
  double sw = double(wp.extent(0));
  for (int r = 0; r < int(wp.extent(0)); ++r)
    for (int q = 0; q < n0; ++q) sw += std::fabs(wp(r, q)) * (2 + r + 5 * q) + (r < n0 ? std::fabs(wt(r, q)) * (1 + r + 3 * q) : 0);
  put("fdTransposedPadded", sw);
}

void elasticity(const Grid& g, Fields& f) {
  const double h = g.h[0];
  const IntList owned("owned", size_t(g.cellsOwned())), grown("grown", size_t(cellRange(g, 1).size()));
  const IntList nz("nonzero", size_t(g.cellsOwned()));
  const int nOwned = elastic::buildActiveList(g, f.psi, -3 * h, cellRange(g), owned);
  const int nGrown = elastic::buildActiveList(g, f.psi, -3 * h, cellRange(g, 1), grown);
  put("buildActiveList.owned", nOwned), put("buildActiveList.ownedList", sumList(owned, nOwned));
  put("buildActiveList.grown", nGrown), put("buildActiveList.grownList", sumList(grown, nGrown));
  const Field q = f.q;
  const int nPos = listCellsWhere("test_list", g, cellRange(g, 1), grown, KOKKOS_LAMBDA(int i, int j, int k) {
    return q(i, j, k) > 0;
  });
  put("listCellsWhere", nPos), put("listCellsWhere.list", sumList(grown, nPos));
  elastic::buildActiveList(g, f.psi, -3 * h, cellRange(g, 1), grown); // as before, for what follows
  const int nNz = elastic::buildNonzeroList(g, f.tauS, nz);
  put("buildNonzeroList", nNz), put("buildNonzeroList.list", sumList(nz, nNz));
  const Range3 box = elastic::listBox(g, owned, nOwned);
  put("listBox", box.b[0] + 10.0 * box.b[1] + 100.0 * box.b[2] + 1000.0 * box.e[0] + 1e4 * box.e[1] + 1e5 * box.e[2]);
  const Range3 cells = cellRange(g, 1);
  for (int c = 0; c < 6; ++c) Kokkos::deep_copy(f.tau2.c[c], f.tauS.c[c]);
  const IntList ownedRuns("owned_runs", size_t(nOwned > 0 ? nOwned : 1));
  const int nOwnedRuns = listRuns(owned, nOwned, ownedRuns);
  elastic::jaumannUpdate(g, f.u, f.tau2, 1.0, 1e-2, owned, nOwned, ownedRuns, nOwnedRuns);
  put("jaumannUpdate.cayley", sumAbs(f.tau2, cells));
  elastic::jaumannUpdate(g, f.u, f.tau2, 1.0, 1e-2, owned, nOwned, ownedRuns, nOwnedRuns, 0.5,
                         elastic::Rotation::Explicit, f.psi, 0.0);
  put("jaumannUpdate.explicit", sumAbs(f.tau2, cells));
  elastic::addSolidStress(g, f.psi, 2 * h, f.tauS, f.tau, grown, nGrown);
  put("addSolidStress", sumAbs(f.tau, cells));
  const IntList runs("runs", size_t(nGrown > 0 ? nGrown : 1));
  const int nRuns = listRuns(grown, nGrown, runs);
  put("listRuns", nRuns), put("listRuns.list", sumList(runs, nRuns));
  extension::sweep(g, f.psi, f.tauS, f.tau2, grown, nGrown, runs, nRuns, 0.0);
  put("sweep", sumAbs(f.tau2, cells));
  const IntList side("side", size_t(nGrown > 0 ? nGrown : 1));
  const int nSide = extension::fluidSide(f.psi, g, grown, nGrown, 0.0, side);
  put("fluidSide", nSide), put("fluidSide.list", sumList(side, nSide));
  extension::copySolidSide(g, f.psi, f.tau, f.tau2, grown, nGrown, 0.0);
  put("copySolidSide", sumAbs(f.tau2, cells));
  put("secondInvariant", elastic::secondInvariant(1, 2, 3, 0.1, 0.2, 0.3));
}

void reinitialisation(const Grid& g, Fields& f) {
  const double h = g.h[0], band = 6 * h;
  const size_t cap = size_t(g.cellsOwned());
  reinit::BandViews b;
  b.cell = IntList("band", cap), b.flags = IntList("flags", cap);
  b.sgn = reinit::RealList("sgn", cap), b.dist = reinit::RealList("dist", cap), b.coef = reinit::RealList("coef", cap);
  const int n = reinit::buildBandList(g, f.q, band, b.cell);
  put("buildBandList", n), put("buildBandList.list", sumList(b.cell, n));
  b.runs = IntList("runs", size_t(n > 0 ? n : 1));
  b.nRuns = listRuns(b.cell, n, b.runs);
  put("listRuns.band", b.nRuns);
  reinit::deltaField(g, f.q, f.dH, 2 * h), put("deltaField", sumAbs(f.dH, cellRange(g)));
  reinit::gradMagField(g, f.q, f.dH, f.gm), put("gradMagField", sumAbs(f.gm, cellRange(g)));
  reinit::prepareBand(g, b, n, f.q, f.dH, f.gm, band, true);
  put("prepareBand.flags", sumList(b.flags, n)), put("prepareBand.values", sumBand(b, n));
  reinit::listConstrained(b, n, f.dH); // prepareBand called it; again: the same list
  put("listConstrained", b.nCon), put("listConstrained.list", sumList(b.con, b.nCon));
  Kokkos::deep_copy(f.psi1, f.q), Kokkos::deep_copy(f.psiT, f.q);
  const double dtau = 0.5 * h;
  for (int sub = 0; sub < 2; ++sub) {
    reinit::eikonalStage(g, b, n, f.q, f.q, f.psi1, 0.0, dtau, sub == 1);
    reinit::eikonalStage(g, b, n, f.psi1, f.q, f.psiT, 0.5, dtau, sub == 1);
    put("eikonalStage." + std::to_string(sub), sumAbs(f.psiT, cellRange(g)));
  }
  reinit::applyConstraint(g, b, n, f.psiT, f.q, f.dH, f.psi1);
  put("applyConstraint", sumAbs(f.psi1, cellRange(g)));
  reinit::copyBand(g, b, n, f.psi1, f.psiT);
  put("copyBand", sumAbs(f.psiT, cellRange(g)));
  put("maxGradError", reinit::maxGradError(g, b, n, f.q, band));
  put("buildBandList.settled", reinit::buildBandList(g, f.q, band, b.cell, 2 * h, 0.05)); // zone_tolerance
  reinit::unsettleDelta(g, f.q, f.dH, 2 * h, 0.05), put("unsettleDelta", sumAbs(f.dH, cellRange(g)));
  put("smoothedDelta", smoothedDelta(0.01, 0.05) + smoothedHeaviside(0.01, 0.05) + sharpHeaviside(-1.0));
}

int compare(const std::string& ref, double rtol) {
  std::ifstream in(ref);
  if (!in) {
    std::fprintf(stderr, "voigt_kernels_all: cannot read %s\n", ref.c_str());
    return 2;
  }
  std::map<std::string, double> want;
  std::string name;
  double v;
  while (in >> name >> v) want[name] = v;
  int bad = 0;
  for (const auto& [k, got] : gSums) {
    const auto it = want.find(k);
    const double w = it == want.end() ? NAN : it->second;
    const double err = std::fabs(got - w) / std::fmax(std::fabs(w), 1e-12);
    if (!(err <= rtol)) {
      std::printf("MISMATCH %s: %.17g, reference %.17g (relative %.3g)\n", k.c_str(), got, w, err);
      ++bad;
    }
  }
  std::printf("%s: %zu checksums, %d outside rtol %.1g of %s\n", bad ? "FAIL" : "PASS", gSums.size(), bad, rtol,
              ref.c_str());
  return bad ? 1 : 0;
}

// Boundary kernels on copies (the others' fields stay as they were): face marks, an
// obstacle, prescribed values, node ghosts (odd, even, outflow) and cell ghosts along x.
void boundaries(const Grid& g, Fields& f) {
  const Range3 nodes = nodeRange(g), all{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}};
  IntField mask("mask", g.ext[0], g.ext[1], g.ext[2]);
  VecField val, u;
  for (int c = 0; c < 3; ++c) {
    val.c[c] = mk(g, "val"), u.c[c] = mk(g, "ub");
    Kokkos::deep_copy(u.c[c], f.u.c[c]);
  }
  Range3 face = all;
  face.b[0] = g.ng, face.e[0] = g.ng + 1;
  markNodes(mask, val, face, 7, 0.5, -0.25, 0.125);
  ObstacleShape o;
  o.kind = 1, o.axis = 2, o.c[0] = 0.5, o.c[1] = 0.4, o.r = 0.15, o.v[0] = 0.3;
  addObstacleNodes(g, o, mask, val);
  applyFixed(mask, val, u, nodes);
  put("markNodes+addObstacleNodes+applyFixed", sumAbs(u, nodes));
  Range3 plane = all;
  plane.b[0] = 0, plane.e[0] = 1;
  const int lo = g.ng, hi = g.local(0, g.n[0]);
  mirrorNodeGhosts(u.c[0], plane, 0, lo, -1, g.ng, g.ext[0], 1, false);
  mirrorNodeGhosts(u.c[1], plane, 0, hi, 1, g.ng, g.ext[0], 0, false);
  mirrorNodeGhosts(u.c[2], plane, 0, hi, 1, g.ng, g.ext[0], 0, true);
  put("mirrorNodeGhosts", sumAbs(u, all));
  Field q = mk(g, "qb");
  Kokkos::deep_copy(q, f.p);
  Range3 ghosts = all;
  ghosts.b[0] = 0, ghosts.e[0] = g.ng;
  mirrorCellGhosts(q, ghosts, 0, 2 * g.ng - 1);
  put("mirrorCellGhosts", sumAbs(q, all));
}

} // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int code = 0;
  {
    Kokkos::ScopeGuard kokkos(argc, argv);
    std::string out, ref;
    double rtol = 1e-9;
    for (int a = 1; a < argc; ++a)
      if (!std::strcmp(argv[a], "--config")) Kokkos::print_configuration(std::cout, true);
    for (int a = 1; a + 1 < argc; ++a) {
      if (!std::strcmp(argv[a], "--out")) out = argv[++a];
      else if (!std::strcmp(argv[a], "--compare")) ref = argv[++a];
      else if (!std::strcmp(argv[a], "--rtol")) rtol = std::atof(argv[++a]);
    }
    // 20 x 16 x 12 cells on one rank: x and z walls (open-boundary flux, node weights), y periodic.
    Grid g = makeGrid(MPI_COMM_SELF, {20, 16, 12}, {0, 0, 0}, {1, 0.8, 0.6}, {false, true, false});
    {
      Fields f;
      for (int c = 0; c < 3; ++c)
        f.u.c[c] = mk(g, "u"), f.u2.c[c] = mk(g, "u2"), f.rhs.c[c] = mk(g, "rhs"), f.coef.c[c] = mk(g, "coef");
      f.p = mk(g, "p"), f.psi = mk(g, "psi"), f.rho = mk(g, "rho"), f.mu = mk(g, "mu"), f.q = mk(g, "q");
      f.o = mk(g, "o"), f.rhsCell = mk(g, "rhs_cell"), f.div = mk(g, "div"), f.dH = mk(g, "dH"), f.gm = mk(g, "gm");
      f.psi1 = mk(g, "psi1"), f.psiT = mk(g, "psiT");
      for (int c = 0; c < 6; ++c) f.tau.c[c] = mk(g, "tau"), f.tauS.c[c] = mk(g, "tauS"), f.tau2.c[c] = mk(g, "tau2");
      FluxScratch scratch;
      fill(g, f);
      advection(g, f, scratch);
      levelSet(g, f);
      projectionStressReductions(g, f);
      elasticity(g, f);
      fastDiagonalization(g, f);
      reinitialisation(g, f);
      check::effects(g, f), check::capillary(g, f), check::viscous(g, f), check::multiphase(g, f); // kernels_*.cpp
      boundaries(g, f);
    }
    freeGrid(g);
    std::printf("voigt_kernels_all: Kokkos %s, %zu checksums\n", Kokkos::DefaultExecutionSpace::name(), gSums.size());
    for (const auto& [k, v] : gSums) std::printf("%s %.17g\n", k.c_str(), v);
    if (!out.empty()) {
      std::ofstream o(out);
      o.precision(17);
      for (const auto& [k, v] : gSums) o << k << ' ' << v << '\n';
    }
    if (!ref.empty()) code = compare(ref, rtol);
  }
  MPI_Finalize();
  return code;
}
