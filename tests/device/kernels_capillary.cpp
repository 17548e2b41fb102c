// Device check, third part (see kernels_all.cpp): the surface-tension kernels
// (kernels/curvature.hpp). Every call's result becomes a checksum (check.hpp). psi is the
// level-set field of fill(); the extension runs two sweeps.
#include "kernels/curvature.hpp"
#include "kernels/height_function.hpp"
#include "kernels/levelset.hpp"
#include "kernels/reinit.hpp"
#include "check.hpp"

namespace voigt {
namespace check {

void capillary(const Grid& g, Fields& f) {
  const double h = g.h[0], kappa = 2 * h, reach = 3 * h;
  const Field kap = mk(g, "kap"), ext = mk(g, "ext"), known = mk(g, "known"), H = mk(g, "H");
  const Field ext2 = mk(g, "ext2"), known2 = mk(g, "known2");
  curvature::cellCurvature(g, f.psi, kap, cellRange(g, 1));
  put("cellCurvature", sumAbs(kap, cellRange(g)));
  // surface_tension.curvature: height_function on a copy (the level set's kappa elsewhere).
  const Field kapH = mk(g, "kap_heights"), okH = mk(g, "ok_heights"), kapF = mk(g, "kap_fallback");
  Kokkos::deep_copy(kapH, kap);
  const VecField rec{mk(g, "rec_x"), mk(g, "rec_y"), mk(g, "rec_z")};
  curvature::columnCrossings(f.psi, rec, cellRange(g));
  put("columnCrossings", sumAbs(rec, cellRange(g)));
  const double fallbacks = curvature::heightCurvature(g, f.psi, rec, kapH, okH, cellRange(g));
  put("heightCurvature", sumAbs(kapH, cellRange(g)) + sumAbs(okH, cellRange(g)) + fallbacks);
  curvature::fallbackCurvature(kapH, okH, kapF, cellRange(g));
  put("fallbackCurvature", sumAbs(kapF, cellRange(g)));
  curvature::interfaceCurvature(f.psi, kap, ext, known, cellRange(g, 1));
  put("interfaceCurvature", sumAbs(ext, cellRange(g)) + sumAbs(known, cellRange(g)));
  curvature::extendSweep(g, f.psi, ext, known, ext2, known2, reach, cellRange(g));
  curvature::extendSweep(g, f.psi, ext2, known2, ext, known, reach, cellRange(g));
  put("extendSweep", sumAbs(ext, cellRange(g)) + sumAbs(known, cellRange(g)));
  curvature::heavisideField(f.psi, H, kappa, cellRange(g, 1));
  put("heavisideField", sumAbs(H, cellRange(g)));
  const VecField rhs{mk(g, "cap_x"), mk(g, "cap_y"), mk(g, "cap_z")}; // zero (fill() leaves f.rhs to others)
  curvature::addCapillaryForce(g, f.psi, H, ext, f.coef, 0.07, reach, rhs, nodeRange(g));
  put("addCapillaryForce", sumAbs(rhs, nodeRange(g)));
  curvature::addPlainCsf(g, f.psi, kap, f.coef, 0.07, kappa, rhs, nodeRange(g));
  put("addPlainCsf", sumAbs(rhs, nodeRange(g)));
  // reinit.zone_curvature (kernels/reinit.hpp, settledCell): psi scaled by 1.025 is settled where
  // the curved allowance (h kappa)^2 / 4 passes 0.025: part of the zone.
  const Field d = mk(g, "scaled_psi"), dH = mk(g, "dH");
  const Field psi = f.psi;
  for_each3("scaled_psi", Range3{{0, 0, 0}, {g.ext[0], g.ext[1], g.ext[2]}},
            KOKKOS_LAMBDA(int i, int j, int k) { d(i, j, k) = 1.025 * psi(i, j, k); });
  const IntList cell("cell", size_t(g.cellsOwned()));
  put("buildBandList.curved", reinit::buildBandList(g, d, 6 * h, cell, kappa, 1e-6, true));
  reinit::deltaField(g, d, dH, kappa), reinit::unsettleDelta(g, d, dH, kappa, 1e-6, true);
  put("unsettleDelta.curved", sumAbs(dH, cellRange(g)));
  // level_set.viscosity_blend: harmonic (kernels/levelset.hpp, blendProperties).
  const Field rhoH = mk(g, "rho_harmonic"), muH = mk(g, "mu_harmonic");
  blendProperties(f.psi, kappa, 1000.0, 1.0, 0.1, 1e-3, rhoH, muH, cellRange(g), true);
  put("blendProperties.harmonic", sumAbs(muH, cellRange(g)));
  // reinit.far_bound: the scaled psi's far side bounded by its neighbours' |psi| + h.
  reinit::boundFarField(g, d, dH, kappa);
  put("boundFarField", sumAbs(dH, cellRange(g)));
}

} // namespace check
} // namespace voigt
