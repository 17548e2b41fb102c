// Device check, fifth part (see kernels_all.cpp): several level sets (kernels/multiphase.hpp,
// kernels/contact.hpp, kernels/levelset.hpp blendOver) and a solid's surface velocity
// (kernels/surface_velocity.hpp). The level sets are fill()'s psi and
// a second one, psi shifted by 1.5 h with its sign turned (a body facing the first).
#include "kernels/contact.hpp"
#include "kernels/levelset.hpp"
#include "kernels/multiphase.hpp"
#include "kernels/surface_velocity.hpp"
#include "check.hpp"

namespace voigt {
namespace check {

void multiphase(const Grid& g, Fields& f) {
  const double h = g.h[0], kappa = 2 * h;
  const Field b = mk(g, "psi_b"), psi = f.psi;
  const Range3 all{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}};
  for_each3("psi_b", all, KOKKOS_LAMBDA(int i, int j, int k) { b(i, j, k) = -psi(i, j, k) - 1.5 * h; });
  const Field rho = mk(g, "rho_over"), mu = mk(g, "mu_over");
  blendProperties(f.psi, kappa, 1000.0, 1.2, 1e-3, 1.8e-5, rho, mu, all);
  blendOver(b, kappa, 1500.0, 0.1, rho, mu, all);
  put("blendOver", sumAbs(rho, cellRange(g)) + sumAbs(mu, cellRange(g)));
  blendOver(b, kappa, 1500.0, 0.1, rho, mu, all, true);
  put("blendOver.harmonic", sumAbs(mu, cellRange(g)));
  put("localBodyGap", localBodyGap(f.psi, b, 6 * h, cellRange(g)));
  const Field u = mk(g, "union");
  Kokkos::deep_copy(u, f.psi);
  maxInto(u, b, all);
  put("maxInto", sumAbs(u, cellRange(g)));
  const Field c = mk(g, "cover");
  multiphase::cover(b, kappa, c, true, cellRange(g));
  multiphase::cover(f.psi, kappa, c, false, cellRange(g));
  put("cover", sumAbs(c, cellRange(g)));
  double v = 0, dv = 0;
  multiphase::localCoveredVolume(g, f.psi, kappa, c, v, dv);
  put("localCoveredVolume", v + dv);
  const Field known = mk(g, "known"), known2 = mk(g, "known2"), fl = mk(g, "fluid"), fl2 = mk(g, "fluid2");
  for_each3("fluid", all, KOKKOS_LAMBDA(int i, int j, int k) { fl(i, j, k) = 0.3 * psi(i, j, k) + 0.01 * h * (j - i); });
  multiphase::markSources(b, kappa + h, known, all);
  multiphase::extendSweep(b, kappa + h, kappa + 2 * h, fl, known, fl2, known2, cellRange(g));
  multiphase::extendSweep(b, kappa + h, kappa + 2 * h, fl2, known2, fl, known, cellRange(g));
  put("extendSweep.multiphase", sumAbs(fl, cellRange(g)) + sumAbs(known, cellRange(g)));
  const Range3 box = multiphase::boxWhere(b, -kappa, cellRange(g));
  put("boxWhere", box.b[0] + 2.0 * box.b[1] + 3.0 * box.b[2] + 5.0 * box.e[0] + 7.0 * box.e[1] + 11.0 * box.e[2]);
  copyCells(fl2, b, box);
  put("copyCells", sumAbs(fl2, cellRange(g)));
  const VecField bu{mk(g, "body_u"), mk(g, "body_v"), mk(g, "body_w")};
  multiphase::setBodyVelocity(b, kappa, 0.2, -0.1, 0.05, bu, nodeRange(g));
  put("setBodyVelocity", sumAbs(bu, nodeRange(g)));
  // A solid's surface velocity (kernels/surface_velocity.hpp): fill()'s velocity extended into
  // the fluid half of psi's zone, with one node's x component prescribed.
  const Field pn = mk(g, "psi_node");
  surface_velocity::nodeLevels(f.psi, pn, nodeRange(g, 1));
  put("nodeLevels", sumAbs(pn, nodeRange(g, 1)));
  const IntList layer("layer", size_t(g.ext[0]) * g.ext[1] * g.ext[2]);
  const int nLayer = surface_velocity::listLayer(g, pn, -(kappa + h), nodeRange(g), layer);
  put("listLayer", nLayer), put("listLayer.list", sumList(layer, nLayer));
  IntField mask("sv_mask", g.ext[0], g.ext[1], g.ext[2]);
  const int n0 = g.ext[0] / 2;
  for_each3("sv_mask", all, KOKKOS_LAMBDA(int i, int j, int k) { mask(i, j, k) = i == n0 ? 1 : 0; });
  const VecField sv{mk(g, "sv_u"), mk(g, "sv_v"), mk(g, "sv_w")};
  for (int c = 0; c < 3; ++c) Kokkos::deep_copy(sv.c[c], f.u.c[c]), Kokkos::deep_copy(bu.c[c], f.u.c[c]);
  surface_velocity::sweep(g, pn, mask, sv, bu, layer, nLayer);
  surface_velocity::sweep(g, pn, mask, bu, sv, layer, nLayer);
  put("surfaceVelocitySweep", sumAbs(sv, nodeRange(g)));
}

} // namespace check
} // namespace voigt
