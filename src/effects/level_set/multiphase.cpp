// Several level sets: fluids under solid bodies (kernels/multiphase.hpp).
//   Extension (after reinit, Corrections stage): for a fluid's psi_f and a body's psi_b, the
//   cells -(kappa_b + h) < psi_b <= kappa_b + 2 h take psi_f extended along grad psi_b from
//   the cells farther out, in Jacobi sweeps (one cell deeper each). The body's smoothing
//   zone and a cell beyond then see the fluid that surrounds the body; deeper inside psi_f
//   is covered (H_b = 1) and left as it is. The sweeps run on the box of the cells to fill.
//   Covered volume: V_f = INT H(psi_f) PROD_{j>f} (1 - H(psi_j)) dV, what the blend gives the fluid.
#include <cmath>

#include "core/boundary.hpp"
#include "core/field_names.hpp"
#include "effects/level_set/level_set.hpp"
#include "kernels/multiphase.hpp"

namespace voigt {

Field LevelSet::cover(State& st, size_t i) const {
  const Grid& g = st.grid;
  Field c = st.fields.scalar("level_set_cover");
  for (size_t j = i + 1; j < ls_.size(); ++j)
    multiphase::cover(st.fields.scalar(ls_[j].info.field), ls_[j].info.geometry.kappa(g), c, j == i + 1, cellRange(g));
  return c;
}

void LevelSet::hideUnderSolids(State& st) {
  if (!hides_) return;
  const Grid& g = st.grid;
  const double h = LevelSetGeometry::hMin(g);
  const Range3 cells = cellRange(g);
  Field known = st.fields.scalar("level_set_known"), knownTmp = st.fields.scalar("level_set_known_tmp");
  Field tmp = st.fields.scalar("psi_old"); // free outside the advection
  for (const LevelSetInstance& body : ls_) {
    if (!body.solid) continue;
    const Field pb = st.fields.scalar(body.info.field);
    const double kappa = body.info.geometry.kappa(g), outside = kappa + h, inside = kappa + 2 * h;
    const int sweeps = int(std::ceil((outside + inside) / h)) + 1;
    for (const LevelSetInstance& fl : ls_) {
      if (fl.solid) continue;
      Field pf = st.fields.scalar(fl.info.field);
      multiphase::markSources(pb, outside, known, cellRange(g, g.ng));
      const Range3 box = multiphase::boxWhere(pb, -outside, cells); // this rank's cells to fill
      for (int s = 0; s < sweeps; ++s) { // every rank: the exchanges are collective
        multiphase::extendSweep(pb, outside, inside, pf, known, tmp, knownTmp, box);
        multiphase::copyOn(pf, tmp, box);
        multiphase::copyOn(known, knownTmp, box);
        st.halo->exchange(std::vector<Field>{pf, known});
        fillCellGhostsEven(g, pf);
        fillCellGhostsEven(g, known);
      }
    }
  }
}

} // namespace voigt
