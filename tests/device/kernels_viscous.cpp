// Device check, fourth part (see kernels_all.cpp): the semi-implicit viscosity kernels
// (kernels/viscous_implicit.hpp), one CG iteration on f.u's increment against f.u2, with
// f.mu and f.rho from fill() and the x- wall plane's nodes prescribed; and the neo-Hookean
// stress update (kernels/elastic.hpp, elasticity.model: neo_hookean) on a copy of f.tau2, and
// its diagnostics (kernels/elastic_diagnostics.hpp); the split projection's two kernels
// (kernels/projection_ops.hpp, projection.variable_density: split) on f.coef and f.p.
#include "kernels/elastic_diagnostics.hpp"
#include "kernels/projection_ops.hpp"
#include "kernels/viscous_implicit.hpp"
#include "check.hpp"

namespace voigt {
namespace check {

void viscous(const Grid& g, Fields& f) {
  auto vec = [&](const char* n) { return VecField{mk(g, n), mk(g, n), mk(g, n)}; };
  const VecField c = vec("vi_edge"), q = vec("vi_q"), x = vec("vi_x"), r = vec("vi_r"), p = vec("vi_p");
  const Field m = mk(g, "vi_mass"), invDiag = mk(g, "vi_inv_diag");
  const IntField mask("vi_mask", g.ext[0], g.ext[1], g.ext[2]);
  const int wall = g.ng;
  for_each3("vi_mask", nodeRange(g), KOKKOS_LAMBDA(int i, int j, int k) { mask(i, j, k) = i == wall ? 7 : 0; });
  const double dt = 0.01;
  viscous::edgeCoefficients(g, f.mu, c, nodeRange(g, 1));
  put("viscous.edgeCoefficients", sumAbs(c, nodeRange(g)));
  viscous::massAndDiagonal(g, f.rho, c, dt, m, invDiag, nodeRange(g));
  put("viscous.massAndDiagonal", sumAbs(m, nodeRange(g)) + sumAbs(invDiag, nodeRange(g)));
  viscous::stageIncrement(f.u, f.u2, q, nodeRange(g, 1));
  put("viscous.stageIncrement", sumAbs(q, nodeRange(g)));
  const viscous::TwoSums s0 = viscous::startResidual(mask, c, invDiag, dt, q, r, x, p, nodeRange(g));
  put("viscous.startResidual", s0.a + s0.b + sumAbs(r, nodeRange(g)));
  const double pq = viscous::applyOperator(mask, c, m, dt, p, q, nodeRange(g));
  put("viscous.applyOperator", pq + sumAbs(q, nodeRange(g)));
  const viscous::TwoSums s1 = viscous::updateIterate(invDiag, s0.b / pq, p, q, x, r, nodeRange(g));
  put("viscous.updateIterate", s1.a + s1.b + sumAbs(x, nodeRange(g)));
  viscous::newDirection(invDiag, s1.b / s0.b, r, p, nodeRange(g));
  put("viscous.newDirection", sumAbs(p, nodeRange(g)));
  const VecField u = vec("vi_u");
  viscous::secondStageIncrement(f.u, f.u2, u, nodeRange(g));
  put("viscous.secondStageIncrement", sumAbs(u, nodeRange(g)));
  viscous::addCorrection(x, 0.5, u, nodeRange(g));
  put("viscous.addCorrection", sumAbs(u, nodeRange(g)));
  // elasticity.model: neo_hookean: every owned cell, Cayley rotations.
  SymTensorField t;
  for (int c = 0; c < 6; ++c) {
    t.c[c] = mk(g, "nh_tau");
    Kokkos::deep_copy(t.c[c], f.tau2.c[c]);
  }
  const elastic::IntList list("nh_list", size_t(g.cellsOwned())), runs("nh_runs", size_t(g.cellsOwned()));
  const int n = elastic::buildActiveList(g, f.psi, -1e300, cellRange(g), list), nRuns = listRuns(list, n, runs);
  elastic::jaumannUpdate(g, f.u, t, 1.0, 1e-2, list, n, runs, nRuns, 0.5, elastic::Rotation::Cayley, Field(),
                         elastic::kAll, true);
  put("jaumannUpdate.neo_hookean", sumAbs(t, cellRange(g)));
  const Field s2 = mk(g, "nh_S2"), lg = mk(g, "nh_lg"); // its diagnostics: energy, tension, det B
  const elastic::ElasticDiag d = elastic::stressDiagnostics(g, t, f.psi, s2, lg, list, n, 2 * g.h[0], 1.0, true);
  put("stressDiagnostics.neo_hookean", d.energy + d.maxS2 + d.tension + d.detDrift + sumAbs(s2, cellRange(g)));
  // projection.variable_density: split. b0 above every coefficient (B - B0 <= 0).
  const VecField c0 = vec("split_coef0"), us = vec("split_u");
  splitCoefficients(f.coef, 3.0, c0, nodeRange(g));
  put("splitCoefficients", sumAbs(c0, nodeRange(g)));
  for (int d2 = 0; d2 < 3; ++d2) Kokkos::deep_copy(us.c[d2], f.u.c[d2]);
  subtractSplitGradient(g, f.p, f.coef, 3.0, 1e-2, us, nodeRange(g));
  put("subtractSplitGradient", sumAbs(us, nodeRange(g)));
}

} // namespace check
} // namespace voigt
