// Device check, third part (see kernels_all.cpp): the surface-tension kernels
// (kernels/curvature.hpp). Every call's result becomes a checksum (check.hpp). psi is the
// level-set field of fill(); the extension runs two sweeps.
#include "kernels/curvature.hpp"
#include "check.hpp"

namespace voigt {
namespace check {

void capillary(const Grid& g, Fields& f) {
  const double h = g.h[0], kappa = 2 * h, reach = 3 * h;
  const Field kap = mk(g, "kap"), ext = mk(g, "ext"), known = mk(g, "known"), H = mk(g, "H");
  const Field ext2 = mk(g, "ext2"), known2 = mk(g, "known2");
  curvature::cellCurvature(g, f.psi, kap, cellRange(g, 1));
  put("cellCurvature", sumAbs(kap, cellRange(g)));
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
}

} // namespace check
} // namespace voigt
