// Device check, second part (see kernels_all.cpp): the kernels of the momentum predictor
// and of the effects (solid body, elastic set-up and diagnostics, gravity, obstacles,
// initial and prescribed flows). Every call's result becomes a checksum (check.hpp).
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "kernels/elastic_diagnostics.hpp"
#include "kernels/fast_diag.hpp"
#include "kernels/fd_tridiagonal.hpp"
#include "kernels/initial_flow.hpp"
#include "kernels/momentum.hpp"
#include "kernels/poisson_apply.hpp"
#include "kernels/poisson_assembly.hpp"
#include "kernels/poisson_rows.hpp"
#include "kernels/prescribed_flow.hpp"
#include "kernels/probes.hpp"
#include "kernels/projection_ops.hpp"
#include "kernels/reductions.hpp"
#include "kernels/shapes.hpp"
#include "kernels/solid_body.hpp"
#include "check.hpp"

namespace voigt {
namespace check {
namespace {

// The momentum predictor's stage updates (kernels/momentum.hpp): at three nodes of
// four one component is prescribed (the mask bit cycles with i + j + k). Runs last:
// it overwrites u2, rhs and div.
void momentum(const Grid& g, Fields& f) {
  const Range3 nodes = nodeRange(g), cells = cellRange(g);
  const IntField mask("mask", g.ext[0], g.ext[1], g.ext[2]);
  Kokkos::parallel_for(
      "check_mask", nodes.policy(), KOKKOS_LAMBDA(int i, int j, int k) { mask(i, j, k) = 1 << ((i + j + k) % 4); });
  const VecField u0{mk(g, "u0x"), mk(g, "u0y"), mk(g, "u0z")};
  const Field r0 = mk(g, "r0"), r1 = mk(g, "r1");
  nodeDensity(g, f.rho, r0, nodes);
  put("nodeDensity", sumAbs(r0, nodes));
  for (int c = 0; c < 3; ++c) Kokkos::deep_copy(f.u2.c[c], f.u.c[c]);
  momentumStage1(f.u2, u0, f.rhs, 1e-2, mask, f.coef, nodes);
  put("momentumStage1", sumAbs(f.u2, nodes) + sumAbs(u0, nodes));
  momentumStage2(f.u2, u0, f.rhs, 1e-2, mask, f.coef, nodes);
  put("momentumStage2", sumAbs(f.u2, nodes));
  momentumStage1Conservative(r0, f.q, r1, f.u2, u0, f.rhs, 1e-2, mask, f.coef, nodes);
  put("momentumStage1Conservative", sumAbs(f.u2, nodes) + sumAbs(r1, nodes));
  momentumStage2Conservative(r0, r1, f.q, f.u2, u0, f.rhs, 1e-2, mask, f.coef, nodes);
  put("momentumStage2Conservative", sumAbs(f.u2, nodes));
  initialVelocityRate(f.u2, f.u, f.q, r0, true, mask, nodes);
  put("initialVelocityRate", sumAbs(f.u2, nodes));
  poissonRhs(f.p, f.div, 2.0, cells);
  addTo(f.q, f.div, cells); // div = q - p / 2
  put("poissonRhs+addTo", sumAbs(f.div, cells));
  projectionCoefficients(g, f.rho, mask, f.u2, nodes);
  put("projectionCoefficients", sumAbs(f.u2, nodes));
  addStressMinusGradient(g, f.tau, f.p, f.coef, 1e-2, f.rhs, nodes); // rhs is free here (runs last)
  put("addStressMinusGradient", sumAbs(f.rhs, nodes));
}

// The solid_body effect's kernels: moments and gaps (a sphere target and a low x face)
// of the psi > 0 sphere, and the bending of its mid-surface in the axis frame.
void solidBody(const Grid& g, Fields& f) {
  SolidTargets tg;
  tg.n = 2;
  tg.t[0].kind = 0, tg.t[0].r = 0.1, tg.t[0].c[0] = 0.5, tg.t[0].c[1] = 0.1, tg.t[0].c[2] = 0.3;
  tg.t[1].kind = 3, tg.t[1].axis = 0, tg.t[1].c[0] = 0.0;
  const double h = g.h[0];
  const SolidAcc a = solidMoments(g, f.psi, f.u, 2 * h, 2 * h, h, tg);
  double s = 0;
  for (int q = 0; q < kSolidSums; ++q) s += std::fabs(a.s[q]);
  put("solidMoments.sums", s);
  put("solidMoments.gaps", a.m[0] + 10 * a.m[1]);
  const int R = 10;
  Kokkos::View<double* [4], MemSpace> bins("bins", (2 * R + 1) * (2 * R + 1));
  const double c[3] = {0.5, 0.4, 0.3}, e[3][3] = {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}};
  put("solidBending", solidBending(g, f.psi, 2 * h, h, R, bins, c, e));
}

// Small kernels of the effects (initial stress, band zeroing, gravity, the fixed-node
// count). Runs after everything else: it overwrites tau2, u2, psi1 and q.
void effectKernels(const Grid& g, Fields& f) {
  const Range3 nodes = nodeRange(g), cells = cellRange(g);
  const double a[6] = {1, 2, 3, 0.1, 0.2, 0.3};
  elastic::initialStress(g, f.psi, f.tau2, a);
  put("initialStress", sumAbs(f.tau2, cells));
  const IntList prev("prev", size_t(g.cellsOwned()));
  const int nPrev = elastic::buildActiveList(g, f.psi, -4 * g.h[0], cells, prev);
  const Range3 box = elastic::listBox(g, prev, nPrev);
  Kokkos::deep_copy(f.psi1, 1.0);
  Kokkos::deep_copy(f.q, 1.0);
  for (int c = 0; c < 6; ++c) Kokkos::deep_copy(f.tau2.c[c], 1.0);
  elastic::zeroOutsideBand(g, f.psi, 0.05, f.tau2, box, true, prev, nPrev, f.psi1, f.q, -3.0);
  put("zeroOutsideBand", sumAbs(f.tau2, cellRange(g, 1)) + sumAbs(f.psi1, cells) + sumAbs(f.q, cells));
  for (int c = 0; c < 3; ++c) Kokkos::deep_copy(f.u2.c[c], 0.5);
  addBodyForce(f.u2, 0.1, -9.81, 0.2, nodes);
  put("addBodyForce", sumAbs(f.u2, nodes));
  const Field ph = mk(g, "ph"), p2 = mk(g, "p2"); // balanced gravity: from the top, below a plane (the rank above), +x
  const Plane top("top", g.ln[0], g.ln[2]), last("last", g.ln[0], g.ln[2]), t0("t0", g.ln[1], g.ln[2]);
  hydrostaticShift(g, 1, -9.81, f.rho, ph, p2, top, true, last);
  hydrostaticShift(g, 1, -9.81, f.rho, ph, p2, last, false, top); // below the first pass's bottom layer
  hydrostaticShift(g, 0, 2.0, f.rho, ph, p2, t0, true, t0), put("hydrostaticShift", sumAbs(ph, cells) + sumAbs(p2, cells));
  const IntField mask("mask7", g.ext[0], g.ext[1], g.ext[2]);
  Kokkos::parallel_for(
      "check_mask7", nodes.policy(), KOKKOS_LAMBDA(int i, int j, int k) { mask(i, j, k) = (i + 2 * j + k) % 3 ? 7 : 3; });
  put("countFullyFixed", double(countFullyFixed(mask, nodes)));
  const elastic::ElasticDiag ed = elastic::stressDiagnostics(g, f.tauS, f.psi, f.psi1, f.q, prev, nPrev, 2 * g.h[0], 100.0);
  put("stressDiagnostics", ed.energy + ed.maxS2 + sumAbs(f.psi1, cells) + sumAbs(f.q, cells));
  put("maxKinematicViscosity", maxKinematicViscosity(f.mu, f.rho, cells));
  for (int mode = 1; mode <= 4; ++mode) { // every closed-form initial flow
    InitialFlow init;
    init.mode = mode, init.A = 0.7, init.rho = 2.0, init.p0 = 0.1, init.U[0] = 0.3, init.U[1] = -0.2;
    init.U[2] = 0.1, init.wLo = -0.5, init.wHi = 1.0;
    fillInitialFlow(g, init, f.u2, f.psi1);
    put("fillInitialFlow." + std::to_string(mode), sumAbs(f.u2, nodes) + sumAbs(f.psi1, cells));
  }
  for (int type = 0; type <= 2; ++type) { // rotation, single vortex, uniform
    FlowParams fp;
    fp.type = type, fp.c[0] = 0.5, fp.c[1] = 0.4, fp.w[2] = 2.0, fp.w[0] = 0.5, fp.v[0] = 0.3, fp.v[2] = -0.1;
    fp.period = 8, fp.len[0] = 1, fp.len[1] = 0.8;
    fillPrescribedFlow(g, fp, 1.3, f.u2);
    put("fillPrescribedFlow." + std::to_string(type), sumAbs(f.u2, nodes));
    put("prescribedFlowRate." + std::to_string(type), prescribedFlowRate(g, fp));
  }
}
} // namespace

// The blow-up and dt-collapse diagnostics of the app (first non-finite point, fastest
// node) and the output's shifted copy.
void diagnostics(const Grid& g, Fields& f) {
  const Range3 nodes = nodeRange(g), cells = cellRange(g);
  Kokkos::deep_copy(f.psi1, 1.0);
  const Field p1 = f.psi1;
  Kokkos::parallel_for(
      "check_nan", Range3{{5, 4, 3}, {7, 6, 5}}.policy(), KOKKOS_LAMBDA(int i, int j, int k) { p1(i, j, k) = NAN; });
  put("firstNonFinite", double(firstNonFinite(g, f.psi1, cells)));
  const double m = maxNodeRate(g, f.u, nodes);
  put("maxNodeRate", m);
  put("firstNodeWithRate", double(firstNodeWithRate(g, f.u, nodes, m)));
  shiftedCopy(f.p, f.psi1, 0.25);
  put("shiftedCopy", sumAbs(f.psi1, cells));
  // Two probe points: node and cell stencils, the second cell one-sided (step 0 in z).
  ProbeIdx idx("idx", 2);
  ProbeWeights w("w", 2);
  ProbeValues res("res", 2, 2);
  Kokkos::parallel_for(
      "check_probe_setup", Kokkos::RangePolicy<ExecSpace>(0, 2), KOKKOS_LAMBDA(int q) {
        for (int a = 0; a < 3; ++a) idx(q, a) = 4 + q + a, idx(q, 3 + a) = 5 + a, idx(q, 6 + a) = a < 2 ? 1 : q;
        for (int a = 0; a < 6; ++a) w(q, a) = 0.1 * (a + 1) + 0.05 * q;
      });
  sampleProbes(f.u.c[1], idx, w, 0, 2, res, 0);
  sampleProbes(f.p, idx, w, 3, 2, res, 1);
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), res);
  put("sampleProbes", std::fabs(h(0, 0)) + std::fabs(h(1, 0)) + std::fabs(h(0, 1)) + std::fabs(h(1, 1)));
}

// The pressure solver's row kernels (kernels/poisson_rows.hpp, poisson_assembly.hpp) on
// plain views in the place of Tpetra's, and the implicit shapes (kernels/shapes.hpp).
void solverRowsAndShapes(const Grid& g, Fields& f) {
  const Range3 cells = cellRange(g);
  const GridGeom G(g);
  const CellRows rw{g.ng, g.ln[0], g.ln[1]};
  const int nr = int(g.cellsOwned()), nb = 1 + g.n[0] + g.n[1] + g.n[2];
  const RowVector v("v", nr);
  const RowFlags ident("ident", nr), none;
  Kokkos::parallel_for(
      "check_ident", Kokkos::RangePolicy<ExecSpace>(0, nr), KOKKOS_LAMBDA(int r) { ident(r) = r % 5 == 0; });
  fieldToRows(f.p, v, rw, cells, none);
  put("fieldToRows", rowSquares(v, nr)); // rowSquares: sum of v^2
  put("rowSum", rowSum(v, ident, nr));
  const NullBasis B{G, rw, 1, 1 + g.n[0], 1 + g.n[0] + g.n[1]};
  std::vector<double> sv(nb), ps(g.n[1]);
  nullAnalyze(B, nb, v, ident, nr, sv.data());
  double s = 0;
  for (int m = 0; m < nb; ++m) s += std::fabs(sv[m]) * (1 + 0.01 * m);
  put("nullAnalyze", s);
  Kokkos::View<double*, MemSpace> c("c", nb);
  Kokkos::parallel_for(
      "check_coef", Kokkos::RangePolicy<ExecSpace>(0, nb), KOKKOS_LAMBDA(int m) { c(m) = 0.1 + 0.01 * m; });
  nullSynthesize(B, c, v, ident, nr, true);
  put("nullSynthesize", rowSquares(v, nr));
  nullSynthesizeConstant(0.5, v, ident, nr, true);
  planeSquares(G, rw, 1, v, nr, ps.data());
  s = 0;
  for (size_t q = 0; q < ps.size(); ++q) s += ps[q] * (1 + 0.1 * q);
  put("nullSynthesizeConstant+planeSquares", s);
  zeroIdentityRows(v, ident, nr);
  rowsToField(v, f.psi1, rw, cells);
  put("zeroIdentityRows+rowsToField", sumAbs(f.psi1, cells));
  // The matrix on 27 slots a row (row r's offset o at 27 r + o), both operators.
  const SlotView slot("slot", nr, kStencil);
  const Kokkos::View<size_t*, MemSpace> rowPtr("rowPtr", nr + 1);
  const Kokkos::View<double*, MemSpace> vals("vals", size_t(nr) * kStencil);
  const int ks = kStencil; // by value: nvcc refuses a namespace constexpr in device code
  Kokkos::parallel_for(
      "check_slots", Kokkos::RangePolicy<ExecSpace>(0, nr + 1), KOKKOS_LAMBDA(int r) {
        rowPtr(r) = size_t(r) * ks;
        for (int o = 0; o < ks && r < nr; ++o) slot(r, o) = r * ks + o;
      });
  const RowFlags pattern("pattern", nr);
  const Kokkos::View<int, MemSpace> changed("changed");
  for (int exact = 0; exact <= 1; ++exact) {
    const double amax = assemblePoisson(vals, rowPtr, slot, ident, pattern, G, rw, exact, f.coef, nr, changed);
    double sv2 = 0;
    Kokkos::parallel_reduce(
        "check_vals", Kokkos::RangePolicy<ExecSpace>(0, nr * kStencil),
        KOKKOS_LAMBDA(int q, double& acc) { acc += Kokkos::Experimental::fabs(vals(q)) * (1 + q % 27); }, sv2);
    put(std::string("assemblePoisson.") + (exact ? "exact" : "approximate"), amax + sv2);
  }
  // Every primitive: (plane ^ wave) u sphere u box u cylinder u superquadric u packing, negated.
  std::vector<ShapeOp> ops(10);
  const double P[10][11] = {{0.5, 0.4, 0.3, 0, 1, 0},
                            {0.5, 0.5, 0.3, 0, -1, 0, 0.05, 1, 0, 0, 12.0},
                            {},
                            {0.5, 0.4, 0.3, 0.2},
                            {0.3, 0.3, 0.3, 0.1, 0.2, 0.1},
                            {0.6, 0.3, 0.3, 0.08, 0.15},
                            {0.5, 0.5, 0.4, 0.2, 0.1, 0.15, 4},
                            {},
                            {},
                            {}};
  const ShapeKind K[10] = {ShapeKind::Plane,    ShapeKind::Wave,         ShapeKind::Intersection, ShapeKind::Sphere,
                           ShapeKind::Box,      ShapeKind::Cylinder,     ShapeKind::Superquadric, ShapeKind::Packing,
                           ShapeKind::Union,    ShapeKind::Complement};
  for (int q = 0; q < 10; ++q) {
    ops[q].kind = K[q];
    for (int a = 0; a < 11; ++a) ops[q].a[a] = P[q][a];
  }
  ops[2].n = 2, ops[5].m = 2, ops[7].n = 0, ops[7].m = 2, ops[8].n = 6;
  const ShapeOps dops("ops", 10);
  auto hops = Kokkos::create_mirror_view(dops);
  for (int q = 0; q < 10; ++q) hops(q) = ops[q];
  Kokkos::deep_copy(dops, hops);
  const ShapeSpheres sp("spheres", 2);
  auto hsp = Kokkos::create_mirror_view(sp);
  const double S[2][4] = {{0.2, 0.6, 0.2, 0.1}, {0.8, 0.2, 0.4, 0.15}};
  for (int q = 0; q < 2; ++q)
    for (int a = 0; a < 4; ++a) hsp(q, a) = S[q][a];
  Kokkos::deep_copy(sp, hsp);
  evaluateShapeOps(g, dops, sp, f.psi1);
  put("evaluateShapeOps", sumAbs(f.psi1, cellRange(g, g.ng)));
}

// The projection's extras: the mean |div| diagnostic, the extrapolated CG initial guess and the
// shift of the pressure rates, and the fast diagonalization's passes in float (the mixed-precision
// preconditioner), checked against the same passes in double: 1 when they agree to float round-off
// (1e-5 of the largest value) on any backend.
void projectionExtras(const Grid& g, Fields& f) {
  const Range3 cells = cellRange(g);
  put("globalMeanAbs", globalMeanAbs(g, f.p, cells));
  Field f1 = mk(g, "f1"), f2 = mk(g, "f2"), dp = mk(g, "dp");
  Kokkos::deep_copy(f1, f.p);
  Kokkos::deep_copy(f2, f.psi);
  extrapolateIncrement(f1, f2, dp, 0.01, true, cells);
  put("extrapolateIncrement", sumAbs(dp, cells));
  shiftPressureRates(f1, f2, dp, 0.02, cells);
  put("shiftPressureRates", sumAbs(f1, cells) + sumAbs(f2, cells));
  // The matrix-free exact operator's passes (kernels/poisson_apply.hpp), every fifth row identity.
  Range3 corners = cells;
  for (int d = 0; d < 3; ++d) corners.e[d] += 1;
  const VecField sc{mk(g, "sx"), mk(g, "sy"), mk(g, "sz")}, qf{mk(g, "qx"), mk(g, "qy"), mk(g, "qz")};
  poissonNodeScale(g, f.coef, sc, corners);
  put("poissonNodeScale", sumAbs(sc, corners));
  poissonNodeFlux(f.p, sc, qf, corners);
  put("poissonNodeFlux", sumAbs(qf, corners));
  const int nr = int(g.cellsOwned());
  const RowVector y("y", nr);
  const RowFlags ident("ident", nr);
  Kokkos::parallel_for(
      "check_ident5", Kokkos::RangePolicy<ExecSpace>(0, nr), KOKKOS_LAMBDA(int r) { ident(r) = r % 5 == 0; });
  poissonCellSum(qf, f.p, y, ident, CellRows{g.ng, g.ln[0], g.ln[1]}, cells);
  put("poissonCellSum", rowSquares(y, nr));
  const RowFlags pat("pattern", nr);
  const Kokkos::View<int, MemSpace> changed("changed");
  const double bound = poissonRowPattern(ident, pat, GridGeom(g), CellRows{g.ng, g.ln[0], g.ln[1]}, f.coef, nr, changed);
  put("poissonRowPattern", bound + rowSum(y, ident, nr) * 1e-3);

  const int n0 = g.ln[0], n1 = g.ln[1], n2 = g.ln[2], m = n0 * n1 * n2;
  Grid3 a("a", n0, n1, n2), b("b", n0, n1, n2), c("c", n0, n1, n2), back("back", n0, n1, n2);
  Kokkos::deep_copy(a, Kokkos::subview(f.p, std::make_pair(cells.b[0], cells.e[0]),
                                       std::make_pair(cells.b[1], cells.e[1]), std::make_pair(cells.b[2], cells.e[2])));
  Dense V[3];
  DenseOf<float> W[3];
  for (int d = 0; d < 3; ++d) {
    V[d] = denseOf(g.ln[d]);
    W[d] = DenseOf<float>("W", g.ln[d], g.ln[d]);
    fdConvertDense<float>(V[d], W[d]);
  }
  Grid3Of<float> af("af", n0, n1, n2), bf("bf", n0, n1, n2);
  fdConvert<double, float>(a, af);
  fdTransform<0, false>(a, b, V[0], n0), fdTransform<0, false>(af, bf, W[0], n0);
  fdTransform<1, true>(b, a, V[1], n1), fdTransform<1, true>(bf, af, W[1], n1);
  fdTransform<2, false>(a, b, V[2], n2), fdTransform<2, false>(af, bf, W[2], n2);
  fdFold<1>(b, c), fdFold<1>(bf, af);
  fdConvert<float, double>(af, back);
  Kokkos::View<float*, Kokkos::LayoutLeft, MemSpace> rf("rf", m);
  RowVector rd("rd", m);
  fdConvertRows<double, float>(Kokkos::View<const double*, Kokkos::LayoutLeft, MemSpace>(back.data(), m), rf, m);
  fdConvertRows<float, double>(Kokkos::View<const float*, Kokkos::LayoutLeft, MemSpace>(rf), rd, m);
  double diff = 0, big = 0;
  Kokkos::parallel_reduce(
      "check_float_passes", Kokkos::RangePolicy<ExecSpace>(0, m),
      KOKKOS_LAMBDA(int r, double& acc) {
        const double d = Kokkos::Experimental::fabs(rd(r) - c.data()[r]);
        acc = d > acc ? d : acc;
      },
      Kokkos::Max<double>(diff));
  Kokkos::parallel_reduce(
      "check_float_big", Kokkos::RangePolicy<ExecSpace>(0, m),
      KOKKOS_LAMBDA(int r, double& acc) {
        const double d = Kokkos::Experimental::fabs(c.data()[r]);
        acc = d > acc ? d : acc;
      },
      Kokkos::Max<double>(big));
  put("fdFloatPasses", diff <= 1e-5 * big ? 1.0 : 0.0);
  // The preconditioner's ends (FastDiagPrec): every third row an identity row.
  Kokkos::View<int*, MemSpace> id("id", m);
  Kokkos::parallel_for("flag_rows", Kokkos::RangePolicy<ExecSpace>(0, m), KOKKOS_LAMBDA(int r) { id(r) = r % 3 == 1; });
  RowVector ym("ym", m);
  Kokkos::deep_copy(ym, 0.25);
  fdMaskIn<float>(rd, id, rf, m);
  fdMaskOut<float>(0.5, rf, id, -2.0, ym, m);
  auto yh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), ym);
  double sy = 0;
  for (int r = 0; r < m; ++r) sy += std::fabs(yh(r)) * (1 + r % 3);
  put("fdMaskInOut", sy);
}

// The solve-axis passes (kernels/fd_tridiagonal.hpp) on this rank's cells as a slab: a 1-D
// Neumann K (2 on the interior diagonal, 1 at the ends, -1 off it), M = I - K/4, eigenvalue
// tables of the transformed axes from 2 - 2 cos; the dense form on every fifth line.
void fdSolveAxis(const Grid& g, Fields& f) {
  const int n0 = g.ln[0], n1 = g.ln[1], n2 = g.ln[2];
  const Range3 cells = cellRange(g);
  Grid3 a("a", n0, n1, n2), out("out", n0, n1, n2), cp("cp", n0, n1, n2), dp("dp", n0, n1, n2);
  Kokkos::deep_copy(a, Kokkos::subview(f.p, std::make_pair(cells.b[0], cells.e[0]),
                                       std::make_pair(cells.b[1], cells.e[1]), std::make_pair(cells.b[2], cells.e[2])));
  auto table = [](int n) {
    Table t("lam", n);
    auto h = Kokkos::create_mirror_view(t);
    for (int q = 0; q < n; ++q) h(q) = 2 - 2 * std::cos(3.14159265358979 * q / n);
    Kokkos::deep_copy(t, h);
    return t;
  };
  auto sumSq = [](const Grid3& v) {
    double s = 0;
    const double* p = v.data();
    Kokkos::parallel_reduce(
        "check_sumsq", Kokkos::RangePolicy<ExecSpace>(0, (int)v.size()),
        KOKKOS_LAMBDA(int r, double& acc) { acc += p[r] * p[r]; }, s);
    return s;
  };
  for (int axis : {1, 2}) {
    const int m = axis == 1 ? n1 : n2, no = axis == 1 ? n2 : n1, nc = axis == 1 ? n2 : n1;
    Table4 tri("tri", m, 4);
    auto th = Kokkos::create_mirror_view(tri);
    for (int q = 0; q < m; ++q) {
      th(q, 0) = (q == 0 || q == m - 1) ? 1.0 : 2.0;
      th(q, 1) = q + 1 < m ? -1.0 : 0.0;
      th(q, 2) = 1.0 - 0.25 * th(q, 0);
      th(q, 3) = -0.25 * th(q, 1);
    }
    Kokkos::deep_copy(tri, th);
    const Table la = table(n0), lc = table(nc), ls = table(m);
    const int nl = (n0 * no + 4) / 5;
    Lines2 lines("lines", nl);
    Kokkos::parallel_for(
        "check_lines", Kokkos::RangePolicy<ExecSpace>(0, nl),
        KOKKOS_LAMBDA(int l) { lines(l, 0) = (5 * l) % n0, lines(l, 1) = (5 * l) / n0; });
    Kokkos::View<double**, Kokkos::LayoutRight, MemSpace> work("work", nl, 3 * m);
    const Dense V = denseOf(m);
    Dense VT("VT", m, m);
    fdTransposeDense(V, VT);
    if (axis == 1) {
      fdTridiagonal<1, double>(a, out, cp, dp, tri, la, lc, 1.0, 1.3, 0.8, 0);
      put("fdTridiagonal<1>", sumSq(out));
      fdDenseLines<1, double>(a, out, lines, V, VT, ls, la, lc, 1.0, 1.3, 0.8, 0, 1e-12, work);
      put("fdDenseLines<1>", sumSq(out));
    } else {
      fdTridiagonal<2, double>(a, out, cp, dp, tri, la, lc, 1.0, 1.3, 0.8, 0);
      put("fdTridiagonal<2>", sumSq(out));
      fdDenseLines<2, double>(a, out, lines, V, VT, ls, la, lc, 1.0, 1.3, 0.8, 0, 1e-12, work);
      put("fdDenseLines<2>", sumSq(out));
    }
  }
}

void effects(const Grid& g, Fields& f) {
  solidBody(g, f);
  momentum(g, f);
  effectKernels(g, f);
  diagnostics(g, f);
  solverRowsAndShapes(g, f);
  projectionExtras(g, f);
  fdSolveAxis(g, f);
}

} // namespace check
} // namespace voigt
